"""A recorded match writes a rerun recording and (on the server's pitch) an .rcg game log;
``replay`` turns the game log into a recording of its own."""

from __future__ import annotations

from collections import Counter
from pathlib import Path

import pytest

from field_models.protocol import LEFT, RIGHT, Action, PlayerRef
from robotsoccer.replay.game_log import rrd_from_rcg
from robotsoccer.replay.rcg_read import read_rcg
from robotsoccer.replay.rrd_files import read_entity_positions, verify_recording
from robotsoccer.runs.runner import TrialSpec, run_trial
from tests.robotsoccer.replay.test_match_recording import blueprint_values, read_chunks
from tests.robotsoccer.replay.test_rcg import show_players


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
    assert game.teams == ("baseline_left", "baseline_right")  # one kind: the sides tell them
    assert [f.tick for f in game.frames] == list(range(1, 21))  # from cycle 1, as a server
    assert game.frames[0].play_mode == "kick_off_l"
    assert game.frames[-1].play_mode == "time_over"
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


def test_a_server_game_log_counts_the_commands_the_server_carried_out(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    from field_models.arena import COMMAND_COUNTERS
    from field_models.soccer_server.dynamics import SoccerServerModel

    carried: Counter[tuple[int, str]] = Counter()  # (model row, command)
    took: set[tuple[int, int]] = set()  # (cycle, model row) of kicks that reached the ball
    command, do_kick = SoccerServerModel.command, SoccerServerModel._do_kick

    def counting(self: SoccerServerModel, i: int, action: Action) -> bool:
        accepted = command(self, i, action)
        if accepted:
            carried[(i, type(action).__name__.lower())] += 1
        return accepted

    def kicking(self: SoccerServerModel, i: int, power: float, d: float, r: int) -> bool:
        hit = do_kick(self, i, power, d, r)
        if hit:
            took.add((self.cycle + 1, i))
        return hit

    monkeypatch.setattr(SoccerServerModel, "command", counting)
    monkeypatch.setattr(SoccerServerModel, "_do_kick", kicking)
    rcg, _ = recorded("soccer_server", tmp_path, half_time_s=15.0)
    shows = [line for line in rcg.read_text().splitlines() if line.startswith("(show ")]
    players = [PlayerRef(t, n) for t in (LEFT, RIGHT) for n in range(1, 12)]  # model rows 1..22
    last = show_players(shows[-1])
    assert sum(int(c) for m in last for c in m["counts"].split()) > 0
    for row, m in enumerate(last, start=1):
        counts = dict(zip(COMMAND_COUNTERS, map(int, m["counts"].split()), strict=True))
        for name in ("kick", "dash", "turn"):
            assert counts[name] == carried[(row, name)], (players[row - 1], name)
        assert counts["catch"] == counts["move"] == counts["tackle"] == 0
    # The kick flag marks each cycle's kicks that reached the ball, and the goalies carry 0x8.
    flagged = set()
    for line in shows:
        cycle = int(line.split(" ", 2)[1])
        for row, m in enumerate(show_players(line), start=1):
            state = int(m["state"], 16)
            assert bool(state & 0x8) == (players[row - 1].number == 1)
            if state & 0x2:
                flagged.add((cycle, row))
    assert flagged == took and took
