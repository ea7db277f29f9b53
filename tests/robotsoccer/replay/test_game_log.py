"""A recorded match writes a rerun recording and (on the server's pitch) an .rcg game log;
``replay`` turns the game log into a recording of its own."""

from __future__ import annotations

from pathlib import Path

import pytest

from robotsoccer.replay.game_log import rrd_from_rcg
from robotsoccer.replay.rcg import read_rcg
from robotsoccer.replay.recording import read_entity_positions, verify_recording
from robotsoccer.runs.runner import TrialSpec, run_trial
from tests.robotsoccer.replay.test_match_recording import blueprint_values, read_chunks


def recorded(field: str, folder: Path, half_time_s: float = 1.0) -> tuple[Path, ...]:
    spec = TrialSpec(
        drill="match", field_model=field, seed=1, record_dir=str(folder), record_trials=1
    ).with_options(left="baseline", right="baseline", half_time_s=half_time_s)
    result = run_trial(spec, 0)
    return tuple(sorted(folder.glob(f"match_0000_{result.label}.*")))


def test_a_server_match_leaves_a_recording_and_a_game_log_that_agree(tmp_path: Path) -> None:
    files = recorded("soccer_server", tmp_path)
    assert [f.suffix for f in files] == [".rcg", ".rrd"]
    rcg, rrd = files
    assert verify_recording(rrd)[0]
    game = read_rcg(rcg)
    assert game.teams == ("baseline", "baseline")
    assert len(game.frames) == 21  # the kick-off frame and one per cycle of the 2 s match
    assert game.frames[0].play_mode == "kick_off_l"
    assert [f.tick for f in game.frames] == list(range(21))
    ball = read_entity_positions(rrd, "field/ball")
    last = game.frames[-1].truth.ball
    assert ball[-1] == pytest.approx((last.x, last.y), abs=1e-3)
    replayed = rrd_from_rcg(rcg)
    assert replayed.name == rcg.name + ".rrd" and replayed.exists()  # the match's .rrd is kept
    assert verify_recording(replayed)[0]
    assert read_entity_positions(replayed, "field/ball")[-1] == pytest.approx(ball[-1], abs=1e-3)


def test_a_robot_match_has_no_game_log(tmp_path: Path) -> None:
    files = recorded("robot_physics", tmp_path)
    assert [f.suffix for f in files] == [".rrd"]
    assert verify_recording(files[0])[0]


def event_lines(rrd: Path) -> dict[str, list[str]]:
    """Every text line under /events, by entity."""
    out: dict[str, list[str]] = {}
    for chunk in read_chunks(rrd):
        batch = chunk.to_record_batch()
        if chunk.entity_path.startswith("/events") and "TextLog:text" in batch.schema.names:
            rows = batch.column("TextLog:text").to_pylist()
            out.setdefault(chunk.entity_path, []).extend(t for row in rows for t in row)
    return out


def test_a_robot_matchs_default_event_log_holds_events_not_routine(tmp_path: Path) -> None:
    (rrd,) = recorded("robot_physics", tmp_path, half_time_s=5.0)
    lines = event_lines(rrd)
    hidden = [
        q[len("- ") :].removesuffix("/**")
        for q in blueprint_values(rrd, "ViewContents:query")
        if q.startswith("- /events")
    ]
    assert hidden == ["/events/routine"]
    shown = {entity: texts for entity, texts in lines.items() if entity not in hidden}
    # The followed player decides at every camera frame; those routine lines are recorded but
    # out of the default view, which keeps the referee's calls and the decisions that kick.
    assert any(t.endswith(": nothing") for t in lines["/events/routine"])
    assert all(not t.endswith("nothing") for texts in shown.values() for t in texts)
    assert all(t.startswith("[decision] ") for t in lines["/events/routine"])
    assert "[referee] kick_off_l" in shown["/events/referee"]
    kicks = [t for t in shown.get("/events/decision", []) if "(kick " in t or " -> " in t]
    assert kicks == shown.get("/events/decision", [])  # only kicks and passes remain there
