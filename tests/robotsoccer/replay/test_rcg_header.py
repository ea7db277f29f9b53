"""Our .rcg header against rcssserver 19.0.0's, key by key and in order.

The reference header is rebuilt here, independently of the
writer, from ``tests/field_models/soccer_server/data/rcssserver_19_defaults.conf`` (rcssserver
19.0.0's defaults in the form the server writes ``server.conf``) and from the rules of the
server's source (commit ce87001): a game log's sender asks as protocol 999, so every registered
server parameter is written, in ``std::map`` order, i.e. sorted by name
(``src/initsender.cpp``; ``server::version`` is a conf-file entry, not a parameter); booleans
print as ``0``/``1``, strings in double quotes, doubles with six significant digits. Its
``player_param`` line and the 18 default ``player_type`` lines come from
``src/playerparam.cpp``'s ``DEFAULT_*`` constants and ``HeteroPlayer::setDefault`` /
``printParamsSExp`` (``src/heteroplayer.cpp``), written out below by hand
(``allow_default_goalie`` is commented out of ``playerparam.cpp``: a real log has none).

``data/rcssserver_19_0_0_header.rcg`` is the header a real rcssserver 19.0.0 wrote (how it was
made: ``data/rcssserver_19_0_0_header.md``); ours is compared to it key by key below. It
differs only where the real server draws at random (``random_seed``, the 17 heterogeneous
types, which our writer gives the default type) and in its version line: 19.0.0 writes
``ULG6`` (its ``game_log_version`` is 6), our writer ``ULG5``.
"""

from __future__ import annotations

import math
import re
from pathlib import Path

from field_models.protocol import LEFT, RIGHT, PlayerRef
from robotsoccer.replay.rcg_write import RcgWriter

REAL = Path(__file__).parent / "data/rcssserver_19_0_0_header.rcg"
CONF = Path(__file__).parents[2] / "field_models/soccer_server/data/rcssserver_19_defaults.conf"

PLAYER_PARAM = (
    "(player_param (allow_mult_default_type 0)"
    "(catchable_area_l_stretch_max 1.3)(catchable_area_l_stretch_min 1)"
    "(dash_power_rate_delta_max 0)(dash_power_rate_delta_min 0)(effort_max_delta_factor -0.004)"
    "(effort_min_delta_factor -0.004)(extra_stamina_delta_max 50)(extra_stamina_delta_min 0)"
    "(foul_detect_probability_delta_factor 0)(inertia_moment_delta_factor 25)"
    "(kick_power_rate_delta_max 0)(kick_power_rate_delta_min 0)(kick_rand_delta_factor 1)"
    "(kickable_margin_delta_max 0.1)(kickable_margin_delta_min -0.1)"
    "(new_dash_power_rate_delta_max 0.0008)(new_dash_power_rate_delta_min -0.0012)"
    "(new_stamina_inc_max_delta_factor -6000)(player_decay_delta_max 0.1)"
    "(player_decay_delta_min -0.1)(player_size_delta_factor -100)"
    "(player_speed_max_delta_max 0)(player_speed_max_delta_min 0)(player_types 18)(pt_max 1)"
    "(random_seed -1)(stamina_inc_max_delta_factor 0)(subs_max 3))"
)
TYPE_FIELDS = (
    "(player_speed_max 1.05)(stamina_inc_max 45)(player_decay 0.4)(inertia_moment 5)"
    "(dash_power_rate 0.006)(player_size 0.3)(kickable_margin 0.7)(kick_rand 0.1)"
    "(extra_stamina 50)(effort_max 1)(effort_min 0.6)(kick_power_rate 0.027)"
    "(foul_detect_probability 0.5)(catchable_area_l_stretch 1)(unum_far_length 20)"
    "(unum_too_far_length 40)(team_far_length 125.096)(team_too_far_length 125.096)"
    "(player_max_observation_length 125.096)(ball_vel_far_length 20)"
    "(ball_vel_too_far_length 40)(ball_max_observation_length 125.096)"
    "(flag_chg_far_length 20)(flag_chg_too_far_length 40)"
    "(flag_max_observation_length 125.096)(dist_noise_rate 0.0125)"
    "(focus_dist_noise_rate 0.0125)(land_dist_noise_rate 0.00125)"
    "(land_focus_dist_noise_rate 0.00125)"
)


def reference_server_param() -> list[tuple[str, str]]:
    """The server_param entries a real rcssserver 19 log starts with (module docstring)."""
    entries = []
    for name, raw in re.findall(r"^server::(\w+) = (.*)$", CONF.read_text(), re.M):
        if name == "version":
            continue
        if raw in ("true", "false"):
            text = "1" if raw == "true" else "0"
        elif raw.startswith("'"):
            text = '"' + raw.strip("'") + '"'
        else:
            text = raw if re.fullmatch(r"-?[0-9]+", raw) else f"{float(raw):g}"
        entries.append((name, text))
    return sorted(entries)


def our_header(tmp_path: Path) -> list[str]:
    """The header our match writer gives a game on rcssserver 19's defaults."""
    params = {"goal_width": 14.02, "ball_size": 0.085, "player_size": 0.3, "ball_decay": 0.94}
    params["kickable_margin"] = 0.7
    path = tmp_path / "game.rcg"
    writer = RcgWriter(
        path,
        players=(PlayerRef(LEFT, 1), PlayerRef(RIGHT, 1)),
        teams=("A", "B"),
        dt_s=0.1,
        server_params=params,
    )
    writer.close()
    return path.read_text().splitlines()


def test_server_param_matches_a_real_servers_key_by_key_in_order(tmp_path: Path) -> None:
    line = our_header(tmp_path)[1]
    ours = re.findall(r"\((\w+) ([^()]*)\)", line[len("(server_param ") : -1])
    want = reference_server_param()
    assert [name for name, _ in ours] == [name for name, _ in want]  # every key, in order
    differing = {name: (a, b) for (name, a), (_, b) in zip(ours, want, strict=True) if a != b}
    assert differing == {}


def test_player_param_and_player_types_match_a_real_servers(tmp_path: Path) -> None:
    lines = our_header(tmp_path)
    assert lines[0] == "ULG5"
    assert lines[2] == PLAYER_PARAM
    assert lines[3:21] == [f"(player_type (id {i}){TYPE_FIELDS})" for i in range(18)]
    assert math.isclose(float("125.096"), math.hypot(105, 68), rel_tol=1e-5)


def _entries(line: str) -> list[tuple[str, str]]:
    return re.findall(r"\((\w+) ([^()]*)\)", line[line.index(" ") + 1 : -1])


def test_our_header_matches_a_real_rcssserver_19_logs_key_by_key(tmp_path: Path) -> None:
    real = REAL.read_text().splitlines()
    ours = our_header(tmp_path)
    assert (real[0], ours[0]) == ("ULG6", "ULG5")  # the one known difference of format
    for index in (1, 2):  # server_param, player_param: every key, in order, same value
        want, got = _entries(real[index]), _entries(ours[index])
        assert [k for k, _ in got] == [k for k, _ in want]
        differing = {k: (a, b) for (k, a), (_, b) in zip(got, want, strict=True) if a != b}
        differing.pop("random_seed", None)  # the real server drew its own (from the clock)
        assert differing == {}
    assert ours[3] == real[3]  # player_type id 0, the default type
