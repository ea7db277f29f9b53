"""The robot benchmark's figures: the engine beside the time its own Chipmunk steps take."""

from __future__ import annotations

import math
from typing import Any

from field_models.benchmarks import ChaseLoad, drive
from field_models.robot_physics.bench import (
    bench_arena,
    benchmarks,
    chipmunk_realtime_factor,
    share_figures,
    step_realtime_factor,
)


def test_share_figures_measure_engine_and_chipmunk() -> None:
    figures = share_figures(2, 0.2, repeats=1)
    assert set(figures) == {"engine", "chipmunk", "share", "step_share"}
    assert all(v > 0 and math.isfinite(v) for v in figures.values())
    assert math.isclose(figures["share"], figures["engine"] / figures["chipmunk"])
    assert chipmunk_realtime_factor(4, 0.3) > 0
    assert step_realtime_factor(4, 0.1) > 0


def test_bench_reports_the_share_beside_the_absolute_figures(monkeypatch: Any) -> None:
    import field_models.robot_physics.bench as bench

    fake = {"engine": 100.0, "chipmunk": 400.0, "share": 0.25, "step_share": 0.1}
    monkeypatch.setattr(bench, "share_figures", lambda *_: fake)
    figures = benchmarks(quick=True)
    assert figures["share_of_chipmunk"] == {"2_robots": 0.25, "12_robots": 0.25}
    assert figures["realtime_factor"]["12_robots"] == 100.0
    assert figures["chipmunk_realtime_factor"]["2_robots"] == 400.0
    assert figures["step_share"]["2_robots"] == 0.1


def test_timing_the_steps_leaves_the_run_as_it_was() -> None:
    plain, timed = bench_arena(4), bench_arena(4)
    raw = timed.world.space_step
    calls = []

    def wrapped(space: Any, dt: float) -> None:
        calls.append(dt)
        raw(space, dt)

    timed.world.space_step = wrapped
    for arena in (plain, timed):
        drive(arena, {ref: ChaseLoad() for ref in arena.players}, 480)
    assert len(calls) == 480
    assert plain.truth() == timed.truth()
