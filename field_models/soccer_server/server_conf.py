"""Presets from a real rcssserver's own configuration: ``server.conf`` or ``server_param``.

A user can run the model with the parameters of an actual server, in the server's own names and
units, over a base preset (``rcssserver_19`` unless told otherwise) that supplies everything
the configuration does not set. Two formats are read, both as rcssserver 19.0.0 writes them:

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
reported in :attr:`ServerConf.ignored`. A name that is not a server parameter, a value of the
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
import re
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Literal, NamedTuple, TypeVar

from field_models.presets import PresetError, RecordError, load_field, read_text
from field_models.soccer_server.messages import MessageParseError, Quoted, parse_sexpr
from field_models.soccer_server.params import (
    DynamicsParams,
    ServerPreset,
    is_server_conf,
    load_server_preset,
)
from field_models.soccer_server.sensing_params import SensingParams

SERVER_PARAMS: tuple[str, ...] = (
    "goal_width",
    "inertia_moment",
    "player_size",
    "player_decay",
    "player_rand",
    "player_weight",
    "player_speed_max",
    "player_accel_max",
    "stamina_max",
    "stamina_inc_max",
    "recover_init",
    "recover_dec_thr",
    "recover_min",
    "recover_dec",
    "effort_init",
    "effort_dec_thr",
    "effort_min",
    "effort_dec",
    "effort_inc_thr",
    "effort_inc",
    "kick_rand",
    "team_actuator_noise",
    "prand_factor_l",
    "prand_factor_r",
    "kick_rand_factor_l",
    "kick_rand_factor_r",
    "ball_size",
    "ball_decay",
    "ball_rand",
    "ball_weight",
    "ball_speed_max",
    "ball_accel_max",
    "dash_power_rate",
    "kick_power_rate",
    "kickable_margin",
    "control_radius",
    "catch_probability",
    "catchable_area_l",
    "catchable_area_w",
    "goalie_max_moves",
    "maxpower",
    "minpower",
    "maxmoment",
    "minmoment",
    "maxneckmoment",
    "minneckmoment",
    "maxneckang",
    "minneckang",
    "visible_angle",
    "visible_distance",
    "audio_cut_dist",
    "quantize_step",
    "quantize_step_l",
    "ckick_margin",
    "wind_dir",
    "wind_force",
    "wind_ang",
    "wind_rand",
    "wind_none",
    "wind_random",
    "half_time",
    "drop_ball_time",
    "port",
    "coach_port",
    "olcoach_port",
    "say_coach_cnt_max",
    "say_coach_msg_size",
    "simulator_step",
    "send_step",
    "recv_step",
    "sense_body_step",
    "say_msg_size",
    "clang_win_size",
    "clang_define_win",
    "clang_meta_win",
    "clang_advice_win",
    "clang_info_win",
    "clang_del_win",
    "clang_rule_win",
    "clang_mess_delay",
    "clang_mess_per_cycle",
    "hear_max",
    "hear_inc",
    "hear_decay",
    "catch_ban_cycle",
    "coach",
    "coach_w_referee",
    "old_coach_hear",
    "send_vi_step",
    "use_offside",
    "offside_active_area_size",
    "forbid_kick_off_offside",
    "verbose",
    "offside_kick_margin",
    "slow_down_factor",
    "synch_mode",
    "synch_offset",
    "synch_micro_sleep",
    "start_goal_l",
    "start_goal_r",
    "fullstate_l",
    "fullstate_r",
    "slowness_on_top_for_left_team",
    "slowness_on_top_for_right_team",
    "landmark_file",
    "send_comms",
    "text_logging",
    "game_logging",
    "game_log_version",
    "text_log_dir",
    "game_log_dir",
    "text_log_fixed_name",
    "game_log_fixed_name",
    "text_log_fixed",
    "game_log_fixed",
    "text_log_dated",
    "game_log_dated",
    "log_date_format",
    "log_times",
    "record_messages",
    "text_log_compression",
    "game_log_compression",
    "profile",
    "point_to_ban",
    "point_to_duration",
    "tackle_dist",
    "tackle_back_dist",
    "tackle_width",
    "tackle_exponent",
    "tackle_cycles",
    "tackle_power_rate",
    "freeform_wait_period",
    "freeform_send_period",
    "free_kick_faults",
    "back_passes",
    "proper_goal_kicks",
    "stopped_ball_vel",
    "max_goal_kicks",
    "auto_mode",
    "kick_off_wait",
    "connect_wait",
    "game_over_wait",
    "team_l_start",
    "team_r_start",
    "keepaway",
    "keepaway_length",
    "keepaway_width",
    "keepaway_logging",
    "keepaway_log_dir",
    "keepaway_log_fixed_name",
    "keepaway_log_fixed",
    "keepaway_log_dated",
    "keepaway_start",
    "nr_normal_halfs",
    "nr_extra_halfs",
    "penalty_shoot_outs",
    "pen_before_setup_wait",
    "pen_setup_wait",
    "pen_ready_wait",
    "pen_taken_wait",
    "pen_nr_kicks",
    "pen_max_extra_kicks",
    "pen_dist_x",
    "pen_random_winner",
    "pen_max_goalie_dist_x",
    "pen_allow_mult_kicks",
    "pen_coach_moves_players",
    "ball_stuck_area",
    "coach_msg_file",
    "max_tackle_power",
    "max_back_tackle_power",
    "player_speed_max_min",
    "extra_stamina",
    "synch_see_offset",
    "max_monitors",
    "extra_half_time",
    "stamina_capacity",
    "max_dash_angle",
    "min_dash_angle",
    "dash_angle_step",
    "side_dash_rate",
    "back_dash_rate",
    "max_dash_power",
    "min_dash_power",
    "tackle_rand_factor",
    "foul_detect_probability",
    "foul_exponent",
    "foul_cycles",
    "golden_goal",
    "red_card_probability",
    "illegal_defense_duration",
    "illegal_defense_number",
    "illegal_defense_dist_x",
    "illegal_defense_width",
    "fixed_teamname_l",
    "fixed_teamname_r",
    "max_catch_angle",
    "min_catch_angle",
    "dist_noise_rate",
    "focus_dist_noise_rate",
    "land_dist_noise_rate",
    "land_focus_dist_noise_rate",
)
"""Every parameter of rcssserver 19.0.0, in the order ``ServerParam::addParams`` registers them
(``src/serverparam.cpp``)."""

INT_PARAMS = frozenset(
    (
        "catch_ban_cycle",
        "clang_advice_win",
        "clang_define_win",
        "clang_del_win",
        "clang_info_win",
        "clang_mess_delay",
        "clang_mess_per_cycle",
        "clang_meta_win",
        "clang_rule_win",
        "clang_win_size",
        "coach_port",
        "connect_wait",
        "drop_ball_time",
        "extra_half_time",
        "foul_cycles",
        "freeform_send_period",
        "freeform_wait_period",
        "game_log_compression",
        "game_log_version",
        "game_over_wait",
        "goalie_max_moves",
        "half_time",
        "hear_decay",
        "hear_inc",
        "hear_max",
        "illegal_defense_duration",
        "illegal_defense_number",
        "keepaway_start",
        "kick_off_wait",
        "max_goal_kicks",
        "max_monitors",
        "nr_extra_halfs",
        "nr_normal_halfs",
        "olcoach_port",
        "pen_before_setup_wait",
        "pen_max_extra_kicks",
        "pen_nr_kicks",
        "pen_ready_wait",
        "pen_setup_wait",
        "pen_taken_wait",
        "point_to_ban",
        "point_to_duration",
        "port",
        "recv_step",
        "say_coach_cnt_max",
        "say_coach_msg_size",
        "say_msg_size",
        "send_step",
        "send_vi_step",
        "sense_body_step",
        "simulator_step",
        "slow_down_factor",
        "start_goal_l",
        "start_goal_r",
        "synch_micro_sleep",
        "synch_offset",
        "synch_see_offset",
        "tackle_cycles",
        "text_log_compression",
    )
)
"""The parameters held as ``int`` in the server (``src/serverparam.h``)."""
BOOL_PARAMS = frozenset(
    (
        "auto_mode",
        "back_passes",
        "coach",
        "coach_w_referee",
        "forbid_kick_off_offside",
        "free_kick_faults",
        "fullstate_l",
        "fullstate_r",
        "game_log_dated",
        "game_log_fixed",
        "game_logging",
        "golden_goal",
        "keepaway",
        "keepaway_log_dated",
        "keepaway_log_fixed",
        "keepaway_logging",
        "log_times",
        "old_coach_hear",
        "pen_allow_mult_kicks",
        "pen_coach_moves_players",
        "pen_random_winner",
        "penalty_shoot_outs",
        "profile",
        "proper_goal_kicks",
        "record_messages",
        "send_comms",
        "synch_mode",
        "team_actuator_noise",
        "text_log_dated",
        "text_log_fixed",
        "text_logging",
        "use_offside",
        "verbose",
        "wind_none",
        "wind_random",
    )
)
"""The parameters held as ``bool``."""
STR_PARAMS = frozenset(
    (
        "coach_msg_file",
        "fixed_teamname_l",
        "fixed_teamname_r",
        "game_log_dir",
        "game_log_fixed_name",
        "keepaway_log_dir",
        "keepaway_log_fixed_name",
        "landmark_file",
        "log_date_format",
        "team_l_start",
        "team_r_start",
        "text_log_dir",
        "text_log_fixed_name",
    )
)
"""The parameters held as ``std::string``; every other parameter is a ``double``."""

ServerValue = bool | int | float | str
"""A parameter's value as the configuration gives it."""
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
_KNOWN = frozenset(SERVER_PARAMS)
MESSAGE_SOURCE = "<server_param message>"
"""How errors and :attr:`ServerPreset.source` name a configuration given as message text."""


class Setting(NamedTuple):
    """One parameter as the configuration sets it.

    Attributes:
        name: The server's parameter name (``ball_decay``).
        key: The key as written (``server::ball_decay`` in a server.conf), named in errors.
        value: The value as read: bool, int, float or str.
        where: The file, with the line in a server.conf (``server.conf:12``), named in errors.
    """

    name: str
    key: str
    value: ServerValue
    where: str


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
    message, loaded over the ``rcssserver_19`` preset by :func:`load_server_conf`. This is
    what the registry entry and the CLI's ``--field-preset`` read.

    Raises:
        PresetError: naming the file (or the message) and the key.
    """
    if is_server_conf(name_or_path):
        return load_server_conf(name_or_path).preset
    return load_server_preset(name_or_path)


def load_server_conf(
    source: str | Path, *, base: str | ServerPreset = "rcssserver_19"
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
    base: str | ServerPreset = "rcssserver_19",
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


# ----------------------------------------------------------------------------- server.conf

_INT_TEXT = re.compile(r"[-+]?[0-9]+")
_REAL_TEXT = re.compile(r"[-+]?(?:[0-9]+\.[0-9]*|\.[0-9]+|[0-9]+(?=[eE]))(?:[eE][-+]?[0-9]+)?")
_NAME_END = frozenset(" \t\r\n\0=\"'")
_MAX_INT_DIGITS = 4000


def parse_server_conf(text: str, *, file: str) -> list[Setting]:
    """The settings of a ``server.conf`` text, in order (format: see the module docstring).

    Raises:
        PresetError: naming the file, the line and the key: a syntax error, a parameter that is
            not a server parameter, or a value of the wrong type.
    """
    settings: list[Setting] = []
    scan = _Scanner(text, file)
    while True:
        scan.skip_junk()
        if scan.done():
            return settings
        line = scan.line
        key = scan.name()
        where = f"{file}:{line}"
        module, _, name = key.rpartition("::")
        if name.lower() in ("include", "help") and not module:
            raise PresetError(f"{where}: key '{key}': '{name}' is not supported here")
        scan.skip_junk()
        if not scan.take("="):
            raise PresetError(f"{where}: key '{key}': expected '=' after the name")
        raw, quoted = scan.value(key, where)
        if module not in ("", "server"):
            raise PresetError(f"{where}: key '{key}': not a server parameter (module '{module}')")
        if name == "version":
            continue  # the server version that wrote the file
        value = _conf_value(raw, quoted)
        settings.append(Setting(name, key, _typed(name, value, key, where), where))


class _Scanner:
    """A cursor over a server.conf text that knows its comments, names and values."""

    def __init__(self, text: str, file: str) -> None:
        self.text = text
        self.file = file
        self.pos = 0
        self.line = 1

    def done(self) -> bool:
        return self.pos >= len(self.text)

    def take(self, char: str) -> bool:
        if self.text.startswith(char, self.pos):
            self.pos += len(char)
            return True
        return False

    def _advance(self, end: int) -> None:
        self.line += self.text.count("\n", self.pos, end)
        self.pos = end

    def skip_junk(self) -> None:
        """Skip space, newlines and comments (``#``, ``//``, ``/* */``)."""
        text = self.text
        while self.pos < len(text):
            char = text[self.pos]
            if char in " \t\r\n\0":
                self._advance(self.pos + 1)
            elif char == "#" or text.startswith("//", self.pos):
                end = text.find("\n", self.pos)
                self._advance(len(text) if end < 0 else end)
            elif text.startswith("/*", self.pos):
                end = text.find("*/", self.pos + 2)
                if end < 0:
                    raise PresetError(f"{self.file}:{self.line}: a '/*' comment is not closed")
                self._advance(end + 2)
            else:
                return

    def name(self) -> str:
        """A parameter name (``server::ball_decay``), after an optional ``-`` or ``--``."""
        self.take("-")
        self.take("-")
        start = self.pos
        while self.pos < len(self.text) and self.text[self.pos] not in _NAME_END:
            self.pos += 1
        key = self.text[start : self.pos]
        if not key or key.startswith(":") or key.endswith(":") or ":::" in key:
            shown = self.text[start : start + 20].split("\n")[0]
            raise PresetError(f"{self.file}:{self.line}: expected a parameter name, got {shown!r}")
        return key

    def value(self, key: str, where: str) -> tuple[str, bool]:
        """The value after ``=`` on the same line: its text and whether it was quoted."""
        text = self.text
        while self.pos < len(text) and text[self.pos] in " \t":
            self.pos += 1
        if self.pos < len(text) and text[self.pos] in "'\"":
            quote = text[self.pos]
            i = self.pos + 1
            while i < len(text) and text[i] != quote:
                i += 2 if text[i] == "\\" else 1
            if i >= len(text):
                raise PresetError(f"{where}: key '{key}': unterminated string")
            raw = text[self.pos + 1 : i].replace("\\" + quote, quote)
            self._advance(i + 1)
            return raw, True
        start = self.pos
        while self.pos < len(text) and text[self.pos] not in " \t\r\n\0":
            self.pos += 1
        raw = text[start : self.pos]
        if not raw:
            raise PresetError(f"{where}: key '{key}': expected a value after '='")
        return raw, False


def _conf_value(raw: str, quoted: bool) -> ServerValue:
    """A server.conf value as the server's parser reads it: truth value, number or string."""
    if quoted:
        return raw
    lower = raw.lower()
    if lower in ("on", "true"):
        return True
    if lower in ("off", "false"):
        return False
    if _INT_TEXT.fullmatch(raw):
        # Python refuses to read integers of more than 4300 digits; as a double such a
        # number is out of range, and _typed says so.
        return int(raw) if len(raw) <= _MAX_INT_DIGITS else math.inf
    if _REAL_TEXT.fullmatch(raw):
        return float(raw)  # 1e999 overflows to inf, refused by _typed as inf is
    return raw


# ----------------------------------------------------------------------------- server_param


def parse_server_param(text: str, *, file: str = MESSAGE_SOURCE) -> list[Setting]:
    """The settings of a ``(server_param (name value) ...)`` message, in order.

    Raises:
        PresetError: naming `file` and the key: a malformed message, a parameter that is not a
            server parameter, or a value of the wrong type.
    """
    try:
        tree = parse_sexpr(text)
    except MessageParseError as exc:
        raise PresetError(f"{file}: not a server_param message ({exc.reason})") from None
    if not tree or tree[0] != "server_param":
        raise PresetError(f"{file}: expected '(server_param (name value) ...)'")
    settings: list[Setting] = []
    for item in tree[1:]:
        if (
            not isinstance(item, list)
            or len(item) != 2
            or not isinstance(item[0], str)
            or isinstance(item[0], Quoted)
            or isinstance(item[1], list)
        ):
            shown = "a list" if isinstance(item, list) else repr(str(item))
            raise PresetError(f"{file}: expected '(name value)' entries, got {shown}")
        name, token = str(item[0]), item[1]
        value: ServerValue = str(token) if isinstance(token, Quoted) else _conf_value(token, False)
        settings.append(Setting(name, name, _typed(name, value, name, file), file))
    return settings


def _typed(name: str, value: ServerValue, key: str, where: str) -> ServerValue:
    """`value` as parameter `name`'s type in the server (int, bool, double or string).

    Raises:
        PresetError: `name` is not a parameter of rcssserver 19, or `value` cannot be its type.
    """
    if name not in _KNOWN:
        raise PresetError(f"{where}: key '{key}': not a parameter of rcssserver 19")
    shown = f"{type(value).__name__} {_short(value)}"
    if name in STR_PARAMS:
        if not isinstance(value, str):
            raise PresetError(f"{where}: key '{key}': expected a string, got {shown}")
        return value
    if name in BOOL_PARAMS:
        if isinstance(value, bool):
            return value
        if isinstance(value, int) and value in (0, 1):
            return bool(value)  # server_param messages print booleans as 0 and 1
        raise PresetError(f"{where}: key '{key}': expected true or false, got {shown}")
    if isinstance(value, bool) or not isinstance(value, int | float):
        raise PresetError(f"{where}: key '{key}': expected a number, got {shown}")
    # The server would read 1e999 as the largest double or inf; either is no parameter value,
    # so an overflowing number is refused like a written inf (which is not a number here).
    if (isinstance(value, float) and not math.isfinite(value)) or abs(value) > _MAX_NUMBER:
        raise PresetError(f"{where}: key '{key}': expected a finite number, got {_short(value)}")
    if name in INT_PARAMS:
        if isinstance(value, float) and not value.is_integer():
            raise PresetError(f"{where}: key '{key}': expected an integer, got {shown}")
        if not _INT_MIN <= value <= _INT_MAX:  # the server holds it in a C int
            raise PresetError(
                f"{where}: key '{key}': expected an integer in [{_INT_MIN}, {_INT_MAX}], "
                f"got {_short(value)}"
            )
        return int(value)
    return float(value)


_MAX_NUMBER = 1e300
"""The largest magnitude a number parameter may have: within a double, with room to compute."""
_INT_MIN, _INT_MAX = -(2**31), 2**31 - 1
"""The range of the server's ``int`` parameters (a 32-bit C int)."""


def _short(value: ServerValue) -> str:
    """A number for a one-line message: 1e999 read as inf, a 4000-digit integer not shown whole."""
    if isinstance(value, float) and math.isinf(value):
        return "a number beyond a double's range"
    text = repr(value)
    return text if len(text) <= 32 else f"an integer of {len(text.lstrip('-'))} digits"
