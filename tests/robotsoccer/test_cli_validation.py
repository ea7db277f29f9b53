"""Issue 30's hostile inputs at the command line: each is refused in one line, exit status 2.

Run in-process (``main``) for speed; the Chipmunk abort of ``mass_kg = inf`` runs in a child
process, so a regression there fails this test instead of killing the test session.
"""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from robotsoccer.cli import main

ROBOT = 'base = "small_size_1997"\n'
SERVER = 'base = "soccer_server_1996"\n'

PRESETS = [
    ("robot_physics", "m.toml", ROBOT + "[robot]\nmass_kg = inf\n", "robot.mass_kg"),
    ("robot_physics", "h.toml", ROBOT + "[timing]\nphysics_hz = 2.4e7\n", "timing.physics_hz"),
    ("robot_physics", "i.toml", ROBOT + "[timing]\nsolver_iterations = 1000000000\n",
     "timing.solver_iterations"),
    ("robot_physics", "s.toml", ROBOT + "[robot]\nsize_m = 10\n", "robot.size_m"),
    ("robot_physics", "c.toml", ROBOT + "[camera]\nposition_sigma_m = inf\n",
     "camera.position_sigma_m"),
    ("robot_physics", "l.toml", ROBOT + "[camera]\nlatency_s = inf\n", "camera.latency_s"),
    ("robot_physics", "d.toml", ROBOT + "[camera]\nlatency_s = 1" + "0" * 400 + "\n",
     "camera.latency_s"),
    ("soccer_server", "p.toml", SERVER + "[dynamics]\ndash_power_rate_m_per_cycle2 = inf\n",
     "dynamics.dash_power_rate_m_per_cycle2"),
    ("soccer_server", "r.conf", "server::player_rand = 1e999\n", "server::player_rand"),
    ("soccer_server", "q.conf", "server::dash_power_rate = 1e999\n", "server::dash_power_rate"),
    ("soccer_server", "t.conf", "server::simulator_step = 1e300\n", "server::simulator_step"),
    ("robot_physics", "n.toml", "a = " + "[" * 5000 + "]" * 5000 + "\n", "nested too deeply"),
]  # fmt: skip


def refused(capsys: pytest.CaptureFixture[str], args: list[str], *words: str) -> str:
    """Run the command in-process; it must exit 2 with one line holding `words`."""
    try:
        status = main(args)
    except SystemExit as exc:  # argparse's own refusals
        status = exc.code  # type: ignore[assignment]
    err = capsys.readouterr().err
    lines = [line for line in err.splitlines() if line]
    assert status == 2, err
    assert len(lines) == 1 and "Traceback" not in err, err
    for word in words:
        assert word in lines[0], lines[0]
    return lines[0]


@pytest.mark.parametrize(("field", "name", "text", "key"), PRESETS, ids=[p[1] for p in PRESETS])
def test_an_absurd_preset_is_one_line_naming_file_and_key(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], field: str, name: str, text: str, key: str
) -> None:
    path = tmp_path / name
    path.write_text(text)
    args = ["demo", "--field", field, "--field-preset", str(path), "--drill", "intercept"]
    refused(capsys, [*args, "--trials", "2", "--out", str(tmp_path / "run")], str(path), key)
    assert not (tmp_path / "run").exists()


def test_a_file_that_is_no_preset_is_one_line(
    tmp_path: Path, capsys: pytest.CaptureFixture[str]
) -> None:
    garbage = tmp_path / "g.toml"
    garbage.write_bytes(bytes(range(128, 256)) * 3)
    refused(capsys, ["demo", "--field-preset", str(garbage)], "g.toml", "not UTF-8")
    if Path("/dev/zero").exists():
        refused(capsys, ["demo", "--field-preset", "/dev/zero"], "/dev/zero", "larger than")


@pytest.mark.parametrize(
    ("args", "words"),
    [
        (["demo", "--ball-noise", "1e308"], ["--ball-noise", "<= 1"]),
        (["demo", "--trials", str(10**13)], ["--trials", "<= 100000000"]),
        (["demo", "--seed", str(2**64)], ["--seed", "2**64"]),
        (["demo", "--workers", "100000"], ["--workers"]),
        (["demo", "--option", "max_time_s=1e9"], ["max_time_s", "3600"]),
        (["match", "--half-time", "1e300"], ["--half-time"]),
        (["match", "--field", "soccer_server", "--left", "baseline", "--half-time", "1e-300"],
         ["half_time_s", "one tick"]),
    ],
)  # fmt: skip
def test_an_absurd_option_is_one_line(
    tmp_path: Path, capsys: pytest.CaptureFixture[str], args: list[str], words: list[str]
) -> None:
    refused(capsys, [*args, "--out", str(tmp_path / "run")], *words)
    assert not (tmp_path / "run").exists()


def test_an_infinite_robot_mass_never_reaches_chipmunk(tmp_path: Path) -> None:
    path = tmp_path / "m.toml"
    path.write_text(ROBOT + "[robot]\nmass_kg = inf\n")
    done = subprocess.run(
        [sys.executable, "-m", "robotsoccer.cli", "demo", "--field-preset", str(path),
         "--trials", "2", "--workers", "2", "--quiet", "--out", str(tmp_path / "run")],
        capture_output=True, text=True, timeout=300,
    )  # fmt: skip
    assert done.returncode == 2, done.stderr  # was 134: Chipmunk's abort
    assert done.stderr.count("\n") == 1 and "robot.mass_kg" in done.stderr


@pytest.mark.skipif(sys.platform != "linux", reason="RLIMIT_FSIZE and SIGXFSZ as on Linux")
def test_rerun_log_lines_are_quiet_when_a_recording_cannot_be_written(tmp_path: Path) -> None:
    import os
    import resource

    def small_files() -> None:  # writes past 100 KB fail (EFBIG), as on a full disk
        resource.setrlimit(resource.RLIMIT_FSIZE, (100_000, 100_000))

    env = {k: v for k, v in os.environ.items() if k != "RUST_LOG"}
    try:
        done = subprocess.run(
            [sys.executable, "-m", "robotsoccer.cli", "demo", "--record", "--trials", "2",
             "--workers", "1", "--quiet", "--out", str(tmp_path / "run")],
            capture_output=True, text=True, timeout=30, env=env, preexec_fn=small_files,
        )  # fmt: skip
        err = done.stderr
    except subprocess.TimeoutExpired as exc:
        # rerun 0.41's disconnect() now and then hangs once its file writer has died; what
        # was printed until then is what this test is about.
        raw = exc.stderr or b""
        err = raw.decode(errors="replace") if isinstance(raw, bytes) else raw
    assert "re_log" not in err and "\x1b[" not in err, err
