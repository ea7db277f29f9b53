"""Closing the transfer gap: fine-tuning curve and domain randomisation (issue 10, item 4)."""

from __future__ import annotations

import dataclasses
import tomllib
from pathlib import Path

import numpy as np
import pytest

from field_models.presets import PresetError
from field_models.registry import field_facts
from learning.interception import InterceptionModel
from robotsoccer.cli import server_ranges_covering_robots
from robotsoccer.experiments.context import RunContext
from robotsoccer.experiments.gap_closing import (
    GapPlan,
    domain_randomised_net,
    fine_tuning_curve,
    gap_plan,
)
from robotsoccer.experiments.gap_report import gap_markdown, plot_curve
from robotsoccer.experiments.gap_variants import (
    ParameterRange,
    Randomisation,
    draw_variants,
    variant_text,
    write_variants,
)
from robotsoccer.experiments.layer1_collect import collect
from robotsoccer.experiments.layer1_plan import base_spec, plan_for, seeds_for
from robotsoccer.experiments.transfer import run_transfer
from robotsoccer.experiments.transfer_study import references
from tests.robotsoccer.experiments.test_transfer import MODELS, nets

SERVER = MODELS[0]
ROBOTS = MODELS[1]


def test_a_range_draws_inside_its_bounds_and_rounds_to_its_step() -> None:
    rng = np.random.default_rng(0)
    plain = ParameterRange("dynamics.player_decay", 0.4, 0.8)
    log = ParameterRange("dynamics.dash_power_rate_m_per_cycle2", 0.001, 0.01, log=True)
    step = ParameterRange("sensing.send_step_ms", 150, 300, step=50)
    draws = [(plain.draw(rng), log.draw(rng), step.draw(rng)) for _ in range(400)]
    assert all(0.4 <= a <= 0.8 and 0.001 <= b <= 0.01 for a, b, _ in draws)
    assert {c for _, _, c in draws} == {150, 200, 250, 300}
    assert all(isinstance(c, int) for _, _, c in draws)
    # Log-uniform: as many draws below the geometric mean as above.
    below = sum(b < 0.001 * 10**0.5 for _, b, _ in draws)
    assert 150 < below < 250


@pytest.mark.parametrize(
    "bad",
    [
        dict(key="player_decay", low=0.1, high=0.2),
        dict(key="a.b.c", low=0.1, high=0.2),
        dict(key="a.b", low=0.3, high=0.2),
        dict(key="a.b", low=0.0, high=0.2, log=True),
        dict(key="a.b", low=0.1, high=0.2, step=0.0),
        dict(key="a.b", low=float("nan"), high=0.2),
    ],
)
def test_a_wrong_range_is_refused(bad: dict[str, object]) -> None:
    with pytest.raises(ValueError):
        ParameterRange(**bad)  # type: ignore[arg-type]


def test_a_randomisation_refuses_no_variants_and_a_key_drawn_twice() -> None:
    r = ParameterRange("dynamics.player_decay", 0.4, 0.8)
    with pytest.raises(ValueError):
        Randomisation("soccer_server_1996", (r,), variants=0)
    with pytest.raises(ValueError):
        Randomisation("soccer_server_1996", (r, r))


def test_variants_depend_on_the_seed_only_and_load_as_presets(tmp_path: Path) -> None:
    randomisation = Randomisation("soccer_server_1996", server_ranges_covering_robots(), 3)
    assert draw_variants(randomisation, 5) == draw_variants(randomisation, 5)
    assert draw_variants(randomisation, 5) != draw_variants(randomisation, 6)
    paths = write_variants(randomisation, tmp_path, 5)
    for path, values in zip(paths, draw_variants(randomisation, 5), strict=True):
        table = tomllib.loads(path.read_text())
        assert table["base"] == "soccer_server_1996"
        assert table["dynamics"]["player_decay"] == values["dynamics.player_decay"]
        facts = field_facts("soccer_server", str(path))
        assert facts.sensor_period_s == pytest.approx(values["sensing.send_step_ms"] / 1000)
        assert facts.unit_m == 1.0  # the pitch is the base's: distances stay in drill units


def test_a_variant_with_an_unknown_key_is_refused_naming_it(tmp_path: Path) -> None:
    path = tmp_path / "bad.toml"
    path.write_text(variant_text("soccer_server_1996", {"dynamics.player_sise_m": 1.0}, "typo"))
    with pytest.raises(PresetError, match="player_sise_m"):
        field_facts("soccer_server", str(path))


def test_the_quick_plan_keeps_sizes_within_the_net(tmp_path: Path) -> None:
    plan = gap_plan(plan_for(True), quick=True)
    assert max(plan.sizes) <= plan.net_examples and plan.eval_trials == 200
    assert gap_plan(plan_for(False), quick=False).sizes == GapPlan.sizes


@pytest.fixture(scope="module")
def matrix(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, dict[str, Path], list]:
    folder = tmp_path_factory.mktemp("gap")
    plan = dataclasses.replace(plan_for(True), eval_trials=16)
    trained = nets(folder)
    cells = run_transfer(MODELS, trained, plan, RunContext(folder, seeds_for(0), 1))
    return folder, trained, cells


def test_the_curve_pairs_scratch_and_tuned_nets_with_the_matrix(matrix) -> None:
    folder, trained, cells = matrix
    seeds = seeds_for(0)
    layer1 = dataclasses.replace(plan_for(True), collect_saves=12, collect_batch=200)
    dataset, _, _ = collect(
        base_spec(*ROBOTS, seeds.collection, "hold"),
        layer1,
        folder / "robot_results",
        folder / "robot_train.npz",
        1,
        "tests",
    )
    plan = GapPlan(sizes=(5, 10), fine_tune_epochs=5, epochs=20, eval_trials=16)
    unit_m = field_facts(*ROBOTS).unit_m
    lines: list[str] = []
    ctx = RunContext(folder, seeds, 1, lines.append)
    curve = fine_tuning_curve(trained["soccer_server"], ROBOTS, dataset, unit_m, plan, ctx)
    assert [p.examples for p in curve] == [5, 10]
    refs = references(cells, "soccer_server", "robot_physics")
    for p in curve:
        assert [r.index for r in p.tuned] == [r.index for r in refs.native] == list(range(16))
    tuned = InterceptionModel.load(folder / "gap" / "fine_tuning" / "tuned" / "net_10.npz")
    assert tuned.n_train_ == 10 and tuned.provenance_ is not None
    assert tuned.provenance_.field_model == "robot_physics"
    assert tuned.feature_schema_.distance_scale_m == pytest.approx(unit_m)
    assert "fine_tuned_from" in tuned.provenance_.extra
    plot = plot_curve(refs, curve, folder / "plots" / "fine_tuning.png")
    assert plot is not None and plot.stat().st_size > 1000
    text = gap_markdown(refs, curve, None, None, plan, plot)
    assert "| 5 |" in text and "| 10 |" in text and "fine_tuning.png" in text


def test_the_randomised_net_pools_every_variant_and_is_tested_on_both_fields(matrix) -> None:
    folder, _, cells = matrix
    ranges = server_ranges_covering_robots()
    randomisation = Randomisation("soccer_server_1996", ranges, variants=2)
    plan = GapPlan(epochs=20, net_examples=8, eval_trials=16)
    ctx = RunContext(folder, seeds_for(0), 1)
    net = domain_randomised_net(SERVER, ROBOTS, randomisation, plan, ctx)
    assert net.saves_per_variant == 4 and len(net.variants) == 2
    assert {k: len(v) for k, v in net.results.items()} == {"robot_physics": 16, "soccer_server": 16}
    model = InterceptionModel.load(net.path)
    assert model.n_train_ == 8 and model.provenance_ is not None
    extra = model.provenance_.extra
    assert extra["variants"] == 2 and "variant_1.dynamics.player_decay" in extra
    refs = references(cells, "soccer_server", "robot_physics")
    text = gap_markdown(refs, [], net, randomisation, plan)
    assert "### Domain randomisation" in text and "`dynamics.player_size_m`" in text
    assert "| randomised |" in text
