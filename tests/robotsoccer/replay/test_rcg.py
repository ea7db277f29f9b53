"""The Soccer Server's text game log: written, read back, and real logs read."""

from __future__ import annotations

import math
import re
from pathlib import Path

import pytest

from field_models.protocol import LEFT, RIGHT, BodyState, PlayerRef, Truth
from robotsoccer.replay.frames import GameFrame
from robotsoccer.replay.rcg import RcgWriter, is_rcg, read_rcg

DT = 0.1
L1 = PlayerRef(LEFT, 1)
L2 = PlayerRef(LEFT, 2)
R1 = PlayerRef(RIGHT, 1)
R3 = PlayerRef(RIGHT, 3)
PLAYERS = (R3, L2, R1, L1)  # deliberately not in the server's order
PARAMS = {
    "goal_width": 14.02,
    "ball_size": 0.085,
    "player_size": 0.3,
    "kickable_margin": 0.7,
    "ball_decay": 0.94,
    "player_decay": 0.4,
    "visible_angle": 90.0,
}


def _frame(tick: int, mode: str, score: tuple[int, int], shift: float = 0.0) -> GameFrame:
    players = {
        L1: BodyState(-10.0 + shift, 10.0, 0.5, 1.2, -0.7),
        L2: BodyState(-20.5, -5.25, -math.pi, 0.0, 0.3),
        R1: BodyState(15.0, 0.0, 3.0, -0.4, 0.0),
        R3: BodyState(30.125, -33.0, -1.25 + shift, 0.05, 2.5),
    }
    ball = BodyState(1.5 + shift, -2.25, 0.0, 2.7, -1.1)
    return GameFrame(Truth(tick, tick * DT, ball, players), mode, score)


FRAMES = [
    _frame(0, "kick_off_l", (0, 0)),
    _frame(1, "play_on", (0, 0), 0.1),
    _frame(2, "play_on", (0, 0), 0.2),
    _frame(3, "goal_l", (1, 0), 0.3),
    _frame(4, "kick_off_r", (1, 0), 0.4),
]


def _write(path: Path, frames: list[GameFrame] = FRAMES) -> Path:
    with RcgWriter(
        path, players=PLAYERS, teams=("Left-Team", "right_2"), dt_s=DT, server_params=PARAMS
    ) as writer:
        for frame in frames:
            writer.write(frame)
    return path


def _close(a: BodyState, b: BodyState, heading: bool = True) -> None:
    assert b.x == pytest.approx(a.x, abs=1e-4)
    assert b.y == pytest.approx(a.y, abs=1e-4)
    # Velocities are kept to 0.0001 m per cycle.
    assert b.vx == pytest.approx(a.vx, abs=1e-4 / DT)
    assert b.vy == pytest.approx(a.vy, abs=1e-4 / DT)
    if heading:
        diff = math.remainder(b.heading - a.heading, 2.0 * math.pi)
        assert abs(diff) < 1e-4


def test_round_trip(tmp_path: Path) -> None:
    path = _write(tmp_path / "match.rcg")
    assert not (tmp_path / "match.rcg.part").exists()
    game = read_rcg(path)
    assert game.teams == ("Left-Team", "right_2")
    assert game.server_params["goal_width"] == "14.02"
    assert game.server_params["simulator_step"] == "100"
    assert len(game.frames) == len(FRAMES)
    for want, got in zip(FRAMES, game.frames, strict=True):
        assert got.tick == want.tick
        assert got.truth.time_s == pytest.approx(want.truth.time_s)
        assert got.play_mode == want.play_mode
        assert got.score == want.score
        _close(want.truth.ball, got.truth.ball, heading=False)
        assert set(got.truth.players) == set(want.truth.players)
        for ref, state in want.truth.players.items():
            _close(state, got.truth.players[ref])


def test_header_lines_in_order(tmp_path: Path) -> None:
    lines = _write(tmp_path / "match.rcg").read_text().splitlines()
    assert lines[0] == "ULG5"
    assert lines[1].startswith("(server_param (goal_width 14.02)(ball_size 0.085)")
    assert "(visible_angle 90)" in lines[1] and "(simulator_step 100)" in lines[1]
    assert lines[2].startswith("(player_param ")
    assert lines[3].startswith("(player_type (id 0)")
    assert "(player_size 0.3)" in lines[3]
    assert lines[4] == "(playmode 0 kick_off_l)"
    assert lines[5] == "(team 0 Left-Team right_2 0 0)"
    assert lines[6].startswith("(show 0 ((b) 1.5000 2.2500 0.2700 0.1100) ((l 1) 0 0x1 ")
    # All 22 slots in the server's order, whatever order the writer was given.
    slots = [f"{side} {n}" for side in "lr" for n in range(1, 12)]
    assert re.findall(r"\(\(([lr] [0-9]+)\)", lines[6]) == slots
    assert "((r 2) 0 0 6.0000 -37.0000 0.0000 0.0000 0.000 0 " in lines[6]


def test_playmode_and_team_lines_only_on_change(tmp_path: Path) -> None:
    lines = _write(tmp_path / "match.rcg").read_text().splitlines()
    kinds = [line.split(" ", 2)[0] + " " + line.split(" ", 2)[1] for line in lines[4:]]
    assert kinds == [
        "(playmode 0",
        "(team 0",
        "(show 0",
        "(playmode 1",
        "(show 1",
        "(show 2",
        "(playmode 3",
        "(team 3",
        "(show 3",
        "(playmode 4",
        "(show 4",
    ]
    assert "(team 3 Left-Team right_2 1 0)" in lines


def test_y_and_angle_flip(tmp_path: Path) -> None:
    lines = _write(tmp_path / "match.rcg").read_text().splitlines()
    show = lines[6]
    # L1 at y = +10 (up), heading +0.5 rad (counter-clockwise), 1.2 / -0.7 m/s.
    assert "((l 1) 0 0x1 -10.0000 -10.0000 0.1200 0.0700 -28.648 0 (v h 90)" in show
    # L2 faces -pi: the server's angle is +180, in (-180, 180].
    assert "((l 2) 0 0x1 -20.5000 5.2500 0.0000 -0.0300 180.000 0 " in show
    assert show.endswith("(s 8000 1 1 130600) (c 0 0 0 0 0 0 0 0 0 0 0)))")


def test_missing_player_written_disconnected(tmp_path: Path) -> None:
    frame = FRAMES[0]
    players = {ref: state for ref, state in frame.truth.players.items() if ref != R3}
    partial = GameFrame(Truth(0, 0.0, frame.truth.ball, players), frame.play_mode, frame.score)
    path = _write(tmp_path / "match.rcg", [partial])
    show = path.read_text().splitlines()[6]
    # rcssserver's Player::disable: x = -3 * unum * side, y = -(68 / 2 + 3).
    assert "((r 3) 0 0 9.0000 -37.0000 0.0000 0.0000 0.000 0 " in show
    assert "((l 11) 0 0 -33.0000 -37.0000 0.0000 0.0000 0.000 0 " in show
    assert set(read_rcg(path).frames[0].truth.players) == {L1, L2, R1}


def test_unknown_player_refused(tmp_path: Path) -> None:
    frame = FRAMES[0]
    players = dict(frame.truth.players)
    players[PlayerRef(RIGHT, 7)] = BodyState(0.0, 0.0, 0.0)
    stray = GameFrame(Truth(0, 0.0, frame.truth.ball, players), "play_on", (0, 0))
    with pytest.raises(ValueError, match="right7"):
        _write(tmp_path / "match.rcg", [stray])


@pytest.mark.parametrize(
    "teams", [("has space", "ok"), ("ok", "x" * 17), ("ok", ""), ("ok", "bad(paren")]
)
def test_bad_team_name_refused(tmp_path: Path, teams: tuple[str, str]) -> None:
    with pytest.raises(ValueError, match="team name"):
        RcgWriter(tmp_path / "m.rcg", players=PLAYERS, teams=teams, dt_s=DT)
    assert not list(tmp_path.iterdir())


def test_bad_player_number_refused(tmp_path: Path) -> None:
    with pytest.raises(ValueError, match="numbers 1 to 11"):
        RcgWriter(tmp_path / "m.rcg", players=(PlayerRef(LEFT, 12),), teams=("a", "b"), dt_s=DT)


def test_non_ulg_file_refused(tmp_path: Path) -> None:
    path = tmp_path / "notes.rcg"
    path.write_text("hello\n(show 1 ((b) 0 0 0 0))\n")
    assert not is_rcg(path)
    with pytest.raises(ValueError, match=r"notes\.rcg:1: not a text game log"):
        read_rcg(path)
    assert not is_rcg(tmp_path / "absent.rcg")


@pytest.mark.parametrize(
    "bad",
    [
        "(show 7 ((b) 0 0 0 0) ((l 1) 0 0x1 1 2 3 4 5 6 (v h 90)",  # truncated
        "(show 7 ((b) 0 zero 0 0))",
        "(show 7 ((b) 0 0 0 0) ((l 1) 0 0x1 1 2 three 4 5 6 (v h 90) (s 1 1 1) (c 0)))",
        "(playmode 7)",
        "(team 7 a b one 0)",
        "just text",
    ],
)
def test_malformed_line_refused(tmp_path: Path, bad: str) -> None:
    path = _write(tmp_path / "match.rcg")
    lines = path.read_text().splitlines()
    lines.insert(8, bad)
    path.write_text("\n".join(lines) + "\n")
    assert is_rcg(path)
    with pytest.raises(ValueError, match=r"match\.rcg:9: "):
        read_rcg(path)


# Lines as rcssserver 19 writes them with game_log_version 5 (src/initsender.cpp,
# src/logger.cpp, src/serializermonitor.cpp): doubles as C++ streams print them, booleans
# 0/1, strings quoted, states with 0x, the goalie flag 0x8, an arm pointing (two numbers after
# the neck), a focus (f r 2), a disconnected player (state 0 at 30, -37), a penalty team line.
REAL_V5 = """\
ULG5
(server_param (audio_cut_dist 50)(auto_mode 0)(back_passes 1)(ball_decay 0.94)(ball_size 0.085)\
(game_log_dir "./")(goal_width 14.02)(simulator_step 100)(visible_angle 90))
(player_param (allow_mult_default_type 0)(catchable_area_l_stretch_max 1.3)(player_types 18))
(player_type (id 0)(player_speed_max 1.05)(stamina_inc_max 45)(player_decay 0.4))
(msg 0 1 "(change_player_type l 2 3)")
(playmode 1 kick_off_l)
(team 1 HELIOS_base test 0 0)
(show 1 ((b) 0 0 0 0) ((l 1) 0 0x9 -49 0 0 0 2.327 0 (v h 180) (s 8000 1 1 130600) \
(c 0 0 906 0 1 907 1 0 0 0 0)) ((l 2) 3 0x1 -25 -5 0.3 -0.12 78.518 -30 12.5 -3 (v h 180) \
(s 8000 0.901147 1 130600) (f r 2) (c 0 0 887 0 1 888 1 0 0 0 0)) ((r 10) 0 0 30 -37 0 0 0 0 \
(v h 90) (s 8000 1 1 130600) (c 0 0 0 0 0 0 0 0 0 0 0)))
(playmode 2 play_on)
(team 2 HELIOS_base test 1 0 2 1 0 0)
(show 2 ((b) 1.2 -0.5 0.6 -0.25) ((l 1) 0 0x9 -49 0 0 0 -170.5 0 (v h 180) \
(s 8000 1 1 130600) (c 0 0 906 0 1 907 1 0 0 0 0)))
"""


def test_reads_real_rcssserver_v5_lines(tmp_path: Path) -> None:
    path = tmp_path / "20240101-HELIOS_base_1-vs-test_0.rcg"
    path.write_text(REAL_V5)
    assert is_rcg(path)
    game = read_rcg(path)
    assert game.teams == ("HELIOS_base", "test")
    assert game.server_params["game_log_dir"] == "./"
    assert game.server_params["ball_decay"] == "0.94"
    first, second = game.frames
    assert (first.tick, first.play_mode, first.score) == (1, "kick_off_l", (0, 0))
    assert (second.tick, second.play_mode, second.score) == (2, "play_on", (1, 0))
    assert set(first.truth.players) == {L1, L2}  # r10 is disconnected
    goalie = first.truth.players[L1]
    assert (goalie.x, goalie.y) == (-49.0, 0.0)
    assert goalie.heading == pytest.approx(math.radians(-2.327))
    l2 = first.truth.players[L2]
    assert (l2.x, l2.y) == (-25.0, 5.0)
    assert (l2.vx, l2.vy) == pytest.approx((3.0, 1.2))
    assert l2.heading == pytest.approx(math.radians(-78.518))
    ball = second.truth.ball
    assert (ball.x, ball.y, ball.vx, ball.vy) == pytest.approx((1.2, 0.5, 6.0, 2.5))
    assert second.truth.players[L1].heading == pytest.approx(math.radians(170.5))
    assert second.truth.time_s == pytest.approx(0.2)


def test_cycle_from_simulator_step(tmp_path: Path) -> None:
    dt = 1.0 / 240.0  # not a whole number of milliseconds: written exactly
    path = tmp_path / "robots.rcg"
    ball = BodyState(0.1, 0.2, 0.0, 0.5, -0.25)
    frame = GameFrame(
        Truth(5, 5 * dt, ball, {L1: BodyState(0.3, -0.4, 1.0, 0.24, 0.0)}), "x", (0, 0)
    )
    with RcgWriter(path, players=(L1,), teams=("a", "b"), dt_s=dt) as writer:
        writer.write(frame)
    game = read_rcg(path)
    assert float(game.server_params["simulator_step"]) == pytest.approx(1000.0 * dt, rel=1e-12)
    got = game.frames[0].truth
    assert got.time_s == pytest.approx(5 * dt)
    assert got.ball.vx == pytest.approx(0.5, abs=1e-4 / dt)
    assert got.players[L1].vx == pytest.approx(0.24, abs=1e-4 / dt)


def test_simulator_step_must_agree(tmp_path: Path) -> None:
    with pytest.raises(ValueError, match="simulator_step"):
        RcgWriter(
            tmp_path / "m.rcg",
            players=(L1,),
            teams=("a", "b"),
            dt_s=DT,
            server_params={"simulator_step": 50},
        )
