"""The lead drill's straight and analytic baselines under both robot drives (issue 21 item 1).

The lead study's robot drill (``robotsoccer learn lead``: ``small_size_1997_arc``, shots across
the goal mouth, the study's ball noise .05), run on the same placements (one seed: paired
trials) with ``robot.drive = "kinematic"`` and ``"motor"``: saves with 95% Wilson intervals,
and each behaviour's paired difference motor minus kinematic. One process (``--workers``).

    python benchmarks/motor_lead_drill.py [--trials 300] [--workers 1]
"""

from __future__ import annotations

import argparse
import tempfile
from pathlib import Path

from robotsoccer.cli.options import LEAD_DRILLS
from robotsoccer.experiments.layer1_evaluate import counts_of
from robotsoccer.experiments.lead_study import StudyDrill
from robotsoccer.experiments.report_cells import paired_cell, percent_cell
from robotsoccer.runs.pool import run_trials

BEHAVIOURS = ("straight", "analytic")
NOISE = 0.05
"""The lead study's ball noise (its plan's)."""


def motor_preset(folder: Path, base: str) -> str:
    """A preset file: `base` with the motor drive."""
    path = folder / f"{base}_motor.toml"
    path.write_text(f'base = "{base}"\n\n[robot]\ndrive = "motor"\n')
    return str(path)


def main() -> None:
    """Print a markdown table (module docstring)."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--trials", type=int, default=300)
    parser.add_argument("--workers", type=int, default=1)
    parser.add_argument("--seed", type=int, default=0)
    args = parser.parse_args()
    preset, options, summary = LEAD_DRILLS["robot_physics"]
    with tempfile.TemporaryDirectory() as folder:
        presets = {"kinematic": preset, "motor": motor_preset(Path(folder), preset)}
        print(f"lead drill ({summary}), n = {args.trials} paired trials per row, seed {args.seed}")
        print("| behaviour | kinematic saves % | motor saves % | motor − kinematic (paired) |")
        print("|---|---|---|---|")
        for behaviour in BEHAVIOURS:
            results = {}
            for drive, name in presets.items():
                drill = StudyDrill("robot_physics", name, options, summary)
                spec = drill.spec(args.seed, "lead", NOISE).with_options(behaviour=behaviour)
                results[drive] = run_trials(spec, args.trials, workers=args.workers, progress=False)
            cells = [percent_cell(counts_of(results[d]).saves, args.trials) for d in presets]
            diff = paired_cell(results["motor"], results["kinematic"])
            print(f"| lead: {behaviour} | {cells[0]} | {cells[1]} | {diff} |")


if __name__ == "__main__":
    main()
