"""Reading rerun recordings back: verifying a file, reading positions, opening the viewer.

:func:`verify_recording` checks that an ``.rrd`` file is complete and decodes;
:func:`read_entity_positions` reads what was logged under one entity (for tests);
:func:`replay` opens a file in the viewer, or says how to, headless (``robotsoccer replay``).
Entity paths are those of :mod:`robotsoccer.replay.recording` and
:mod:`robotsoccer.replay.match_recording`.

Rerun is imported inside functions only, so importing this module does not load the SDK.
"""

from __future__ import annotations

import os
import re
import subprocess
import sys
import warnings
from pathlib import Path

import numpy as np

from robotsoccer.replay.palette import SIM_TIME

_ANSI = re.compile(r"\x1b\[[0-9;]*m")


def rerun_executable() -> Path:
    """The ``rerun`` CLI installed beside the running interpreter (the rerun-sdk wheel's)."""
    name = "rerun.exe" if os.name == "nt" else "rerun"
    return Path(sys.executable).parent / name


def _cli_env() -> dict[str, str]:
    """Environment for the rerun CLI: ``CI=true`` keeps it from writing analytics files."""
    return {**os.environ, "CI": "true"}


def _check_with_reader(path: Path, *, read_chunks: bool) -> tuple[bool, str]:
    """Read `path` with ``RrdReader``: optionally decode every chunk, then require the footer.

    ``rerun rrd verify`` (0.41) accepts a file whose last few dozen bytes (the footer) were
    cut off; ``RrdReader.store()`` refuses it, so this check backs the CLI up.
    """
    from rerun.chunk import RrdReader

    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")  # the reader warns on footer-less files; we report
            reader = RrdReader(str(path))
            n_chunks = len(reader.stream().to_chunks()) if read_chunks else 0
            reader.store()
    except Exception as err:  # the reader raises RuntimeError; report anything as a failure
        return False, f"{path}: {err}"
    detail = f"{n_chunks} chunks read, " if read_chunks else ""
    return True, f"{path}: {detail}footer present"


def verify_recording(path: Path) -> tuple[bool, str]:
    """Check that an ``.rrd`` file is complete and decodes.

    Runs ``rerun rrd verify`` (the CLI beside ``sys.executable``, with ``CI=true``) and then
    requires the footer with ``RrdReader``; without the executable, reads the whole file with
    ``RrdReader`` instead.

    Returns:
        Whether the file verified, and a one-line message saying why or why not.
    """
    path = Path(path)
    if not path.is_file():
        return False, f"{path}: no such file"
    exe = rerun_executable()
    if not exe.is_file():
        return _check_with_reader(path, read_chunks=True)
    try:
        proc = subprocess.run(
            [str(exe), "rrd", "verify", str(path)],
            env=_cli_env(),
            capture_output=True,
            text=True,
            timeout=600,
            check=False,
        )
    except (OSError, subprocess.TimeoutExpired) as err:
        return False, f"{path}: could not run {exe}: {err}"
    lines = [ln.strip() for ln in _ANSI.sub("", proc.stdout + proc.stderr).splitlines()]
    message = " | ".join(ln for ln in lines if ln) or f"rerun rrd verify exited {proc.returncode}"
    if proc.returncode != 0:
        return False, message
    ok, footer_message = _check_with_reader(path, read_chunks=False)
    return (True, message) if ok else (False, footer_message)


def read_entity_positions(path: Path, entity: str) -> np.ndarray:
    """Read the positions logged under one entity back from an ``.rrd`` file (for tests).

    Takes the first position-like column (``Points2D:positions``, ``Arrows2D:origins``,
    ``Boxes2D:centers``) of every temporal chunk of `entity`, sorted by ``sim_time``; rows with
    several instances contribute them in logged order. Works on footer-less files too.

    Args:
        path: The ``.rrd`` file.
        entity: Entity path, with or without the leading ``/`` (e.g. ``"field/ball"``).

    Returns:
        A (N, 2) float64 array (float32 values, as rerun stores them); (0, 2) if none.
    """
    from rerun.chunk import RrdReader

    target = "/" + entity.strip("/")
    times: list[np.ndarray] = []
    points: list[np.ndarray] = []
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # footer-less files warn but read fine
        chunks = RrdReader(str(path)).stream().to_chunks()
    for chunk in chunks:
        if chunk.entity_path != target:
            continue
        batch = chunk.to_record_batch()
        names = batch.schema.names
        if SIM_TIME not in names:
            continue  # static styles
        column = next(
            (n for n in names if n.endswith((":positions", ":origins", ":centers"))), None
        )
        if column is None:
            continue
        values = batch.column(column)
        lengths = values.value_lengths().fill_null(0).to_numpy(zero_copy_only=False)
        xy = np.asarray(values.flatten().flatten(), dtype=np.float64).reshape(-1, 2)
        row_ns = batch.column(SIM_TIME).cast("int64").to_numpy(zero_copy_only=False)
        times.append(np.repeat(row_ns, lengths))
        points.append(xy)
    if not points:
        return np.zeros((0, 2))
    order = np.argsort(np.concatenate(times), kind="stable")
    return np.concatenate(points)[order]


# ----------------------------------------------------------------------------- replay


def has_display() -> bool:
    """Whether a graphical session is available to open the native viewer in."""
    return bool(os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY"))


def replay(path: Path) -> int:
    """Open a recording in the rerun viewer, or say how to, headless (``robotsoccer replay``).

    With a display, spawns the viewer on the file (detached) and returns 0. Without one,
    prints how to open it on a desktop or serve it to a browser, verifies it and prints the
    result.

    Returns:
        0 when the viewer was spawned or the file verifies, 1 when it does not verify, 2 when
        the file does not exist.
    """
    path = Path(path)
    if not path.is_file():
        print(f"robotsoccer replay: no such file: {path}", file=sys.stderr)
        return 2
    exe = rerun_executable()
    if has_display():
        try:
            subprocess.Popen(
                [str(exe), str(path)],
                env=_cli_env(),
                stdin=subprocess.DEVNULL,
                stdout=subprocess.DEVNULL,
                stderr=subprocess.DEVNULL,
                start_new_session=True,  # the viewer outlives this command
            )
        except OSError as err:
            print(f"could not start the rerun viewer ({exe}): {err}")
        else:
            print(f"opened the rerun viewer on {path}")
            return 0
    else:
        print("no display found (neither DISPLAY nor WAYLAND_DISPLAY is set).")
    # The venv's rerun is not on PATH unless the venv is active; name it in full. The web
    # viewer binds to localhost: serving to all interfaces is the user's explicit choice.
    print(f"On a desktop, open it with:      {exe} {path}")
    print(f"To serve it to a web browser:    {exe} --web-viewer --bind 127.0.0.1 {path}")
    print("  then open the http://127.0.0.1:9090 address it prints")
    print(f"verifying {path} ...", flush=True)
    ok, message = verify_recording(path)
    print(f"{'verified' if ok else 'verification FAILED'}: {message}")
    return 0 if ok else 1
