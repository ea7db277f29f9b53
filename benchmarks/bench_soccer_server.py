"""Speed of the Soccer Server dynamics: one trial in plain Python, many trials as arrays.

Targets (issue 3): >= 30,000 cycles/s for 2 players + ball in one process *including sensing*
(so the dynamics alone should stay well under 15 us per cycle), and >= 2,000,000 object-cycles/s
in batch mode. The load is drill-like: a shooter kicks at the start, a defender dashes every
cycle and turns now and then, noise on, referee on.

Run: ``python benchmarks/bench_soccer_server.py --seconds 2`` (prints JSON).
"""

from __future__ import annotations

import argparse
import json
import math
import time

import numpy as np

from field_models.protocol import LEFT, RIGHT, PlayerRef
from field_models.soccer_server.batch import BatchSoccerServer
from field_models.soccer_server.dynamics import SoccerServerModel
from field_models.soccer_server.params import load_server_preset

PLAYERS = (PlayerRef(LEFT, 1), PlayerRef(RIGHT, 1))
TRIAL_CYCLES = 100
BATCH_TRIALS = 2000


def _single_trial(model: SoccerServerModel) -> None:
    """One drill-like trial of TRIAL_CYCLES cycles."""
    model.move_ball(-20.0, 0.0)
    model.move_player(1, -20.5, 0.0, 0.0)
    model.move_player(2, 5.0, 1.0, math.pi)
    model.kick(1, 80.0, 0.0)
    for t in range(TRIAL_CYCLES):
        if t % 5 == 0:
            model.turn(2, 0.05)
        else:
            model.dash(2, 60.0)
        model.step()


def measure_single(preset_name: str, seconds: float) -> dict[str, float]:
    """Cycles per second of one model with 2 players and the ball (dynamics only)."""
    model = SoccerServerModel(load_server_preset(preset_name), PLAYERS, np.random.default_rng(0))
    cycles = 0
    start = time.perf_counter()
    while time.perf_counter() - start < seconds:
        _single_trial(model)
        cycles += TRIAL_CYCLES
    elapsed = time.perf_counter() - start
    return {"cycles_per_s": cycles / elapsed, "step_us": 1e6 * elapsed / cycles}


def measure_batch(preset_name: str, seconds: float, trials: int = BATCH_TRIALS) -> dict[str, float]:
    """Object-cycles per second of `trials` trials stepped together (3 objects each)."""
    rngs = [np.random.default_rng([1, k]) for k in range(trials)]
    batch = BatchSoccerServer(load_server_preset(preset_name), PLAYERS, rngs)
    cycles = 0
    start = time.perf_counter()
    while time.perf_counter() - start < seconds:
        batch.move_ball(-20.0, 0.0)
        batch.move_player(1, -20.5, 0.0, 0.0)
        batch.move_player(2, 5.0, 1.0, math.pi)
        batch.kick(1, 80.0, 0.0)
        for t in range(TRIAL_CYCLES):
            if t % 5 == 0:
                batch.turn(2, 0.05)
            else:
                batch.dash(2, 60.0)
            batch.step()
        cycles += TRIAL_CYCLES
    elapsed = time.perf_counter() - start
    objects = trials * (len(PLAYERS) + 1)
    return {
        "trials": trials,
        "object_cycles_per_s": objects * cycles / elapsed,
        "step_ms": 1e3 * elapsed / cycles,
    }


def measure_dynamics(seconds: float) -> dict[str, object]:
    """Single-trial cycles/s and batch object-cycles/s for both presets, `seconds` in total."""
    share = seconds / 4.0
    result: dict[str, object] = {
        "targets": {"single_cycles_per_s_with_sensing": 30_000, "batch_object_cycles_per_s": 2e6}
    }
    for name in ("soccer_server_1996", "rcssserver_19"):
        result[name] = {
            "single": measure_single(name, share),
            "batch": measure_batch(name, share),
        }
    return result


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seconds", type=float, default=4.0, help="total measuring time")
    args = parser.parse_args()
    print(json.dumps(measure_dynamics(args.seconds), indent=2))


if __name__ == "__main__":
    main()
