"""The match drill and its referees on both field models."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from field_models.protocol import LEFT, RIGHT, PlayerRef
from learning.datasets import write_npz
from learning.features import LEAD_FEATURE_NAMES, LEAD_TARGET_NAME
from robotsoccer.drills.match import MatchDrill, TeamKind
from robotsoccer.drills.referee import RESTART_DISTANCE_UNITS
from robotsoccer.runs.pool import run_trials
from robotsoccer.runs.runner import TrialSpec, build_trial, run_trial
from tests.robotsoccer.drills.test_passing import _tree_file
from tests.robotsoccer.skills.test_intercept import net_file


def baseline(field: str, half: float = 2.0, **options: object) -> TrialSpec:
    spec = TrialSpec(drill="match", field_model=field, seed=3)
    return spec.with_options(left="baseline", right="baseline", half_time_s=half, **options)


def started(spec: TrialSpec):  # type: ignore[no-untyped-def]
    rngs, drill, arena = build_trial(spec, 0)
    drill.setup(arena, rngs)
    drill.minds(arena, rngs)
    assert isinstance(drill, MatchDrill)
    return drill, arena


@pytest.mark.parametrize(("field", "per_side"), [("soccer_server", 11), ("robot_physics", 5)])
def test_each_field_gets_its_own_team_size_and_a_kick_off(field: str, per_side: int) -> None:
    drill, arena = started(baseline(field))
    assert len(arena.players) == 2 * per_side
    assert drill.referee is not None and drill.referee.play_mode == "kick_off_l"
    ball = arena.ball_state()
    assert (ball.x, ball.y) == (0.0, 0.0)
    for ref in arena.players:  # everyone in its own half at the kick-off
        x = arena.player_state(ref).x
        assert x <= 0.0 if ref.team == LEFT else x >= 0.0


@pytest.mark.parametrize("field", ["soccer_server", "robot_physics"])
def test_a_match_runs_to_full_time_with_half_time_and_consistent_measures(field: str) -> None:
    result = run_trial(baseline(field), 0)
    assert result.label in ("LEFT_WIN", "DRAW", "RIGHT_WIN")
    assert result.time_s == pytest.approx(4.0)
    m = dict(result.measures)
    assert m["possession_l"] + m["possession_r"] == pytest.approx(1.0)
    left, right = m["goals_l"], m["goals_r"]
    assert result.label == ("LEFT_WIN" if left > right else "RIGHT_WIN" if right > left else "DRAW")


def test_the_series_is_the_same_whatever_the_worker_count(tmp_path: Path) -> None:
    spec = baseline("soccer_server", half=1.0)
    one = run_trials(spec, 2, workers=1, progress=False)
    two = run_trials(spec, 2, workers=2, progress=False)
    assert [r.csv_row() for r in one] == [r.csv_row() for r in two]


def test_ball_over_a_side_line_is_a_kick_in_for_the_other_team() -> None:
    drill, arena = started(baseline("soccer_server"))
    referee = drill.referee
    assert referee is not None
    referee._restart_team = None  # play is on
    referee.play_mode = "play_on"
    toucher = PlayerRef(LEFT, 7)
    arena.place_player(toucher, 10.0, 33.0, 0.0)
    arena.place_ball(10.0, 33.5)
    referee.step(arena)
    assert referee.last_touch == toucher
    opponent = PlayerRef(RIGHT, 5)
    arena.place_player(opponent, 12.0, 30.0, 0.0)
    arena.place_ball(12.0, 35.0)
    referee.step(arena)
    assert referee.play_mode == "kick_in_r"
    ball = arena.ball_state()
    assert (ball.x, ball.y) == pytest.approx((12.0, 34.0))
    arena.step()
    referee.step(arena)  # the restart holds: the other team is kept away
    p = arena.player_state(toucher)
    assert ((p.x - 12.0) ** 2 + (p.y - 34.0) ** 2) ** 0.5 >= RESTART_DISTANCE_UNITS


def test_wide_of_the_goal_after_a_defender_is_a_corner_after_an_attacker_a_goal_kick() -> None:
    for last, mode in ((PlayerRef(RIGHT, 3), "corner_kick_l"), (PlayerRef(LEFT, 9), "goal_kick_r")):
        drill, arena = started(baseline("soccer_server"))
        referee = drill.referee
        assert referee is not None
        referee._restart_team = None
        referee.last_touch = last
        arena.place_player(last, 0.0, 30.0, 0.0)
        arena.place_ball(52.0, 20.0)
        referee.step(arena)
        arena.place_ball(54.0, 20.0)
        referee.step(arena)
        assert referee.play_mode == mode


def test_a_goal_scores_and_the_conceding_team_kicks_off() -> None:
    drill, arena = started(baseline("robot_physics"))
    referee = drill.referee
    assert referee is not None
    referee._restart_team = None
    half = arena.facts.pitch.half_length_m
    arena.place_ball(half - 0.01, 0.0)
    referee.step(arena)
    arena.place_ball(half + 0.05, 0.0)
    referee.step(arena)
    assert referee.score == [1, 0]
    assert referee.play_mode == "kick_off_r"
    assert arena.ball_state()[:2] == (0.0, 0.0)


def test_a_stuck_ball_on_the_table_is_dropped_on_a_free_ball_spot() -> None:
    drill, arena = started(baseline("robot_physics", half=60.0))
    referee = drill.referee
    assert referee is not None
    referee._restart_team = None
    pitch = arena.facts.pitch
    corner = (pitch.half_length_m - 0.03, pitch.half_width_m - 0.03)
    arena.place_ball(*corner)
    referee.step(arena)
    for _ in range(referee._stuck_ticks + 1):
        arena.step()
        referee.step(arena)
    assert "drop_ball" in [e.text for e in referee.drain()]
    ball = arena.ball_state()
    assert (ball.x, ball.y) == pytest.approx((0.25 * pitch.length_m, 0.25 * pitch.width_m))


def test_a_layered_team_needs_its_files_and_refuses_another_fields(tmp_path: Path) -> None:
    with pytest.raises(ValueError, match="needs a net and a tree"):
        MatchDrill(left="layered")
    net = net_file(tmp_path / "net.npz", preset="soccer_server_1996")
    tree = _tree_file(tmp_path, "soccer_server")
    spec = TrialSpec(drill="match", field_model="robot_physics").with_options(
        net=str(net), tree=str(tree), half_time_s=1.0
    )
    with pytest.raises(ValueError, match="transfer=true"):
        started(spec)
    server = TrialSpec(drill="match", field_model="soccer_server").with_options(
        net=str(net), tree=str(tree), half_time_s=1.0
    )
    result = run_trial(server, 0)
    assert result.label in MatchDrill.labels


def test_teams_of_one_kind_carry_their_side_in_every_output() -> None:
    drill, _ = started(baseline("soccer_server"))
    assert drill.team_names() == ("baseline (left)", "baseline (right)")
    assert drill.goalies() == (PlayerRef(LEFT, 1), PlayerRef(RIGHT, 1))
    result = run_trial(baseline("soccer_server", half=1.0), 0)
    assert result.reason.startswith("baseline (left) ") and result.reason.endswith(
        " baseline (right)"
    )
    mixed = MatchDrill(left="baseline", right="baseline")
    mixed.kinds[RIGHT] = TeamKind.LAYERED  # (a layered team's model files are not needed here)
    assert mixed.team_names() == ("baseline", "layered")  # two kinds: the names suffice


def test_a_server_match_frame_carries_the_command_counts() -> None:
    drill, arena = started(baseline("soccer_server"))
    frame = drill.game_frame(arena)
    assert frame.commands is not None and set(frame.commands) == set(arena.players)
    drill, arena = started(baseline("robot_physics"))
    assert drill.game_frame(arena).commands is None  # the robots' arena counts none


def lead_net_file(tmp_path: Path) -> Path:
    """A robot lead net (random weights): a turn-net file whose columns name the lead's."""
    turn = net_file(tmp_path / "turn.npz", preset="small_size_1997_arc", field="robot_physics")
    with np.load(turn, allow_pickle=False) as data:
        arrays = {k: data[k] for k in data.files if k != "metadata"}
        meta = json.loads(str(data["metadata"]))
    meta["schema"].update(feature_names=list(LEAD_FEATURE_NAMES), target_name=LEAD_TARGET_NAME)
    arrays["input_mean"] = np.array([0.5, 0.0, 0.55])  # metres and radians, as on the table
    arrays["input_scale"] = np.array([0.1, 0.2, 0.1])
    return write_npz(tmp_path / "lead.npz", arrays, meta)


def test_a_robot_match_with_a_lead_team_is_the_same_whatever_the_worker_count(
    tmp_path: Path,
) -> None:
    net = lead_net_file(tmp_path)
    tree = _tree_file(tmp_path, "robot_physics")
    spec = TrialSpec(
        drill="match", field_model="robot_physics", preset="small_size_1997_arc", seed=3
    ).with_options(net=str(net), tree=str(tree), half_time_s=3.0, transfer=True)
    one = run_trials(spec, 2, workers=1, progress=False)
    two = run_trials(spec, 2, workers=2, progress=False)
    assert [r.csv_row() for r in one] == [r.csv_row() for r in two]
    drill, _ = started(spec)
    minds = drill.minds_by_ref
    lead_team = [m for r, m in minds.items() if r.team == LEFT]
    assert all(m.lead is not None and m.setup.push_kick for m in lead_team)
    assert all(m.lead is None for r, m in minds.items() if r.team == RIGHT)


@pytest.mark.parametrize("client", ["see", "cycle"])
def test_net_domain_trained_gives_the_layered_team_the_guarded_net_only(
    tmp_path: Path, client: str
) -> None:
    from robotsoccer.skills.turn_policies import NetPolicy, TrainedDomainPolicy

    net = net_file(tmp_path / "net.npz", preset="soccer_server_1996")
    tree = _tree_file(tmp_path, "soccer_server")
    spec = TrialSpec(drill="match", field_model="soccer_server").with_options(
        net=str(net), tree=str(tree), half_time_s=1.0, client=client
    )
    for domain, kind in (("any", NetPolicy), ("trained", TrainedDomainPolicy)):
        drill, _ = started(spec.with_options(net_domain=domain))
        for ref, mind in drill.minds_by_ref.items():
            if ref.team == LEFT:  # the layered team
                assert isinstance(mind.interception, kind)
            else:
                assert mind.interception is None
