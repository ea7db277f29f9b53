"""Calibration's output (issue 20, step 3 of :mod:`robotsoccer.experiments.calibration`).

:func:`preset_text` and :func:`write_preset`: a Soccer Server preset on the reference preset
(the caller names it: ``soccer_server_1996`` in ``robotsoccer transfer``) whose comments say it
was fitted, from which traces (field, preset, seed) and with which residuals;
:func:`calibrated_drill`: the robot drill mapped onto the calibrated server, in units.
"""

from __future__ import annotations

from pathlib import Path

from robotsoccer.experiments.calibration_fit import CYCLES_PER_SEE, Calibration
from robotsoccer.experiments.calibration_traces import DASH_POWER, STILL_DISTANCES_UNITS
from robotsoccer.experiments.lead_study import StudyDrill


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
