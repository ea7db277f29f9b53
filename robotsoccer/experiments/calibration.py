"""Calibration: fit the Soccer Server model's parameters to robot traces, then retrain (issue 20).

The transfer study moves a net from the Soccer Server model to the robots as it is (distances
in drill units). Calibration is the other way to close that gap: make the simulator behave like
the robots, then learn there. This module does the first half, in three steps:

1. **record** (:func:`record_traces`): on any field model, through the arena interface only
   (coach placements, the truth, the percepts a client gets), record

   * the ball rolling free after a launch at each of the drill's launch speeds (its speed at
     every tick, no ball noise);
   * a player at rest commanded ``DASH 100`` at every tick (its speed at every tick);
   * a player and a ball at rest 20, 25 and 30 units apart: the percepts' arrival ticks, their
     sample ticks (latency) and the seen distance's log error (sensing noise).

   Speeds are in drill units per second (:attr:`~field_models.arena.FieldFacts.unit_m`), so a
   trace of the robot table and one of the server's pitch are in the same units.
2. **fit** (pure functions on arrays, each closed-form least squares):

   * the cycle: half the sensor's period as the client sees it, and a see every two cycles
     (``send_step = 2 simulator_step``, spec §3.1): the server carries out one body command
     per cycle (spec §2), so the see client's "turn, then dash" takes two cycles where the
     robots' host runs both as one arc within a camera frame (:data:`CYCLES_PER_SEE`);
   * ``ball_decay`` (spec §1.2: v ← decay·v each cycle): :func:`fit_geometric_decay`, least
     squares through the origin of v(n+1) against v(n) over every launch, speeds sampled once
     per cycle;
   * ``player_decay`` and ``dash_power_rate`` (§2.1: v ← decay·(v + rate·power)):
     :func:`fit_dash`, least squares of v(n+1) against v(n) with an intercept (slope = decay,
     intercept = decay·rate·power); ``player_speed_max`` is the top speed the trace reached;
   * ``quantize_step`` (§3.3: distances are rounded in log space with this step, an error
     uniform over one step, standard deviation step/√12): :func:`fit_quantize_step`, √12 times
     the standard deviation of the seen distance's log error;
   * geometry through the unit: the pitch's width, the goal's width and depth, the ball's and
     the player's radii, in units of the trace's field (the pitch's length stays 105 m: one
     unit is one metre of the server, as in every drill);
   * the view cone: the robots' overhead camera sees the whole table, so ±180°.

   Not covered, because the Soccer Server model has no such parameter: the camera's latency
   (:attr:`Calibration.latency_s`, measured and reported), a robot's turning time (the server
   turns within one cycle), the walls and the link's lost packets.
3. **write** (:func:`preset_text`): a Soccer Server preset on the reference preset (the
   caller names it: ``soccer_server_1996`` in ``robotsoccer transfer``) whose
   comments say it was fitted, from which traces (field, preset, seed) and with which residuals.

The transfer study (:mod:`robotsoccer.experiments.transfer`) then trains a lead net on the
calibrated preset with the robot drill mapped onto it (:func:`calibrated_drill`) and tests it on
the robots beside the uncalibrated server net. The fit is checked in closed form in the tests:
traces the Soccer Server model itself records with known parameters give those parameters back.
"""

from __future__ import annotations

import itertools
import math
import statistics
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from field_models.arena import FieldFacts, FieldOptions
from field_models.protocol import RIGHT, Dash, PlayerRef
from field_models.registry import make_arena
from field_models.seeding import TrialRngs
from robotsoccer.experiments.lead_study import StudyDrill
from robotsoccer.experiments.report import paired_cell, percent_cell
from robotsoccer.runs.runner import TrialResult

PLAYER = PlayerRef(RIGHT, 1)
"""The one player of the traces."""

TRACE_S = 1.0
"""Each motion trace lasts this long [s]: past a robot's time to top speed (0.4 s) and a 0.7 m
shot's flight."""

STILL_DISTANCES_UNITS = (20.0, 25.0, 30.0)
"""Ball-to-player distances of the sensing trace [units]: the drill's start distances."""

STILL_TRACE_S = 2.0
"""The sensing trace's length at each distance [s]."""

DASH_POWER = 100.0
"""The dash of the traces (the drills' defenders dash at full power)."""

CYCLES_PER_SEE = 2
"""Calibrated cycles per see: a turn and a dash, one body command per cycle (spec §2). With a see
every cycle the see client would only ever turn."""

MIN_SPEED_SHARE = 0.05
"""Ball-decay pairs below this share of the launch speed are left out (a stopped ball's zeros
say nothing of its decay)."""


# ----------------------------------------------------------------------------- traces


@dataclass(frozen=True)
class Traces:
    """What one field model did, as a client and a coach see it, in units and seconds.

    Attributes:
        field_model: The field model recorded.
        preset: Its preset.
        seed: The recording's experiment seed.
        unit_m: One drill unit on that field [m].
        dt_s: Its tick [s].
        ball: For each launch, the ball's speed after every tick [units/s].
        launch_speeds: Each launch's speed [units/s].
        dash: The player's speed after every tick of ``DASH 100`` from rest [units/s].
        percept_ticks: The ticks at which the still player's percepts arrived.
        latency_ticks: Each such percept's arrival tick minus its sample tick.
        log_errors: log(seen distance / true distance) of the ball at rest, per percept.
    """

    field_model: str
    preset: str
    seed: int
    unit_m: float
    dt_s: float
    ball: tuple[tuple[float, ...], ...]
    launch_speeds: tuple[float, ...]
    dash: tuple[float, ...]
    percept_ticks: tuple[int, ...]
    latency_ticks: tuple[int, ...]
    log_errors: tuple[float, ...]


def record_traces(
    field_model: str, preset: str, launch_speeds_units: Sequence[float], seed: int
) -> Traces:
    """Record the ball, dash and sensing traces of one field model (module docstring, step 1).

    Args:
        field_model: The field model.
        preset: Its preset (a name or a ``.toml`` path).
        launch_speeds_units: The ball launches' speeds [units/s].
        seed: The experiment seed (trial i of the recording uses stream i).

    Raises:
        ValueError: No launch speed, or one that is not positive.
    """
    if not launch_speeds_units or min(launch_speeds_units) <= 0.0:
        raise ValueError(f"launch speeds must be positive units/s, got {launch_speeds_units!r}")
    options = FieldOptions(ball_noise=0.0)
    ball = []
    facts: FieldFacts | None = None
    for k, speed in enumerate(launch_speeds_units):
        arena = make_arena(field_model, preset, (PLAYER,), TrialRngs.for_trial(seed, k), options)
        facts = arena.facts
        u = facts.unit_m
        # The player stands aside, out of the ball's way; the ball rolls along the long axis.
        arena.place_player(PLAYER, 0.0, 0.8 * facts.pitch.half_width_m, 0.0)
        start = -0.5 * speed * TRACE_S * u
        arena.place_ball(start, 0.0, speed * u, 0.0)
        speeds = []
        for _ in range(_ticks(TRACE_S, facts.dt_s)):
            arena.step()
            speeds.append(arena.ball_state().speed / u)
        ball.append(tuple(speeds))
    n = len(launch_speeds_units)
    arena = make_arena(field_model, preset, (PLAYER,), TrialRngs.for_trial(seed, n), options)
    facts = arena.facts
    u = facts.unit_m
    arena.place_player(PLAYER, -0.5 * facts.pitch.half_length_m, 0.0, 0.0)
    arena.place_ball(0.0, 0.9 * facts.pitch.half_width_m)
    dash = []
    for _ in range(_ticks(TRACE_S, facts.dt_s)):
        arena.submit(PLAYER, (Dash(DASH_POWER),))
        arena.step()
        dash.append(arena.player_state(PLAYER).speed / u)
    ticks: list[int] = []
    latency: list[int] = []
    errors: list[float] = []
    for j, distance in enumerate(STILL_DISTANCES_UNITS):
        rngs = TrialRngs.for_trial(seed, n + 1 + j)
        arena = make_arena(field_model, preset, (PLAYER,), rngs, options)
        facts = arena.facts
        u = facts.unit_m
        arena.place_player(PLAYER, 0.0, 0.0, math.pi)
        arena.place_ball(-distance * u, 0.0)
        for _ in range(_ticks(STILL_TRACE_S, facts.dt_s)):
            for percept in arena.step():
                if percept.player != PLAYER:
                    continue
                if j == 0:
                    ticks.append(percept.tick)
                latency.append(percept.tick - percept.observed_tick)
                if percept.ball is not None and percept.ball.distance_m > 0.0:
                    truth = arena.truth()
                    me, it = truth.players[PLAYER], truth.ball
                    true = math.hypot(it.x - me.x, it.y - me.y)
                    errors.append(math.log(percept.ball.distance_m / true))
    assert facts is not None
    return Traces(
        field_model=field_model,
        preset=preset,
        seed=seed,
        unit_m=facts.unit_m,
        dt_s=facts.dt_s,
        ball=tuple(ball),
        launch_speeds=tuple(float(s) for s in launch_speeds_units),
        dash=tuple(dash),
        percept_ticks=tuple(ticks),
        latency_ticks=tuple(latency),
        log_errors=tuple(errors),
    )


def _ticks(seconds: float, dt_s: float) -> int:
    return max(2, round(seconds / dt_s))


# ----------------------------------------------------------------------------- fits


def fit_geometric_decay(series: Sequence[Sequence[float]], floor: float = 0.0) -> float:
    """The decay d of v(n+1) = d·v(n) fitting every series best (least squares through 0).

    Args:
        series: Speeds once per cycle, each series one free roll.
        floor: Pairs whose v(n) or v(n+1) is at most this are left out (a stopped ball).

    Raises:
        ValueError: No pair above the floor.
    """
    num = den = 0.0
    for speeds in series:
        v = np.asarray(speeds, dtype=np.float64)
        now, nxt = v[:-1], v[1:]
        keep = (now > floor) & (nxt > floor)  # a ball stopping within a cycle: the stop rule
        num += float(np.dot(now[keep], nxt[keep]))
        den += float(np.dot(now[keep], now[keep]))
    if den <= 0.0:
        raise ValueError("no speeds above the floor to fit a decay to")
    return num / den


def fit_dash(speeds: Sequence[float], power: float) -> tuple[float, float, float]:
    """(decay, rate, rms residual) of v(n+1) = decay·(v(n) + rate·power), least squares.

    Args:
        speeds: The player's speed once per cycle under a dash of `power` every cycle, from
            rest (the first entry is the speed after the first cycle).
        power: The dash power.

    Raises:
        ValueError: Fewer than three speeds, or speeds that never change.
    """
    v = np.concatenate([[0.0], np.asarray(speeds, dtype=np.float64)])
    if len(v) < 4:
        raise ValueError(f"a dash fit needs at least three speeds, got {len(v) - 1}")
    now, nxt = v[:-1], v[1:]
    design = np.column_stack([now, np.ones_like(now)])
    (slope, intercept), *_ = np.linalg.lstsq(design, nxt, rcond=None)
    if slope <= 0.0 or not math.isfinite(float(slope)):
        raise ValueError("the dash trace gives no positive decay")
    residual = nxt - (slope * now + intercept)
    rms = float(np.sqrt(np.mean(residual**2)))
    return float(slope), float(intercept / (slope * power)), rms


def fit_quantize_step(log_errors: Sequence[float]) -> float:
    """The log-distance step whose uniform rounding error has the errors' spread: √12·SD.

    Raises:
        ValueError: Fewer than two errors.
    """
    if len(log_errors) < 2:
        raise ValueError(f"a sensing fit needs at least two percepts, got {len(log_errors)}")
    return math.sqrt(12.0) * statistics.pstdev(log_errors)


def per_cycle(speeds: Sequence[float], ticks_per_cycle: int) -> list[float]:
    """Every `ticks_per_cycle`-th speed, the first at the end of the first cycle."""
    return [speeds[i] for i in range(ticks_per_cycle - 1, len(speeds), ticks_per_cycle)]


# ----------------------------------------------------------------------------- calibration


@dataclass(frozen=True)
class Calibration:
    """The fitted Soccer Server parameters and how well they fit (module docstring, step 2).

    Distances are in units of the traced field, written as metres of the server's pitch.

    Attributes:
        traces: What was fitted to.
        cycle_ticks: Trace ticks per calibrated cycle (the sensor's period over
            :data:`CYCLES_PER_SEE`).
        cycle_ms: The calibrated cycle (``simulator_step``; ``send_step`` is
            :data:`CYCLES_PER_SEE` of them) [ms].
        ball_decay: Per calibrated cycle.
        ball_rms: Ball-speed residual of the decay fit [units/cycle].
        player_decay: Per calibrated cycle.
        dash_power_rate: [units/cycle² per power].
        player_speed_max: The top speed the dash trace reached [units/cycle].
        dash_rms: Player-speed residual of the dash fit [units/cycle].
        quantize_step: Log-distance step (ball, players and landmarks).
        latency_s: The sensor's median latency [s] (not covered: the server has none).
        geometry: Pitch and body sizes in units, by preset key (``[dynamics]``).
    """

    traces: Traces
    cycle_ticks: int
    cycle_ms: int
    ball_decay: float
    ball_rms: float
    player_decay: float
    dash_power_rate: float
    player_speed_max: float
    dash_rms: float
    quantize_step: float
    latency_s: float
    geometry: dict[str, float]


def calibrate(traces: Traces, facts: FieldFacts) -> Calibration:
    """Fit the Soccer Server's parameters to `traces` of the field `facts` describes.

    Args:
        traces: The field's traces (:func:`record_traces`).
        facts: Its facts, for the geometry in units.

    Raises:
        ValueError: Traces too short to fit, or from a field whose percepts never came twice.
    """
    if len(traces.percept_ticks) < 2:
        raise ValueError("the sensing trace holds fewer than two percepts: no sensor period")
    gaps = np.diff(np.asarray(traces.percept_ticks))
    sensor_ticks = int(np.median(gaps))
    if sensor_ticks < CYCLES_PER_SEE:
        raise ValueError(
            f"the sensor's period ({sensor_ticks} tick) is shorter than {CYCLES_PER_SEE} ticks: "
            "no whole cycle fits a turn and a dash"
        )
    cycle_ticks = sensor_ticks // CYCLES_PER_SEE
    cycle_s = cycle_ticks * traces.dt_s
    to_cycle = cycle_s  # units/s -> units/cycle
    balls = [[v * to_cycle for v in per_cycle(speeds, cycle_ticks)] for speeds in traces.ball]
    floor = MIN_SPEED_SHARE * min(traces.launch_speeds) * to_cycle
    ball_decay = fit_geometric_decay(balls, floor)
    ball_res = [
        b - ball_decay * a for series in balls for a, b in itertools.pairwise(series) if a > floor
    ]
    dash = [v * to_cycle for v in per_cycle(traces.dash, cycle_ticks)]
    player_decay, rate, dash_rms = fit_dash(dash, DASH_POWER)
    u = facts.unit_m
    pitch = facts.pitch
    geometry = {
        "pitch_width_m": pitch.width_m / u,
        "goal_width_m": pitch.goal_width_m / u,
        "goal_depth_m": pitch.goal_depth_m / u,
        "ball_size_m": pitch.ball_radius_m / u,
        "player_size_m": pitch.player_radius_m / u,
    }
    return Calibration(
        traces=traces,
        cycle_ticks=cycle_ticks,
        cycle_ms=max(1, round(1000.0 * cycle_s)),
        ball_decay=ball_decay,
        ball_rms=float(np.sqrt(np.mean(np.square(ball_res)))) if ball_res else 0.0,
        player_decay=player_decay,
        dash_power_rate=rate,
        player_speed_max=max(dash),
        dash_rms=dash_rms,
        quantize_step=fit_quantize_step(traces.log_errors),
        latency_s=float(np.median(traces.latency_ticks)) * traces.dt_s,
        geometry=geometry,
    )


def preset_text(cal: Calibration, base: str, created_by: str) -> str:
    """The calibrated Soccer Server preset (TOML on `base`), provenance in comments.

    `base` is the Soccer Server preset whose every key not fitted is kept (the paper's).

    Speeds, the cycle and the rates are those fitted; a cycle written in whole milliseconds
    keeps the fitted per-second rates (decays are re-based to it, the rate keeps the terminal
    speed).
    """
    t = cal.traces
    fitted_cycle_s = cal.cycle_ticks * t.dt_s
    written_s = cal.cycle_ms / 1000.0
    ratio = written_s / fitted_cycle_s
    ball_decay = cal.ball_decay**ratio
    player_decay = cal.player_decay**ratio
    terminal = cal.player_decay * cal.dash_power_rate / (1.0 - cal.player_decay) / fitted_cycle_s
    rate = terminal * written_s * (1.0 - player_decay) / player_decay
    speed_max = cal.player_speed_max * ratio
    launches = ", ".join(f"{v:.4g}" for v in t.launch_speeds)
    lines = [
        "# The Soccer Server model calibrated to robot traces: FITTED, not a real server.",
        f"# Written by {created_by} (robotsoccer.experiments.calibration).",
        f"# Traces: {t.field_model} `{t.preset}`, seed {t.seed}; one unit = {t.unit_m:.6g} m",
        f"# there = 1 m here (the pitch stays 105 m long). Ball launches at {launches} units/s,",
        f"# DASH {DASH_POWER:g} every tick from rest, a still ball at "
        + ", ".join(f"{d:g}" for d in STILL_DISTANCES_UNITS)
        + " units.",
        f"# Fit residuals (rms): ball speed {cal.ball_rms:.4g}, player speed {cal.dash_rms:.4g}"
        " units/cycle.",
        f"# Not covered (no server parameter): the sensor's latency ({1000 * cal.latency_s:.0f} ms"
        " measured),",
        "# turning time (the server turns within a cycle), walls, lost packets.",
        f'base = "{base}"',
        "",
        "[dynamics]",
        f"simulator_step_ms = {cal.cycle_ms}  # fitted: 1/{CYCLES_PER_SEE} of the sensor's "
        f"period ({cal.cycle_ticks} ticks of {1000 * t.dt_s:.4g} ms)",
        f"ball_decay = {ball_decay:.6f}  # fitted: least squares on the ball traces",
        f"player_decay = {player_decay:.6f}  # fitted: least squares on the dash trace",
        f"dash_power_rate_m_per_cycle2 = {rate:.6g}  # fitted, same",
        f"player_speed_max_m_per_cycle = {speed_max:.6g}  # the dash trace's top speed",
        "player_rand = 0.0  # the traced player's motion shows no noise of this kind",
        "inertia_moment_cycle_per_m = 0.0  # a moving robot turns as far as a still one",
    ]
    for key, value in cal.geometry.items():
        lines.append(f"{key} = {value:.6g}  # mapped through the unit")
    lines += [
        "",
        "[sensing]",
        f"simulator_step_ms = {cal.cycle_ms}  # the cycle above",
        f"send_step_ms = {CYCLES_PER_SEE * cal.cycle_ms}  # fitted: the sensor's period "
        "(a turn and a dash per see)",
        f"quantize_step = {cal.quantize_step:.6g}  # fitted: sqrt(12) x SD of log distance error",
        f"quantize_step_l = {cal.quantize_step:.6g}  # same, for landmarks",
        "view_half_angle_deg = 180.0  # an overhead camera sees the whole table",
    ]
    return "\n".join(lines) + "\n"


def write_preset(cal: Calibration, path: Path, base: str, created_by: str) -> Path:
    """Write the calibrated preset on `base` to `path` (its folder is made) and return it."""
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(preset_text(cal, base, created_by))
    return path


def calibrated_drill(
    robot: StudyDrill, server_model: str, preset: Path, robot_unit_m: float
) -> StudyDrill:
    """The robot drill on the calibrated server: its options, speeds put in server units.

    The calibrated server is the robot table in units (one unit = 1 m), so a launch speed of
    v m/s on the robots is v / unit m/s there.
    """
    options: list[tuple[str, str | float]] = []
    for key, value in robot.options:
        if key.endswith("_mps") and isinstance(value, float | int):
            value = float(value) / robot_unit_m
        options.append((key, value))
    return StudyDrill(
        server_model,
        str(preset.resolve()),
        tuple(options),
        f"the robot drill in units ({robot.summary}) on the calibrated server",
    )


def calibration_lines(cal: Calibration, reference: FieldFacts) -> list[str]:
    """The report's table of what was fitted, beside the reference server's own values."""
    t = cal.traces
    rows = [
        ("cycle / see interval [ms]", f"{cal.cycle_ms} / {CYCLES_PER_SEE * cal.cycle_ms}",
         f"{1000 * reference.dt_s:.0f} / {1000 * reference.sensor_period_s:.0f}"),
        ("ball decay per 100 ms", f"{cal.ball_decay ** (0.1 / (cal.cycle_ticks * t.dt_s)):.4f}",
         f"{reference.ball.decay_per_tick ** (0.1 / reference.dt_s):.4f}"),
        ("player top speed [units/s]", f"{cal.player_speed_max / (cal.cycle_ticks * t.dt_s):.1f}",
         f"{reference.player_top_speed_mps / reference.unit_m:.1f}"),
        ("quantize step (log distance)", f"{cal.quantize_step:.4g}", "0.1"),
        ("sensor latency [ms] (not covered)", f"{1000 * cal.latency_s:.0f}", "0"),
    ]  # fmt: skip
    lines = [
        f"| parameter | fitted to {t.field_model} | {reference.preset} |",
        "|---|---|---|",
        *[f"| {a} | {b} | {c} |" for a, b, c in rows],
        "",
        f"Fit residuals (rms): ball speed {cal.ball_rms:.3g} units/cycle over "
        f"{len(t.ball)} launches; player speed {cal.dash_rms:.3g} units/cycle (the robot "
        "accelerates at a constant rate to its top speed, the server's law is geometric).",
    ]
    return lines


# ----------------------------------------------------------------------------- report

GAP_BOOTSTRAP = 2000
"""Resamples of the paired bootstrap of the share of the gap closed."""


def gap_share(
    uncalibrated: Sequence[TrialResult],
    calibrated: Sequence[TrialResult],
    native: Sequence[TrialResult],
    seed: int,
) -> tuple[float, float, float] | None:
    """The share of the gap closed, (calibrated - uncalibrated) / (native - uncalibrated).

    The three share their trials (paired placements); the 95% interval is a percentile
    bootstrap over trials (:data:`GAP_BOOTSTRAP` resamples of the trial indices, seeded), the
    resamples whose gap is zero left out. None without common trials, or where the native net
    does no better than the uncalibrated one (no gap to close: a share of it means nothing).
    """
    by_cal = {r.index: r.label == "SAVE" for r in calibrated}
    by_nat = {r.index: r.label == "SAVE" for r in native}
    rows = [
        (r.label == "SAVE", by_cal[r.index], by_nat[r.index])
        for r in uncalibrated
        if r.index in by_cal and r.index in by_nat
    ]
    if not rows:
        return None
    data = np.asarray(rows, dtype=np.float64)

    def share(sample: np.ndarray) -> float:
        gap = sample[:, 2].mean() - sample[:, 0].mean()
        return math.nan if gap == 0.0 else (sample[:, 1].mean() - sample[:, 0].mean()) / gap

    if data[:, 2].mean() <= data[:, 0].mean():
        return None  # the moved net does as well as the native one: no gap to share
    point = share(data)
    rng = np.random.default_rng(seed)
    draws = [share(data[rng.integers(0, len(data), len(data))]) for _ in range(GAP_BOOTSTRAP)]
    kept = np.asarray([d for d in draws if not math.isnan(d)])
    low, high = np.percentile(kept, [2.5, 97.5])
    return point, float(low), float(high)


def recovered_markdown(
    cal: Calibration,
    reference: FieldFacts,
    target: str,
    tables: Mapping[str, Mapping[str, Sequence[TrialResult]]],
    seed: int,
    preset_file: str,
) -> str:
    """The calibration's report section: what was fitted, and what it recovered on `target`.

    Args:
        cal: The calibration.
        reference: The uncalibrated server's facts (the table's right column).
        target: The field tested on (the robots).
        tables: By decision (``lead``, ``turn``), trials on `target` by role: ``straight``,
            ``uncalibrated`` (the reference server's net moved), ``calibrated`` (the calibrated
            server's net moved), ``native`` (the target's own net) and, where run,
            ``analytic``.
        seed: The bootstrap's seed.
        preset_file: Where the calibrated preset was written (relative to the run folder).
    """
    lines = [
        "## Calibration: the Soccer Server model fitted to robot traces, then retrained",
        "",
        f"Traces of {cal.traces.field_model} `{cal.traces.preset}` (seed {cal.traces.seed}) "
        "fitted by least squares (:mod:`robotsoccer.experiments.calibration`) and written as a "
        f"*calibrated* Soccer Server preset (`{preset_file}` in the run folder, provenance in "
        "its comments). Nets trained on it by §5's recipe, on the robot drill put in units, are "
        "tested on the robots with `transfer=true` (a lead net's τ in seconds, as in the matrix).",
        "",
        *calibration_lines(cal, reference),
    ]
    for decision, rows in tables.items():
        lines += ["", *_recovered_lines(decision, target, rows, seed)]
    return "\n".join(lines) + "\n"


ROLE_NAMES = {
    "straight": "straight pursuit",
    "uncalibrated": "server {decision} net, transferred (uncalibrated)",
    "calibrated": "server {decision} net, transferred (calibrated)",
    "native": "{target}'s own {decision} net",
    "analytic": "analytic",
}
"""How the calibration table names each role."""


def _recovered_lines(
    decision: str, target: str, rows: Mapping[str, Sequence[TrialResult]], seed: int
) -> list[str]:
    un, ca, na, straight = (
        rows["uncalibrated"],
        rows["calibrated"],
        rows["native"],
        rows["straight"],
    )
    lines = [
        f"On {target}, {decision} decision, paired placements ({len(na)} trials per row):",
        "",
        f"| defender on {target} | saves % | minus straight | minus the native net |",
        "|---|---|---|---|",
    ]
    for key, name in ROLE_NAMES.items():
        if key not in rows:
            continue
        res = rows[key]
        saves = sum(r.label == "SAVE" for r in res)
        lines.append(
            f"| {name.format(decision=decision, target=target)} | "
            f"{percent_cell(saves, len(res))} | "
            f"{'—' if key == 'straight' else paired_cell(res, straight)} | "
            f"{'—' if key == 'native' else paired_cell(res, na)} |"
        )
    found = gap_share(un, ca, na, seed)
    share = (
        "no gap to close (the uncalibrated net does at least as well as the native one)"
        if found is None
        else f"{100 * found[0]:.0f}% [{100 * found[1]:.0f}%, {100 * found[2]:.0f}%] (paired "
        "bootstrap, 95%)"
    )
    return [
        *lines,
        "",
        f"- recovered by calibration (calibrated minus uncalibrated): {paired_cell(ca, un)} "
        "points;",
        f"- the gap it was measured against (native minus uncalibrated): {paired_cell(na, un)} "
        "points;",
        f"- share of the gap closed: {share}.",
    ]
