"""One fixed robot workload per process: what a whole-process CPU comparison of two trees times.

Issue 21's speed-ups are compared by running the same workload under the old and the new tree,
one process each, alternating, and taking the ratio of their CPU seconds pair by pair (start-up
and imports included, the same in both), e.g. with a paired timer::

    PYTHONPATH=NEW python benchmarks/robot_workloads.py intercept   # and PYTHONPATH=OLD ...

Workloads (all on ``small_size_1997``, one process, no pool):

* ``intercept``: 2,000 interception trials, straight defender, ball noise 0.05;
* ``pass``: 300 pass-drill trials (random receiver, straight interceptors: no model file);
* ``match``: one 5 v 5 match of two baseline teams, two 60 s halves;
* ``chase2`` / ``chase12``: ``robotsoccer bench``'s chase with 2 robots for 600 simulated
  seconds, or 12 robots for 150 (camera, host, link and firmware running).

It prints nothing: the timer measures the process.
"""

from __future__ import annotations

import argparse

from field_models.benchmarks import ChaseLoad
from field_models.robot_physics.bench import bench_arena
from robotsoccer.runs.runner import TrialSpec, run_trial

WORKLOADS = ("intercept", "pass", "match", "chase2", "chase12")
"""The workloads' names, as the command line takes them."""


def run_workload(name: str) -> None:
    """Run workload `name` (module docstring) to its end."""
    if name == "intercept":
        spec = TrialSpec(drill="intercept", field_model="robot_physics", seed=1)
        spec = spec.with_options(behaviour="straight").with_field(ball_noise=0.05)
        for index in range(2000):
            run_trial(spec, index)
    elif name == "pass":
        spec = TrialSpec(drill="pass", field_model="robot_physics", seed=1)
        for index in range(300):
            run_trial(spec, index)
    elif name == "match":
        spec = TrialSpec(drill="match", field_model="robot_physics", seed=0).with_options(
            left="baseline", right="baseline", half_time_s=60.0
        )
        run_trial(spec, 0)
    else:
        chase(int(name.removeprefix("chase")))


def chase(n_robots: int) -> None:
    """The bench's chase: 600 simulated seconds with 2 robots, 150 with more."""
    arena = bench_arena(n_robots, 0)
    minds = {ref: ChaseLoad() for ref in arena.players}
    ticks = round((600.0 if n_robots == 2 else 150.0) / arena.facts.dt_s)
    for _ in range(ticks):
        for percept in arena.step():
            arena.submit(percept.player, minds[percept.player].act(percept))


def main() -> None:
    """Run the workload named on the command line."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("workload", choices=WORKLOADS)
    run_workload(parser.parse_args().workload)


if __name__ == "__main__":
    main()
