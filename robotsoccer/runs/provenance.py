"""What produced a run's results: the code version and the files its trials read.

A resumed run may only add trials to results made by the same thing; these fingerprints are
what "the same" means. The code version is a digest of the project's source and preset files
(the three packages), so an edit anywhere that could change a trial's outcome changes it,
whether or not the checkout is a git repository.
"""

from __future__ import annotations

import hashlib
from functools import lru_cache
from pathlib import Path

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
