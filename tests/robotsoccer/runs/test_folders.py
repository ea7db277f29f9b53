"""Run folders: one writer at a time, a resume after a kill, a copied folder that resumes."""

from __future__ import annotations

import json
import os
import shutil
import signal
import subprocess
import sys
import time
from collections.abc import Callable
from pathlib import Path

import pytest

from learning.lookup import LookupTable
from robotsoccer.runs import pool
from robotsoccer.runs.folders import (
    LOCK_NAME,
    FolderInUseError,
    held_folder,
    lock_run_folder,
    prepare_run_folder,
    release_run_folder,
    release_run_folders,
)
from robotsoccer.runs.pool import manifest, manifest_path, read_results, run_trials
from robotsoccer.runs.runner import TrialSpec

HOLD = (
    "import sys; from pathlib import Path; from robotsoccer.runs.folders import lock_run_folder; "
    "lock_run_folder(Path(sys.argv[1])); print('held', flush=True); sys.stdin.read()"
)
"""A process that holds a folder until its stdin closes."""


def cli(*args: str) -> subprocess.Popen[str]:
    return subprocess.Popen(
        [sys.executable, "-m", "robotsoccer.cli", *args],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )


def finished(process: subprocess.Popen[str]) -> tuple[int, str]:
    _, err = process.communicate(timeout=300)
    return process.returncode, err


def demo(out: Path, trials: int, *more: str) -> subprocess.Popen[str]:
    return cli(
        "demo", "--trials", str(trials), "--workers", "1", "--quiet", "--out", str(out), *more
    )


def rows(path: Path) -> list[str]:
    """The table's rows, each trial once (checked), in index order."""
    table = read_results(path)
    lines = path.read_text().splitlines()[1:]
    assert len(lines) == len(table), "a trial appears twice"
    return [table[i].csv_row() for i in sorted(table)]


def test_a_folder_lock_is_reentrant_and_names_its_holder(tmp_path) -> None:
    run = tmp_path / "run"
    run.mkdir()
    try:
        assert lock_run_folder(run) == run.resolve()
        assert (run / LOCK_NAME).read_text() == f"{os.getpid()}\n"
        assert lock_run_folder(run / "results" / "x") == run.resolve()  # below a held folder
        assert held_folder(run / "a" / "b") == run.resolve()
        prepare_run_folder(run, resume=True, overwrite=False)  # this process may go on
    finally:
        release_run_folders()
    assert held_folder(run) is None


def test_a_second_writer_is_refused_while_the_first_holds_the_folder(tmp_path) -> None:
    out = tmp_path / "run"
    out.mkdir()
    holder = subprocess.Popen(
        [sys.executable, "-c", HOLD, str(out)], stdin=subprocess.PIPE, stdout=subprocess.PIPE,
        text=True,
    )  # fmt: skip
    try:
        assert holder.stdout is not None and holder.stdout.readline() == "held\n"
        with pytest.raises(FolderInUseError, match=f"in use by another run .pid {holder.pid}"):
            prepare_run_folder(out, resume=False, overwrite=False)
        spec = TrialSpec(drill="shootout", field_model="robot_physics")
        with pytest.raises(FolderInUseError, match=str(holder.pid)):
            run_trials(spec, 2, workers=1, results_path=out / "results.csv", progress=False)
        status, err = finished(demo(out, 2))
        assert status == 2 and "Traceback" not in err
        assert err.strip().splitlines() == [
            f"robotsoccer: error: {out} is in use by another run (pid {holder.pid}): "
            "wait for it to end, or choose another --out"
        ]
        assert sorted(p.name for p in out.iterdir()) == [LOCK_NAME]  # nothing written
    finally:
        holder.communicate("")  # its stdin closes: it exits, and the OS drops its lock
    assert finished(demo(out, 2)) == (0, "")
    assert len(rows(out / "results.csv")) == 2


def test_overwrite_of_a_held_folder_is_refused_and_deletes_nothing(tmp_path) -> None:
    out = tmp_path / "run"
    assert finished(demo(out, 2))[0] == 0
    before = (out / "results.csv").read_bytes()
    lock_run_folder(out)  # this test process is now "the other run"
    try:
        status, err = finished(demo(out, 2, "--overwrite"))
        assert status == 2 and f"pid {os.getpid()}" in err
        assert (out / "results.csv").read_bytes() == before
    finally:
        release_run_folder(out)


@pytest.mark.slow
@pytest.mark.parametrize("resume", [False, True], ids=["fresh", "resume"])
def test_two_runs_at_once_into_one_folder_leave_each_trial_once(tmp_path, resume) -> None:
    # The scenario: two runs started together into one folder. One may finish before
    # the other starts (then a fresh second run is refused as "already holds a run", a resumed
    # one has nothing left to do); otherwise the second is refused by the lock. Never both.
    n = 240
    reference = tmp_path / "reference"
    assert finished(demo(reference, n))[0] == 0
    out = tmp_path / "run"
    extra = ("--resume",) if resume else ()
    if resume:
        assert finished(demo(out, n // 4))[0] == 0  # a partial run to continue
    outcomes = [finished(p) for p in [demo(out, n, *extra), demo(out, n, *extra)]]
    assert sorted(status for status, _ in outcomes)[0] == 0, outcomes
    for status, err in outcomes:
        assert status in (0, 2) and "Traceback" not in err, err
        if status == 2:
            assert "in use by another run (pid" in err or "already holds a run" in err, err
    assert rows(out / "results.csv") == rows(reference / "results.csv")


def _wait_for(condition: Callable[[], bool], what: str, process: subprocess.Popen[str]) -> None:
    deadline = time.monotonic() + 120
    while not condition():
        assert process.poll() is None, f"the run ended before {what}"
        assert time.monotonic() < deadline, f"no {what} in 120 s"
        time.sleep(0.002)


def _size(path: Path) -> int:
    return path.stat().st_size if path.exists() else -1


@pytest.mark.slow
def test_a_run_killed_at_any_moment_resumes_to_the_uninterrupted_table(tmp_path) -> None:
    n = 160
    reference = tmp_path / "reference"
    assert finished(demo(reference, n))[0] == 0
    whole = (reference / "results.csv").read_bytes()
    moments = {
        "folder locked": lambda out: _size(out / LOCK_NAME) > 0,
        "table opened": lambda out: _size(out / "results.csv") >= 0,
        "first rows written": lambda out: _size(out / "results.csv") > len(whole) // 4,
        "most rows written": lambda out: _size(out / "results.csv") > 3 * len(whole) // 4,
    }
    for moment, reached in moments.items():
        out = tmp_path / moment.replace(" ", "_")
        run = demo(out, n)
        _wait_for(lambda out=out, reached=reached: reached(out), moment, run)
        run.send_signal(signal.SIGKILL)
        run.wait()
        status, err = finished(demo(out, n, "--resume"))
        assert status == 0, (moment, err)
        assert (out / "results.csv").read_bytes() == whole, moment  # one worker: same order


def lookup_spec(model: Path) -> TrialSpec:
    """Trials that read a model file (a lookup table made by hand: no origin to check)."""
    spec = TrialSpec(drill="intercept", field_model="soccer_server", seed=1)
    return spec.with_options(behaviour="lookup", model=str(model), transfer=True)


def test_a_copied_run_folder_resumes(tmp_path, monkeypatch) -> None:
    # The manifests name the run's own model files relative to the run folder, so a copy
    # (cp -r RUN RUN2) is the same run; a model file outside the folder keeps its full path.
    run, copy = tmp_path / "run", tmp_path / "copy"
    (run / "models").mkdir(parents=True)
    outside = tmp_path / "elsewhere.json"
    for model in (run / "models" / "table.json", outside):
        LookupTable([-0.1, 0.1], [0.0, 0.05]).save(model)
    prepare_run_folder(run, resume=True, overwrite=False)  # it holds its model already
    try:
        spec = lookup_spec(run / "models" / "table.json")
        run_trials(spec, 3, workers=1, results_path=run / "results.csv", progress=False)
        elsewhere = lookup_spec(outside)
        run_trials(elsewhere, 2, workers=1, results_path=run / "o.csv", progress=False)
    finally:
        release_run_folders()
    written = manifest_path(run / "results.csv").read_text()
    assert str(run) not in written and '"models/table.json"' in written
    assert str(outside) in manifest_path(run / "o.csv").read_text()  # not the run's: kept whole
    shutil.copytree(run, copy)

    ran: list[int] = []
    real_chunk = pool.run_chunk

    def counting(spec, indices):  # type: ignore[no-untyped-def]
        ran.extend(indices)
        return real_chunk(spec, indices)

    monkeypatch.setattr(pool, "run_chunk", counting)
    prepare_run_folder(copy, resume=True, overwrite=False)
    try:
        spec = lookup_spec(copy / "models" / "table.json")
        resumed = run_trials(
            spec, 5, workers=1, results_path=copy / "results.csv", resume=True, progress=False
        )
        run_trials(  # the model outside: the same file, named the same way
            elsewhere, 3, workers=1, results_path=copy / "o.csv", resume=True, progress=False
        )
    finally:
        release_run_folders()
    assert ran == [3, 4, 2] and [r.index for r in resumed] == list(range(5))


def test_a_manifest_with_absolute_paths_is_still_read(tmp_path) -> None:
    run = tmp_path / "run"
    (run / "models").mkdir(parents=True)
    LookupTable([-0.1, 0.1], [0.0, 0.05]).save(run / "models" / "table.json")
    spec = lookup_spec(run / "models" / "table.json")
    path = run / "results.csv"
    run_trials(spec, 2, workers=1, results_path=path, progress=False)
    old = manifest(spec)  # no run folder given: every path whole, as manifests used to be
    assert str(run / "models" / "table.json") in old["inputs"]
    manifest_path(path).write_text(json.dumps(old))
    assert len(run_trials(spec, 3, workers=1, results_path=path, resume=True, progress=False)) == 3
