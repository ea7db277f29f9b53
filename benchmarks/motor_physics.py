"""The motor drive's physics against the kinematic drive's on the same commands (issue 21 item 1).

One robot on an empty 20 × 20 m table (no walls in reach), driven by wheel targets given
straight to the world, under ``robot.drive = "kinematic"`` and ``"motor"`` and beside the exact
unicycle integration of the ramped wheel speeds (``tests/field_models/robot_physics/
test_world.py``'s closed form). Prints one JSON object: per case, each drive's figures.

    python benchmarks/motor_physics.py [--preset small_size_1997]
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import math
from typing import Any

from field_models.protocol import LEFT, PlayerRef
from field_models.robot_physics.config import RobotPhysicsPreset, load_preset
from field_models.robot_physics.motor import make_world
from field_models.robot_physics.world import RobotWorld

ARCS = ((0.3, 0.5), (1.0, 1.2), (0.6, 0.2), (0.8, 1.2), (-0.3, 0.3), (-1.2, 1.2), (1.2, 1.2))
"""Held wheel targets (left, right) [m/s] from rest, 2 s each."""


def _world(preset: RobotPhysicsPreset, drive: str) -> RobotWorld:
    robot = dataclasses.replace(preset.robot, drive=drive)
    big = dataclasses.replace(preset.field, length_m=20.0, width_m=20.0)
    world = make_world(dataclasses.replace(preset, robot=robot, field=big), (PlayerRef(LEFT, 1),))
    world.place_robot(0, 0.0, 0.0, 0.0)
    world.place_ball(9.0, 9.0)
    return world


def unicycle(preset: RobotPhysicsPreset, plan: list[tuple[float, float, int]]) -> dict[str, float]:
    """Exact unicycle pose of the ramped wheel speeds of `plan` ((left, right, ticks) legs)."""
    r, dt, fine = preset.robot, preset.dt_s, 20
    ramp, h = r.wheel_accel_mps2 * dt, dt / fine
    x = y = th = left = right = 0.0
    for vl, vr, ticks in plan:
        for _ in range(ticks):
            left += max(-ramp, min(ramp, vl - left))
            right += max(-ramp, min(ramp, vr - right))
            v, w = 0.5 * (left + right), (right - left) / r.track_m
            for _ in range(fine):
                x += v * math.cos(th + 0.5 * w * h) * h
                y += v * math.sin(th + 0.5 * w * h) * h
                th += w * h
    return {"x": x, "y": y, "heading": th}


def run(world: RobotWorld, plan: list[tuple[float, float, int]]) -> dict[str, Any]:
    """Drive `plan`; the final pose, peak acceleration and peak sideways speed."""
    prev, peak_accel, peak_side, turned = world.robot_state(0), 0.0, 0.0, 0.0
    for vl, vr, ticks in plan:
        world.set_wheel_targets(0, vl, vr)
        for _ in range(ticks):
            world.step()
            s = world.robot_state(0)
            accel = math.hypot(s.vx - prev.vx, s.vy - prev.vy) / world.dt_s
            peak_accel = max(peak_accel, accel)
            side = -s.vx * math.sin(s.heading) + s.vy * math.cos(s.heading)
            peak_side = max(peak_side, abs(side))
            turned += math.remainder(s.heading - prev.heading, 2 * math.pi)
            prev = s
    return {
        "x": prev.x,
        "y": prev.y,
        "heading": turned,
        "speed": math.hypot(prev.vx, prev.vy),
        "peak_accel": peak_accel,
        "peak_side_speed": peak_side,
    }


def stop_case(preset: RobotPhysicsPreset, drive: str) -> dict[str, float]:
    """Full speed ahead for 1 s, then stop: time to top speed, stop distance and time."""
    world = _world(preset, drive)
    top = preset.robot.max_wheel_speed_mps
    world.set_wheel_targets(0, top, top)
    reach = None
    for tick in range(1, round(1.0 / world.dt_s) + 1):
        world.step()
        if reach is None and world.robot_state(0).speed >= 0.999 * top:
            reach = tick * world.dt_s
    start = world.robot_state(0).x
    world.set_wheel_targets(0, 0.0, 0.0)
    ticks = 0
    while world.robot_state(0).speed > 1e-6 and ticks < 10_000:
        world.step()
        ticks += 1
    return {
        "time_to_top_s": reach if reach is not None else math.nan,
        "top_speed_mps": top,
        "stop_distance_m": world.robot_state(0).x - start,
        "stop_time_s": ticks * world.dt_s,
    }


def compare(preset: RobotPhysicsPreset) -> dict[str, Any]:
    """Every case under both drives, with the closed form where there is one."""
    ticks = round(2.0 / preset.dt_s)
    out: dict[str, Any] = {}
    for vl, vr in ARCS:
        plan = [(vl, vr, ticks)]
        exact = unicycle(preset, plan)
        row: dict[str, Any] = {"closed_form": exact}
        for drive in ("kinematic", "motor"):
            got = run(_world(preset, drive), plan)
            got["position_error_m"] = math.hypot(got["x"] - exact["x"], got["y"] - exact["y"])
            got["heading_error_rad"] = got["heading"] - exact["heading"]
            row[drive] = got
        out[f"wheels {vl:+.1f} {vr:+.1f}, 2 s"] = row
    spiral = [(1.2, 1.2, ticks // 4), (-1.2, 1.2, ticks // 4), (0.6, 1.2, ticks // 2)]
    exact = unicycle(preset, spiral)
    row = {"closed_form": exact}
    for drive in ("kinematic", "motor"):
        got = run(_world(preset, drive), spiral)
        got["position_error_m"] = math.hypot(got["x"] - exact["x"], got["y"] - exact["y"])
        got["heading_error_rad"] = got["heading"] - exact["heading"]
        row[drive] = got
    out["dash 0.5 s, spin 0.5 s, arc 1 s"] = row
    out["full speed then stop"] = {d: stop_case(preset, d) for d in ("kinematic", "motor")}
    return out


def main() -> None:
    """Print the comparison as JSON (module docstring)."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--preset", default="small_size_1997")
    args = parser.parse_args()
    print(json.dumps(compare(load_preset(args.preset)), indent=1))


if __name__ == "__main__":
    main()
