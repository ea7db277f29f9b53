"""What produced a run's results: the code version and the files its trials read.

A resumed run may only add trials to results made by the same thing; these fingerprints are
what "the same" means. The code version is a digest of the project's source and preset files
(the three packages), so an edit anywhere that could change a trial's outcome changes it,
whether or not the checkout is a git repository.

:func:`machine` says where the results were computed: results do not depend on it (README,
"Determinism"), and a manifest records it so that a claim of that kind can be checked.
"""

from __future__ import annotations

import hashlib
import importlib
import platform
import sys
from functools import lru_cache
from importlib import metadata
from pathlib import Path
from typing import Any

import field_models
import learning
import robotsoccer

_PACKAGES = (field_models, learning, robotsoccer)
_SUFFIXES = (".py", ".toml")


@lru_cache(maxsize=1)
def code_version() -> str:
    """A short digest of every source and preset file of the three packages (cached)."""
    digest = hashlib.sha256()
    for package in _PACKAGES:
        assert package.__file__ is not None
        root = Path(package.__file__).resolve().parent
        for path in sorted(p for p in root.rglob("*") if p.suffix in _SUFFIXES):
            digest.update(path.relative_to(root.parent).as_posix().encode())
            digest.update(path.read_bytes())
    return digest.hexdigest()[:16]


def file_digest(path: str | Path) -> str:
    """The SHA-256 of a file's bytes (short), or ``"missing"`` when it cannot be read."""
    try:
        data = Path(path).read_bytes()
    except OSError:
        return "missing"
    return hashlib.sha256(data).hexdigest()[:16]


@lru_cache(maxsize=1)
def machine() -> dict[str, Any]:
    """The CPU, the SIMD features numpy dispatches on it, and the versions that compute a trial.

    numpy's dispatched features are the ones its kernels use here (after any
    ``NPY_DISABLE_CPU_FEATURES``); the trials' results must not depend on them.
    """
    umath: Any = importlib.import_module("numpy._core._multiarray_umath")  # its dispatch record
    dispatched = [f for f in umath.__cpu_dispatch__ if umath.__cpu_features__.get(f)]
    return {
        "cpu": _cpu_model(),
        "machine": platform.machine(),
        "numpy_simd_baseline": list(umath.__cpu_baseline__),
        "numpy_simd_dispatched": dispatched,
        "python": platform.python_version(),
        "platform": sys.platform,
        "packages": {name: _version(name) for name in _ENGINES},
    }


_ENGINES = ("numpy", "pymunk", "torch", "scikit-learn")
"""The packages whose code computes trials and models."""


def _version(package: str) -> str:
    try:
        return metadata.version(package)
    except metadata.PackageNotFoundError:
        return "not installed"


def _cpu_model() -> str:
    """The CPU's model name (Linux's /proc/cpuinfo), else what ``platform`` knows."""
    try:
        with open("/proc/cpuinfo", encoding="utf-8", errors="replace") as info:
            for line in info:
                if line.startswith("model name"):
                    return line.partition(":")[2].strip()
    except OSError:
        pass
    return platform.processor() or platform.machine() or "unknown"
