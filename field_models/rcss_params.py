"""The parameters rcssserver 19.0.0 sends and logs: names, versions, defaults, text form.

A real server sends a client of protocol version V every parameter registered with a version
<= V, in the order of a ``std::map`` keyed by name, i.e. **sorted by name**
(``src/initsender.cpp``, ``InitSenderCommonV8::sendServerParams`` iterating
``ServerParam::verMap()``; ``src/serverparam.h``: ``typedef std::map< std::string, unsigned int >
VerMap``). A game log gets them all (its sender uses version 999, ``src/initsenderlogger.cpp``).
The same holds for ``player_param`` (``PlayerParam::verMap()``). A ``player_type`` lists the
type's values in ``HeteroPlayer::printParamsSExp``'s fixed order, cut by version (14, 18, 19).

The tables below were generated from rcssserver's source at commit ce87001 (19.0.0):
names and versions from ``ServerParam::addParams`` / ``PlayerParam::addParams`` (the
``NEW_QSTEP`` block is compiled out; ``random_seed``, ``long_kick_*`` are commented out there, so
they are never sent), default values from ``ServerParam::setDefaults`` as written in
``tests/field_models/soccer_server/data/rcssserver_19_defaults.conf`` and from
``PlayerParam``'s ``DEFAULT_*`` constants. A value's Python type is its C++ type: ``bool``
(sent as ``0``/``1``), ``int``, ``float`` (``double``) or ``str`` (sent in double quotes).

This module is about the server's wire format and logs, not any one field model: the Soccer
Server model fills in its own values (:mod:`field_models.soccer_server.wire`), a game-log writer
the values it knows.
"""

from __future__ import annotations

import math
from collections.abc import Mapping

ParamValue = bool | int | float | str
"""A parameter's value, typed as the server holds it."""

SERVER_PARAMS: tuple[tuple[str, int, ParamValue], ...] = (
    ("audio_cut_dist", 7, 50.0),
    ("auto_mode", 9, False),
    ("back_dash_rate", 13, 0.7),
    ("back_passes", 8, True),
    ("ball_accel_max", 7, 2.7),
    ("ball_decay", 7, 0.94),
    ("ball_rand", 7, 0.05),
    ("ball_size", 7, 0.085),
    ("ball_speed_max", 7, 3.0),
    ("ball_stuck_area", 11, 3.0),
    ("ball_weight", 7, 0.2),
    ("catch_ban_cycle", 7, 5),
    ("catch_probability", 7, 1.0),
    ("catchable_area_l", 7, 1.2),
    ("catchable_area_w", 7, 1.0),
    ("ckick_margin", 7, 1.0),
    ("clang_advice_win", 7, 1),
    ("clang_define_win", 7, 1),
    ("clang_del_win", 8, 1),
    ("clang_info_win", 7, 1),
    ("clang_mess_delay", 7, 50),
    ("clang_mess_per_cycle", 7, 1),
    ("clang_meta_win", 7, 1),
    ("clang_rule_win", 8, 1),
    ("clang_win_size", 7, 300),
    ("coach", 7, False),
    ("coach_msg_file", 999, ""),
    ("coach_port", 8, 6001),
    ("coach_w_referee", 7, False),
    ("connect_wait", 9, 300),
    ("control_radius", 7, 2.0),
    ("dash_angle_step", 13, 1.0),
    ("dash_power_rate", 7, 0.006),
    ("dist_noise_rate", 19, 0.0125),
    ("drop_ball_time", 7, 100),
    ("effort_dec", 7, 0.005),
    ("effort_dec_thr", 7, 0.3),
    ("effort_inc", 7, 0.01),
    ("effort_inc_thr", 7, 0.6),
    ("effort_init", 7, 1.0),
    ("effort_min", 7, 0.6),
    ("extra_half_time", 13, 100),
    ("extra_stamina", 12, 50.0),
    ("fixed_teamname_l", 16, ""),
    ("fixed_teamname_r", 16, ""),
    ("focus_dist_noise_rate", 19, 0.0125),
    ("forbid_kick_off_offside", 7, True),
    ("foul_cycles", 14, 5),
    ("foul_detect_probability", 14, 0.5),
    ("foul_exponent", 14, 10.0),
    ("free_kick_faults", 8, True),
    ("freeform_send_period", 8, 20),
    ("freeform_wait_period", 8, 600),
    ("fullstate_l", 7, False),
    ("fullstate_r", 7, False),
    ("game_log_compression", 8, 0),
    ("game_log_dated", 8, True),
    ("game_log_dir", 8, "./"),
    ("game_log_fixed", 8, False),
    ("game_log_fixed_name", 8, "rcssserver"),
    ("game_log_version", 8, 6),
    ("game_logging", 8, True),
    ("game_over_wait", 9, 100),
    ("goal_width", 7, 14.02),
    ("goalie_max_moves", 7, 2),
    ("golden_goal", 14, False),
    ("half_time", 7, 300),
    ("hear_decay", 7, 1),
    ("hear_inc", 7, 1),
    ("hear_max", 7, 1),
    ("illegal_defense_dist_x", 16, 16.5),
    ("illegal_defense_duration", 16, 20),
    ("illegal_defense_number", 16, 0),
    ("illegal_defense_width", 16, 40.32),
    ("inertia_moment", 7, 5.0),
    ("keepaway", 9, False),
    ("keepaway_length", 9, 20.0),
    ("keepaway_log_dated", 9, True),
    ("keepaway_log_dir", 9, "./"),
    ("keepaway_log_fixed", 9, False),
    ("keepaway_log_fixed_name", 9, "rcssserver"),
    ("keepaway_logging", 9, True),
    ("keepaway_start", 9, -1),
    ("keepaway_width", 9, 20.0),
    ("kick_off_wait", 9, 100),
    ("kick_power_rate", 7, 0.027),
    ("kick_rand", 7, 0.1),
    ("kick_rand_factor_l", 7, 1.0),
    ("kick_rand_factor_r", 7, 1.0),
    ("kickable_margin", 7, 0.7),
    ("land_dist_noise_rate", 19, 0.00125),
    ("land_focus_dist_noise_rate", 19, 0.00125),
    ("landmark_file", 8, "~/.rcssserver-landmark.xml"),
    ("log_date_format", 8, "%Y%m%d%H%M%S-"),
    ("log_times", 8, False),
    ("max_back_tackle_power", 12, 0.0),
    ("max_catch_angle", 17, 90.0),
    ("max_dash_angle", 13, 180.0),
    ("max_dash_power", 13, 100.0),
    ("max_goal_kicks", 8, 3),
    ("max_monitors", 999, -1),
    ("max_tackle_power", 12, 100.0),
    ("maxmoment", 7, 180.0),
    ("maxneckang", 7, 90.0),
    ("maxneckmoment", 7, 180.0),
    ("maxpower", 7, 100.0),
    ("min_catch_angle", 17, -90.0),
    ("min_dash_angle", 13, -180.0),
    ("min_dash_power", 13, 0.0),
    ("minmoment", 7, -180.0),
    ("minneckang", 7, -90.0),
    ("minneckmoment", 7, -180.0),
    ("minpower", 7, -100.0),
    ("nr_extra_halfs", 9, 2),
    ("nr_normal_halfs", 9, 2),
    ("offside_active_area_size", 7, 2.5),
    ("offside_kick_margin", 7, 9.15),
    ("olcoach_port", 8, 6002),
    ("old_coach_hear", 7, False),
    ("pen_allow_mult_kicks", 9, True),
    ("pen_before_setup_wait", 9, 10),
    ("pen_coach_moves_players", 9, True),
    ("pen_dist_x", 9, 42.5),
    ("pen_max_extra_kicks", 9, 5),
    ("pen_max_goalie_dist_x", 9, 14.0),
    ("pen_nr_kicks", 9, 5),
    ("pen_random_winner", 9, False),
    ("pen_ready_wait", 9, 10),
    ("pen_setup_wait", 9, 70),
    ("pen_taken_wait", 9, 150),
    ("penalty_shoot_outs", 9, True),
    ("player_accel_max", 7, 1.0),
    ("player_decay", 7, 0.4),
    ("player_rand", 7, 0.1),
    ("player_size", 7, 0.3),
    ("player_speed_max", 7, 1.05),
    ("player_speed_max_min", 12, 0.75),
    ("player_weight", 7, 60.0),
    ("point_to_ban", 8, 5),
    ("point_to_duration", 8, 20),
    ("port", 8, 6000),
    ("prand_factor_l", 7, 1.0),
    ("prand_factor_r", 7, 1.0),
    ("profile", 8, False),
    ("proper_goal_kicks", 8, False),
    ("quantize_step", 7, 0.1),
    ("quantize_step_l", 7, 0.01),
    ("record_messages", 8, False),
    ("recover_dec", 7, 0.002),
    ("recover_dec_thr", 7, 0.3),
    ("recover_init", 9, 1.0),
    ("recover_min", 7, 0.5),
    ("recv_step", 7, 10),
    ("red_card_probability", 15, 0.0),
    ("say_coach_cnt_max", 7, 128),
    ("say_coach_msg_size", 7, 128),
    ("say_msg_size", 7, 10),
    ("send_comms", 8, False),
    ("send_step", 7, 150),
    ("send_vi_step", 7, 100),
    ("sense_body_step", 7, 100),
    ("side_dash_rate", 13, 0.4),
    ("simulator_step", 7, 100),
    ("slow_down_factor", 7, 1),
    ("slowness_on_top_for_left_team", 8, 1.0),
    ("slowness_on_top_for_right_team", 8, 1.0),
    ("stamina_capacity", 13, 130600.0),
    ("stamina_inc_max", 7, 45.0),
    ("stamina_max", 7, 8000.0),
    ("start_goal_l", 7, 0),
    ("start_goal_r", 7, 0),
    ("stopped_ball_vel", 8, 0.01),
    ("synch_micro_sleep", 8, 1),
    ("synch_mode", 8, False),
    ("synch_offset", 8, 60),
    ("synch_see_offset", 12, 0),
    ("tackle_back_dist", 8, 0.0),
    ("tackle_cycles", 8, 10),
    ("tackle_dist", 8, 2.0),
    ("tackle_exponent", 8, 6.0),
    ("tackle_power_rate", 8, 0.027),
    ("tackle_rand_factor", 14, 2.0),
    ("tackle_width", 8, 1.25),
    ("team_actuator_noise", 7, False),
    ("team_l_start", 9, ""),
    ("team_r_start", 9, ""),
    ("text_log_compression", 8, 0),
    ("text_log_dated", 8, True),
    ("text_log_dir", 8, "./"),
    ("text_log_fixed", 8, False),
    ("text_log_fixed_name", 8, "rcssserver"),
    ("text_logging", 8, True),
    ("use_offside", 7, True),
    ("verbose", 8, False),
    ("visible_angle", 7, 90.0),
    ("visible_distance", 7, 3.0),
    ("wind_ang", 7, 0.0),
    ("wind_dir", 7, 0.0),
    ("wind_force", 7, 0.0),
    ("wind_none", 7, False),
    ("wind_rand", 7, 0.0),
    ("wind_random", 7, False),
)
"""Every server parameter as (name, first protocol version that gets it, default), by name."""

PLAYER_PARAMS: tuple[tuple[str, int, ParamValue], ...] = (
    ("allow_mult_default_type", 12, False),
    ("catchable_area_l_stretch_max", 14, 1.3),
    ("catchable_area_l_stretch_min", 14, 1.0),
    ("dash_power_rate_delta_max", 7, 0.0),
    ("dash_power_rate_delta_min", 7, 0.0),
    ("effort_max_delta_factor", 7, -0.004),
    ("effort_min_delta_factor", 7, -0.004),
    ("extra_stamina_delta_max", 7, 50.0),
    ("extra_stamina_delta_min", 7, 0.0),
    ("foul_detect_probability_delta_factor", 14, 0.0),
    ("inertia_moment_delta_factor", 7, 25.0),
    ("kick_power_rate_delta_max", 14, 0.0),
    ("kick_power_rate_delta_min", 14, 0.0),
    ("kick_rand_delta_factor", 7, 1.0),
    ("kickable_margin_delta_max", 7, 0.1),
    ("kickable_margin_delta_min", 7, -0.1),
    ("new_dash_power_rate_delta_max", 8, 0.0008),
    ("new_dash_power_rate_delta_min", 8, -0.0012),
    ("new_stamina_inc_max_delta_factor", 8, -6000.0),
    ("player_decay_delta_max", 7, 0.1),
    ("player_decay_delta_min", 7, -0.1),
    ("player_size_delta_factor", 7, -100.0),
    ("player_speed_max_delta_max", 7, 0.0),
    ("player_speed_max_delta_min", 7, 0.0),
    ("player_types", 7, 18),
    ("pt_max", 7, 1),
    ("random_seed", 8, -1),
    ("stamina_inc_max_delta_factor", 7, 0.0),
    ("subs_max", 7, 3),
)
"""Every player parameter as (name, first protocol version, default), by name."""

PLAYER_TYPE_FIELDS: tuple[tuple[str, int], ...] = (
    ("player_speed_max", 0),
    ("stamina_inc_max", 0),
    ("player_decay", 0),
    ("inertia_moment", 0),
    ("dash_power_rate", 0),
    ("player_size", 0),
    ("kickable_margin", 0),
    ("kick_rand", 0),
    ("extra_stamina", 0),
    ("effort_max", 0),
    ("effort_min", 0),
    ("kick_power_rate", 14),
    ("foul_detect_probability", 14),
    ("catchable_area_l_stretch", 14),
    ("unum_far_length", 18),
    ("unum_too_far_length", 18),
    ("team_far_length", 18),
    ("team_too_far_length", 18),
    ("player_max_observation_length", 18),
    ("ball_vel_far_length", 18),
    ("ball_vel_too_far_length", 18),
    ("ball_max_observation_length", 18),
    ("flag_chg_far_length", 18),
    ("flag_chg_too_far_length", 18),
    ("flag_max_observation_length", 18),
    ("dist_noise_rate", 19),
    ("focus_dist_noise_rate", 19),
    ("land_dist_noise_rate", 19),
    ("land_focus_dist_noise_rate", 19),
)
"""A player type's fields in ``printParamsSExp`` order, with the version that adds each."""

LOG_VERSION = 999
"""The client version a game log's header is written for: every parameter."""

PITCH_DIAGONAL_M = math.hypot(105.0, 68.0)
"""The pitch's diagonal: today's team and observation lengths (``setDefaultObservationParams``)."""


def default_server_params() -> dict[str, ParamValue]:
    """The server parameters of rcssserver 19.0.0 with their defaults, by name."""
    return {name: value for name, _, value in SERVER_PARAMS}


def default_player_params() -> dict[str, ParamValue]:
    """The player parameters of rcssserver 19.0.0 with their defaults, by name."""
    return {name: value for name, _, value in PLAYER_PARAMS}


def default_player_type(server: Mapping[str, ParamValue]) -> dict[str, ParamValue]:
    """Player type 0 (the default type) from server parameters (``HeteroPlayer::setDefault``)."""
    return {
        "player_speed_max": server["player_speed_max"],
        "stamina_inc_max": server["stamina_inc_max"],
        "player_decay": server["player_decay"],
        "inertia_moment": server["inertia_moment"],
        "dash_power_rate": server["dash_power_rate"],
        "player_size": server["player_size"],
        "kickable_margin": server["kickable_margin"],
        "kick_rand": server["kick_rand"],
        "extra_stamina": server["extra_stamina"],
        "effort_max": server["effort_init"],
        "effort_min": server["effort_min"],
        "kick_power_rate": server["kick_power_rate"],
        "foul_detect_probability": server["foul_detect_probability"],
        "catchable_area_l_stretch": 1.0,
        "unum_far_length": 20.0,
        "unum_too_far_length": 40.0,
        "team_far_length": PITCH_DIAGONAL_M,
        "team_too_far_length": PITCH_DIAGONAL_M,
        "player_max_observation_length": PITCH_DIAGONAL_M,
        "ball_vel_far_length": 20.0,
        "ball_vel_too_far_length": 40.0,
        "ball_max_observation_length": PITCH_DIAGONAL_M,
        "flag_chg_far_length": 20.0,
        "flag_chg_too_far_length": 40.0,
        "flag_max_observation_length": PITCH_DIAGONAL_M,
        "dist_noise_rate": server["dist_noise_rate"],
        "focus_dist_noise_rate": server["focus_dist_noise_rate"],
        "land_dist_noise_rate": server["land_dist_noise_rate"],
        "land_focus_dist_noise_rate": server["land_focus_dist_noise_rate"],
    }


def cxx_text(value: ParamValue) -> str:
    """A value as the server's stream prints it: ``%g`` doubles, bools 0/1, quoted strings.

    Doubles get six significant digits, as a C++ stream's default precision gives them (the
    pitch diagonal 125.0959... is sent as ``125.096``).

    >>> cxx_text(0.94), cxx_text(True), cxx_text(6000), cxx_text("%Y"), cxx_text(125.0959)
    ('0.94', '1', '6000', '"%Y"', '125.096')
    """
    if isinstance(value, bool):
        return "1" if value else "0"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, str):
        return f'"{value}"'
    return f"{value:g}"


def param_message(
    kind: str,
    values: Mapping[str, ParamValue],
    order: tuple[tuple[str, int, ParamValue], ...],
    version: int,
) -> str:
    """``(server_param (name value)...)`` or ``(player_param ...)`` for a client of `version`.

    Every name of `order` whose version is <= `version`, in that order, valued from `values`
    (the default where `values` lacks it).
    """
    parts = [
        f"({name} {cxx_text(values.get(name, default))})"
        for name, since, default in order
        if since <= version
    ]
    return f"({kind} " + "".join(parts) + ")"


def player_type_message(type_id: int, values: Mapping[str, ParamValue], version: int) -> str:
    """``(player_type (id N)(player_speed_max V)...)`` for a client of `version`."""
    parts = [
        f"({name} {cxx_text(values[name])})"
        for name, since in PLAYER_TYPE_FIELDS
        if since <= version
    ]
    return f"(player_type (id {type_id})" + "".join(parts) + ")"
