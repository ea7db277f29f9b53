"""Layer 3's study: the layer3 team in a match, training determinism, the report."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from field_models.protocol import PlayerRef
from learning.tpot import TpotTable, load_table, save_table
from robotsoccer.drills.match import MatchDrill, layer3_experiences
from robotsoccer.experiments.team_study import (
    EVERY_PLAN,
    TeamPlan,
    match_base,
    plan_for,
    run_team_study,
    train,
)
from robotsoccer.runs.provenance import file_digest
from robotsoccer.runs.runner import TrialSpec, build_trial, run_trial
from tests.robotsoccer.drills.test_passing import _tree_file
from tests.robotsoccer.skills.test_intercept import net_file

TINY = TeamPlan("tiny", 4, 2, 8.0, 0.5, 0.1, 2, 5.0, 2)
"""Two rounds of two short games; two-game series."""


def files(tmp_path: Path) -> tuple[Path, Path]:
    net = net_file(tmp_path / "net.npz", preset="soccer_server_1996")
    return net, _tree_file(tmp_path, "soccer_server")


def test_a_layer3_team_needs_a_table_of_its_size_and_reports_rewards_only_when_learning(
    tmp_path: Path,
) -> None:
    net, tree = files(tmp_path)
    with pytest.raises(ValueError, match="needs its table"):
        MatchDrill(left="layer3", net=str(net), tree=str(tree))
    with pytest.raises(ValueError, match="explore must be a number"):
        MatchDrill(left="layer3", net=str(net), tree=str(tree), tpot="t", explore="lots")
    small = save_table(TpotTable.empty(5), tmp_path / "five.npz")
    spec = TrialSpec(drill="match", field_model="soccer_server", seed=2).with_options(
        left="layer3", right="baseline", net=str(net), tree=str(tree), half_time_s=20.0
    )
    with pytest.raises(ValueError, match="5 positions, not 11"):
        run_trial(spec.with_options(tpot=str(small)), 0)
    table = save_table(TpotTable.empty(11), tmp_path / "eleven.npz")
    playing = run_trial(spec.with_options(tpot=str(table)), 0)
    assert playing.data == ()
    learning = run_trial(spec.with_options(tpot=str(table), learn=True, explore=0.5), 0)
    experiences = layer3_experiences(learning.data)
    assert experiences, "a 40 s game gives the layer-3 team at least one decision"
    assert all(team == "left" and 1 <= e.number <= 11 for team, e in experiences)
    assert all(-1.0 <= e.reward <= 1.0 for _, e in experiences)


def test_training_gives_the_same_tables_whatever_the_worker_count(tmp_path: Path) -> None:
    net, tree = files(tmp_path)
    base = match_base("soccer_server", None, 5, net, tree)
    one = train(base, TINY, tmp_path / "one", workers=1, log=lambda _: None)
    two = train(base, TINY, tmp_path / "two", workers=2, log=lambda _: None)
    assert one.table.n.sum() > 0, "the tiny plan must learn something to compare"
    assert np.array_equal(one.table.q, two.table.q) and np.array_equal(one.table.n, two.table.n)
    assert [g.goals_for for g in one.games] == [g.goals_for for g in two.games]
    saved = load_table(one.path)
    assert saved.digest() == one.table.digest()
    assert saved.provenance["games"] == 4 and saved.provenance["seed"] == 5
    assert len(saved.provenance["tree_digest"]) == 16


def test_the_study_writes_curves_table_and_both_series(tmp_path: Path) -> None:
    net, tree = files(tmp_path)
    base = match_base("soccer_server", None, 1, net, tree)
    plan = TeamPlan("tiny", 2, 2, 5.0, 0.5, 0.1, 2, 5.0, 1)
    report = run_team_study(base, plan, tmp_path / "study", workers=1, log=lambda _: None)
    text = report.read_text()
    assert "| training games | epsilon |" in text
    assert "Layer 3 against the layered team (2 games" in text
    assert "Layer 3 against the baseline team (2 games" in text
    assert (tmp_path / "study" / "series-vs-layered" / "layered_left" / "results.csv").exists()


def test_every_ball_training_is_the_same_whatever_the_worker_count_and_says_its_rule(
    tmp_path: Path,
) -> None:
    net, tree = files(tmp_path)
    base = match_base("soccer_server", None, 5, net, tree)
    plan = TeamPlan("tiny-every", 4, 2, 8.0, 0.5, 0.1, 2, 5.0, 2, True, 0.95)
    one = train(base, plan, tmp_path / "one", workers=1, log=lambda _: None)
    two = train(base, plan, tmp_path / "two", workers=2, log=lambda _: None)
    assert one.table.n.sum() > 0, "the tiny plan must learn something to compare"
    assert np.array_equal(one.table.q, two.table.q) and np.array_equal(one.table.n, two.table.n)
    saved = load_table(one.path).provenance["plan"]
    assert saved["every"] is True and saved["success"] == 0.95
    with pytest.raises(ValueError, match="success"):
        TeamPlan("bad", 4, 2, 8.0, 0.5, 0.1, 2, 5.0, 2, True, 1.5)


def test_the_horizon_window_trains_the_same_whatever_the_worker_count_and_is_recorded(
    tmp_path: Path,
) -> None:
    net, tree = files(tmp_path)
    base = match_base("soccer_server", None, 5, net, tree)
    choice = TeamPlan("tiny-every", 4, 2, 8.0, 0.5, 0.1, 2, 5.0, 2, True, 0.95)
    horizon = TeamPlan("tiny-every", 4, 2, 8.0, 0.5, 0.1, 2, 5.0, 2, True, 0.95, "horizon")
    one = train(base, horizon, tmp_path / "one", workers=1, log=lambda _: None)
    two = train(base, horizon, tmp_path / "two", workers=2, log=lambda _: None)
    assert one.table.n.sum() > 0, "the tiny plan must learn something to compare"
    assert np.array_equal(one.table.q, two.table.q) and np.array_equal(one.table.n, two.table.n)
    saved = load_table(one.path).provenance
    assert saved["plan"]["window"] == "horizon" and saved["reward_window"] == "horizon"
    old = train(base, choice, tmp_path / "old", workers=1, log=lambda _: None)
    assert load_table(old.path).provenance["plan"]["window"] == "choice"
    # the same games' first round, rewards closed differently: the tables differ
    assert not np.array_equal(old.table.q, one.table.q)


def test_plan_for_takes_the_window_and_refuses_an_unknown_one() -> None:
    assert plan_for(False, True) is EVERY_PLAN  # the default keeps the earlier study's plan
    plan = plan_for(False, True, "horizon")
    assert plan.window == "horizon" and plan.training_games == EVERY_PLAN.training_games
    assert plan.drill_options()["tpot_window"] == "horizon"
    with pytest.raises(ValueError, match="window must be one of choice, horizon"):
        plan_for(True, True, "episode")
    with pytest.raises(ValueError, match="tpot_window must be one of"):
        MatchDrill(left="baseline", tpot_window="episode")


def test_guard_and_loss_train_the_same_whatever_the_worker_count_and_are_recorded(
    tmp_path: Path,
) -> None:
    net, tree = files(tmp_path)
    base = match_base("soccer_server", None, 5, net, tree)
    horizon = TeamPlan("tiny-every", 4, 2, 8.0, 0.5, 0.1, 2, 5.0, 2, True, 0.95, "horizon")
    guarded = replace(horizon, guard=True, loss=0.5)
    assert "tpot_guard" not in horizon.drill_options()  # the earlier plans' specs unchanged
    assert guarded.drill_options().items() >= {"tpot_guard": True, "tpot_loss": 0.5}.items()
    one = train(base, guarded, tmp_path / "one", workers=1, log=lambda _: None)
    two = train(base, guarded, tmp_path / "two", workers=2, log=lambda _: None)
    assert one.table.n.sum() > 0, "the tiny plan must learn something to compare"
    assert np.array_equal(one.table.q, two.table.q) and np.array_equal(one.table.n, two.table.n)
    saved = load_table(one.path).provenance["plan"]
    assert saved["guard"] is True and saved["loss"] == 0.5
    with pytest.raises(ValueError, match="guard needs every"):
        replace(horizon, every=False, guard=True)
    with pytest.raises(ValueError, match="tpot_guard needs tpot_every"):
        MatchDrill(left="baseline", tpot_guard=True)


def test_a_losing_touch_closes_a_learning_match_s_rewards_with_the_penalty(tmp_path: Path) -> None:
    net, tree = files(tmp_path)
    table = save_table(TpotTable.empty(11), tmp_path / "eleven.npz")
    spec = TrialSpec(drill="match", field_model="soccer_server", seed=2).with_options(
        left="layer3", right="baseline", net=str(net), tree=str(tree), half_time_s=20.0,
        tpot=str(table), learn=True, explore=0.5, tpot_every=True, tpot_window="horizon",
    )  # fmt: skip
    penalised = spec.with_options(tpot_loss=1.0)
    plain = [e.reward for _, e in layer3_experiences(run_trial(spec, 0).data)]
    full = [e.reward for _, e in layer3_experiences(run_trial(penalised, 0).data)]
    # The same game (the penalty changes no kick): the same choices, and every reward the
    # opponents' touch closed lost up to the whole penalty.
    assert len(plain) == len(full) and plain
    assert all(f <= p + 1e-12 for p, f in zip(plain, full, strict=True))
    assert any(f < p - 0.1 for p, f in zip(plain, full, strict=True))


def test_layer3_can_take_its_features_from_a_tree_of_its_own(tmp_path: Path) -> None:
    net, tree = files(tmp_path)
    own = _tree_file(tmp_path / "own", "soccer_server")
    table = save_table(TpotTable.empty(11), tmp_path / "eleven.npz")
    spec = match_base("soccer_server", None, 2, net, tree).with_options(
        left="layer3", right="baseline", tpot=str(table), tpot_tree=str(own), half_time_s=5.0
    )
    rngs, drill, arena = build_trial(spec, 0)
    drill.setup(arena, rngs)
    minds = drill.minds(arena, rngs)
    assert isinstance(drill, MatchDrill)
    policy = drill.policies["left"]
    assert policy.evaluator is not minds[PlayerRef("left", 2)].evaluator  # the team keeps tree
    assert str(own) in drill.inputs()  # its digest is in the run's manifest
    plain = dict(spec.drill_options) | {"tpot_tree": ""}
    _, drill, _ = build_trial(replace(spec, drill_options=tuple(plain.items())), 0)
    assert str(own) not in drill.inputs()
    plan = TeamPlan("tiny-every", 2, 2, 8.0, 0.5, 0.1, 2, 5.0, 2, True, 0.5, "horizon")
    assert "tpot_tree" not in plan.drill_options()  # the earlier plans' specs unchanged
    chosen = replace(plan, features_tree=str(own))
    assert chosen.drill_options()["tpot_tree"] == str(own)
    trained = train(match_base("soccer_server", None, 5, net, tree), chosen, tmp_path / "t",
                    workers=1, log=lambda _: None)  # fmt: skip
    saved = load_table(trained.path).provenance
    assert saved["plan"]["features_tree"] == str(own)
    assert saved["features_tree_digest"] == file_digest(own)
