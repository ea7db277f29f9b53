"""The batched interception drill gives exactly the one-trial path's results, trial by trial."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
import pytest

from learning.lookup import LookupTable
from robotsoccer.drills.intercept_batch import batch_reason, run_intercept_batch
from robotsoccer.runs.pool import batched, run_chunk, run_trials
from robotsoccer.runs.runner import TrialResult, TrialSpec, run_trial
from tests.robotsoccer.skills.test_intercept import net_file

N = 60


def both(spec: TrialSpec, n: int = N, batch_size: int = 16) -> tuple[list[TrialResult], ...]:
    one = [run_trial(spec, i) for i in range(n)]
    return one, run_intercept_batch(spec, list(range(n)), batch_size=batch_size)


def spec(seed: int = 2, **options: str | float | bool) -> TrialSpec:
    return TrialSpec(drill="intercept", field_model="soccer_server", seed=seed).with_options(
        transfer=True, **options
    )


@pytest.fixture(scope="module")
def models(tmp_path_factory: pytest.TempPathFactory) -> dict[str, str]:
    folder = tmp_path_factory.mktemp("models")
    grid = [float(a) for a in np.radians(np.arange(-40, 41, 10))]
    table = LookupTable(grid, [-2.0 * a for a in grid]).save(folder / "table.json")
    net = net_file(folder / "net.npz", seed=3, preset="soccer_server_1996")
    return {"net": str(net), "lookup": str(table)}


@pytest.mark.parametrize("behaviour", ["still", "straight", "random", "net", "lookup", "analytic"])
@pytest.mark.parametrize("ta_mode", ["hold", "every_see"])
def test_every_behaviour_gives_the_one_trial_results(
    behaviour: str, ta_mode: str, models: dict[str, str]
) -> None:
    model = models.get(behaviour, "")
    one, many = both(spec(behaviour=behaviour, model=model, ta_mode=ta_mode))
    assert many == one
    assert len({r.label for r in one}) > 1  # not a degenerate drill
    if behaviour != "still":
        assert sum(bool(r.data) for r in one) > N // 2  # the defender decided in most trials


@pytest.mark.parametrize(
    "field",
    [
        {"ball_noise": 0.0},
        {"ball_noise": 0.05},
        {"ball_noise": 0.2},
        {"perfect_perception": True},
        {"perfect_perception": True, "ball_noise": 0.1},
    ],
)
def test_every_noise_level_gives_the_one_trial_results(field: dict[str, float | bool]) -> None:
    one, many = both(spec(behaviour="analytic").with_field(**field))
    assert many == one


@pytest.mark.parametrize(
    "options",
    [
        {"launch": "coach", "behaviour": "random"},
        {"aim_offset_deg": 4.0, "kick_power": 80.0},
        {"sector_deg": 80.0, "max_time_s": 1.7},  # wide shots, and time-outs
    ],
)
def test_drill_options_give_the_one_trial_results(options: dict[str, str | float]) -> None:
    one, many = both(spec(**options))
    assert many == one


def test_todays_server_gives_the_one_trial_results() -> None:
    # rcssserver 19: 150 ms sees, so a new decision can cut the previous one's dash.
    one, many = both(dataclasses.replace(spec(behaviour="random"), preset="rcssserver_19_async"))
    assert many == one


def test_results_do_not_depend_on_the_batch_size_or_the_order_of_indices() -> None:
    s = spec(behaviour="random")
    indices = [7, 3, 100, 0, 41, 5, 6]
    alone = [run_intercept_batch(s, [i], batch_size=1)[0] for i in indices]
    assert run_intercept_batch(s, indices, batch_size=3) == alone
    assert [r.index for r in alone] == indices


def test_what_the_batch_cannot_run_is_named() -> None:
    assert batch_reason(spec()) is None
    assert "kick" in (batch_reason(spec(defender_kick=True)) or "")
    robots = TrialSpec(drill="intercept", field_model="robot_physics")
    assert "robot_physics model has no batch form" in (batch_reason(robots) or "")
    assert "intercept" in (batch_reason(TrialSpec(drill="pass", field_model="soccer_server")) or "")
    with pytest.raises(ValueError, match="kick"):
        run_intercept_batch(spec(defender_kick=True), [0])


def test_a_model_from_another_field_is_refused_without_transfer(tmp_path: Path) -> None:
    net = str(net_file(tmp_path / "net.npz"))  # made on preset "p": not this field
    s = TrialSpec(drill="intercept", field_model="soccer_server").with_options(
        behaviour="net", model=net
    )
    with pytest.raises(ValueError, match="transfer=true"):
        run_intercept_batch(s, [0])


def test_the_pool_runs_the_batch_with_the_one_trial_results_whatever_the_workers(
    tmp_path: Path,
) -> None:
    s = spec(behaviour="random")
    assert batched(s) and not batched(TrialSpec(drill="intercept", field_model="robot_physics"))
    one = [run_trial(s, i) for i in range(30)]
    assert run_trials(s, 30, workers=1, progress=False) == one
    table = tmp_path / "r.csv"
    two = run_trials(s, 30, workers=2, chunk_size=7, progress=False, results_path=table)
    assert two == one
    recorded = dataclasses.replace(s, record_dir=str(tmp_path / "rec"), record_trials=2)
    assert [r.label for r in run_chunk(recorded, [0, 1, 2])] == [r.label for r in one[:3]]
    assert len(list((tmp_path / "rec").glob("*.rrd"))) == 2  # recorded on the one-trial path
