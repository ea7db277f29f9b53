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
from robotsoccer.replay import recording
from robotsoccer.replay.recording import (
    TrialRecorder,
    egocentric_to_field,
    outline_template,
    place_outlines,
    read_entity_positions,
    replay,
    verify_recording,
)

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
        pitch=PITCH,
        players=(A, B),
        dt_s=DT_S,
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
    assert sorted(commands) == sorted(f"left1: dash 50 #{k}" for k in range(0, N_TICKS, 7))
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
    monkeypatch.setattr(recording, "rerun_executable", lambda: tmp_path / "no-rerun")
    ok, message = verify_recording(run_file)
    assert ok, message
    bad = tmp_path / "bad.rrd"
    bad.write_bytes(run_file.read_bytes()[:-16])
    assert not verify_recording(bad)[0]


def test_unclosed_recording_fails_until_closed(tmp_path: Path) -> None:
    path = tmp_path / "open.rrd"
    rec = TrialRecorder(
        path, pitch=PITCH, players=(A,), dt_s=0.1, recording_id="r", player_shape="circle"
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
            Path("unused.rrd"), pitch=PITCH, players=(), dt_s=0.1, recording_id="r", every_ticks=0
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
    assert "no display" in out and "--web-viewer" in out and "verified" in out


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
    monkeypatch.setattr(recording.subprocess, "Popen", FakePopen)
    assert replay(run_file) == 0
    assert calls == [[str(recording.rerun_executable()), str(run_file)]]
