"""Calibration: fit the Soccer Server model's parameters to robot traces, then retrain (issue 20).

The transfer study moves a net from the Soccer Server model to the robots as it is (distances
in drill units). Calibration is the other way to close that gap: make the simulator behave like
the robots, then learn there. The first half is three steps, each in a module of its own:

1. **record** (:mod:`~robotsoccer.experiments.calibration_traces`): on any field model,
   through the arena interface only (coach placements, the truth, the percepts a client gets),
   record

   * the ball rolling free after a launch at each of the drill's launch speeds (its speed at
     every tick, no ball noise);
   * a player at rest commanded ``DASH 100`` at every tick (its speed at every tick);
   * a player and a ball at rest 20, 25 and 30 units apart: the percepts' arrival ticks, their
     sample ticks (latency) and the seen distance's log error (sensing noise).

   Speeds are in drill units per second (:attr:`~field_models.arena.FieldFacts.unit_m`), so a
   trace of the robot table and one of the server's pitch are in the same units.
2. **fit** (:mod:`~robotsoccer.experiments.calibration_fit`; pure functions on arrays, each
   closed-form least squares):

   * the cycle: half the sensor's period as the client sees it, and a see every two cycles
     (``send_step = 2 simulator_step``, spec §3.1): the server carries out one body command
     per cycle (spec §2), so the see client's "turn, then dash" takes two cycles where the
     robots' host runs both as one arc within a camera frame (``CYCLES_PER_SEE``);
   * ``ball_decay`` (spec §1.2: v ← decay·v each cycle): ``fit_geometric_decay``, least
     squares through the origin of v(n+1) against v(n) over every launch, speeds sampled once
     per cycle;
   * ``player_decay`` and ``dash_power_rate`` (§2.1: v ← decay·(v + rate·power)):
     ``fit_dash``, least squares of v(n+1) against v(n) with an intercept (slope = decay,
     intercept = decay·rate·power); ``player_speed_max`` is the top speed the trace reached;
   * ``quantize_step`` (§3.3: distances are rounded in log space with this step, an error
     uniform over one step, standard deviation step/√12): ``fit_quantize_step``, √12 times
     the standard deviation of the seen distance's log error;
   * geometry through the unit: the pitch's width, the goal's width and depth, the ball's and
     the player's radii, in units of the trace's field (the pitch's length stays 105 m: one
     unit is one metre of the server, as in every drill);
   * the view cone: the robots' overhead camera sees the whole table, so ±180°.

   Not covered, because the Soccer Server model has no such parameter: the camera's latency
   (``Calibration.latency_s``, measured and reported), a robot's turning time (the server
   turns within one cycle), the walls and the link's lost packets.
3. **write** (:mod:`~robotsoccer.experiments.calibration_preset`): a Soccer Server preset on
   the reference preset (the caller names it: ``soccer_server_1996`` in ``robotsoccer
   transfer``) whose comments say it was fitted, from which traces (field, preset, seed) and
   with which residuals.

The transfer study (:mod:`robotsoccer.experiments.transfer`) then trains a lead net on the
calibrated preset with the robot drill mapped onto it (``calibrated_drill``) and tests it on
the robots beside the uncalibrated server net. This module writes the report's section on it:
what was fitted (:func:`calibration_lines`), what it recovered (:func:`recovered_markdown`) and
the share of the gap closed (:func:`gap_share`). The fit is checked in closed form in the tests:
traces the Soccer Server model itself records with known parameters give those parameters back.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence

import numpy as np

from field_models.arena import FieldFacts
from robotsoccer.experiments.calibration_fit import CYCLES_PER_SEE, Calibration
from robotsoccer.experiments.report_cells import paired_cell, percent_cell
from robotsoccer.runs.runner import TrialResult


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
