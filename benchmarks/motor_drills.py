"""Robot drills under both drives on the same placements (issue 21 item 1).

Runs, with ``robot.drive = "kinematic"`` and ``"motor"``, trial by trial alternating the two
drives (one seed: paired trials; one process, so both see the same machine load):

* the lead study's robot drill (``robotsoccer learn lead``: ``small_size_1997_arc``, shots
  across the goal mouth, the study's ball noise .05), its straight and analytic baselines;
* the robot pass drill (``pass`` on ``small_size_1997``, its default options).

Prints a markdown table: each drive's successes (saves; completed passes) with 95% Wilson
intervals, the paired difference motor minus kinematic, the mean trial length in ticks and the
engine's process CPU time per tick.

    python benchmarks/motor_drills.py [--trials 500] [--pass-trials 200]
"""

from __future__ import annotations

import argparse
import tempfile
import time
from pathlib import Path

from robotsoccer.cli.options import LEAD_DRILLS
from robotsoccer.experiments.lead_study import StudyDrill
from robotsoccer.experiments.report_cells import paired_cell, percent_cell
from robotsoccer.runs.runner import TrialResult, TrialSpec, run_trial

NOISE = 0.05
"""The lead study's ball noise (its plan's)."""


def motor_preset(folder: Path, base: str) -> str:
    """A preset file: `base` with the motor drive."""
    path = folder / f"{base}_motor.toml"
    path.write_text(f'base = "{base}"\n\n[robot]\ndrive = "motor"\n')
    return str(path)


def paired_runs(
    specs: dict[str, TrialSpec], trials: int
) -> tuple[dict[str, list[TrialResult]], dict[str, float]]:
    """Trials 0..`trials`-1 of each spec, alternating; results and CPU seconds per spec.

    Trial 0 of each runs once first, untimed (loading and caches are not the engine's speed).
    """
    results: dict[str, list[TrialResult]] = {name: [] for name in specs}
    cpu = dict.fromkeys(specs, 0.0)
    for spec in specs.values():  # once unmeasured: one-off loading and caches
        run_trial(spec, 0)
    for index in range(trials):
        for name, spec in specs.items():
            start = time.process_time()
            results[name].append(run_trial(spec, index))
            cpu[name] += time.process_time() - start
    return results, cpu


def row(title: str, label: str, specs: dict[str, TrialSpec], trials: int) -> str:
    """One table row: both drives' share of `label`, the paired difference, ticks, CPU µs/tick."""
    results, cpu = paired_runs(specs, trials)
    cells = []
    for name in specs:
        wins = sum(r.label == label for r in results[name])
        ticks = sum(r.ticks for r in results[name])
        cells.append(
            f"{percent_cell(wins, trials)} | {ticks / trials:.1f} | {1e6 * cpu[name] / ticks:.1f}"
        )
    diff = paired_cell(results["motor"], results["kinematic"], label)
    return f"| {title} | {trials} | {cells[0]} | {cells[1]} | {diff} |"


def main() -> None:
    """Print the table (module docstring)."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--trials", type=int, default=500, help="lead-drill trials per row")
    parser.add_argument("--pass-trials", type=int, default=200)
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args()
    preset, options, summary = LEAD_DRILLS["robot_physics"]
    print(
        "| drill | n | kinematic % | ticks/trial | CPU µs/tick | motor % | ticks/trial "
        "| CPU µs/tick | motor − kinematic (paired) |"
    )
    print("|---|---|---|---|---|---|---|---|---|")
    with tempfile.TemporaryDirectory() as folder:
        presets = {"kinematic": preset, "motor": motor_preset(Path(folder), preset)}
        for behaviour in ("straight", "analytic"):
            specs = {
                name: StudyDrill("robot_physics", p, options, summary)
                .spec(args.seed, "lead", NOISE)
                .with_options(behaviour=behaviour)
                for name, p in presets.items()
            }
            print(row(f"lead drill, {behaviour}: saves", "SAVE", specs, args.trials))
    specs = {
        name: TrialSpec(drill="pass", field_model="robot_physics", preset=p, seed=args.seed)
        for name, p in (("kinematic", "small_size_1997"), ("motor", "small_size_1997_motor"))
    }
    print(row("pass drill: completed passes", "SUCCESS", specs, args.pass_trials))


if __name__ == "__main__":
    main()
