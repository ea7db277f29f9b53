"""The Soccer Server field model: a re-implementation of rcssserver's dynamics and sensing.

Modules (specs/soccer_server.md):

* :mod:`~field_models.soccer_server.params` — :class:`DynamicsParams`, :class:`ServerPreset` and
  :func:`load_server_preset` for the presets ``soccer_server_1996`` (the paper's era) and
  ``rcssserver_19`` (today's server as a version-19 client gets it) and ``rcssserver_19_async``
  (its defaults with the asynchronous sees of a client below protocol 18) in
  ``field_models/presets/soccer_server/``.
* :mod:`~field_models.soccer_server.sensing_params` — :class:`SensingParams` (see/hear timing,
  view cone, quantisation).
* :mod:`~field_models.soccer_server.dynamics` — :class:`SoccerServerModel`: one trial's 100 ms
  cycles (commands, movement with noise, goals and referee messages), with the rules it shares
  with the batch in :mod:`~field_models.soccer_server.cycle_rules` (play modes, random rows,
  command formulas) and :mod:`~field_models.soccer_server.collisions`.
* :mod:`~field_models.soccer_server.batch` — :class:`BatchSoccerServer`: K trials as numpy
  arrays, equal to K single models seed for seed (random rows in
  :mod:`~field_models.soccer_server.batch_random`, collisions in
  :mod:`~field_models.soccer_server.batch_collisions`).
* :mod:`~field_models.soccer_server.server_conf` — :func:`load_server_conf`: a preset from a
  real server's ``server.conf`` or ``(server_param ...)`` message (read by
  :mod:`~field_models.soccer_server.server_conf_text`, named in
  :mod:`~field_models.soccer_server.server_param_table`).
* :mod:`~field_models.soccer_server.sensing` (see contents; its numbers in
  :mod:`~field_models.soccer_server.see_numbers`, its timer in
  :mod:`~field_models.soccer_server.see_timing`), :mod:`~field_models.soccer_server.hearing`
  (say and hear), :mod:`~field_models.soccer_server.messages`,
  :mod:`~field_models.soccer_server.percepts` — see and hear contents, their text, percepts.
* :mod:`~field_models.soccer_server.serving` — :class:`~.serving.ServedGame`: the model as a server
  (with ``serving_state``, ``serving_clients``, ``serving_commands``), on UDP in
  :mod:`~field_models.soccer_server.udp`.

Typical use (noise from the trial's own generator)::

    preset = load_server_preset("soccer_server_1996")
    model = SoccerServerModel(preset, (PlayerRef(LEFT, 1),), rng)
    model.move_ball(0.0, 0.0)
    model.move_player(1, -1.0, 0.0, 0.0)
    model.command(1, Kick(100.0, 0.0))
    messages = model.step()          # referee messages of the cycle, e.g. ["goal_l_1"]
"""

from field_models.soccer_server.batch import BatchSoccerServer
from field_models.soccer_server.cycle_rules import PLAY_MODES, dash_rate, kick_effectiveness
from field_models.soccer_server.dynamics import SoccerServerModel
from field_models.soccer_server.params import (
    DynamicsParams,
    ServerPreset,
    load_server_preset,
)
from field_models.soccer_server.sensing_params import SensingParams
from field_models.soccer_server.server_conf import ServerConf, load_server_conf

__all__ = [
    "PLAY_MODES",
    "BatchSoccerServer",
    "DynamicsParams",
    "SensingParams",
    "ServerConf",
    "ServerPreset",
    "SoccerServerModel",
    "dash_rate",
    "kick_effectiveness",
    "load_server_conf",
    "load_server_preset",
]
