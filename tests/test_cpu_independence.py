"""Results do not depend on the CPU: every numpy dispatch level the machine has gives them.

numpy chooses SIMD kernels at import by CPU feature; ``NPY_DISABLE_CPU_FEATURES`` switches the
upper levels off. So one machine can stand in for older CPUs: :mod:`tests.cpu_probe` runs in a
subprocess per level (default, then each supported dispatch target switched off from the top)
and the levels must agree (README, "Determinism"):

* at every level the batched drill equals the one-trial drill and the vector environment the
  single ones, and numpy's ``sin``/``cos`` equal the C library's;
* every result is the same at every level, except the interception net's below AVX2 (x86-64
  v3), where numpy's ``tanh`` rounds differently (:mod:`field_models.fpmath`).
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import numpy._core._multiarray_umath as umath
import pytest

ROOT = Path(__file__).resolve().parent.parent
TANH_LEVEL = "X86_V3"
"""The dispatch target from which numpy's float64 tanh gives the same bits as above it."""


def dispatch_levels() -> list[tuple[str, ...]]:
    """Feature groups to switch off: none, then each supported target from the top down."""
    supported = [f for f in umath.__cpu_dispatch__ if umath.__cpu_features__.get(f)]
    levels: list[tuple[str, ...]] = [()]
    for i in range(len(supported) - 1, -1, -1):
        levels.append(tuple(reversed(supported[i:])))
    return levels


def probe(disabled: tuple[str, ...]) -> dict[str, object]:
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    env.pop("NPY_DISABLE_CPU_FEATURES", None)
    if disabled:
        env["NPY_DISABLE_CPU_FEATURES"] = " ".join(disabled)
    done = subprocess.run(
        [sys.executable, "-m", "tests.cpu_probe"],
        capture_output=True,
        text=True,
        cwd=ROOT,
        env=env,
        timeout=300,
    )
    assert done.returncode == 0, done.stderr
    report: dict[str, object] = json.loads(done.stdout)
    return report


@pytest.fixture(scope="module")
def reports() -> dict[tuple[str, ...], dict[str, object]]:
    return {disabled: probe(disabled) for disabled in dispatch_levels()}


def test_each_level_really_switches_its_features_off(
    reports: dict[tuple[str, ...], dict[str, object]],
) -> None:
    for disabled, report in reports.items():
        features = report["features"]
        assert isinstance(features, list)
        assert not set(disabled) & set(features)


def test_the_engines_agree_at_every_dispatch_level(
    reports: dict[tuple[str, ...], dict[str, object]],
) -> None:
    for disabled, report in reports.items():
        assert report["kernels_match_math"], disabled
        assert report["engines_equal"] and all(report["engines_equal"].values()), (  # type: ignore[attr-defined]
            disabled,
            report["engines_equal"],
        )


def test_every_level_gives_the_same_results(
    reports: dict[tuple[str, ...], dict[str, object]],
) -> None:
    default = reports[()]["digests"]
    assert isinstance(default, dict)
    for disabled, report in reports.items():
        digests = report["digests"]
        assert isinstance(digests, dict)
        for case, value in digests.items():
            if case == "net" and TANH_LEVEL in disabled:
                continue
            assert value == default[case], (disabled, case)
