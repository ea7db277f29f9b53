"""What one numpy dispatch level computes: run as ``python -m tests.cpu_probe`` in a subprocess.

``tests/test_cpu_independence.py`` starts it once per SIMD dispatch level the machine supports
(``NPY_DISABLE_CPU_FEATURES`` switches the upper levels off at numpy's import) and compares
what each level prints, as one JSON object:

* ``kernels_match_math``: whether numpy's ``sin`` and ``cos`` give the C library's bits (the
  engines rely on it; :mod:`field_models.fpmath` says why those two are not in it);
* ``engines_equal``: per case, whether the batched interception drill gives exactly the
  one-trial drill's results, and the vector environment exactly the single environments';
* ``digests``: a hash of each case's results, to compare between levels;
* ``features``: the dispatched SIMD features, to show which level ran.
"""

from __future__ import annotations

import hashlib
import json
import math
import sys
import tempfile
from pathlib import Path

import numpy as np

TRIALS = 30


def digest(values: object) -> str:
    return hashlib.sha256(repr(values).encode()).hexdigest()[:16]


def kernels_match_math() -> bool:
    x = np.random.default_rng(0).uniform(-8.0, 8.0, 20_000)
    listed = x.tolist()
    return bool(
        np.array_equal(np.sin(x), [math.sin(v) for v in listed])
        and np.array_equal(np.cos(x), [math.cos(v) for v in listed])
    )


def intercept_cases(folder: Path) -> dict[str, tuple[bool, str]]:
    from robotsoccer.drills.intercept_batch import run_intercept_batch
    from robotsoccer.runs.runner import TrialSpec, run_trial
    from tests.robotsoccer.skills.test_intercept import net_file

    net = str(net_file(folder / "net.npz", seed=3, preset="soccer_server_1996"))
    base = TrialSpec(drill="intercept", field_model="soccer_server", seed=5)
    cases = {
        "straight": base.with_options(transfer=True, behaviour="straight"),
        "analytic": base.with_options(transfer=True, behaviour="analytic"),
        "analytic_perfect": base.with_options(transfer=True, behaviour="analytic").with_field(
            perfect_perception=True, ball_noise=0.1
        ),
        "random_every_see": base.with_options(
            transfer=True, behaviour="random", ta_mode="every_see"
        ),
        "net": base.with_options(transfer=True, behaviour="net", model=net),
    }
    out = {}
    for name, spec in cases.items():
        one = [run_trial(spec, i) for i in range(TRIALS)]
        many = run_intercept_batch(spec, list(range(TRIALS)), batch_size=8)
        out[name] = (many == one, digest(one))
    return out


def vector_env_case() -> tuple[bool, str]:
    from robotsoccer.envs import InterceptVectorEnv
    from robotsoccer.envs.intercept import InterceptEnv

    n = 8
    vec = InterceptVectorEnv(n, ball_noise=0.05)
    singles = [InterceptEnv("soccer_server", ball_noise=0.05) for _ in range(n)]
    obs, _ = vec.reset(seed=11)
    same = bool(np.array_equal(obs, [e.reset(seed=11 + i)[0] for i, e in enumerate(singles)]))
    actions = np.random.default_rng(1).uniform(-1.0, 1.0, (n, 1)).astype(np.float32)
    _, rewards, _, _, info = vec.step(actions)
    played = [e.step(actions[i]) for i, e in enumerate(singles)]
    same = same and bool(np.array_equal(rewards, [p[1] for p in played]))
    same = same and list(info["label"]) == [p[4]["label"] for p in played]
    return same, digest((obs.tolist(), rewards.tolist(), list(info["label"])))


def robot_digest() -> str:
    from robotsoccer.runs.runner import TrialSpec, run_trial

    spec = TrialSpec(drill="intercept", field_model="robot_physics", seed=5).with_options(
        behaviour="analytic"
    )
    return digest([run_trial(spec, i) for i in range(3)])


def main() -> None:
    import numpy._core._multiarray_umath as umath

    with tempfile.TemporaryDirectory() as folder:
        cases = intercept_cases(Path(folder))
    cases["vector_env"] = vector_env_case()
    digests = {name: d for name, (_, d) in cases.items()}
    digests["robots"] = robot_digest()
    report = {
        "kernels_match_math": kernels_match_math(),
        "engines_equal": {name: ok for name, (ok, _) in cases.items()},
        "digests": digests,
        "features": [f for f in umath.__cpu_dispatch__ if umath.__cpu_features__.get(f)],
    }
    json.dump(report, sys.stdout)


if __name__ == "__main__":
    main()
