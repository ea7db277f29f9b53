"""The Soccer Server pass drill's trial loop: its CPU time, its profile and its digests.

A speed-up of the server's pass drill (issue 21, item 3) must leave everything it computes bit
for bit the same and cost less CPU. This script plays the pass drill as ``robotsoccer bench``
does (seed 1, the drill's defaults: random receiver, straight interceptors), in this process:

* ``time``: the process's CPU time (``time.process_time``) of `--trials` trials in one loop;
* ``profile``: the same loop under ``cProfile``, the top `--top` functions by own time;
* ``digest``: SHA-256 of the trials' results (every table row, floats exactly) and of every
  percept delivered (``repr``), and of an 11 v 11 baseline match's result and percepts.

Run it on two trees (``PYTHONPATH=TREE``), alternating, and compare: equal digests, and the
ratio of the CPU times. One JSON object.

    python benchmarks/server_pass_speed.py time|profile|digest [--trials 300]
"""

from __future__ import annotations

import argparse
import cProfile
import hashlib
import io
import json
import pstats
import time
from typing import Any

from field_models.arena import Arena
from field_models.protocol import Percept
from robotsoccer.runs.runner import TrialResult, TrialSpec, build_trial, play, run_trial

PASS = TrialSpec(drill="pass", field_model="soccer_server", seed=1)
"""The bench's pass drill on the Soccer Server."""


def trial_loop(trials: int) -> None:
    """Play trials 0 .. `trials` - 1 of the pass drill."""
    for index in range(trials):
        run_trial(PASS, index)


def cpu_seconds(trials: int) -> float:
    """Process CPU seconds of a `trials`-trial loop."""
    start = time.process_time()
    trial_loop(trials)
    return time.process_time() - start


def profile(trials: int, top: int) -> list[dict[str, Any]]:
    """The loop's `top` functions by own time: share of the total, own and cumulative s."""
    profiler = cProfile.Profile()
    profiler.runcall(trial_loop, trials)
    stats = pstats.Stats(profiler, stream=io.StringIO())
    total = stats.total_tt  # type: ignore[attr-defined]
    rows = sorted(stats.stats.items(), key=lambda item: -item[1][2])  # type: ignore[attr-defined]
    out = []
    for (path, line, name), (_, calls, own, cumulative, _) in rows[:top]:
        where = f"{'/'.join(path.rsplit('/', 2)[-2:])}:{line}"
        out.append(
            {
                "function": f"{where}({name})",
                "calls": calls,
                "share": round(own / total, 3),
                "own_s": round(own, 3),
                "cumulative_s": round(cumulative, 3),
            }
        )
    return out


def played_digest(spec: TrialSpec, indices: range) -> tuple[str, str]:
    """SHA-256 of the trials' table rows and of every percept they delivered, in order."""
    rows, seen = hashlib.sha256(), hashlib.sha256()

    def observe(_: Arena, percepts: list[Percept]) -> None:
        for percept in percepts:
            seen.update(repr(percept).encode())

    for index in indices:
        # run_trial's own steps, with an observer on the loop for the percepts.
        rngs, drill, arena = build_trial(spec, index)
        drill.setup(arena, rngs)
        verdict = play(arena, drill, drill.minds(arena, rngs), observer=observe)
        result = TrialResult(
            index,
            verdict.label,
            verdict.reason,
            arena.tick,
            arena.tick * arena.facts.dt_s,
            drill.data(),
            tuple(drill.measures().items()),
        )
        same = result.csv_fields() == run_trial(spec, index).csv_fields()
        assert same, "the observed trial is not run_trial's"
        rows.update("\x1f".join(result.csv_fields()).encode())
    return rows.hexdigest(), seen.hexdigest()


def digests(trials: int, half_time_s: float) -> dict[str, str]:
    """The pass trials' and an 11 v 11 baseline match's digests."""
    pass_rows, pass_percepts = played_digest(PASS, range(trials))
    match = TrialSpec(drill="match", field_model="soccer_server", seed=0).with_options(
        left="baseline", right="baseline", half_time_s=half_time_s
    )
    match_rows, match_percepts = played_digest(match, range(1))
    return {
        "pass_results": pass_rows,
        "pass_percepts": pass_percepts,
        "match_results": match_rows,
        "match_percepts": match_percepts,
    }


def main() -> None:
    """Parse the arguments and print one JSON object."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("what", choices=("time", "profile", "digest"))
    parser.add_argument("--trials", type=int, default=300)
    parser.add_argument("--top", type=int, default=10, help="profile: functions shown")
    parser.add_argument("--half-time-s", type=float, default=30.0, help="digest: match half")
    args = parser.parse_args()
    out: dict[str, Any] = {"trials": args.trials}
    if args.what == "time":
        out["cpu_s"] = round(cpu_seconds(args.trials), 3)
    elif args.what == "profile":
        out["profile"] = profile(args.trials, args.top)
    else:
        out["half_time_s"] = args.half_time_s
        out.update(digests(args.trials, args.half_time_s))
    print(json.dumps(out, indent=1))


if __name__ == "__main__":
    main()
