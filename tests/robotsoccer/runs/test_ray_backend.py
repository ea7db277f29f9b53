"""The Ray backend: the same results and the same table as the process pool, Ray or not."""

from __future__ import annotations

import sys

import pytest

from robotsoccer.drills import DRILLS
from robotsoccer.runs.pool import (
    manifest_path,
    read_results,
    run_chunk,
    run_trials,
    using_backend,
)
from robotsoccer.runs.ray_backend import IN_FLIGHT_PER_CPU, MISSING_RAY, execute_ray
from robotsoccer.runs.runner import TrialResult, TrialSpec

pytestmark = pytest.mark.ray  # a Ray instance per module: .ci/run keeps it apart

INTERCEPT = TrialSpec(drill="intercept", field_model="soccer_server", seed=3)
SHOOTOUT = TrialSpec(drill="shootout", field_model="robot_physics", seed=3)


def test_without_ray_the_ray_backend_fails_in_one_line_before_writing(
    tmp_path, monkeypatch
) -> None:
    monkeypatch.setitem(sys.modules, "ray", None)  # `import ray` now fails
    path = tmp_path / "results.csv"
    with pytest.raises(ValueError, match="needs Ray") as caught, using_backend("ray"):
        run_trials(INTERCEPT, 4, workers=2, results_path=path, progress=False)
    assert str(caught.value) == MISSING_RAY == "backend 'ray' needs Ray: pip install '.[ray]'"
    assert not path.exists() and not manifest_path(path).exists()


def test_an_unknown_backend_is_refused() -> None:
    with pytest.raises(ValueError, match="unknown backend 'dask'"), using_backend("dask"):
        run_trials(INTERCEPT, 2, workers=1, progress=False)


@pytest.fixture(scope="module")
def ray_instance():
    ray = pytest.importorskip("ray")
    ray.init(
        address="local",
        num_cpus=2,
        include_dashboard=False,
        log_to_driver=False,
        logging_level="WARNING",
    )
    yield ray
    ray.shutdown()


def rows(path) -> list[bytes]:
    """The table's data rows, byte for byte, by trial index (chunks land as they finish)."""
    header, *data = path.read_bytes().splitlines(keepends=True)
    assert header == (TrialResult.CSV_HEADER + "\n").encode()
    return sorted(data, key=lambda row: int(row.split(b",", 1)[0]))


@pytest.mark.parametrize(
    ("spec", "n"), [(INTERCEPT, 20), (SHOOTOUT, 6)], ids=["intercept", "shootout"]
)
def test_ray_gives_the_results_and_table_of_the_process_pool(
    ray_instance, tmp_path, spec: TrialSpec, n: int
) -> None:
    one = run_trials(spec, n, workers=1, progress=False)
    pool = run_trials(spec, n, workers=2, results_path=tmp_path / "pool.csv", progress=False)
    with using_backend("ray"):
        ray = run_trials(spec, n, workers=2, results_path=tmp_path / "ray.csv", progress=False)
    assert [r.index for r in ray] == list(range(n))
    assert ray == one == pool
    assert rows(tmp_path / "ray.csv") == rows(tmp_path / "pool.csv")
    assert (tmp_path / "ray.json").read_bytes() == (tmp_path / "pool.json").read_bytes()
    with using_backend("ray"):  # one chunk: the whole table byte for byte, row order included
        single = run_trials(
            spec, n, workers=2, results_path=tmp_path / "ray1.csv", progress=False, chunk_size=n
        )
    run_trials(spec, n, workers=1, results_path=tmp_path / "one.csv", progress=False)
    assert single == one
    assert (tmp_path / "ray1.csv").read_bytes() == (tmp_path / "one.csv").read_bytes()


def test_a_process_pool_table_is_resumed_on_ray(ray_instance, tmp_path) -> None:
    path = tmp_path / "results.csv"
    run_trials(INTERCEPT, 8, workers=2, results_path=path, progress=False)
    with using_backend("ray"):
        resumed = run_trials(
            INTERCEPT, 16, workers=2, results_path=path, resume=True, progress=False
        )
    assert resumed == run_trials(INTERCEPT, 16, workers=1, progress=False)
    assert read_results(path) == {r.index: r for r in resumed}


def test_stopping_early_cancels_the_tasks_still_out(ray_instance, monkeypatch) -> None:
    cancelled: list[object] = []
    real_cancel = ray_instance.cancel

    def cancel(ref, **kwargs):
        cancelled.append(ref)
        return real_cancel(ref, **kwargs)

    monkeypatch.setattr(ray_instance, "cancel", cancel)
    chunks = execute_ray(INTERCEPT, ([i] for i in range(40)), workers=2, run_chunk=run_chunk)
    assert len(next(chunks)) == 1
    chunks.close()  # what a Ctrl-C in run_trials does: the finally cancels the rest
    # The chunks still out, not all 40: those not finished by now (a finished one is not
    # cancelled: ray_backend._cancel says why).
    assert 1 <= len(cancelled) <= IN_FLIGHT_PER_CPU * 2 - 1
    monkeypatch.undo()
    with using_backend("ray"):
        again = run_trials(INTERCEPT, 4, workers=2, progress=False)
    assert again == run_trials(INTERCEPT, 4, workers=1, progress=False)


def test_an_error_inside_a_task_is_raised_as_itself(ray_instance, monkeypatch) -> None:
    """A drill this process knows and the Ray workers do not: the tasks raise."""
    monkeypatch.setitem(DRILLS, "boom", DRILLS["shootout"])
    spec = TrialSpec(drill="boom", field_model="robot_physics")
    with pytest.raises(ValueError, match="unknown drill 'boom'") as caught, using_backend("ray"):
        run_trials(spec, 8, workers=2, progress=False, chunk_size=1)
    assert type(caught.value) is ValueError  # not Ray's wrapper, whose first line is its pid


def test_using_backend_sends_every_run_inside_to_ray(ray_instance, monkeypatch) -> None:
    import robotsoccer.runs.ray_backend as ray_backend

    calls = []
    real = ray_backend.execute_ray

    def spy(*args, **kwargs):  # type: ignore[no-untyped-def]
        calls.append(args[2])
        yield from real(*args, **kwargs)

    monkeypatch.setattr(ray_backend, "execute_ray", spy)
    spec = TrialSpec(drill="intercept", field_model="soccer_server", seed=4)
    with using_backend("ray"):
        on_ray = run_trials(spec, 12, workers=2, progress=False)
    assert calls == [2]
    assert on_ray == run_trials(spec, 12, workers=1, progress=False)
    with using_backend("nowhere"), pytest.raises(ValueError, match="unknown backend"):
        run_trials(spec, 1, workers=1, progress=False)
