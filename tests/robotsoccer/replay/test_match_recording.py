"""Match recordings: a synthetic 11 v 11 match is written, verified and read back."""

from __future__ import annotations

import math
import subprocess
import sys
import warnings
from dataclasses import replace
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from field_models.arena import ArenaEvent
from field_models.protocol import (
    LEFT,
    RIGHT,
    BodyState,
    Percept,
    Pitch,
    PlayerRef,
    SeenBall,
    SeenPlayer,
    Truth,
)
from robotsoccer.replay.field_recorder import Scene
from robotsoccer.replay.frames import GameFrame
from robotsoccer.replay.lettering import text_strokes
from robotsoccer.replay.match_recording import MatchRecorder
from robotsoccer.replay.palette import team_colour
from robotsoccer.replay.rrd_files import read_entity_positions, verify_recording

PITCH = Pitch(
    length_m=105.0,
    width_m=68.0,
    goal_width_m=14.02,
    goal_depth_m=2.44,
    ball_radius_m=0.085,
    player_radius_m=0.3,
)
DT_S = 0.1
SENSOR_S = 0.15  # a percept stays current for ceil(1.5 * 0.15 / 0.1) = 3 ticks
N_TICKS = 300
GOAL_TICK = 123  # the ball's centre reaches the right goal line here
KICKOFF_TICK = 150  # the ball is put back on the centre spot here
TRAIL_TICKS = 15  # the default: 1.5 s of 0.1 s ticks
PLAYERS = tuple(PlayerRef(team, n) for team in (LEFT, RIGHT) for n in range(1, 12))
SELECTED = PlayerRef(LEFT, 9)
OTHER = PlayerRef(RIGHT, 4)
TEAMS = ("layered", "baseline")
SEEN_OFFSET = (1.0, -0.5)  # the selected player sees the ball this far from where it is
NO_BALL_TICK = 90  # the selected player's percept at this tick has no ball


def ball_at(tick: int) -> tuple[float, float]:
    if tick < GOAL_TICK:
        return -9.0 + 0.5 * tick, 3.0 - 0.0137 * tick
    if tick < KICKOFF_TICK:
        return 53.5, 3.0 - 0.0137 * GOAL_TICK  # in the net
    k = tick - KICKOFF_TICK
    return -0.31 * k, 0.17 * k


def play_mode_at(tick: int) -> str:
    changes = [
        (0, "before_kick_off"),
        (5, "kick_off_l"),
        (10, "play_on"),
        (GOAL_TICK, "goal_l"),
        (KICKOFF_TICK, "kick_off_r"),
        (KICKOFF_TICK + 5, "play_on"),
    ]
    return [mode for start, mode in changes if tick >= start][-1]


MODE_CHANGES = [t for t in range(1, N_TICKS) if play_mode_at(t) != play_mode_at(t - 1)]


def score_at(tick: int) -> tuple[int, int]:
    return (1, 0) if tick >= GOAL_TICK else (0, 0)


def pose_at(player: PlayerRef, tick: int) -> BodyState:
    side = -1.0 if player.team == LEFT else 1.0
    return BodyState(
        x=side * (5.0 + 4.0 * player.number) + 0.02 * tick,
        y=-30.0 + 5.5 * player.number + math.sin(0.05 * tick + player.number),
        heading=0.03 * tick + player.number,
    )


def truth_at(tick: int) -> Truth:
    x, y = ball_at(tick)
    players = {p: pose_at(p, tick) for p in PLAYERS}
    return Truth(tick=tick, time_s=tick * DT_S, ball=BodyState(x, y, 0.0), players=players)


def seen_ball(me: BodyState, tick: int) -> SeenBall:
    x, y = ball_at(tick)
    dx, dy = x + SEEN_OFFSET[0] - me.x, y + SEEN_OFFSET[1] - me.y
    return SeenBall(math.hypot(dx, dy), math.atan2(dy, dx) - me.heading)


def record_match(path: Path, *, every_ticks: int = 1, shape: str = "circle") -> None:
    with MatchRecorder(
        path,
        Scene(
            pitch=PITCH,
            players=PLAYERS,
            dt_s=DT_S,
            player_shape="circle" if shape == "circle" else "square",
            sensor_period_s=SENSOR_S,
            title="synthetic match",
        ),
        teams=TEAMS,
        selected=SELECTED,
        recording_id="test-match",
        every_ticks=every_ticks,
        chunk_frames=64,
    ) as rec:
        for tick in range(N_TICKS):
            truth = truth_at(tick)
            rec.log_frame(GameFrame(truth, play_mode_at(tick), score_at(tick)))
            if tick % 3 == 0:
                me = truth.players[SELECTED]
                ball = None if tick == NO_BALL_TICK else seen_ball(me, tick)
                seen = (SeenPlayer(10.0, 0.2, RIGHT, 4),)
                rec.log_percept(Percept(SELECTED, tick, tick, ball, seen), me)
            other = truth.players[OTHER]
            rec.log_percept(Percept(OTHER, tick, tick, seen_ball(other, tick)), other)
            events = [ArenaEvent(tick, "command", "(dash 100)", p) for p in PLAYERS]
            events.append(ArenaEvent(tick, "see", "(see ...)", SELECTED))
            if tick in MODE_CHANGES:
                events.append(ArenaEvent(tick, "referee", play_mode_at(tick)))
            if tick % 50 == 25:
                events.append(ArenaEvent(tick, "decision", f"pass to 7 #{tick}", SELECTED))
            rec.log_events(events)


@pytest.fixture(scope="module")
def match_file(tmp_path_factory: pytest.TempPathFactory) -> Path:
    path = tmp_path_factory.mktemp("match") / "match.rrd"
    record_match(path)
    return path


def read_chunks(path: Path, *, blueprint: bool = False) -> list[Any]:
    from rerun.chunk import RrdReader

    reader = RrdReader(str(path))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        store = reader.blueprints()[0] if blueprint else None
        return list(reader.stream(store=store).to_chunks())


def entity_paths(path: Path) -> set[str]:
    return {chunk.entity_path for chunk in read_chunks(path)}


def rows(path: Path, entity: str, column: str) -> list[tuple[int, list[Any]]]:
    """(tick, values) of every temporal row of `entity`'s `column`, in tick order."""
    out: list[tuple[int, list[Any]]] = []
    for chunk in read_chunks(path):
        if chunk.entity_path != "/" + entity:
            continue
        batch = chunk.to_record_batch()
        if "tick" not in batch.schema.names or column not in batch.schema.names:
            continue
        ticks = batch.column("tick").to_pylist()
        out.extend(zip(ticks, batch.column(column).to_pylist(), strict=True))
    return sorted(out, key=lambda row: row[0])


def f32(values: Any) -> np.ndarray:
    """`values` as rerun stores them (float32), back in float64."""
    return np.asarray(values, dtype=np.float64).astype(np.float32).astype(np.float64)


# ----------------------------------------------------------------------------- the file


def test_match_recording_verifies(match_file: Path) -> None:
    ok, message = verify_recording(match_file)
    assert ok, message


def test_ball_positions_read_back(match_file: Path) -> None:
    got = read_entity_positions(match_file, "field/ball")
    np.testing.assert_array_equal(got, f32([ball_at(t) for t in range(N_TICKS)]))


def test_players_are_labelled_by_number(match_file: Path) -> None:
    labelled = rows(match_file, "field/players/left/name", "Points2D:labels")
    assert len(labelled) == N_TICKS
    assert all(labels == [str(n) for n in range(1, 12)] for _, labels in labelled)
    got = read_entity_positions(match_file, "field/players/right")
    expected = [pose_at(p, t)[:2] for t in range(N_TICKS) for p in PLAYERS if p.team == RIGHT]
    np.testing.assert_array_equal(got, f32(expected))
    # Headings: an arrow per player; round players have no outline (the arrow says it all).
    assert len(rows(match_file, "field/players/left/heading", "Arrows2D:vectors")) == N_TICKS
    assert not rows(match_file, "field/players/left/outline", "LineStrips2D:strips")


def test_square_robots_keep_their_outlines(tmp_path: Path) -> None:
    path = tmp_path / "robots.rrd"
    record_match(path, shape="square", every_ticks=50)
    outlines = rows(path, "field/players/left/outline", "LineStrips2D:strips")
    assert [tick for tick, _ in outlines] == list(range(0, N_TICKS, 50))
    assert all(len(strips) == 11 for _, strips in outlines)


# ----------------------------------------------------------------------------- the trail


def test_trail_lags_the_ball(match_file: Path) -> None:
    trail = dict(rows(match_file, "field/ball/trail", "LineStrips2D:strips"))
    colours = dict(rows(match_file, "field/ball/trail", "LineStrips2D:colors"))
    assert set(trail) == set(range(N_TICKS))
    assert trail[0] == []  # one position: nothing to join yet
    # Mid-run, in straight motion: 15 positions (ticks 46..60), joined by 14 segments that
    # run from 1.4 s ago to the ball now, each starting where the previous one ended.
    segments = np.asarray(trail[60], dtype=np.float64)
    assert segments.shape == (TRAIL_TICKS - 1, 2, 2)
    np.testing.assert_array_equal(segments[-1, 1], f32(ball_at(60)))
    np.testing.assert_array_equal(segments[0, 0], f32(ball_at(60 - TRAIL_TICKS + 1)))
    np.testing.assert_array_equal(segments[1:, 0], segments[:-1, 1])
    assert np.all(np.diff(segments[:, 0, 0]) > 0.0)  # the ball moves right; the trail follows
    # It fades: the newest segment is the brightest, the oldest the dimmest.
    brightness = [sum(rgba.to_bytes(4, "big")[:3]) for rgba in colours[60]]
    assert brightness == sorted(brightness)
    assert brightness[0] < brightness[-1]


def test_trail_is_cut_where_the_ball_was_put_back(match_file: Path) -> None:
    trail = dict(rows(match_file, "field/ball/trail", "LineStrips2D:strips"))
    after = np.asarray(trail[KICKOFF_TICK + 5], dtype=np.float64)
    assert after.shape == (5, 2, 2)  # ticks 150..155 only: not back into the net
    np.testing.assert_array_equal(after[0, 0], f32(ball_at(KICKOFF_TICK)))
    assert np.abs(after[..., 0]).max() < 5.0
    assert trail[KICKOFF_TICK] == []


def test_trail_length_and_thinning(tmp_path: Path) -> None:
    path = tmp_path / "fine.rrd"
    # Fine ticks (1/240 s): the default trail is 360 ticks, thinned to at most 24 positions.
    with MatchRecorder(
        path,
        Scene(
            pitch=PITCH,
            players=(),
            dt_s=1.0 / 240.0,
            player_shape="square",
            sensor_period_s=0.05,
            title="fine",
        ),
        teams=TEAMS,
        selected=None,
        recording_id="fine",
    ) as rec:
        assert rec.trail_ticks == 360
        for tick in range(500):
            ball = BodyState(0.01 * tick, 0.0, 0.0)
            rec.log_frame(GameFrame(Truth(tick, tick / 240.0, ball), "play_on", (0, 0)))
    trail = dict(rows(path, "field/ball/trail", "LineStrips2D:strips"))
    last = np.asarray(trail[499], dtype=np.float64)
    assert len(last) <= 24
    assert last[0, 0, 0] == pytest.approx(0.01 * 150, abs=1e-5)  # first grid tick in (139, 499]
    assert last[-1, 1, 0] == pytest.approx(0.01 * 499, abs=1e-5)


# ----------------------------------------------------------------------------- score, board


def test_score_series_steps_at_the_goal_tick(match_file: Path) -> None:
    left = rows(match_file, "score/left", "Scalars:scalars")
    right = rows(match_file, "score/right", "Scalars:scalars")
    assert [tick for tick, _ in left] == list(range(N_TICKS))
    assert [v for _, (v,) in left] == [float(t >= GOAL_TICK) for t in range(N_TICKS)]
    assert all(v == 0.0 for _, (v,) in right)


def test_score_series_catches_a_goal_between_recorded_ticks(tmp_path: Path) -> None:
    path = tmp_path / "thin.rrd"
    record_match(path, every_ticks=5)
    left = rows(path, "score/left", "Scalars:scalars")
    ticks = [tick for tick, _ in left]
    assert ticks == sorted([*range(0, N_TICKS, 5), GOAL_TICK])  # 123 is no multiple of 5
    assert dict(left)[GOAL_TICK - 3] == [0.0] and dict(left)[GOAL_TICK] == [1.0]
    assert len(read_entity_positions(path, "field/ball")) == N_TICKS // 5


def test_scoreboard_shows_the_score_in_team_colours(match_file: Path) -> None:
    board = rows(match_file, "field/scoreboard", "LineStrips2D:strips")
    assert [tick for tick, _ in board] == [0, GOAL_TICK]
    strokes = text_strokes(f"{TEAMS[0]} 1 : 0 {TEAMS[1]}", height_m=1.0, centre_x_m=0, base_y_m=0)
    assert len(board[1][1]) == len(strokes)
    ys = [y for stroke in board[1][1] for _, y in stroke]
    assert min(ys) > PITCH.half_width_m  # above the field
    colours = dict(rows(match_file, "field/scoreboard", "LineStrips2D:colors"))[GOAL_TICK]

    def rgba(colour: tuple[int, int, int]) -> int:
        return int.from_bytes(bytes([*colour, 255]), "big")

    left, right = rgba(team_colour(LEFT, (LEFT, RIGHT))), rgba(team_colour(RIGHT, (LEFT, RIGHT)))
    # "layered 1" in the left colour (L, A, Y, E, R, E, D and the 1), the colon in white, then
    # "0 baseline" in the right colour: colours run left, white, right, in that order.
    n_left = len(text_strokes(f"{TEAMS[0]} 1", height_m=1.0, centre_x_m=0, base_y_m=0))
    n_right = len(text_strokes(f"0 {TEAMS[1]}", height_m=1.0, centre_x_m=0, base_y_m=0))
    assert colours[:n_left] == [left] * n_left
    assert colours[-n_right:] == [right] * n_right
    assert len(set(colours[n_left:-n_right])) == 1 and colours[n_left] not in (left, right)


def test_status_line_follows_play_mode_and_clock(match_file: Path) -> None:
    status = rows(match_file, "field/scoreboard/status", "LineStrips2D:strips")
    expected = sorted({*range(0, N_TICKS, 10), *MODE_CHANGES})
    assert [tick for tick, _ in status] == expected
    for tick, strokes in status:
        seconds = int(tick * DT_S + 1e-9)
        text = f"{play_mode_at(tick)}  00:{seconds:02d}"
        assert len(strokes) == len(text_strokes(text, height_m=1.0, centre_x_m=0, base_y_m=0))


def test_goal_and_events_in_the_log(match_file: Path) -> None:
    paths = entity_paths(match_file)
    assert {"/events/referee", "/events/decision", "/events/score"} <= paths
    assert not {"/events/command", "/events/see"} & paths  # dropped on arrival

    def texts(entity: str) -> list[str]:
        return [t for _, row in rows(match_file, entity, "TextLog:text") for t in row]

    assert texts("events/referee") == [f"[referee] {play_mode_at(t)}" for t in MODE_CHANGES]
    assert texts("events/decision") == [
        f"[decision] left9: pass to 7 #{t}" for t in range(25, N_TICKS, 50)
    ]
    assert texts("events/score") == ["[goal] layered: layered 1 : 0 baseline"]
    assert [tick for tick, _ in rows(match_file, "events/score", "TextLog:text")] == [GOAL_TICK]


# ----------------------------------------------------------------------------- selected player


def test_only_the_selected_players_percepts_are_drawn(match_file: Path) -> None:
    paths = entity_paths(match_file)
    assert "/field/perceived/left9/ball" in paths
    assert not any(p.startswith("/field/perceived/right4") for p in paths)
    got = read_entity_positions(match_file, "field/perceived/left9/ball")
    ticks = [t for t in range(0, N_TICKS, 3) if t != NO_BALL_TICK]
    expected = [np.add(ball_at(t), SEEN_OFFSET) for t in ticks]
    np.testing.assert_allclose(got, expected, atol=2e-5)  # float32 of a converted position


def test_selected_player_is_highlighted_with_a_line_of_sight(match_file: Path) -> None:
    halo = read_entity_positions(match_file, "field/selected")
    np.testing.assert_array_equal(halo, f32([pose_at(SELECTED, t)[:2] for t in range(N_TICKS)]))
    # One row per percept (every 3 ticks, each current for 3), logged after that tick's frame
    # as a runner does; the percept of tick 90 saw no ball, so its row clears the line.
    sight = rows(match_file, "field/selected/sight", "LineStrips2D:strips")
    assert [tick for tick, _ in sight] == list(range(0, N_TICKS, 3))
    assert [tick for tick, strips in sight if not strips] == [NO_BALL_TICK]
    ((start, end),) = np.asarray(dict(sight)[60], dtype=np.float64)
    np.testing.assert_array_equal(start, f32(pose_at(SELECTED, 60)[:2]))
    np.testing.assert_allclose(end, np.add(ball_at(60), SEEN_OFFSET), atol=2e-5)


def test_stale_line_of_sight_is_cleared(tmp_path: Path) -> None:
    path = tmp_path / "stale.rrd"
    with MatchRecorder(
        path,
        Scene(
            pitch=PITCH,
            players=PLAYERS,
            dt_s=DT_S,
            player_shape="circle",
            sensor_period_s=SENSOR_S,
            title="t",
        ),
        teams=TEAMS,
        selected=SELECTED,
        recording_id="r",
    ) as rec:
        for tick in range(40):
            truth = truth_at(tick)
            rec.log_frame(GameFrame(truth, "play_on", (0, 0)))
            if tick in (5, 20):
                me = truth.players[SELECTED]
                rec.log_percept(Percept(SELECTED, tick, tick, seen_ball(me, tick)), me)
    sight = rows(path, "field/selected/sight", "LineStrips2D:strips")
    assert [(tick, len(strips)) for tick, strips in sight] == [(5, 1), (8, 0), (20, 1), (23, 0)]
    ring = rows(path, "field/perceived/left9/ball", "Ellipses2D:centers")
    assert [tick for tick, _ in ring] == [tick for tick, _ in sight]  # line and ring agree


# ----------------------------------------------------------------------------- the layout


def blueprint_values(path: Path, column: str) -> list[Any]:
    out: list[Any] = []
    for chunk in read_chunks(path, blueprint=True):
        batch = chunk.to_record_batch()
        if column in batch.schema.names:
            out.extend(v for row in batch.column(column).to_pylist() for v in row)
    return out


def test_default_blueprint_is_embedded(match_file: Path) -> None:
    from rerun.chunk import RrdReader

    reader = RrdReader(str(match_file))
    assert [r.recording_id for r in reader.recordings()] == ["test-match"]
    assert len(reader.blueprints()) == 1  # rec.save(path, default_blueprint=...) wrote it
    kinds = blueprint_values(match_file, "ViewBlueprint:class_identifier")
    origins = blueprint_values(match_file, "ViewBlueprint:space_origin")
    assert sorted(zip(kinds, origins, strict=True)) == [
        ("2D", "/"),  # the root: the flip on /field applies
        ("TextDocument", "/legend"),
        ("TextLog", "/events"),
        ("TimeSeries", "/score"),
    ]
    # The selected player's perceived players are recorded, but hidden in the field view.
    assert "- /field/perceived/left9/players" in blueprint_values(match_file, "ViewContents:query")
    assert blueprint_values(match_file, "TimePanelBlueprint:timeline") == ["sim_time"]
    # The goals view spans the whole match (both boundaries infinite, stored as nulls).
    assert blueprint_values(match_file, "TimeAxis:view_range") == [{"start": None, "end": None}]
    (bounds,) = blueprint_values(match_file, "VisualBounds2D:range")
    # The view's y runs down: the scoreboard's room is at negative y, above the field.
    assert bounds["y_range"][0] < -(PITCH.half_width_m + 0.095 * PITCH.length_m)


def test_field_is_flipped_for_display(match_file: Path) -> None:
    (flip,) = [
        batch.column("Transform3D:scale").to_pylist()[0]
        for chunk in read_chunks(match_file)
        if chunk.entity_path == "/field"
        for batch in [chunk.to_record_batch()]
        if "Transform3D:scale" in batch.schema.names
    ]
    assert flip == [[1.0, -1.0, 1.0]]


# ----------------------------------------------------------------------------- the API


def test_import_does_not_load_rerun() -> None:
    code = "import sys, robotsoccer.replay.match_recording; assert 'rerun' not in sys.modules"
    subprocess.run([sys.executable, "-c", code], check=True)


def test_bad_arguments(tmp_path: Path) -> None:
    scene = Scene(PITCH, PLAYERS, DT_S, "circle", SENSOR_S, "t")
    common: dict[str, Any] = {"teams": TEAMS, "recording_id": "r"}
    with pytest.raises(ValueError, match="selected"):
        MatchRecorder(tmp_path / "a.rrd", scene, selected=PlayerRef(LEFT, 12), **common)
    with pytest.raises(ValueError, match="trail_ticks"):
        MatchRecorder(tmp_path / "b.rrd", scene, selected=None, trail_ticks=0, **common)
    scene = replace(scene, players=(PlayerRef("coach", 1),))
    with pytest.raises(ValueError, match="LEFT or the RIGHT"):
        MatchRecorder(tmp_path / "c.rrd", scene, selected=None, **common)


def test_closed_recorder_refuses_more(tmp_path: Path) -> None:
    path = tmp_path / "closed.rrd"
    rec = MatchRecorder(
        path,
        Scene(
            pitch=PITCH,
            players=PLAYERS,
            dt_s=DT_S,
            player_shape="circle",
            sensor_period_s=SENSOR_S,
            title="t",
        ),
        teams=TEAMS,
        selected=SELECTED,
        recording_id="r",
    )
    rec.log_frame(GameFrame(truth_at(0), "before_kick_off", (0, 0)))
    rec.close()
    rec.close()  # idempotent
    assert verify_recording(path)[0]
    with pytest.raises(RuntimeError):
        rec.log_frame(GameFrame(truth_at(1), "before_kick_off", (0, 0)))
    with pytest.raises(RuntimeError):
        rec.log_events([ArenaEvent(1, "command", "(dash 100)")])


def test_routine_decisions_go_where_the_default_layout_hides_them(tmp_path: Path) -> None:
    from field_models.protocol import Dash, Kick, Say, Turn

    path = tmp_path / "decisions.rrd"
    decisions = [
        ((), "nothing"),
        ((Turn(0.5), Dash(100.0)), "(turn -28.6) (dash 100)"),
        ((Kick(80.0, 0.0),), "(kick 80 0)"),
        ((Say("go"),), "(say go)"),
    ]
    with MatchRecorder(
        path,
        Scene(
            pitch=PITCH,
            players=PLAYERS,
            dt_s=DT_S,
            player_shape="circle",
            sensor_period_s=SENSOR_S,
            title="t",
        ),
        teams=TEAMS,
        selected=SELECTED,
        recording_id="d",
    ) as rec:
        for tick, (actions, text) in enumerate(decisions):
            rec.log_frame(GameFrame(truth_at(tick), "play_on", (0, 0)))
            rec.log_decision(ArenaEvent(tick, "decision", text, SELECTED), actions)

    def texts(entity: str) -> list[str]:
        return [t for _, row in rows(path, entity, "TextLog:text") for t in row]

    assert texts("events/routine") == [
        "[decision] left9: nothing",
        "[decision] left9: (turn -28.6) (dash 100)",
    ]
    assert texts("events/decision") == [
        "[decision] left9: (kick 80 0)",
        "[decision] left9: (say go)",
    ]
    assert "- /events/routine/**" in blueprint_values(path, "ViewContents:query")
