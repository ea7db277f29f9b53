"""Presets from a real rcssserver's own configuration: ``server.conf`` or ``server_param``.

A user can run the model with the parameters of an actual server, in the server's own names and
units, over a base preset (``rcssserver_19_async``, the server's own defaults, unless told
otherwise) that supplies everything the configuration does not set. Two formats are read
(:mod:`~field_models.soccer_server.server_conf_text`), both as rcssserver 19.0.0 writes them:

* a ``server.conf`` file (``rcss/conf/builder.hpp``, ``createConfFileEntry``; parsed as
  ``rcss/conf/parser.cpp`` does): lines ``server::ball_decay = 0.94``; comments ``# ...``,
  ``// ...`` and ``/* ... */`` (several lines); blank lines; values ``true``/``false``/``on``/
  ``off`` (any case), integers, reals (``0.94``, ``1e-05``) and strings, quoted ``'...'`` or
  ``"..."`` or bare, on the line of their ``=``; an optional ``-``/``--`` before a name and
  the module ``server::`` are accepted (a name without a module counts as a server
  parameter); ``server::version`` is accepted and not used; a later setting of a parameter
  replaces an earlier one; ``include`` and ``help`` are refused;
* the text of a ``(server_param (goal_width 14.02) (ball_decay 0.94) ...)`` message as a
  server sends it to clients (``src/initsender.cpp``, ``InitSenderCommonV8``): doubles as a
  C++ stream prints them, booleans as ``0``/``1``, strings in double quotes.

Values are checked against the parameter's type in the server (``src/serverparam.h``): a
double takes any number, an integer an integral number, a boolean a truth value or 0/1, a
string a string. Every parameter the model has (:data:`MAPPED`) is converted to its preset
field: angles in degrees become radians (``minmoment``, ``maxmoment``, ``min_dash_angle``,
``max_dash_angle``, ``dash_angle_step``); ``visible_angle`` is the full cone, so it becomes
the half angle ``view_half_angle_rad``; ``simulator_step`` sets both records' cycle; speeds
and accelerations keep the server's per-cycle units; ``coach`` (no referee) and
``coach_w_referee`` set ``referee``. Every other parameter of rcssserver 19
(:data:`SERVER_PARAMS`: stamina, tackle, catch, wind, ports, logging, ...) is accepted and
reported in :attr:`ServerConf.ignored` (:mod:`~field_models.soccer_server.server_param_table`
lists them all). A name that is not a server parameter, a value of the
wrong type or out of the field's range raises :class:`~field_models.presets.PresetError`
naming the file (and line) and the key.

What a server configuration cannot say comes from the base: the version's rules (noise model,
kick reduction, client protocol, changes in sees, landmark set, hearing per team), compiled
constants (pitch, goal-post radius, the 50-cycle after-goal wait) and the player-type values
(``unum_far_length``, ``team_far_length``, ...: ``player_type`` messages, not server
parameters).
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Literal, TypeVar

from field_models.presets import PresetError, RecordError, load_field, read_text
from field_models.soccer_server.params import (
    DynamicsParams,
    ServerPreset,
    is_server_conf,
    load_server_preset,
)
from field_models.soccer_server.sensing_params import SensingParams
from field_models.soccer_server.server_conf_text import (
    MESSAGE_SOURCE,
    Setting,
    parse_server_conf,
    parse_server_param,
)
from field_models.soccer_server.server_param_table import ServerValue

Record = Literal["dynamics", "sensing"]
_R = TypeVar("_R", DynamicsParams, SensingParams)


def _same(value: ServerValue) -> ServerValue:
    return value


def _radians(value: ServerValue) -> float:
    return math.radians(float(value))


def _half_cone(value: ServerValue) -> float:
    return math.radians(float(value) / 2.0)


MAPPED: dict[str, tuple[tuple[Record, str, Callable[[ServerValue], ServerValue]], ...]] = {
    "simulator_step": (
        ("dynamics", "simulator_step_ms", _same),
        ("sensing", "simulator_step_ms", _same),
    ),
    "goal_width": (("dynamics", "goal_width_m", _same),),
    "ball_size": (("dynamics", "ball_size_m", _same),),
    "ball_decay": (("dynamics", "ball_decay", _same),),
    "ball_rand": (("dynamics", "ball_rand", _same),),
    "ball_speed_max": (("dynamics", "ball_speed_max_m_per_cycle", _same),),
    "ball_accel_max": (("dynamics", "ball_accel_max_m_per_cycle2", _same),),
    "player_size": (("dynamics", "player_size_m", _same),),
    "player_decay": (("dynamics", "player_decay", _same),),
    "player_rand": (("dynamics", "player_rand", _same),),
    "player_speed_max": (("dynamics", "player_speed_max_m_per_cycle", _same),),
    "player_accel_max": (("dynamics", "player_accel_max_m_per_cycle2", _same),),
    "inertia_moment": (("dynamics", "inertia_moment_cycle_per_m", _same),),
    "dash_power_rate": (("dynamics", "dash_power_rate_m_per_cycle2", _same),),
    "kick_power_rate": (("dynamics", "kick_power_rate_m_per_cycle2", _same),),
    "kickable_margin": (("dynamics", "kickable_margin_m", _same),),
    "kick_rand": (("dynamics", "kick_rand", _same),),
    "minpower": (("dynamics", "minpower", _same),),
    "maxpower": (("dynamics", "maxpower", _same),),
    "min_dash_power": (("dynamics", "min_dash_power", _same),),
    "max_dash_power": (("dynamics", "max_dash_power", _same),),
    "minmoment": (("dynamics", "minmoment_rad", _radians),),
    "maxmoment": (("dynamics", "maxmoment_rad", _radians),),
    "side_dash_rate": (("dynamics", "side_dash_rate", _same),),
    "back_dash_rate": (("dynamics", "back_dash_rate", _same),),
    "dash_angle_step": (("dynamics", "dash_angle_step_rad", _radians),),
    "min_dash_angle": (("dynamics", "min_dash_angle_rad", _radians),),
    "max_dash_angle": (("dynamics", "max_dash_angle_rad", _radians),),
    "minneckang": (("dynamics", "minneckang_rad", _radians),),
    "maxneckang": (("dynamics", "maxneckang_rad", _radians),),
    "minneckmoment": (("dynamics", "minneckmoment_rad", _radians),),
    "maxneckmoment": (("dynamics", "maxneckmoment_rad", _radians),),
    "send_step": (("sensing", "send_step_ms", _same),),
    "recv_step": (("sensing", "recv_step_ms", _same),),
    "visible_angle": (("sensing", "view_half_angle_rad", _half_cone),),
    "visible_distance": (("sensing", "visible_distance_m", _same),),
    "quantize_step": (("sensing", "quantize_step", _same),),
    "quantize_step_l": (("sensing", "quantize_step_l", _same),),
    "audio_cut_dist": (("sensing", "audio_cut_dist_m", _same),),
    "say_msg_size": (("sensing", "say_msg_size", _same),),
    "hear_max": (("sensing", "hear_max", _same),),
    "hear_inc": (("sensing", "hear_inc", _same),),
    "hear_decay": (("sensing", "hear_decay", _same),),
}
"""The server parameters the model has: each one's preset fields and unit conversion."""

REFEREE_PARAMS = ("coach", "coach_w_referee")
"""``server::coach`` turns the referee off unless ``server::coach_w_referee`` keeps it (§5)."""

_RECORDS: dict[Record, type] = {"dynamics": DynamicsParams, "sensing": SensingParams}
_SERVER_NAME = {field: name for name, targets in MAPPED.items() for _, field, _ in targets}
_SERVER_NAME["referee"] = "coach"


@dataclass(frozen=True, slots=True)
class ServerConf:
    """A preset loaded from a server's configuration, and what was done with each parameter.

    Attributes:
        preset: The base preset with every modelled parameter of the configuration applied.
        applied: The server parameters that set preset fields, in the configuration's order.
        ignored: The server parameters the model does not have (stamina, tackle, ports, ...),
            accepted and left out, in the configuration's order.
    """

    preset: ServerPreset
    applied: tuple[str, ...]
    ignored: tuple[str, ...]


def load_preset(name_or_path: str) -> ServerPreset:
    """Any Soccer Server preset argument: a name or TOML file, or a real server's configuration.

    A configuration is a path ending in ``.conf`` or the text of a ``(server_param ...)``
    message, loaded over the ``rcssserver_19_async`` preset by :func:`load_server_conf`. This is
    what the registry entry and the CLI's ``--field-preset`` read.

    Raises:
        PresetError: naming the file (or the message) and the key.
    """
    if is_server_conf(name_or_path):
        return load_server_conf(name_or_path).preset
    return load_server_preset(name_or_path)


def load_server_conf(
    source: str | Path, *, base: str | ServerPreset = "rcssserver_19_async"
) -> ServerConf:
    """A preset from a server's configuration, over `base` (a preset name or path, or a preset).

    `source` is a ``server.conf`` file, a file holding a ``(server_param ...)`` message, or
    such a message's text. The preset is named after the file's stem (``server_param`` for
    message text) and keeps the base's era (the server version's rules: noise model, kick
    reduction, protocol).

    Raises:
        PresetError: naming the file and the key: an unreadable file, a name that is not a
            server parameter, a value of the wrong type or outside its field's range.
    """
    text = str(source)
    if isinstance(source, str) and text.lstrip().startswith("(server_param"):
        settings = parse_server_param(text, file=MESSAGE_SOURCE)
        return preset_from_settings(settings, base=base, name="server_param", source=MESSAGE_SOURCE)
    path = Path(source)
    content = read_text(path, "server configuration file")
    if content.lstrip().startswith("(server_param"):
        settings = parse_server_param(content, file=str(path))
    else:
        settings = parse_server_conf(content, file=str(path))
    return preset_from_settings(settings, base=base, name=path.stem, source=str(path))


def preset_from_settings(
    settings: list[Setting],
    *,
    base: str | ServerPreset = "rcssserver_19_async",
    name: str,
    source: str,
) -> ServerConf:
    """The base preset with the modelled settings applied (see the module docstring).

    Raises:
        PresetError: naming where a setting was made and its key, for a value of the wrong
            type or range, or settings that contradict each other (e.g. minpower > maxpower).
    """
    preset = load_server_preset(base) if isinstance(base, str) else base
    last = {s.name: s for s in settings}  # as in the server, a later setting wins
    changes: dict[Record, dict[str, ServerValue]] = {"dynamics": {}, "sensing": {}}
    applied: list[str] = []
    ignored: list[str] = []
    for setting in last.values():
        targets = MAPPED.get(setting.name)
        if targets is None:
            if setting.name not in REFEREE_PARAMS:
                ignored.append(setting.name)
            continue
        applied.append(setting.name)
        for record, fld, convert in targets:
            changes[record][fld] = load_field(
                _RECORDS[record],
                fld,
                convert(setting.value),
                file=setting.where,
                key=setting.key,
            )
    referee = _referee(last)
    if referee is not None:
        changes["dynamics"]["referee"] = referee
    (ignored if referee is None else applied).extend(n for n in REFEREE_PARAMS if n in last)
    dynamics = _replace(preset.dynamics, changes["dynamics"], last, source)
    sensing = _replace(preset.sensing, changes["sensing"], last, source)
    loaded = dataclasses.replace(
        preset, name=name, dynamics=dynamics, sensing=sensing, source=source
    )
    order = {s.name: i for i, s in enumerate(last.values())}
    return ServerConf(
        loaded,
        tuple(sorted(applied, key=order.__getitem__)),
        tuple(sorted(ignored, key=order.__getitem__)),
    )


def _referee(last: dict[str, Setting]) -> bool | None:
    """``referee`` from ``coach``/``coach_w_referee``; None when neither decides it."""
    coach = last.get("coach")
    with_referee = last.get("coach_w_referee")
    if with_referee is not None and with_referee.value:
        return True
    if coach is not None:
        return not coach.value
    return None


def _replace(
    record: _R, changes: dict[str, ServerValue], last: dict[str, Setting], source: str
) -> _R:
    """`record` with `changes`; its own consistency checks become PresetErrors."""
    try:
        return record.replace(**changes)
    except RecordError as exc:
        field, message = exc.key, exc.message
    name = _SERVER_NAME.get(field)
    setting = last.get(name) if name is not None else None
    if setting is None:
        raise PresetError(f"{source}: key '{field}': {message}") from None
    raise PresetError(f"{setting.where}: key '{setting.key}': {message}") from None
