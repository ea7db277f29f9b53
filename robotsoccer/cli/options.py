"""The command line's shared parts: exit statuses, option types and the field models by name.

Exit statuses, the option types with their bounds, and the field models the commands run by
name (the one place above the percept/action line that names them:
``tests/test_boundaries.py``). The option groups that use them are in
:mod:`robotsoccer.cli.shared`; each command's parser is in its module of
:mod:`robotsoccer.cli.commands`.
"""

from __future__ import annotations

import argparse
import math

from field_models.arena import MAX_BALL_NOISE
from robotsoccer.options import MAX_COUNT, MAX_SEED, MAX_SIMULATED_S, MAX_WORKERS

DEFAULT_FIELD = "robot_physics"
"""The field model every command runs on unless told otherwise: the paper's mini-robots."""
PAPER_MODELS = ("soccer_server", "robot_physics")
"""The field models ``reproduce`` runs, in report order."""

TEAM_FIELD = "soccer_server"
"""Where ``reproduce`` runs layer 3: the 11-a-side match of the paper's §7 and of TPOT-RL."""
REFERENCE_FIELD, TARGET_FIELD = "soccer_server", "robot_physics"
"""The transfer study's source of randomised variants and the field it closes the gap on."""

LEAD_DRILLS: dict[str, tuple[str, tuple[tuple[str, str | float], ...], str]] = {
    "robot_physics": (
        "small_size_1997_arc",
        (
            ("shot", "goal_mouth"),
            ("scaling", "task"),
            ("launch", "coach"),
            ("launch_speed_mps", 0.6),
            ("launch_speed_max_mps", 1.2),
        ),
        "shots across the goal mouth at 0.6-1.2 m/s from 0.52-0.78 m, arcs, 30 Hz camera",
    ),
    "soccer_server": (
        "soccer_server_1996",
        (),
        "the paper's drill (§5), shots at the defender",
    ),
}
"""The lead study's drill on each field: (preset, drill options, summary)
(:mod:`robotsoccer.experiments.lead_study`, whose docstring gives the numbers' sources)."""

BENCH_TARGETS = {
    "robot_physics.realtime_factor.2_robots": (">=", 300.0),
    "robot_physics.realtime_factor.12_robots": (">=", 60.0),
    "robot_physics.share_of_chipmunk.2_robots": (">=", 0.5),
    "robot_physics.share_of_chipmunk.12_robots": (">=", 0.4),
    "soccer_server.cycles_per_s.2_players": (">=", 30_000.0),
    "soccer_server.object_cycles_per_s.batch": (">=", 2_000_000.0),
    "intercept.trials_per_s.soccer_server": (">=", 3_000.0),
    "intercept.trials_per_s.robot_physics": (">=", 100.0),
    "intercept.trials_per_s.soccer_server_batch": (">=", 90_000.0),
    "pass.trials_per_s.soccer_server": (">=", 300.0),
    "pass.trials_per_s.robot_physics": (">=", 200.0),  # issue 21 (was 40)
    "training.net_1000_saves_s": ("<=", 5.0),
    "match.wall_s.soccer_server": ("<=", 60.0),
    "match.realtime_factor.robot_physics": (">=", 150.0),  # issue 21 (was 50)
    "envs.score_env_to_bare_ratio.robot_physics": (">=", 0.8),
    "envs.score_env_to_bare_ratio.soccer_server": (">=", 0.8),
}
"""What ``robotsoccer bench`` checks each figure against."""

TEAM_KINDS = ("layered", "baseline", "layer3")
"""The match drill's team kinds (:class:`robotsoccer.drills.match_options.TeamKind`)."""
SERVE_FIELD = "soccer_server"
"""The field model ``serve`` serves over UDP; its presets are what ``--field-preset`` names."""
SERVE_PRESET = "rcssserver_19_async"
"""The preset ``serve`` runs unless told: today's server, what existing agents expect."""

EXIT_USAGE, EXIT_FAILURE, EXIT_INTERRUPTED, EXIT_BROKEN_PIPE = 2, 1, 130, 141
"""Exit statuses: bad input; a failure while running; Ctrl-C; the output pipe closed."""


class UsageError(ValueError):
    """A user error reported as one line (exit status 2)."""


# ----------------------------------------------------------------------------- option types


def _positive_int(text: str, most: int = MAX_COUNT) -> int:
    value = _int(text)
    if not 0 < value <= most:
        raise argparse.ArgumentTypeError(f"expected a whole number > 0 and <= {most}, got {text!r}")
    return value


def _workers(text: str) -> int:
    return _positive_int(text, MAX_WORKERS)


def _positive_float(text: str) -> float:
    """A simulated duration [s] (``--half-time``): finite, > 0 and within the sane limit."""
    try:
        value = float(text)
    except ValueError:
        value = math.nan
    if not math.isfinite(value) or not 0.0 < value <= MAX_SIMULATED_S:
        raise argparse.ArgumentTypeError(
            f"expected a finite number > 0 and <= {MAX_SIMULATED_S:g}, got {text!r}"
        )
    return value


def _port(text: str) -> int:
    value = _int(text)
    if not 0 <= value <= 65535:
        raise argparse.ArgumentTypeError(f"a UDP port is 0..65535 (0: any free one), got {value}")
    return value


def _index(text: str) -> int:
    value = _int(text)
    if not 0 <= value <= MAX_SEED:
        raise argparse.ArgumentTypeError(f"expected a whole number >= 0 and < 2**64, got {text!r}")
    return value


def _int(text: str) -> int:
    try:
        return int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a whole number, got {text!r}") from None


def _noise(text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        value = math.nan
    if not math.isfinite(value) or not 0.0 <= value <= MAX_BALL_NOISE:
        raise argparse.ArgumentTypeError(
            f"expected a finite number >= 0 and <= {MAX_BALL_NOISE:g}, got {text!r}"
        )
    return value


def _drill_option(text: str) -> tuple[str, str | float | int | bool]:
    """``name=value`` → (name, value as bool, int, float or str)."""
    name, sep, raw = text.partition("=")
    if not sep or not name:
        raise argparse.ArgumentTypeError(f"expected NAME=VALUE, got {text!r}")
    if raw.lower() in ("true", "false"):
        return name, raw.lower() == "true"
    for kind in (int, float):
        try:
            value = kind(raw)
        except ValueError:
            continue
        if isinstance(value, float) and not math.isfinite(value):
            raise argparse.ArgumentTypeError(f"{name}: expected a finite number, got {raw!r}")
        return name, value
    return name, raw
