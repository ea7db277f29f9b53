"""Runs a user can trust: run folders, resume and overwrite, and every error as one line."""

from __future__ import annotations

import os
import subprocess
import sys
import textwrap
import tracemalloc
from pathlib import Path

import pytest

import robotsoccer.runs.pool as pool
from learning.datasets import Provenance
from robotsoccer.runs.runner import TrialSpec

FAST = ("--trials", "4", "--workers", "1", "--quiet")


def cli(*args: str, cwd: Path | None = None, env: dict[str, str] | None = None):
    return subprocess.run(
        [sys.executable, "-m", "robotsoccer.cli", *args],
        capture_output=True,
        text=True,
        cwd=cwd,
        env=env,
        timeout=300,
    )


def one_line(done: subprocess.CompletedProcess[str], status: int, *words: str) -> str:
    """The single error line of a failed command, checked."""
    assert done.returncode == status, (done.returncode, done.stderr)
    assert "Traceback" not in done.stderr, done.stderr
    lines = [line for line in done.stderr.strip().splitlines() if line]
    assert len(lines) == 1, done.stderr
    for word in words:
        assert word in lines[0], lines[0]
    return lines[0]


# ----------------------------------------------------------------------------- run folders


def test_a_second_run_into_a_folder_is_refused_resumed_or_overwritten(tmp_path) -> None:
    out = tmp_path / "run"
    assert cli("demo", *FAST, "--out", str(out)).returncode == 0
    rows = (out / "results.csv").read_text()
    one_line(cli("demo", *FAST, "--out", str(out)), 2, "already holds a run", "--resume")
    assert (out / "results.csv").read_text() == rows  # nothing truncated
    line = one_line(cli("demo", *FAST, "--out", str(out), "--seed", "3", "--resume"), 2)
    assert "seed 0 then, 3 now" in line
    grown = cli("demo", "--trials", "6", "--workers", "1", "--quiet", "--out", str(out), "--resume")
    assert grown.returncode == 0 and len((out / "results.csv").read_text().splitlines()) == 7
    replaced = cli("demo", *FAST, "--out", str(out), "--seed", "3", "--overwrite")
    assert replaced.returncode == 0 and len((out / "results.csv").read_text().splitlines()) == 5
    one_line(cli("demo", *FAST, "--out", str(out), "--resume", "--overwrite"), 2, "not both")


def test_overwrite_refuses_a_folder_that_is_not_a_run(tmp_path) -> None:
    precious = tmp_path / "thesis"
    precious.mkdir()
    (precious / "chapter1.tex").write_text("...")
    one_line(cli("demo", *FAST, "--out", str(precious), "--overwrite"), 2, "not a run folder")
    assert (precious / "chapter1.tex").exists()


@pytest.mark.parametrize("case", ["out is a file", "parent is a file", "read-only place"])
def test_unwritable_outputs_are_one_line(tmp_path, case: str) -> None:
    a_file = tmp_path / "a_file"
    a_file.write_text("x")
    out = {
        "out is a file": a_file,
        "parent is a file": a_file / "run",
        "read-only place": Path("/sys/kernel/robotsoccer_run"),
    }[case]
    line = one_line(cli("demo", *FAST, "--out", str(out), "--record"), 2)
    assert str(out) in line


@pytest.mark.skipif(os.geteuid() == 0, reason="root writes into read-only folders")
def test_a_read_only_folder_is_one_line(tmp_path) -> None:
    folder = tmp_path / "ro"
    folder.mkdir()
    folder.chmod(0o500)
    one_line(cli("demo", *FAST, "--out", str(folder / "run")), 2, "cannot write")


def test_output_piped_into_head_ends_quietly(tmp_path) -> None:
    command = (
        f"{sys.executable} -m robotsoccer.cli demo --trials 20 --workers 2 --quiet "
        f"--out {tmp_path / 'run'} | head -1; echo status=${{PIPESTATUS[0]}}"
    )
    done = subprocess.run(["bash", "-c", command], capture_output=True, text=True, timeout=300)
    assert "Traceback" not in done.stderr and "BrokenPipe" not in done.stderr
    assert done.stdout.strip().splitlines()[-1] in ("status=0", "status=141")


def test_an_error_inside_a_worker_is_one_line(tmp_path) -> None:
    """A drill the parent knows and the workers do not: the workers raise."""
    (tmp_path / "boom_drill.py").write_text(
        textwrap.dedent(
            """
            from robotsoccer.drills import DRILLS
            from robotsoccer.drills.shootout import ShootoutDrill
            DRILLS["boom"] = ShootoutDrill
            """
        )
    )

    def script(drill: str, out: str) -> str:
        return (
            "import sys, boom_drill\n"
            "from robotsoccer.cli import main\n"
            f"sys.exit(main(['demo', '--drill', {drill!r}, '--trials', '4', '--workers', '2',"
            f" '--quiet', '--out', {str(tmp_path / out)!r}]))\n"
        )

    env = {**os.environ, "PYTHONPATH": str(tmp_path)}
    run = [sys.executable, "-c"]
    ok = subprocess.run([*run, script("shootout", "a")], capture_output=True, text=True, env=env)
    assert ok.returncode == 0, ok.stderr
    done = subprocess.run([*run, script("boom", "b")], capture_output=True, text=True, env=env)
    one_line(done, 2, "unknown drill 'boom'")


# ----------------------------------------------------------------------------- bad input


@pytest.mark.parametrize(
    ("args", "words"),
    [
        (("demo", "--ball-noise", "nan"), ("--ball-noise", "finite")),
        (("demo", "--ball-noise", "-0.1"), ("--ball-noise", ">= 0")),
        (("demo", "--seed", "-1"), ("--seed", ">= 0")),
        (("demo", "--trials", "0"), ("--trials",)),
        (("trace", "--trial", "-2"), ("--trial",)),
        (("demo", "--drill", "intercept", "--option", "behavior=net"), ("behavior", "options:")),
        (("demo", "--drill", "intercept", "--option", "behaviour=dance"), ("behaviour", "known:")),
        (("demo", "--option", "max_time_s=inf"), ("max_time_s", "finite")),
        (("demo", "--option", "max_time_s"), ("NAME=VALUE",)),
        (
            ("demo", "--field", "soccer_server", "--drill", "setplay", "--option", "client=udp"),
            ("client", "known: see, cycle"),
        ),
        (
            ("demo", *FAST, "--drill", "setplay", "--option", "client=cycle"),
            ("client=cycle", "robots' host"),
        ),
        (
            ("demo", "--field", "soccer_server", "--drill", "pass", "--option", "client=udp"),
            ("client", "known: see, cycle"),
        ),
        (
            ("demo", *FAST, "--drill", "pass", "--option", "client=cycle"),
            ("client=cycle", "robots' host"),
        ),
    ],
)
def test_bad_values_are_refused_naming_the_option(args, words) -> None:
    one_line(cli(*args), 2, *words)


def test_a_net_from_another_field_is_refused_unless_it_is_a_transfer(tmp_path) -> None:
    from learning.interception import InterceptionModel

    rng = __import__("numpy").random.default_rng(0)
    x = rng.uniform([5, -0.2, 5], [14, 0.2, 16], (40, 3))
    origin = Provenance("soccer_server", "soccer_server_1996", 0, 0.05, "random", 100)
    net = InterceptionModel(epochs=5).fit(x, 0.3 * x[:, 1]).save(tmp_path / "net.npz", origin)
    base = ("demo", "--drill", "intercept", "--option", "behaviour=net")
    model = ("--option", f"model={net}", *FAST)
    line = one_line(cli(*base, *model, "--field", "robot_physics"), 2, "transfer=true")
    assert "soccer_server `soccer_server_1996`" in line and "robot_physics" in line
    across = cli(*base, *model, "--field", "robot_physics", "--option", "transfer=true",
                 "--out", str(tmp_path / "t"))  # fmt: skip
    assert across.returncode == 0, across.stderr
    same = cli(*base, *model, "--field", "soccer_server", "--out", str(tmp_path / "s"))
    assert same.returncode == 0, same.stderr


# ----------------------------------------------------------------------------- discoverability


def test_the_bare_command_lists_the_commands_and_there_is_a_version() -> None:
    bare = cli()
    assert bare.returncode == 2
    for command in ("demo", "trace", "learn", "reproduce", "transfer", "bench", "replay"):
        assert command in bare.stdout
    assert cli("--version").stdout.startswith("robotsoccer ")
    assert "(default: robot_physics)" in cli("trace", "--help").stdout
    assert "(default: robot_physics)" in cli("demo", "--help").stdout


def test_debug_shows_the_traceback() -> None:
    done = cli("demo", "--drill", "intercept", "--option", "behaviour=dance", "--debug")
    assert done.returncode != 0 and "Traceback" in done.stderr


# ----------------------------------------------------------------------------- memory


def test_a_huge_run_allocates_nothing_per_trial_before_its_work(tmp_path, monkeypatch) -> None:
    calls: list[int] = []

    def interrupted(spec, indices):
        calls.append(len(indices))
        raise KeyboardInterrupt

    monkeypatch.setattr(pool, "run_chunk", interrupted)
    spec = TrialSpec(drill="shootout", field_model="robot_physics")
    tracemalloc.start()
    with pytest.raises(KeyboardInterrupt):
        pool.run_trials(
            spec, 30_000_000, workers=1, results_path=tmp_path / "r.csv", progress=False,
            on_result=lambda _: None,
        )  # fmt: skip
    _, peak = tracemalloc.get_traced_memory()
    tracemalloc.stop()
    assert calls == [50]
    assert peak < 60e6  # one byte a trial (30 MB), not a list of indices (over 1 GB)
    assert (tmp_path / "r.csv").read_text().startswith("index,")  # the table the message names
