"""Run folders: one run each, never mixed, never silently replaced, one writer at a time.

A run folder holds what one run wrote (results tables and their manifests, reports, models,
recordings). Three ways in:

* a new or empty folder: the run starts;
* ``resume``: the run continues a folder it made before; whether the folder was made by the
  same run is checked by what writes into it (results manifests, an experiment's config);
* ``overwrite``: the folder is emptied first, but only if it looks like a run folder (it holds
  a manifest), so a mistyped ``--out`` cannot delete an unrelated folder.

Anything else on a non-empty folder is refused with one line saying what to do.

**One writer at a time.** A run holds an OS lock (``flock``) on the folder's :data:`LOCK_NAME`
file for as long as it writes there, with its PID in the file; a second run into the same
folder is refused with one line naming that PID (:class:`FolderInUseError`), before it reads
or writes anything. The OS drops the lock when its holder exits, however it exits (``kill -9``
included), so a lock is never stale. Locks are per process and re-entrant: a run that holds a
folder may write anywhere below it, and that folder is the one its manifests store paths
relative to (:func:`held_folder`).
"""

from __future__ import annotations

import contextlib
import fcntl
import os
import shutil
import time
from collections.abc import Iterator
from pathlib import Path

RUN_MARKERS = ("results.json", "config.json")
"""Files whose presence marks a folder as a run folder (a results manifest, an experiment's
configuration)."""

LOCK_NAME = ".lock"
"""The lock file in a run folder: its holder's PID, locked with ``flock`` while it runs."""

_HELD: dict[Path, int] = {}
"""The folders this process holds (resolved path → the lock file's descriptor)."""


class RunFolderError(ValueError):
    """A run folder cannot be used as asked (one line; the CLI exits with status 2)."""


class FolderInUseError(RunFolderError):
    """Another process holds the folder's lock: another run is writing there."""


def prepare_run_folder(out: Path, *, resume: bool, overwrite: bool) -> None:
    """Make `out` ready for a run and hold its lock, or refuse (module docstring).

    The lock is held until :func:`release_run_folders` (the CLI calls it when a command ends)
    or the process exits.

    Raises:
        FolderInUseError: Another process holds `out`.
        RunFolderError: `out` is a file, sits under a file, holds another run and neither
            `resume` nor `overwrite` was asked, is not a run folder but `overwrite` was
            asked, or cannot be written.
    """
    if resume and overwrite:
        raise RunFolderError("choose --resume or --overwrite, not both")
    if out.exists() and not out.is_dir():
        raise RunFolderError(f"{out} is a file, not a folder: choose another --out")
    _check_contents(out, resume=resume, overwrite=overwrite)  # refuse before leaving a lock file
    already = held_folder(out) is not None
    try:
        out.mkdir(parents=True, exist_ok=True)
        lock_run_folder(out)
    except OSError as exc:
        raise RunFolderError(f"cannot write to {out}: {exc.strerror or exc}") from None
    try:
        # Again under the lock: another run may have written here since the first look
        if _check_contents(out, resume=resume, overwrite=overwrite):
            _empty(out)
        probe = out / ".write-test"
        probe.touch()
        probe.unlink()
    except (OSError, RunFolderError) as exc:
        if not already:
            release_run_folder(out)
        if isinstance(exc, OSError):
            raise RunFolderError(f"cannot write to {out}: {exc.strerror or exc}") from None
        raise


def _check_contents(out: Path, *, resume: bool, overwrite: bool) -> bool:
    """Whether `out` must be emptied first; refuse a folder that cannot be used as asked."""
    if not out.is_dir() or not any(p.name != LOCK_NAME for p in out.iterdir()):
        return False
    if resume:
        return False
    if not overwrite:
        raise RunFolderError(
            f"{out} already holds a run: --resume continues it, --overwrite replaces it"
        )
    if not any((out / marker).exists() for marker in RUN_MARKERS):
        raise RunFolderError(f"{out} is not a run folder (no manifest): refusing to empty it")
    return True


def _empty(out: Path) -> None:
    """Delete what `out` holds except its lock file (which this process has locked)."""
    for entry in out.iterdir():
        if entry.name == LOCK_NAME:
            continue
        if entry.is_dir() and not entry.is_symlink():
            shutil.rmtree(entry)
        else:
            entry.unlink()


def lock_run_folder(folder: Path) -> Path:
    """Hold `folder`'s lock (re-entrant in this process) and return the folder held.

    When this process already holds `folder` or a folder above it, that one is returned and
    nothing more is locked.

    Raises:
        FolderInUseError: Another process holds the lock (the message names its PID).
        OSError: The lock file cannot be made.
    """
    held = held_folder(folder)
    if held is not None:
        return held
    key = folder.resolve()
    descriptor = os.open(key / LOCK_NAME, os.O_RDWR | os.O_CREAT | os.O_CLOEXEC, 0o644)
    try:
        fcntl.flock(descriptor, fcntl.LOCK_EX | fcntl.LOCK_NB)
    except BlockingIOError:
        holder = _holder(descriptor)
        os.close(descriptor)
        raise FolderInUseError(
            f"{folder} is in use by another run (pid {holder}): wait for it to end, "
            "or choose another --out"
        ) from None
    except OSError:
        os.close(descriptor)
        raise
    os.ftruncate(descriptor, 0)
    os.pwrite(descriptor, f"{os.getpid()}\n".encode(), 0)
    _HELD[key] = descriptor
    return key


def _holder(descriptor: int) -> str:
    """The PID the lock's holder wrote (it writes it just after locking: wait a moment)."""
    for _ in range(20):
        text = os.pread(descriptor, 32, 0).decode(errors="replace").strip()
        if text:
            return text
        time.sleep(0.01)
    return "unknown"


def held_folder(path: Path) -> Path | None:
    """The folder this process holds that is `path` or lies above it (resolved), or None."""
    if not _HELD:
        return None
    resolved = path.resolve()
    for folder in (resolved, *resolved.parents):
        if folder in _HELD:
            return folder
    return None


def release_run_folder(folder: Path) -> None:
    """Let go of `folder`'s lock, if this process holds that very folder."""
    descriptor = _HELD.pop(folder.resolve(), None)
    if descriptor is not None:
        os.close(descriptor)  # closing the only descriptor drops the flock


def release_run_folders() -> None:
    """Let go of every run folder this process holds (a command has ended)."""
    for folder in list(_HELD):
        release_run_folder(folder)


@contextlib.contextmanager
def holding(folder: Path) -> Iterator[Path]:
    """Hold `folder` for the block (:func:`lock_run_folder`), yielding the folder held.

    A folder this process held already (it or one above it) stays held after the block.
    """
    already = held_folder(folder) is not None
    held = lock_run_folder(folder)
    try:
        yield held
    finally:
        if not already:
            release_run_folder(held)
