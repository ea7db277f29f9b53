"""Rerun recordings: a short synthetic run is written, verified and read back."""

from __future__ import annotations

import math
import subprocess
import sys
import warnings
from pathlib import Path

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
from robotsoccer.replay import rrd_files
from robotsoccer.replay.field_recorder import Scene
from robotsoccer.replay.geometry import (
    MIN_BALL_FRACTION,
    MIN_PLAYER_FRACTION,
    draw_sizes,
    egocentric_to_field,
    outline_template,
    pitch_markings,
    place_outlines,
)
from robotsoccer.replay.lettering import text_strokes
from robotsoccer.replay.recording import TrialRecorder, recording_name
from robotsoccer.replay.rrd_files import read_entity_positions, replay, verify_recording
from robotsoccer.runs.runner import TrialSpec, run_trial

PITCH = Pitch(
    length_m=2.74,
    width_m=1.525,
    goal_width_m=0.5,
    goal_depth_m=0.1,
    ball_radius_m=0.0213,
    player_radius_m=0.075,
)
A = PlayerRef(LEFT, 1)
B = PlayerRef(RIGHT, 2)
SERVER_PITCH = Pitch(
    length_m=105.0,
    width_m=68.0,
    goal_width_m=14.02,
    goal_depth_m=2.44,
    ball_radius_m=0.085,
    player_radius_m=0.3,
)
DT_S = 1.0 / 240.0
N_TICKS = 50


def ball_at(tick: int) -> BodyState:
    # Irrational-looking steps so float32 storage cannot be exact by accident.
    return BodyState(x=-1.0 + 0.0137 * tick, y=0.3 - 0.0071 * tick, heading=0.0, vx=3.3, vy=-1.7)


def truth_at(tick: int) -> Truth:
    players = {
        A: BodyState(x=-0.5 + 0.01 * tick, y=0.1, heading=0.05 * tick),
        B: BodyState(x=0.7, y=-0.2 - 0.002 * tick, heading=math.pi - 0.01 * tick),
    }
    return Truth(tick=tick, time_s=tick * DT_S, ball=ball_at(tick), players=players)


def record_run(path: Path, *, every_ticks: int = 1, chunk_frames: int = 16) -> None:
    with TrialRecorder(
        path,
        Scene(pitch=PITCH, players=(A, B), dt_s=DT_S),
        recording_id="test-trial-0",
        every_ticks=every_ticks,
        chunk_frames=chunk_frames,
    ) as rec:
        for tick in range(N_TICKS):
            truth = truth_at(tick)
            rec.log_truth(truth)
            if tick % 10 == 5:
                me = truth.players[A]
                dx, dy = truth.ball.x - me.x, truth.ball.y - me.y
                seen = SeenBall(math.hypot(dx, dy), math.atan2(dy, dx) - me.heading)
                rec.log_percept(
                    Percept(A, tick, tick - 2, seen, (SeenPlayer(1.2, 0.3, RIGHT, None),)), me
                )
            if tick == 25:
                rec.log_percept(Percept(B, tick, tick - 2, None), truth.players[B])
            if tick % 7 == 0:
                rec.log_events([ArenaEvent(tick, "command", f"dash 50 #{tick}", A)])
        rec.log_label(N_TICKS - 1, "GOAL", "ball over the right goal line")


@pytest.fixture(scope="module")
def run_file(tmp_path_factory: pytest.TempPathFactory) -> Path:
    path = tmp_path_factory.mktemp("rec") / "run.rrd"
    record_run(path)
    return path


def read_batches(path: Path, entity: str) -> list:
    from rerun.chunk import RrdReader

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        chunks = RrdReader(str(path)).stream().to_chunks()
    return [c.to_record_batch() for c in chunks if c.entity_path == entity]


def test_recording_verifies(run_file: Path) -> None:
    ok, message = verify_recording(run_file)
    assert ok, message
    assert "verified" in message


def test_ball_positions_read_back_in_time_order(run_file: Path) -> None:
    logged = np.array([[ball_at(k).x, ball_at(k).y] for k in range(N_TICKS)])
    got = read_entity_positions(run_file, "field/ball")
    assert got.shape == (N_TICKS, 2)
    # rerun stores Vec2D as float32: bit-identical to the float32 of what was logged.
    np.testing.assert_array_equal(got, logged.astype(np.float32).astype(np.float64))
    np.testing.assert_allclose(got, logged, rtol=0, atol=1e-6)


def test_sim_time_is_ticks_times_dt(run_file: Path) -> None:
    batches = read_batches(run_file, "/field/ball")
    ns = np.concatenate(
        [
            b.column("sim_time").cast("int64").to_numpy()
            for b in batches
            if "sim_time" in b.schema.names
        ]
    )
    ticks = np.concatenate(
        [b.column("tick").to_numpy() for b in batches if "tick" in b.schema.names]
    )
    order = np.argsort(ticks)
    np.testing.assert_array_equal(ticks[order], np.arange(N_TICKS))
    np.testing.assert_array_equal(
        ns[order], np.rint(np.arange(N_TICKS) * DT_S * 1e9).astype(np.int64)
    )


def test_players_one_entity_per_team_with_labels(run_file: Path) -> None:
    left = read_entity_positions(run_file, "/field/players/left")
    expected = np.array([[truth_at(k).players[A].x, 0.1] for k in range(N_TICKS)])
    np.testing.assert_allclose(left, expected, atol=1e-6)
    labels = [
        lab
        for b in read_batches(run_file, "/field/players/right")
        if "Points2D:labels" in b.schema.names
        for row in b.column("Points2D:labels").to_pylist()
        for lab in row
    ]
    assert labels == ["right2"] * N_TICKS
    origins = read_entity_positions(run_file, "field/players/right/heading")
    np.testing.assert_allclose(origins[:, 0], 0.7, atol=1e-6)


def test_perceived_ball_is_in_field_frame(run_file: Path) -> None:
    got = read_entity_positions(run_file, "field/perceived/left1/ball")
    expected = np.array([[ball_at(k).x, ball_at(k).y] for k in range(5, N_TICKS, 10)])
    np.testing.assert_allclose(got, expected, atol=1e-6)
    # B's percept saw no ball: an empty row, so nothing comes back.
    assert read_entity_positions(run_file, "field/perceived/right2/ball").shape == (0, 2)


def test_events_and_label_are_text(run_file: Path) -> None:
    commands = [
        t
        for b in read_batches(run_file, "/events/command")
        for row in b.column("TextLog:text").to_pylist()
        for t in row
    ]
    expected = [f"[command] left1: dash 50 #{k}" for k in range(0, N_TICKS, 7)]
    assert sorted(commands) == sorted(expected)
    labels = [
        t
        for b in read_batches(run_file, "/events/label")
        for row in b.column("TextLog:text").to_pylist()
        for t in row
    ]
    assert labels == ["GOAL: ball over the right goal line"]


def test_static_pitch_and_blueprint(run_file: Path) -> None:
    from rerun.chunk import RrdReader

    lines = read_batches(run_file, "/field/lines")
    assert lines and "sim_time" not in lines[0].schema.names
    strips = lines[0].column("LineStrips2D:strips").to_pylist()[0]
    assert [len(s) for s in strips] == [5, 2]
    assert strips[1][0] == [0.0, pytest.approx(-PITCH.half_width_m)]
    assert read_batches(run_file, "/field/goals/right")
    reader = RrdReader(str(run_file))
    assert [r.recording_id for r in reader.recordings()] == ["test-trial-0"]
    assert reader.blueprints(), "default blueprint missing"


def test_every_ticks_thins_the_truth(tmp_path: Path) -> None:
    path = tmp_path / "thin.rrd"
    record_run(path, every_ticks=5, chunk_frames=1000)
    got = read_entity_positions(path, "field/ball")
    expected = np.array([[ball_at(k).x, ball_at(k).y] for k in range(0, N_TICKS, 5)])
    np.testing.assert_allclose(got, expected, atol=1e-6)


def test_truncated_file_fails_verification(run_file: Path, tmp_path: Path) -> None:
    data = run_file.read_bytes()
    for cut in (16, len(data) // 2):  # footer only (the CLI alone accepts this) and mid-file
        bad = tmp_path / f"cut{cut}.rrd"
        bad.write_bytes(data[: len(data) - cut])
        ok, message = verify_recording(bad)
        assert not ok, (cut, message)
        assert message


def test_reader_fallback_without_cli(
    run_file: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setattr(rrd_files, "rerun_executable", lambda: tmp_path / "no-rerun")
    ok, message = verify_recording(run_file)
    assert ok, message
    bad = tmp_path / "bad.rrd"
    bad.write_bytes(run_file.read_bytes()[:-16])
    assert not verify_recording(bad)[0]


def test_unclosed_recording_fails_until_closed(tmp_path: Path) -> None:
    path = tmp_path / "open.rrd"
    rec = TrialRecorder(
        path, Scene(pitch=PITCH, players=(A,), dt_s=0.1, player_shape="circle"), recording_id="r"
    )
    rec.log_truth(truth_at(0))
    rec.close()
    rec.close()  # idempotent
    assert verify_recording(path)[0]
    with pytest.raises(RuntimeError):
        rec.log_truth(truth_at(1))


def test_bad_arguments() -> None:
    with pytest.raises(ValueError, match="player_shape"):
        outline_template("hexagon", 0.1)
    with pytest.raises(ValueError, match="every_ticks"):
        TrialRecorder(
            Path("unused.rrd"),
            Scene(pitch=PITCH, players=(), dt_s=0.1),
            recording_id="r",
            every_ticks=0,
        )


def test_outline_geometry() -> None:
    square = outline_template("square", 0.075)
    placed = place_outlines(square, np.array([[1.0, 2.0, math.pi / 2]]))[0]
    np.testing.assert_allclose(placed[0], [1.0 - 0.075, 2.0 + 0.075])
    np.testing.assert_array_equal(placed[0], placed[-1])
    circle = outline_template("circle", 0.3)
    np.testing.assert_allclose(np.hypot(circle[:, 0], circle[:, 1]), 0.3)
    x, y = egocentric_to_field(BodyState(1.0, 1.0, math.pi / 2), 2.0, math.pi / 2)
    assert (x, y) == (pytest.approx(-1.0), pytest.approx(1.0))


def test_import_does_not_load_rerun() -> None:
    code = "import sys, robotsoccer.replay.recording; print('rerun' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"


def test_replay_missing_file(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    assert replay(tmp_path / "nope.rrd") == 2
    err = capsys.readouterr().err
    assert "no such file" in err and len(err.strip().splitlines()) == 1


def test_replay_headless(
    run_file: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    monkeypatch.delenv("DISPLAY", raising=False)
    monkeypatch.delenv("WAYLAND_DISPLAY", raising=False)
    assert replay(run_file) == 0
    out = capsys.readouterr().out
    assert "no display" in out and "verified" in out
    # Commands that work without an active venv, and a viewer served to this machine only.
    exe = str(rrd_files.rerun_executable())
    assert f"{exe} --web-viewer --bind 127.0.0.1 {run_file}" in out
    assert f"{exe} {run_file}" in out


def test_replay_headless_bad_file(
    tmp_path: Path, run_file: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.delenv("DISPLAY", raising=False)
    monkeypatch.delenv("WAYLAND_DISPLAY", raising=False)
    bad = tmp_path / "bad.rrd"
    bad.write_bytes(run_file.read_bytes()[:200])
    assert replay(bad) == 1


def test_replay_with_display_spawns_viewer(run_file: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    calls: list[list[str]] = []

    class FakePopen:
        def __init__(self, args: list[str], **kwargs: object) -> None:
            calls.append(args)

    monkeypatch.setenv("DISPLAY", ":0")
    monkeypatch.setattr(rrd_files.subprocess, "Popen", FakePopen)
    assert replay(run_file) == 0
    assert calls == [[str(rrd_files.rerun_executable()), str(run_file)]]


# ----------------------------------------------------------------------------- what is drawn


def rows(path: Path, entity: str, column: str) -> list[tuple[int, list]]:
    """(tick, values) of every temporal row of `entity`'s `column`, in tick order."""
    out = [
        (tick, values)
        for b in read_batches(path, "/" + entity)
        if "tick" in b.schema.names and column in b.schema.names
        for tick, values in zip(
            b.column("tick").to_pylist(), b.column(column).to_pylist(), strict=True
        )
    ]
    return sorted(out, key=lambda row: row[0])


def static_value(path: Path, entity: str, column: str) -> list:
    """The static value of `entity`'s `column`."""
    for b in read_batches(path, "/" + entity):
        if "tick" not in b.schema.names and column in b.schema.names:
            return b.column(column).to_pylist()[0]
    raise AssertionError(f"no static {column} on {entity}")


def test_small_things_are_drawn_at_a_visible_minimum_size() -> None:
    server = draw_sizes(SERVER_PITCH)
    assert server.ball_enlarged and server.players_enlarged
    assert server.ball_m == pytest.approx(MIN_BALL_FRACTION * SERVER_PITCH.length_m)
    assert server.player_m == pytest.approx(MIN_PLAYER_FRACTION * SERVER_PITCH.length_m)
    table = draw_sizes(PITCH)  # the robot table: true sizes are large enough already
    assert not table.ball_enlarged and not table.players_enlarged
    assert (table.ball_m, table.player_m) == (PITCH.ball_radius_m, PITCH.player_radius_m)
    for sizes, pitch in ((server, SERVER_PITCH), (table, PITCH)):
        # Heading arrows reach past the body by a pitch-scaled length.
        assert sizes.arrow_length_m > sizes.player_m + 0.01 * pitch.length_m


def test_recording_draws_the_enlarged_sizes_and_says_so(tmp_path: Path) -> None:
    path = tmp_path / "server.rrd"
    with TrialRecorder(
        path,
        Scene(pitch=SERVER_PITCH, players=(A,), dt_s=0.1, player_shape="circle"),
        recording_id="r",
    ) as rec:
        rec.log_truth(truth_at(0))
    sizes = draw_sizes(SERVER_PITCH)
    assert static_value(path, "field/ball", "Points2D:radii") == [pytest.approx(sizes.ball_m)]
    assert static_value(path, "field/players/left", "Points2D:radii") == [
        pytest.approx(sizes.player_m)
    ]
    (_, legend), *_ = rows(path, "legend", "TextDocument:text")
    assert "drawn enlarged" in legend[0] and "8.5 cm" in legend[0]
    # The data stay true: the ball is where it was logged, whatever its drawn size.
    np.testing.assert_allclose(
        read_entity_positions(path, "field/ball"), [[ball_at(0).x, ball_at(0).y]], atol=1e-6
    )


def test_field_is_flipped_for_display_only(run_file: Path) -> None:
    # rerun's 2-D view draws y down; a scale of -1 on y at /field turns the field frame up.
    assert static_value(run_file, "field", "Transform3D:scale") == [[1.0, -1.0, 1.0]]
    got = read_entity_positions(run_file, "field/players/left")
    assert np.all(got[:, 1] > 0.0)  # left1 stays at y = +0.1 in the data


def test_pitch_markings_fit_the_pitch() -> None:
    for pitch in (PITCH, SERVER_PITCH):
        circle, *penalty = pitch_markings(pitch)
        radius = np.hypot(circle[:, 0], circle[:, 1])
        np.testing.assert_allclose(radius, radius[0])
        assert radius[0] < pitch.half_width_m
        assert len(penalty) == 2
        for area in penalty:
            assert np.all(np.abs(area[:, 1]) < pitch.half_width_m)
            assert np.all(np.abs(area[:, 1]).max() > 0.5 * pitch.goal_width_m)


def record_percepts(path: Path, percept_ticks: list[int], *, sensor_period_s: float | None) -> None:
    with TrialRecorder(
        path,
        Scene(pitch=PITCH, players=(A, B), dt_s=DT_S, sensor_period_s=sensor_period_s),
        recording_id="expiry",
    ) as rec:
        for tick in range(N_TICKS):
            truth = truth_at(tick)
            rec.log_truth(truth)
            if tick in percept_ticks:
                seen = (SeenPlayer(1.2, 0.3, RIGHT, 2),)
                rec.log_percept(Percept(A, tick, tick, SeenBall(0.5, 0.1), seen), truth.players[A])


def test_percepts_are_cleared_once_stale(tmp_path: Path) -> None:
    path = tmp_path / "expiry.rrd"
    # A period of 10 ticks: a percept stays current for 15 ticks.
    record_percepts(path, [5, 10, 30], sensor_period_s=10 * DT_S)
    for entity in ("field/perceived/left1/ball", "field/perceived/left1/players"):
        got = [(tick, len(centres)) for tick, centres in rows(path, entity, "Ellipses2D:centers")]
        # 10 + 15 = 25 < 30: cleared at 25; 30 + 15 = 45 within the run: cleared at 45.
        assert got == [(5, 1), (10, 1), (25, 0), (30, 1), (45, 0)], entity
    # Without a sensor period a percept stays until the next one.
    path = tmp_path / "no-expiry.rrd"
    record_percepts(path, [5, 10, 30], sensor_period_s=None)
    got = rows(path, "field/perceived/left1/ball", "Ellipses2D:centers")
    assert [tick for tick, _ in got] == [5, 10, 30]


def test_percept_current_at_the_end_is_kept(tmp_path: Path) -> None:
    path = tmp_path / "end.rrd"
    record_percepts(path, [40], sensor_period_s=10 * DT_S)  # current until 55 > last tick
    got = rows(path, "field/perceived/left1/ball", "Ellipses2D:centers")
    assert [(tick, len(c)) for tick, c in got] == [(40, 1)]


def test_percept_without_ball_clears_the_ball_ring_only(run_file: Path) -> None:
    got = rows(run_file, "field/perceived/right2/ball", "Ellipses2D:centers")
    assert [(tick, len(c)) for tick, c in got] == [(25, 0)]
    rings = rows(run_file, "field/perceived/left1/ball", "Ellipses2D:half_sizes")
    assert all(len(sizes) == 1 for _, sizes in rings)  # one size per ring, so none left over


def test_outcome_is_shown_on_the_field_from_the_verdict_on(run_file: Path) -> None:
    verdict = N_TICKS - 1
    text = "GOAL — ball over the right goal line"
    ((tick, labels),) = rows(run_file, "field/outcome/reason", "Points2D:labels")
    assert (tick, labels) == (verdict, [text])
    ((tick, strokes),) = rows(run_file, "field/outcome", "LineStrips2D:strips")
    assert tick == verdict and len(strokes) == len(
        text_strokes("GOAL", height_m=1.0, centre_x_m=0.0, base_y_m=0.0)
    )
    assert min(y for stroke in strokes for _, y in stroke) > PITCH.half_width_m  # above it
    ((tick, _),) = rows(run_file, "field/outcome/frame", "LineStrips2D:strips")
    assert tick == verdict
    legend = rows(run_file, "legend", "TextDocument:text")
    assert [tick for tick, _ in legend] == [0, verdict]
    assert "not yet decided" in legend[0][1][0] and legend[1][1][0].startswith(f"### {text}")


def test_text_strokes_are_centred_and_skip_unknown_characters() -> None:
    strokes = text_strokes("SAVE", height_m=6.0, centre_x_m=10.0, base_y_m=2.0)
    xy = np.concatenate(strokes)
    assert xy[:, 0].min() == pytest.approx(10.0 - 11.0) and xy[:, 0].max() == pytest.approx(21.0)
    assert xy[:, 1].min() == pytest.approx(2.0) and xy[:, 1].max() == pytest.approx(8.0)
    assert len(text_strokes("a?b", height_m=1.0, centre_x_m=0.0, base_y_m=0.0)) == len(
        text_strokes("AB", height_m=1.0, centre_x_m=0.0, base_y_m=0.0)
    )
    assert text_strokes("", height_m=1.0, centre_x_m=0.0, base_y_m=0.0) == []


def test_events_view_shows_the_message_body_first(run_file: Path) -> None:
    from rerun.blueprint.encodings import TextLogColumnKind
    from rerun.chunk import RrdReader

    reader = RrdReader(str(run_file))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        chunks = reader.stream(store=reader.blueprints()[0]).to_chunks()
    columns = [
        c.to_record_batch().column("TextLogColumns:text_log_columns").to_pylist()[0]
        for c in chunks
        if c.entity_path.endswith("/TextLogColumns")
    ]
    assert len(columns) == 1
    first = columns[0][0]
    assert first == {"visible": True, "kind": TextLogColumnKind.Body.value}
    origins = [
        origin
        for c in chunks
        if "ViewBlueprint:space_origin" in c.to_record_batch().schema.names
        for origin in c.to_record_batch().column("ViewBlueprint:space_origin").to_pylist()[0]
    ]
    # The field view's origin is the root, so the flip on /field applies to it.
    assert sorted(origins) == ["/", "/events", "/legend"]


# ----------------------------------------------------------------------------- file names


def test_recording_name_carries_the_outcome() -> None:
    assert recording_name(7, "GOAL") == "trial_0007_GOAL.rrd"
    assert recording_name(12, "a/b c") == "trial_0012_a_b_c.rrd"


@pytest.mark.parametrize("field_model", ["soccer_server", "robot_physics"])
def test_run_trial_names_its_recording_with_the_outcome(tmp_path: Path, field_model: str) -> None:
    spec = TrialSpec(
        drill="intercept", field_model=field_model, record_dir=str(tmp_path), record_trials=1
    )
    result = run_trial(spec, 0)
    assert sorted(p.name for p in tmp_path.iterdir()) == [f"trial_0000_{result.label}.rrd"]
    path = tmp_path / recording_name(0, result.label)
    assert verify_recording(path)[0]
    ((_, labels),) = rows(path, "field/outcome/reason", "Points2D:labels")
    assert labels == [f"{result.label} — {result.reason}"]
