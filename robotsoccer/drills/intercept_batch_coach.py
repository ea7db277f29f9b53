"""The coach of the batched interception drill: labels, reasons and measures as arrays.

:class:`BatchCoach` is :class:`~robotsoccer.drills.intercept.InterceptDrill`'s judge (its
``_Judge`` and :class:`~robotsoccer.drills.base.GoalWatch` rules, in the same order and with
the same floating-point operations) for every trial of a batch
(:mod:`robotsoccer.drills.intercept_batch`), and builds each ended trial's
:class:`~robotsoccer.runs.runner.TrialResult` as :func:`~robotsoccer.runs.runner.run_trial`
does. Verdicts are small integer codes into (label, reason) pairs. Distances in metres.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
import numpy.typing as npt

from field_models.batch_arena import BatchArena
from field_models.protocol import Crossing, Pitch, end_line_crossing
from robotsoccer.drills.intercept_judge import (
    AT_END_LINE_WIDE,
    AT_SIDE_LINE,
    BACKWARD_SHARE,
    DEFLECTED_STOPPED,
    INTO_GOAL,
    MOVING_BACK,
    OVER_LINE_WIDE,
    OVER_OWN_LINE,
    PAST_INTO_GOAL,
    PAST_WIDE,
    SAVE_SPEED_PER_LENGTH,
    STOPPED_SHORT,
    deflected_then,
)
from robotsoccer.drills.intercept_plan import LaunchPlan
from robotsoccer.runs.runner import TrialResult

Array = npt.NDArray[np.float64]
Mask = npt.NDArray[np.bool_]

SHOOTER_ROW, DEFENDER_ROW = 1, 2
"""The batch arena's player rows (row 0 is the ball): the shooter's and the defender's."""

# Verdicts as codes: (label, reason) pairs; a "not in" reason has a deflected twin at +1.
_VERDICTS: list[tuple[str, str]] = [
    ("GOAL", INTO_GOAL),
    ("SAVE", DEFLECTED_STOPPED),
    ("SAVE", MOVING_BACK),
    ("GOAL", PAST_INTO_GOAL),
    ("MISS", STOPPED_SHORT),
]
_NOT_IN: dict[str, int] = {}
for _reason in (OVER_OWN_LINE, OVER_LINE_WIDE, AT_SIDE_LINE, AT_END_LINE_WIDE, PAST_WIDE):
    _NOT_IN[_reason] = len(_VERDICTS)
    _VERDICTS += [("MISS", _reason), ("SAVE", deflected_then(_reason))]
_INTO_GOAL, _DEFLECTED_STOPPED, _MOVING_BACK, _PAST_INTO_GOAL, _STOPPED_SHORT = range(5)


class BatchCoach:
    """The coach's state and rules over a batch of trials (module docstring).

    Args:
        server: The batch arena with every trial placed (read at each tick).
        pitch: The field's geometry.
        dt_s: The length of a tick [s].
        plan: The drill's launch plan (its unit and sensor period, for the measures).
    """

    def __init__(self, server: BatchArena, pitch: Pitch, dt_s: float, plan: LaunchPlan) -> None:
        self.server = server
        self.pitch = pitch
        self.dt_s = dt_s
        self.plan = plan
        s = server
        x0, y0 = s.x[:, 0].copy(), s.y[:, 0].copy()
        ddx, ddy = s.x[:, DEFENDER_ROW] - x0, s.y[:, DEFENDER_ROW] - y0
        # math.hypot, as the one-trial judge: numpy's hypot differs in the last bit.
        distance = _hypots(ddx, ddy)
        self.j = {
            "x0": x0,
            "y0": y0,
            "ux": ddx / distance,
            "uy": ddy / distance,
            "past": distance + pitch.player_radius_m + pitch.ball_radius_m,
            "last_x": x0.copy(),
            "last_y": y0.copy(),
            "trig_t": np.full(len(x0), np.nan),
            "trig_x": np.zeros(len(x0)),
            "trig_y": np.zeros(len(x0)),
        }
        self.approaching = np.zeros(len(x0), dtype=bool)
        self.deflected = np.zeros(len(x0), dtype=bool)
        self.scores = (s.score_left.copy(), s.score_right.copy())

    def judge(self, triggered: Mask, alive: Mask) -> npt.NDArray[np.int_]:
        """InterceptDrill.judge (the _Judge and GoalWatch rules, in order) for every trial.

        `triggered`: the trials whose defender has started for the ball; `alive`: those still
        without a verdict. Returns each trial's verdict code at this tick, -1 for none.
        """
        s, j, pitch = self.server, self.j, self.pitch
        newly = triggered & np.isnan(j["trig_t"])
        if newly.any():
            j["trig_t"] = np.where(newly, s.cycle * self.dt_s, j["trig_t"])
            j["trig_x"] = np.where(newly, s.x[:, DEFENDER_ROW], j["trig_x"])
            j["trig_y"] = np.where(newly, s.y[:, DEFENDER_ROW], j["trig_y"])
        k = 1.0 / self.dt_s  # BodyState's m/tick -> m/s
        x, y, vx, vy = s.x[:, 0], s.y[:, 0], s.vx[:, 0] * k, s.vy[:, 0] * k
        verdict = np.full(len(x), -1)
        open_ = alive.copy()

        def decide(where: Mask, code: npt.NDArray[np.int_] | int) -> None:
            nonlocal open_
            hit = where & open_
            if hit.any():  # most rules fire in no trial at a given tick
                verdict[hit] = np.broadcast_to(code, verdict.shape)[hit]
                open_ = open_ & ~hit

        def not_in(where: Mask, reason: str) -> None:
            if where.any():
                decide(where, _NOT_IN[reason] + self.deflected.astype(int))

        self._goal_line(x, y, decide, not_in)
        edge = pitch.ball_radius_m + 0.01 * pitch.half_length_m
        not_in(np.abs(y) >= pitch.half_width_m - edge, AT_SIDE_LINE)
        wide = (x >= pitch.half_length_m - edge) & (np.abs(y) >= 0.5 * pitch.goal_width_m)
        not_in(wide, AT_END_LINE_WIDE)
        eps = SAVE_SPEED_PER_LENGTH * pitch.length_m
        decide(self.deflected & (vx * vx + vy * vy < eps * eps), _DEFLECTED_STOPPED)
        along = vx * j["ux"] + vy * j["uy"]
        self.approaching |= open_ & (along > eps)
        back = open_ & ~(along > eps) & self.approaching & (along < -eps)
        if back.any():
            speed = np.zeros(len(x))
            rows = np.flatnonzero(back)
            speed[rows] = _hypots(vx[rows], vy[rows])
            decide(back & (along < -BACKWARD_SHARE * speed), _MOVING_BACK)
            self.deflected |= back & open_
        past = open_ & ((x - j["x0"]) * j["ux"] + (y - j["y0"]) * j["uy"] > j["past"])
        if past.any():
            with np.errstate(divide="ignore", invalid="ignore"):
                cross = y + (pitch.half_length_m - x) * vy / vx
            decide(past & (vx > 0.0) & (np.abs(cross) < 0.5 * pitch.goal_width_m), _PAST_INTO_GOAL)
            not_in(past, PAST_WIDE)
        return verdict

    def _goal_line(
        self,
        x: Array,
        y: Array,
        decide: Callable[[Mask, npt.NDArray[np.int_] | int], None],
        not_in: Callable[[Mask, str], None],
    ) -> None:
        """GoalWatch.step: a referee's goal, else the one goal-line rule where the ball is out."""
        s, j, pitch = self.server, self.j, self.pitch
        lx, ly = j["last_x"], j["last_y"]
        j["last_x"], j["last_y"] = x.copy(), y.copy()
        scored_left = s.score_left != self.scores[0]
        scored = scored_left | (s.score_right != self.scores[1])
        line = 0.5 * pitch.length_m + pitch.ball_radius_m
        out = ~scored & ~((-line <= x) & (x <= line))
        if not (scored.any() or out.any()):
            return
        crossing = np.zeros(len(x), dtype=int)
        crossing[scored] = np.where(scored_left, int(Crossing.RIGHT_GOAL), int(Crossing.LEFT_GOAL))[
            scored
        ]
        for row in np.flatnonzero(out).tolist():
            step = (float(lx[row]), float(ly[row]), float(x[row]), float(y[row]))
            crossing[row] = int(end_line_crossing(pitch, *step))
        decide(crossing == int(Crossing.RIGHT_GOAL), _INTO_GOAL)
        not_in(crossing == int(Crossing.LEFT_GOAL), OVER_OWN_LINE)
        not_in(crossing != 0, OVER_LINE_WIDE)

    def time_out_codes(self) -> npt.NDArray[np.int_]:
        """InterceptDrill.timeout's verdict code for every trial."""
        return np.where(self.deflected, _DEFLECTED_STOPPED, _STOPPED_SHORT)

    def results(
        self,
        rows: npt.NDArray[np.intp],
        codes: npt.NDArray[np.int_],
        positions: npt.NDArray[np.intp],
        trials: npt.NDArray[np.int64],
        example: Array,
    ) -> dict[int, TrialResult]:
        """The results of the trials in array rows `rows` (TrialResult, as run_trial builds it).

        Args:
            rows: The array rows that ended now.
            codes: Every row's verdict code.
            positions: Each array row's position in `trials` (the batch compacts its rows).
            trials: The batch's trial indices.
            example: Every row's example (BD, BA, previous BD, TA), NaN without a decision.

        Returns:
            position in `trials` → its result.
        """
        s, j, plan = self.server, self.j, self.plan
        ticks = s.cycle
        time_s = ticks * self.dt_s
        t0 = j["trig_t"][rows]
        seconds = time_s - t0  # the one-trial judge's float operations, elementwise
        dx = s.x[rows, DEFENDER_ROW] - j["trig_x"][rows]
        dy = s.y[rows, DEFENDER_ROW] - j["trig_y"][rows]
        travel = _hypots(dx, dy) / plan.unit_m
        positions = positions[rows]
        columns = zip(
            positions.tolist(),
            trials[positions].tolist(),
            codes[rows].tolist(),
            example[rows].tolist(),
            np.isnan(t0).tolist(),
            travel.tolist(),
            seconds.tolist(),
            (seconds / plan.sensor_period_s).tolist(),
            strict=True,
        )
        out: dict[int, TrialResult] = {}
        verdicts = _VERDICTS
        for position, trial, code, example, untriggered, units, secs, updates in columns:
            label, reason = verdicts[code]
            data = () if example[0] != example[0] else tuple(example)  # NaN: no decision
            measures = () if untriggered else (
                ("defender_travel_units", units),
                ("trigger_to_end_s", secs),
                ("updates_after_trigger", updates),
            )  # fmt: skip
            out[position] = TrialResult(trial, label, reason, ticks, time_s, data, measures)
        return out

    def keep(self, rows: npt.NDArray[np.intp]) -> None:
        """Keep only the array rows `rows` (the batch compacts itself)."""
        self.j = {name: values[rows] for name, values in self.j.items()}
        self.scores = (self.scores[0][rows], self.scores[1][rows])
        self.approaching = self.approaching[rows]
        self.deflected = self.deflected[rows]


def _hypots(a: Array, b: Array) -> Array:
    """``math.hypot`` elementwise, as the one-trial judge does.

    numpy's hypot differs in the last bit; this runs once per trial or on rare events only.
    """
    return np.array([math.hypot(u, v) for u, v in zip(a.tolist(), b.tolist(), strict=True)])
