"""The Soccer Server's text game log: written, read back, and real logs read."""

from __future__ import annotations

import dataclasses
import math
import re
from pathlib import Path

import pytest

from field_models.protocol import LEFT, RIGHT, BodyState, PlayerRef, Truth
from robotsoccer.replay.frames import GameFrame
from robotsoccer.replay.rcg import AFTER_GOAL_WAIT
from robotsoccer.replay.rcg_read import is_rcg, read_rcg
from robotsoccer.replay.rcg_write import RcgWriter

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


# The left team scores in cycle 3: the next frame is the first with the new score.
FRAMES = [
    _frame(1, "kick_off_l", (0, 0)),
    _frame(2, "play_on", (0, 0), 0.1),
    _frame(3, "play_on", (0, 0), 0.2),
    _frame(4, "kick_off_r", (1, 0), 0.3),
    _frame(5, "play_on", (1, 0), 0.4),
]
GOAL_CYCLE = 3


def _written(frames: list[GameFrame] = FRAMES) -> list[GameFrame]:
    """The frames a log of `frames` holds: the goal's cycle as the server writes it."""
    out: list[GameFrame] = []
    for frame, after in zip(frames, [*frames[1:], None], strict=True):
        if after is None or after.score == frame.score:
            out.append(frame)
            continue
        ball = frame.truth.ball._replace(vx=0.0, vy=0.0)
        scored = GameFrame(dataclasses.replace(frame.truth, ball=ball), "goal_l", after.score)
        held = {ref: s._replace(vx=0.0, vy=0.0) for ref, s in frame.truth.players.items()}
        frozen = GameFrame(
            dataclasses.replace(frame.truth, ball=ball, players=held), "goal_l", after.score
        )
        out += [scored] + [frozen] * (AFTER_GOAL_WAIT - 1)
    return out


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
    expected = _written()
    assert len(game.frames) == len(FRAMES) - 1 + AFTER_GOAL_WAIT
    for want, got in zip(expected, game.frames, strict=True):
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
    assert lines[1].startswith("(server_param (audio_cut_dist 50)(auto_mode 0)")
    assert "(goal_width 14.02)" in lines[1] and "(simulator_step 100)" in lines[1]
    assert lines[2].startswith("(player_param ")
    assert lines[3].startswith("(player_type (id 0)")
    assert "(player_size 0.3)" in lines[3] and lines[20].startswith("(player_type (id 17)")
    del lines[4:21]  # player types 1..17
    assert lines[4] == "(playmode 1 kick_off_l)"
    assert lines[5] == "(team 1 Left-Team right_2 0 0)"
    assert lines[6].startswith("(show 1 ((b) 1.5000 2.2500 0.2700 0.1100) ((l 1) 0 0x1 ")
    # All 22 slots in the server's order, whatever order the writer was given.
    slots = [f"{side} {n}" for side in "lr" for n in range(1, 12)]
    assert re.findall(r"\(\(([lr] [0-9]+)\)", lines[6]) == slots
    assert "((r 2) 0 0 6.0000 -37.0000 0.0000 0.0000 0.000 0 " in lines[6]


HEADER_LINES = 21
"""ULG5, server_param, player_param and 18 player_type lines."""


def test_playmode_and_team_lines_only_on_change(tmp_path: Path) -> None:
    lines = _write(tmp_path / "match.rcg").read_text().splitlines()
    kinds = [line.split(" ", 2)[0] + " " + line.split(" ", 2)[1] for line in lines[HEADER_LINES:]]
    assert kinds == [
        "(playmode 1",
        "(team 1",
        "(show 1",
        "(playmode 2",
        "(show 2",
        "(playmode 3",  # goal_l: the cycle the ball went in
        "(team 3",
        *["(show 3"] * AFTER_GOAL_WAIT,  # the clock held
        "(playmode 4",
        "(show 4",
        "(playmode 5",
        "(show 5",
    ]
    assert "(playmode 3 goal_l)" in lines and "(team 3 Left-Team right_2 1 0)" in lines
    assert "(playmode 4 kick_off_r)" in lines


def test_y_and_angle_flip(tmp_path: Path) -> None:
    lines = _write(tmp_path / "match.rcg").read_text().splitlines()
    show = lines[HEADER_LINES + 2]
    # L1 at y = +10 (up), heading +0.5 rad (counter-clockwise), 1.2 / -0.7 m/s.
    assert "((l 1) 0 0x1 -10.0000 -10.0000 0.1200 0.0700 -28.648 0 (v h 90)" in show
    # L2 faces -pi: the server's angle is +180, in (-180, 180].
    assert "((l 2) 0 0x1 -20.5000 5.2500 0.0000 -0.0300 180.000 0 " in show
    assert show.endswith("(s 8000 1 1 130600) (c 0 0 0 0 0 0 0 0 0 0 0)))")


def test_missing_player_written_disconnected(tmp_path: Path) -> None:
    frame = FRAMES[0]
    players = {ref: state for ref, state in frame.truth.players.items() if ref != R3}
    partial = GameFrame(Truth(1, DT, frame.truth.ball, players), frame.play_mode, frame.score)
    path = _write(tmp_path / "match.rcg", [partial])
    show = path.read_text().splitlines()[HEADER_LINES + 2]
    # rcssserver's Player::disable: x = -3 * unum * side, y = -(68 / 2 + 3).
    assert "((r 3) 0 0 9.0000 -37.0000 0.0000 0.0000 0.000 0 " in show
    assert "((l 11) 0 0 -33.0000 -37.0000 0.0000 0.0000 0.000 0 " in show
    assert set(read_rcg(path).frames[0].truth.players) == {L1, L2, R1}


def test_unknown_player_refused(tmp_path: Path) -> None:
    frame = FRAMES[0]
    players = dict(frame.truth.players)
    players[PlayerRef(RIGHT, 7)] = BodyState(0.0, 0.0, 0.0)
    stray = GameFrame(Truth(1, DT, frame.truth.ball, players), "play_on", (0, 0))
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


# ----------------------------------------------------------------------------- as a server writes


def _lines(path: Path) -> list[str]:
    return path.read_text().splitlines()


def test_finish_ends_the_log_with_time_over_at_the_last_cycle(tmp_path: Path) -> None:
    path = tmp_path / "m.rcg"
    writer = RcgWriter(path, players=PLAYERS, teams=("a", "b"), dt_s=DT)
    for frame in FRAMES:
        writer.write(frame)
    writer.finish()
    assert writer.closed
    lines = _lines(path)
    assert lines[-2] == "(playmode 5 time_over)"
    assert lines[-1].startswith("(show 5 ")
    assert read_rcg(path).frames[-1].play_mode == "time_over"


def test_a_goal_in_the_last_cycle_is_written_before_time_over(tmp_path: Path) -> None:
    path = tmp_path / "m.rcg"
    writer = RcgWriter(path, players=PLAYERS, teams=("a", "b"), dt_s=DT)
    for frame in FRAMES:
        writer.write(frame)
    writer.finish((1, 1))  # the right team scored in cycle 5, after its frame was taken
    lines = _lines(path)
    tail = [line.split(" ((b)")[0] for line in lines[-(AFTER_GOAL_WAIT + 4) :]]
    assert tail == [
        "(playmode 5 goal_r)",
        "(team 5 a b 1 1)",
        *["(show 5"] * AFTER_GOAL_WAIT,
        "(playmode 5 time_over)",
        "(show 5",
    ]


def test_the_goal_scene_stops_the_ball_and_holds_everyone(tmp_path: Path) -> None:
    game = read_rcg(_write(tmp_path / "m.rcg"))
    scene = [f for f in game.frames if f.tick == GOAL_CYCLE]
    assert len(scene) == AFTER_GOAL_WAIT
    assert {(f.play_mode, f.score) for f in scene} == {("goal_l", (1, 0))}
    assert all(f.truth.ball.speed == 0.0 for f in scene)
    goal = FRAMES[GOAL_CYCLE - 1].truth
    assert (scene[0].truth.ball.x, scene[-1].truth.ball.x) == pytest.approx((goal.ball.x,) * 2)
    assert all(s.speed == 0.0 for f in scene[1:] for s in f.truth.players.values())
    # In the goal's own show the players still move as they did.
    assert scene[0].truth.players[L1].vx == pytest.approx(goal.players[L1].vx)
    at = [i for i, f in enumerate(game.frames) if f.tick == GOAL_CYCLE]
    assert at == list(range(at[0], at[0] + AFTER_GOAL_WAIT))  # one run, the clock held
    before, after = game.frames[at[0] - 1], game.frames[at[-1] + 1]
    assert before.tick == GOAL_CYCLE - 1
    assert (after.tick, after.play_mode) == (GOAL_CYCLE + 1, "kick_off_r")


def test_cycles_start_at_one_and_never_go_back(tmp_path: Path) -> None:
    writer = RcgWriter(tmp_path / "m.rcg", players=PLAYERS, teams=("a", "b"), dt_s=DT)
    with pytest.raises(ValueError, match="starts at cycle 1"):
        writer.write(dataclasses.replace(FRAMES[0], truth=_frame(0, "x", (0, 0)).truth))
    writer.write(FRAMES[2])
    with pytest.raises(ValueError, match="tick 2 comes after tick 3"):
        writer.write(FRAMES[1])
    writer.close()


def test_goalies_must_play(tmp_path: Path) -> None:
    with pytest.raises(ValueError, match="goalies"):
        RcgWriter(tmp_path / "m.rcg", players=(L1,), teams=("a", "b"), dt_s=DT, goalies=(R1,))


def test_log_team_names_keep_the_side() -> None:
    from robotsoccer.replay.rcg_write import log_team_name

    assert log_team_name("baseline (left)") == "baseline_left"
    assert log_team_name("layered") == "layered"
    with pytest.raises(ValueError, match="cannot be written"):
        log_team_name("((()))")
    with pytest.raises(ValueError, match="cannot be written"):
        log_team_name("a very long team name indeed")


# rcssserver 19's show line with game_log_version 5 (src/serializermonitor.cpp,
# SerializerMonitorStdv4): the cycle and the ball, then per player, in this order: its id,
# type, state (hex, 0 unprefixed), x, y, vx, vy, body, neck, an optional arm point (x y),
# the view mode (v h|l width), stamina (s stamina effort recovery capacity), an optional focus
# (f side unum), the eleven counters (c kick dash turn catch move turn_neck change_view say
# tackle pointto attentionto).
_N = r"-?[0-9]+(?:\.[0-9]+)?(?:e[-+]?[0-9]+)?"
ULG5_PLAYER = re.compile(
    rf"\(\((?P<side>[lr]) (?P<unum>[0-9]+)\) (?P<type>[0-9]+) (?P<state>0|0x[0-9a-f]+)"
    rf" (?P<x>{_N}) (?P<y>{_N}) (?P<vx>{_N}) (?P<vy>{_N}) (?P<body>{_N}) (?P<neck>{_N})"
    rf"(?: (?P<px>{_N}) (?P<py>{_N}))?"
    rf" \(v (?P<quality>[hl]) (?P<width>{_N})\)"
    rf" \(s (?P<stamina>{_N}) (?P<effort>{_N}) (?P<recovery>{_N}) (?P<capacity>{_N})\)"
    r"(?: \(f [lr] [0-9]+\))?"
    r" \(c (?P<counts>[0-9]+(?: [0-9]+){10})\)\)"
)
ULG5_SHOW = re.compile(rf"\(show (?P<cycle>[0-9]+) \(\(b\) {_N} {_N} {_N} {_N}\)(?P<players>.*)\)")


def show_players(line: str) -> list[re.Match[str]]:
    show = ULG5_SHOW.fullmatch(line)
    assert show is not None, line[:80]
    rest = show.group("players")
    found = list(ULG5_PLAYER.finditer(rest))
    assert "".join(" " + m.group(0) for m in found) == rest  # every player, nothing else
    return found


def test_the_format_check_reads_a_real_servers_show_lines() -> None:
    shows = [line for line in REAL_V5.splitlines() if line.startswith("(show ")]
    players = [show_players(line) for line in shows]
    assert [len(p) for p in players] == [3, 1]
    l2 = players[0][1]
    assert (l2["state"], l2["px"], l2["py"], l2["neck"]) == ("0x1", "12.5", "-3", "-30")
    assert l2["counts"] == "0 0 887 0 1 888 1 0 0 0 0"


def test_each_show_line_holds_the_servers_fields_in_their_order(tmp_path: Path) -> None:
    from field_models.arena import COMMAND_COUNTERS, CommandTally

    def counts(**named: int) -> tuple[int, ...]:
        return tuple(named.get(name, 0) for name in COMMAND_COUNTERS)

    tallies = {
        L1: CommandTally(counts(kick=3, dash=40, turn=12), kicked=True),
        L2: CommandTally(counts(dash=7, say=2), kick_missed=True),
        R1: CommandTally(counts(turn=1)),
    }  # R3 has none: zeros
    frames = [dataclasses.replace(f, commands=tallies) for f in FRAMES]
    path = tmp_path / "m.rcg"
    with RcgWriter(
        path, players=PLAYERS, teams=("a", "b"), dt_s=DT, server_params=PARAMS,
        goalies=(L1, R1),
    ) as writer:  # fmt: skip
        for frame in frames:
            writer.write(frame)
    shows = [line for line in _lines(path) if line.startswith("(show ")]
    assert len(shows) == len(FRAMES) - 1 + AFTER_GOAL_WAIT
    for line in shows:
        players = show_players(line)
        assert [(m["side"], int(m["unum"])) for m in players] == [
            (side, n) for side in "lr" for n in range(1, 12)
        ]
        by = {PlayerRef(LEFT if m["side"] == "l" else RIGHT, int(m["unum"])): m for m in players}
        assert by[PlayerRef(LEFT, 5)]["state"] == "0"  # not playing: disabled
        for ref in PLAYERS:
            m = by[ref]
            assert m["type"] == "0" and m["neck"] == "0"
            assert (m["quality"], m["width"]) == ("h", "90")
            assert (m["stamina"], m["effort"], m["recovery"], m["capacity"]) == (
                "8000", "1", "1", "130600"
            )  # fmt: skip
            want = tallies.get(ref, CommandTally(counts()))
            assert tuple(int(c) for c in m["counts"].split()) == want.counts
    first = {m["side"] + m["unum"]: m["state"] for m in show_players(shows[0])}
    # Goalies 0x9 (STAND | GOALIE), a kick that reached the ball 0x2, one that missed 0x4.
    assert (first["l1"], first["l2"], first["r1"], first["r3"]) == ("0xb", "0x5", "0x9", "0x1")
    held = {m["side"] + m["unum"]: m["state"] for m in show_players(shows[GOAL_CYCLE])}
    assert (held["l1"], held["l2"]) == ("0x9", "0x1")  # a held cycle kicks nothing
