"""Calibration's fits (issue 20, step 2 of :mod:`robotsoccer.experiments.calibration`).

Pure functions on arrays, each closed-form least squares, and :func:`calibrate`, which applies
them to a field's :class:`~robotsoccer.experiments.calibration_traces.Traces` to give the Soccer
Server's parameters (:class:`Calibration`). What each parameter is fitted from, and what the
server model cannot cover, is told in :mod:`robotsoccer.experiments.calibration`.
"""

from __future__ import annotations

import itertools
import math
import statistics
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from field_models.arena import FieldFacts
from robotsoccer.experiments.calibration_traces import DASH_POWER, Traces

CYCLES_PER_SEE = 2
"""Calibrated cycles per see: a turn and a dash, one body command per cycle (spec §2). With a see
every cycle the see client would only ever turn."""

MIN_SPEED_SHARE = 0.05
"""Ball-decay pairs below this share of the launch speed are left out (a stopped ball's zeros
say nothing of its decay)."""


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
        traces: The field's traces
            (:func:`~robotsoccer.experiments.calibration_traces.record_traces`).
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
