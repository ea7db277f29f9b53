"""Release fuzz (issue 30): hostile inputs through every parser and guard a user can reach.

Usage::

    PYTHONPATH=. .venv/bin/python scripts/fuzz.py [--cases 100000] [--seed 0] [--trial-every 10]

Each case feeds one target a generated input: a mutated robot or Soccer Server preset, a
``server.conf`` or ``server_param`` message, raw bytes as a preset, command text, a server
message, a game-log line, a model file, environment actions and seeds, a command-line option
value. A case either **works** (the input is valid and was used), is **refused** with the
target's documented error type (:data:`DOCUMENTED`), or is a **finding**: any other exception,
a broken invariant (a loaded preset outside its ranges, a command that does not survive render
and parse), or a case that runs past ``--case-timeout`` seconds. One in ``--trial-every``
presets that load also plays one trial on it, so a value that loads but breaks the simulation
(Chipmunk's C asserts, a cast of NaN, a loop without end) is found too; a C abort kills this
process, and ``faulthandler`` then names the case.

Cases are reproducible: case i's input comes from ``random.Random(f"{seed}:{i}")`` alone, and
``--case i`` reruns one case. The exit status is 1 when there is a finding.
"""

from __future__ import annotations

import argparse
import contextlib
import dataclasses
import faulthandler
import json
import math
import random
import signal
import string
import sys
import tempfile
import time
import typing
from collections import Counter
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np

from field_models.commands import CommandParseError, parse_command, render_command
from field_models.presets import PRESET_DIR, Bounds, PresetError, bounds_of, range_problem
from field_models.protocol import Dash, Kick, Say, Turn
from field_models.robot_physics.config import RobotPhysicsPreset, load_preset
from field_models.soccer_server import server_conf
from field_models.soccer_server.messages import MessageParseError, parse_sexpr
from field_models.soccer_server.params import DynamicsParams, load_server_preset
from field_models.soccer_server.sensing_params import SensingParams
from field_models.soccer_server.server_param_table import SERVER_PARAMS
from learning.features import ModelFileError
from learning.lookup import LookupTable
from robotsoccer.cli import options as cli
from robotsoccer.envs import InterceptVectorEnv, pass_parallel_env
from robotsoccer.envs.intercept import InterceptEnv
from robotsoccer.replay.rcg_read import read_rcg
from robotsoccer.runs.runner import TrialSpec, run_trial

NASTY = [
    "inf", "-inf", "nan", "+inf", "1e999", "-1e999", "1e308", "1e300", "-1e300", "1e-300",
    "5e-324", "0", "-0.0", "0.0", "1" + "0" * 400, "-1" + "0" * 400, "2.4e7", "1000000000",
    "10", "-1", "0.5", "1", "100", "1e6", "true", "false", '"text"', "''", "[1, 2]", "[]",
    "{ a = 1 }", "1979-05-27", "0x10", "0o7", "1_000", "nan0", "--1", "1e", ".", "",
]  # fmt: skip
"""Values a hostile user writes: non-finite, overflowing, huge, tiny, negative, mistyped."""

DOCUMENTED: dict[str, tuple[type[BaseException], ...]] = {
    "robot_preset": (PresetError,),
    "server_preset": (PresetError,),
    "server_conf": (PresetError,),
    "server_param": (PresetError,),
    "preset_bytes": (PresetError,),
    "command": (CommandParseError,),
    "server_message": (MessageParseError,),
    "game_log": (ValueError,),
    "model_file": (ModelFileError,),
    "env_actions": (ValueError,),
    "env_seeds": (ValueError,),
    "cli_option": (argparse.ArgumentTypeError,),
}
"""The error each target documents for an input it refuses; any other exception is a finding.
A trial played on a loaded preset documents ValueError (a drill that cannot be set up there)."""


class Finding(Exception):
    """A broken invariant: the input was accepted but the result is wrong."""


class CaseTimeout(Exception):
    """A case ran past its time limit (a loop without a bound)."""


# ----------------------------------------------------------------------------- generators


def number(rng: random.Random) -> str:
    """A number's text: a nasty literal, or a random one of any magnitude and sign."""
    roll = rng.random()
    if roll < 0.5:
        return rng.choice(NASTY)
    if roll < 0.8:
        return repr(rng.choice((-1, 1)) * 10 ** rng.uniform(-12, 12))
    return str(rng.randint(-(10**12), 10**12))


SPECIAL_FLOATS = [math.inf, -math.inf, math.nan, 1e308, -1e308, 5e-324, 0.0, -0.0, 1e300, 2.4e7]


def real(rng: random.Random) -> float:
    """A float: a special one (non-finite, extreme, signed zero) or of any magnitude and sign."""
    if rng.random() < 0.3:
        return rng.choice(SPECIAL_FLOATS)
    return rng.choice((-1, 1)) * 10 ** rng.uniform(-12, 12)


def text(rng: random.Random, size: int = 20) -> str:
    """Random text: printable, parentheses and quotes, some control and non-ASCII characters."""
    alphabet = string.printable + "()()\"\"''\0\x1c\u00e9\u2028\U0001f600"
    return "".join(rng.choice(alphabet) for _ in range(rng.randint(0, size)))


def record_bounds(root: type) -> dict[str, Bounds]:
    """Each dotted preset key of record `root` (and the records in it) with its bounds."""
    hints = typing.get_type_hints(root)
    out: dict[str, Bounds] = {}
    for fld in dataclasses.fields(root):
        bounds = bounds_of(fld)
        if bounds is not None:
            out[fld.name] = bounds
        elif dataclasses.is_dataclass(hints[fld.name]) and isinstance(hints[fld.name], type):
            out |= {f"{fld.name}.{k}": b for k, b in record_bounds(hints[fld.name]).items()}
    return out


def edge_values(rng: random.Random, source: str, bounds: dict[str, Bounds]) -> str:
    """A preset text with one to three numbers set to an end of their stated range.

    The ends are valid, so the preset loads, and they are where a simulation is likeliest to
    break (a robot at its smallest, a ball at its fastest, physics at 10 kHz).
    """
    lines = source.splitlines()
    table, candidates = "", []
    for i, line in enumerate(lines):
        if line.startswith("["):
            table = line.strip("[] ")
        elif _value(line) is not None:
            key = line.partition("=")[0].strip()
            degrees = key.endswith("_deg")
            dotted = f"{table}.{key.removesuffix('_deg') + '_rad' if degrees else key}"
            if dotted in bounds:
                candidates.append((i, key, bounds[dotted], degrees))
    for i, key, b, degrees in rng.sample(candidates, rng.randint(1, min(3, len(candidates)))):
        value = b.high if rng.random() < 0.5 else b.low
        if degrees:
            value = math.degrees(value) * (1 - 1e-12)  # no rounding past the end in radians
        lines[i] = f"{key} = {value!r}"
    return "\n".join(lines) + "\n"


def scale_values(rng: random.Random, source: str) -> str:
    """A preset text with one to three numbers scaled by up to 100 either way.

    Most such presets still load, and those that do are played: this finds values that load
    but break the simulation.
    """
    lines = source.splitlines()
    numeric = [i for i, line in enumerate(lines) if _value(line) is not None]
    for i in rng.sample(numeric, rng.randint(1, min(3, len(numeric)))):
        key, _, _ = lines[i].partition("=")
        old = _value(lines[i])
        assert old is not None
        lines[i] = f"{key}= {old * 10 ** rng.uniform(-2, 2)!r}"
    return "\n".join(lines) + "\n"


def _value(line: str) -> float | None:
    """The number a ``key = value  # comment`` line sets, or None."""
    key, equals, rest = line.partition("=")
    if not equals or key.strip().startswith("#"):
        return None
    try:
        return float(rest.split("#")[0])
    except ValueError:
        return None


def mutate_lines(rng: random.Random, source: str) -> str:
    """A preset-like text with one to three edits.

    A value replaced by a nasty one, a line dropped or duplicated, garbage inserted, the text
    cut short, deep nesting added.
    """
    lines = source.splitlines()
    for _ in range(rng.randint(1, 3)):
        i = rng.randrange(len(lines))
        kind = rng.random()
        if kind < 0.6 and "=" in lines[i]:
            key = lines[i].partition("=")[0]
            lines[i] = f"{key}= {number(rng)}"
        elif kind < 0.7:
            del lines[i]
        elif kind < 0.8:
            lines.insert(i, lines[i])
        elif kind < 0.9:
            lines.insert(i, text(rng, 30))
        elif kind < 0.95:
            depth = rng.randint(1, 3000)
            lines.insert(i, "deep = " + "[" * depth + "]" * depth)
        else:
            lines = lines[: i + 1]
            lines[-1] = lines[-1][: rng.randint(0, len(lines[-1]))]
        if not lines:
            lines = [""]
    return "\n".join(lines) + "\n"


# ----------------------------------------------------------------------------- targets


class Fuzz:
    """The targets, sharing a scratch folder, the source texts and the environments."""

    def __init__(self, folder: Path, trial_every: int) -> None:
        self.folder = folder
        self.trial_every = trial_every
        self.loaded = Counter[str]()
        self.written: list[Path] = []
        self.robot_bounds = record_bounds(RobotPhysicsPreset)
        self.server_bounds = {
            f"{table}.{key}": b
            for table, record in (("dynamics", DynamicsParams), ("sensing", SensingParams))
            for key, b in record_bounds(record).items()
        }
        self.played = 0
        self.robot_text = (PRESET_DIR / "robot_physics" / "small_size_1997.toml").read_text()
        self.server_text = (PRESET_DIR / "soccer_server" / "rcssserver_19_async.toml").read_text()
        self.trial_refusals = Counter[str]()
        self.rcg = self._game_log()
        self.lookup = LookupTable([-1.0, 0.0, 1.0], [0.5, 0.0, -0.5]).save(folder / "table.json")
        self.vector = InterceptVectorEnv(2)
        self.vector.reset(seed=0)
        self.targets: dict[str, Callable[[random.Random, int], str]] = {
            "robot_preset": self.robot_preset,
            "server_preset": self.server_preset,
            "server_conf": self.server_conf,
            "server_param": self.server_param,
            "preset_bytes": self.preset_bytes,
            "command": self.command,
            "server_message": self.server_message,
            "game_log": self.game_log,
            "model_file": self.model_file,
            "env_actions": self.env_actions,
            "env_seeds": self.env_seeds,
            "cli_option": self.cli_option,
        }

    def _game_log(self) -> str:
        return (
            "ULG5\n(server_param (goal_width 14.02)(simulator_step 100))\n(playmode 1 play_on)\n"
            "(team 1 a b 0 0)\n(show 1 ((b) 1.5 -2 0.1 0) ((l 1) 0 0x1 -10 3 0.2 0.1 45 0 "
            "(v h 90) (s 8000 1 1 130600) (c 0 0 0 0 0 0 0 0 0 0 0)))\n"
        )

    def _file(self, case: int, suffix: str, content: str | bytes) -> Path:
        # A new name per case: the field models cache presets by name.
        path = self.folder / f"case{case}{suffix}"
        if isinstance(content, bytes):
            path.write_bytes(content)
        else:
            path.write_text(content)
        self.written.append(path)
        return path

    def clean(self) -> None:
        """Remove the files the last case wrote."""
        for path in self.written:
            path.unlink(missing_ok=True)
        self.written.clear()

    def _mutant(self, rng: random.Random, text: str, bounds: dict[str, Bounds]) -> str:
        """A preset text: nasty edits, values scaled, or values at the ends of their ranges."""
        roll = rng.random()
        if roll < 0.4:
            return mutate_lines(rng, text)
        if roll < 0.7:
            return scale_values(rng, text)
        return edge_values(rng, text, bounds)

    def _trial_due(self, model: str, rng: random.Random) -> bool:
        # Drawn from the case's own generator, so that --case i plays it again.
        self.loaded[model] += 1
        due = self.trial_every > 0 and rng.random() * self.trial_every < 1.0
        self.played += due
        return due

    def _play(self, model: str, preset: str, drill: str) -> None:
        """One trial on a loaded preset: it must end with a verdict or a ValueError."""
        spec = TrialSpec(drill=drill, field_model=model, preset=preset)
        try:
            result = run_trial(spec, 0)
        except ValueError as err:  # a drill that cannot be set up on this field
            reason = str(err).replace(preset, "<preset>").replace(Path(preset).stem, "<preset>")
            self.trial_refusals[f"{model}: {reason[:90]}"] += 1
            return
        if not math.isfinite(result.time_s):
            raise Finding(f"a trial on {preset} took {result.time_s} s")

    def robot_preset(self, rng: random.Random, case: int) -> str:
        """A mutated robot preset: it loads within its ranges (and plays) or is refused."""
        path = self._file(case, ".toml", self._mutant(rng, self.robot_text, self.robot_bounds))
        preset = load_preset(str(path))
        _in_range(preset)
        if self._trial_due("robot_physics", rng):
            self._play("robot_physics", str(path), rng.choice(["shootout", "intercept"]))
        return "ok"

    def server_preset(self, rng: random.Random, case: int) -> str:
        """A mutated Soccer Server preset, as :meth:`robot_preset`."""
        path = self._file(case, ".toml", self._mutant(rng, self.server_text, self.server_bounds))
        preset = load_server_preset(str(path))
        _in_range(preset.dynamics)
        _in_range(preset.sensing)
        if self._trial_due("soccer_server", rng):
            self._play("soccer_server", str(path), rng.choice(["intercept", "pass"]))
        return "ok"

    def _settings(self, rng: random.Random) -> list[tuple[str, str]]:
        names = [rng.choice(SERVER_PARAMS) if rng.random() < 0.9 else text(rng, 8)
                 for _ in range(rng.randint(1, 5))]  # fmt: skip
        return [(name, number(rng) if rng.random() < 0.9 else text(rng, 8)) for name in names]

    def server_conf(self, rng: random.Random, case: int) -> str:
        """A server.conf of random settings (and the odd garbage line)."""
        lines = [f"server::{n} = {v}" for n, v in self._settings(rng)]
        if rng.random() < 0.2:
            lines.insert(rng.randrange(len(lines) + 1), text(rng, 30))
        preset = server_conf.load_preset(str(self._file(case, ".conf", "\n".join(lines) + "\n")))
        _in_range(preset.dynamics)
        _in_range(preset.sensing)
        return "ok"

    def server_param(self, rng: random.Random, case: int) -> str:
        """A ``(server_param ...)`` message of random entries."""
        body = " ".join(f"({n} {v})" for n, v in self._settings(rng))
        message = f"(server_param {body})"
        if rng.random() < 0.2:
            i = rng.randrange(len(message))
            message = message[:i] + text(rng, 5) + message[i:]
        preset = server_conf.load_preset(message)
        _in_range(preset.dynamics)
        _in_range(preset.sensing)
        return "ok"

    def preset_bytes(self, rng: random.Random, case: int) -> str:
        """Raw bytes as a preset or a server.conf."""
        data = rng.randbytes(rng.randint(0, 400))
        if rng.random() < 0.5:
            load_preset(str(self._file(case, ".toml", data)))
        else:
            server_conf.load_preset(str(self._file(case, ".conf", data)))
        return "ok"

    def command(self, rng: random.Random, case: int) -> str:
        """Command text parses or is refused; any action survives render and parse."""
        roll = rng.random()
        if roll < 0.4:
            parse_command(rng.choice(["", "(", "(say ", "(turn ", "(dash ", "(kick "]) + text(rng))
            return "ok"
        if roll < 0.7:
            message = text(rng) or "x"
            if parse_command(render_command(Say(message))) != Say(message):
                raise Finding(f"Say({message!r}) does not survive render and parse")
            return "ok"
        values = [real(rng) if rng.random() < 0.7 else rng.uniform(-200, 200) for _ in range(2)]
        if not all(math.isfinite(v) for v in values):
            return "refused"  # a non-finite action is no command; render_command is not asked
        action = rng.choice([Turn(values[0]), Dash(*values), Kick(*values)])
        rendered = render_command(action)
        if render_command(parse_command(rendered)) != rendered:
            raise Finding(f"{action!r} renders as {rendered!r}, which does not read back")
        return "ok"

    def server_message(self, rng: random.Random, case: int) -> str:
        """A server message (see, hear, server_param) with random edits."""
        base = rng.choice([
            "(see 0 ((b) 10 -20) ((p \"a\" 1) 5 3))", "(hear 10 referee kick_off_l)",
            "(server_param (ball_decay 0.94))", "(see 5 ((f c) 1e999 2))",
        ])  # fmt: skip
        i = rng.randrange(len(base) + 1)
        parse_sexpr(base[:i] + text(rng, 6) + base[i + rng.randint(0, 3) :])
        return "ok"

    def game_log(self, rng: random.Random, case: int) -> str:
        """A game log with one line's numbers (or characters) replaced."""
        lines = self.rcg.splitlines()
        i = rng.randrange(1, len(lines))
        words = lines[i].split(" ")
        for _ in range(rng.randint(1, 3)):  # a word's text, its parentheses kept
            j = rng.randrange(len(words))
            opening = words[j][: len(words[j]) - len(words[j].lstrip("("))]
            closing = words[j][len(words[j].rstrip(")")) :]
            words[j] = opening + (number(rng) if rng.random() < 0.8 else text(rng, 4)) + closing
        lines[i] = " ".join(words)
        game = read_rcg(self._file(case, ".rcg", "\n".join(lines) + "\n"))
        for frame in game.frames:
            truth = frame.truth
            for s in (truth.ball, *truth.players.values()):
                if not all(math.isfinite(v) for v in (s.x, s.y, s.heading, s.vx, s.vy)):
                    raise Finding(f"a game log read to a non-finite state: {lines[i][:100]!r}")
        return "ok"

    def model_file(self, rng: random.Random, case: int) -> str:
        """A lookup-table file with a value replaced or its text cut."""
        doc = json.loads(self.lookup.read_text())
        roll = rng.random()
        if roll < 0.6:
            key = rng.choice(["ball_angle_rad", "turn_angle_rad"])
            doc[key][rng.randrange(len(doc[key]))] = json.loads(
                rng.choice(["1e999", "-1e999", "1e308", "0", '"x"', "null", "[]"])
            )
            content = json.dumps(doc)
        elif roll < 0.8:
            content = self.lookup.read_text()[: rng.randint(0, 200)]
        else:
            content = "[" * rng.randint(1, 5000)
        LookupTable.load(self._file(case, ".json", content))
        return "ok"

    def env_actions(self, rng: random.Random, case: int) -> str:
        """Actions of a random shape and values for a vector env of 2."""
        shape = rng.choice([(2, 1), (2,), (4,), (0,), (2, 2), (1, 2), (), (2, 1, 1)])
        values = [real(rng) if rng.random() < 0.3 else rng.uniform(-3, 3)
                  for _ in range(int(np.prod(shape)))]  # fmt: skip
        actions = np.array(values, dtype=np.float64).reshape(shape)
        obs, *_ = self.vector.step(actions)
        if not self.vector.observation_space.contains(obs):
            raise Finding(f"observation out of its space after {actions!r}")
        return "ok"

    def env_seeds(self, rng: random.Random, case: int) -> str:
        """A random seed for the single, the vector and the PettingZoo env."""
        seed: Any = rng.choice([
            rng.randint(-(2**70), 2**70), rng.randint(0, 2**64 - 1), rng.random(), None,
            True, str(rng.randint(0, 9)), 2**64, -1,
        ])  # fmt: skip
        env = rng.choice([InterceptEnv("soccer_server"), pass_parallel_env("soccer_server"),
                          InterceptVectorEnv(1)])  # fmt: skip
        env.reset(seed=seed)
        return "ok"

    def cli_option(self, rng: random.Random, case: int) -> str:
        """A command-line number option's value: within its bounds or refused."""
        parse, low, high = rng.choice([
            (cli._noise, 0.0, 1.0), (cli._positive_float, 0.0, 3600.0),
            (cli._positive_int, 1, 10**8), (cli._index, 0, 2**64 - 1), (cli._workers, 1, 1024),
        ])  # fmt: skip
        value = parse(number(rng) if rng.random() < 0.8 else text(rng, 10))
        if not (math.isfinite(value) and low <= value <= high):
            raise Finding(f"{parse.__name__} gave {value!r}")
        return "ok"


def _in_range(record: Any) -> None:
    """A loaded record's numbers all inside their stated bounds, or a Finding."""
    for fld in dataclasses.fields(record):
        value = getattr(record, fld.name)
        if dataclasses.is_dataclass(value):
            _in_range(value)
        elif range_problem(bounds_of(fld), value) is not None:
            raise Finding(f"{type(record).__name__}.{fld.name} = {value!r} loaded out of range")


# ----------------------------------------------------------------------------- main


def _on_alarm(signum: int, frame: Any) -> None:
    raise CaseTimeout


def run(cases: range, seed: int, fuzz: Fuzz, timeout_s: float, quiet: bool) -> int:
    """Run the cases; print the counts per target; return the number of findings."""
    names = list(fuzz.targets)
    counts: dict[str, Counter[str]] = {name: Counter() for name in names}
    examples: list[str] = []
    signal.signal(signal.SIGALRM, _on_alarm)
    start = time.perf_counter()
    for i in cases:
        name = names[i % len(names)]
        rng = random.Random(f"{seed}:{i}")
        signal.setitimer(signal.ITIMER_REAL, timeout_s)
        try:
            outcome = fuzz.targets[name](rng, i)
        except DOCUMENTED[name]:
            outcome = "refused"
        except CaseTimeout:
            outcome = "finding"
            examples.append(f"case {i} ({name}): ran past {timeout_s:g} s")
        except Exception as exc:  # anything else is what the fuzz is for
            outcome = "finding"
            examples.append(f"case {i} ({name}): {type(exc).__name__}: {str(exc)[:200]}")
        finally:
            signal.setitimer(signal.ITIMER_REAL, 0)
            fuzz.clean()
        counts[name][outcome] += 1
        if not quiet and (i + 1) % 5000 == 0:
            found = sum(c["finding"] for c in counts.values())
            elapsed = time.perf_counter() - start
            print(f"{i + 1} cases, {found} findings, {elapsed:.0f} s", file=sys.stderr, flush=True)
    _report(counts, examples, fuzz, time.perf_counter() - start)
    return sum(c["finding"] for c in counts.values())


def _report(counts: dict[str, Counter[str]], examples: list[str], fuzz: Fuzz, wall: float) -> None:
    print(f"{'target':<16}{'cases':>9}{'ok':>9}{'refused':>9}{'findings':>10}")
    total: Counter[str] = Counter()
    for name, c in counts.items():
        total.update(c)
        n = sum(c.values())
        print(f"{name:<16}{n:>9}{c['ok']:>9}{c['refused']:>9}{c['finding']:>10}")
    n = sum(total.values())
    print(f"{'all':<16}{n:>9}{total['ok']:>9}{total['refused']:>9}{total['finding']:>10}")
    refused = sum(fuzz.trial_refusals.values())
    print(f"\ntrials played on loaded presets: {fuzz.played} (refused at set-up: {refused})")
    for reason, k in fuzz.trial_refusals.most_common(5):
        print(f"  {k:>5} x {reason}")
    print(f"{wall:.0f} s wall")
    for line in examples[:30]:
        print(line)


def main(argv: list[str] | None = None) -> int:
    """Parse the options, run the fuzz, exit 1 on any finding."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--cases", type=int, default=100_000, help="how many cases")
    parser.add_argument("--seed", type=int, default=0, help="seed of the case generator")
    parser.add_argument("--case", type=int, default=None, help="run this one case only")
    parser.add_argument(
        "--trial-every", type=int, default=10, help="play a trial on one in k loaded presets"
    )
    parser.add_argument("--case-timeout", type=float, default=60.0, help="seconds per case")
    parser.add_argument("--quiet", action="store_true", help="no progress lines")
    args = parser.parse_args(argv)
    # A C abort (Chipmunk's asserts) still names the case's stack; stderr without a file
    # descriptor (a test capturing it) has one of its own already.
    with contextlib.suppress(ValueError):
        faulthandler.enable()
    cases = range(args.case, args.case + 1) if args.case is not None else range(args.cases)
    with tempfile.TemporaryDirectory(prefix="robotsoccer-fuzz-") as scratch:
        fuzz = Fuzz(Path(scratch), args.trial_every)
        findings = run(cases, args.seed, fuzz, args.case_timeout, args.quiet)
    return 1 if findings else 0


if __name__ == "__main__":
    sys.exit(main())
