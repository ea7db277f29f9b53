"""The robot benchmark's figures: the engine beside the same world under ``space.step`` alone."""

from __future__ import annotations

import math

from field_models.robot_physics.bench import bench_arena, chipmunk_realtime_factor, share_figures


def test_share_figures_measure_engine_and_bare_world() -> None:
    figures = share_figures(2, 0.2, repeats=1)
    assert set(figures) == {"engine", "chipmunk", "share"}
    assert all(v > 0 and math.isfinite(v) for v in figures.values())
    assert math.isclose(figures["share"], figures["engine"] / figures["chipmunk"])


def test_bare_world_is_the_benchmark_world() -> None:
    arena = bench_arena(4)
    assert len(arena.world.space.bodies) == len(bench_arena(4).world.space.bodies)
    assert chipmunk_realtime_factor(4, 0.1) > 0


def test_drive_control_moves_a_robot_under_space_step_alone() -> None:
    world = bench_arena(2).world
    x0 = world.robot_pose(0)[0]
    world.drive_control(0, 0.5, 0.0, 0.0)
    for _ in range(240):
        world.space.step(world.dt_s)
    x1 = world.robot_pose(0)[0]
    assert x1 - x0 > 0.2  # pulled along x by its grip-limited pivot (it may meet a wall)
