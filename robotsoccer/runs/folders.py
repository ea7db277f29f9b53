"""Run folders: one run each, never mixed, never silently replaced.

A run folder holds what one run wrote (results tables and their manifests, reports, models,
recordings). Three ways in:

* a new or empty folder: the run starts;
* ``resume``: the run continues a folder it made before; whether the folder was made by the
  same run is checked by what writes into it (results manifests, an experiment's config);
* ``overwrite``: the folder is emptied first, but only if it looks like a run folder (it holds
  a manifest), so a mistyped ``--out`` cannot delete an unrelated folder.

Anything else on a non-empty folder is refused with one line saying what to do.
"""

from __future__ import annotations

import shutil
from pathlib import Path

RUN_MARKERS = ("results.json", "config.json")
"""Files whose presence marks a folder as a run folder (a results manifest, an experiment's
configuration)."""


class RunFolderError(ValueError):
    """A run folder cannot be used as asked (one line; the CLI exits with status 2)."""


def prepare_run_folder(out: Path, *, resume: bool, overwrite: bool) -> None:
    """Make `out` ready for a run, or refuse (module docstring).

    Raises:
        RunFolderError: `out` is a file, sits under a file, holds another run and neither
            `resume` nor `overwrite` was asked, is not a run folder but `overwrite` was
            asked, or cannot be written.
    """
    if resume and overwrite:
        raise RunFolderError("choose --resume or --overwrite, not both")
    if out.exists() and not out.is_dir():
        raise RunFolderError(f"{out} is a file, not a folder: choose another --out")
    if out.is_dir() and any(out.iterdir()):
        if resume:
            return
        if not overwrite:
            raise RunFolderError(
                f"{out} already holds a run: --resume continues it, --overwrite replaces it"
            )
        if not any((out / marker).exists() for marker in RUN_MARKERS):
            raise RunFolderError(f"{out} is not a run folder (no manifest): refusing to empty it")
        shutil.rmtree(out)
    try:
        out.mkdir(parents=True, exist_ok=True)
        probe = out / ".write-test"
        probe.touch()
        probe.unlink()
    except OSError as exc:
        raise RunFolderError(f"cannot write to {out}: {exc.strerror or exc}") from None
