"""The interception drill for thousands of Soccer Server trials at once, as arrays.

:func:`run_intercept_batch` runs trials of :class:`~robotsoccer.drills.intercept.InterceptDrill`
on the Soccer Server model together: the dynamics
(:func:`field_models.registry.make_batch_arena`: on the Soccer Server its batch dynamics,
directed dash included, see timer, view cone and quantisation), the
coach's placement and labels, the shooter and every defender behaviour (still, straight,
random, net, lookup, analytic; TA held or chosen at every see). Each trial gives exactly the
:class:`~robotsoccer.runs.runner.TrialResult` of the one-trial path
(:func:`~robotsoccer.runs.runner.run_trial`) for the same spec and index: the same label,
reason, ticks, example and measures, bit for bit (``tests/robotsoccer/drills/
test_intercept_batch.py`` checks it across behaviours, modes and noise levels). It can,
because every random number comes from the trial's counter-based streams
(:mod:`field_models.seeding`), drawn here as arrays, and every rule does the same floating-point
operations in the same order as its one-trial form.

**One rule, one implementation where it can be shared.** The net (:func:`~learning.
interception_file.batch_turn_function`) and the lookup table (:meth:`~learning.lookup.
LookupTable.predict`) have one batch form that the one-trial path's scalar form equals bit for
bit; the analytic rule, the goal line (:func:`~field_models.protocol.end_line_crossing`) and
other rare events call the one-trial code on the few trials they concern. The defender's
watch/trigger/dash cycle, the shooter, the placement and the coach's labels are written here
again as array code, kept equal to the one-trial classes by the equality test.

**Scope.** The drill's own options on any field model with a batch arena
(:class:`field_models.batch_arena.BatchArena`: today the Soccer Server, any preset without swept
ball collisions), with the field options (ball noise, perfect perception). Not here, so
:func:`batch_reason` sends such trials to the one-trial path: the defender's clearing kick
(``defender_kick``, it reads landmarks), the robot field, and recorded trials
(:mod:`robotsoccer.runs.pool` decides).

Trials that end leave the arrays (the batch compacts itself), so a batch costs what its
longest trials cost, not its size times the longest.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from field_models.arena import FieldFacts
from field_models.batch_arena import BatchArena
from field_models.protocol import Crossing, Pitch, end_line_crossing, wrap_angle
from field_models.registry import batch_reason as field_batch_reason
from field_models.registry import field_facts, make_batch_arena
from field_models.seeding import StreamBatch
from learning.interception_file import BatchTurnFunction, load_batch_turn_function
from robotsoccer.drills import make_drill
from robotsoccer.drills.intercept import InterceptDrill
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
from robotsoccer.drills.intercept_options import ClientKind, Decision, Launch, Shot
from robotsoccer.drills.intercept_plan import DEFENDER, SHOOTER, LaunchPlan
from robotsoccer.runs.runner import TrialResult, TrialSpec, field_options
from robotsoccer.skills.intercept import (
    DASH_POWER,
    RANDOM_TA_HALF_RANGE_RAD,
    TA_CLIP_RAD,
    AnalyticPolicy,
    Behaviour,
    TaMode,
    file_key,
    load_lookup_table,
)

Array = npt.NDArray[np.float64]
Mask = npt.NDArray[np.bool_]

DEFAULT_BATCH = 8192
"""Trials stepped together by default: large enough that numpy's per-call cost is spread thin,
small enough that the arrays stay in cache (``robotsoccer bench``: trials/s against size)."""
COMPACT_SHARE = 0.75
"""The batch drops its finished trials once fewer than this share of its rows still run."""

_NONE, _TURN, _DASH = 0, 1, 2
_SHOOTER_ROW, _DEFENDER_ROW = 1, 2

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


def batch_reason(spec: TrialSpec) -> str | None:
    """Why `spec`'s trials cannot run batched (None: they can).

    Raises:
        ValueError: The drill's options are invalid (as the one-trial path raises).
    """
    if spec.drill != "intercept":
        return f"the batch engine runs the intercept drill, not {spec.drill!r}"
    drill = make_drill(spec.drill, dict(spec.drill_options))
    assert isinstance(drill, InterceptDrill)
    if drill.defender_kick:
        return "the defender's clearing kick reads landmarks, which the batch does not see"
    if drill.client is not ClientKind.SEE:
        return "the batch plays the see-triggered client"
    if drill.decision is not Decision.TURN:
        return "the batch plays the paper's turn-angle decision, not the lead"
    if drill.shot is not Shot.DEFENDER:
        return "the batch aims every shot at the defender"
    options = field_options(spec, drill)
    reason = field_batch_reason(spec.field_model, spec.preset, options)
    if reason is not None:
        return reason
    if drill.plan_for(field_facts(spec.field_model, spec.preset, options)).decision_period_s:
        return "the batch decides at every percept; this plan sets a longer decision period"
    return None


def run_intercept_batch(
    spec: TrialSpec, indices: Sequence[int], batch_size: int = DEFAULT_BATCH
) -> list[TrialResult]:
    """Run the trials `indices` of `spec` as arrays, `batch_size` at a time.

    Returns the results in the order of `indices`, each equal to ``run_trial(spec, index)``.

    Raises:
        ValueError: `spec` cannot run batched (:func:`batch_reason`), or bad drill options.
    """
    reason = batch_reason(spec)
    if reason is not None:
        raise ValueError(reason)
    results: list[TrialResult] = []
    for start in range(0, len(indices), batch_size):
        chunk = np.asarray(indices[start : start + batch_size], dtype=np.int64)
        results.extend(_InterceptBatch(spec, chunk).run())
    return results


def decisions_batch(
    spec: TrialSpec, seeds: npt.NDArray[np.int64], trials: npt.NDArray[np.int64]
) -> Array:
    """Each trial run up to its defender's decision: (BD [m], BA [rad], previous BD [m]) there.

    Trial k is trial ``trials[k]`` of experiment seed ``seeds[k]``; a row of NaN: the trial
    ended before the defender decided. What the one-trial environment
    (:class:`~robotsoccer.envs.intercept.InterceptEnv`) observes at its reset.
    """
    batch = _InterceptBatch(spec, trials, seeds)
    batch.stop_at_decision = True
    batch.run()
    return batch.decisions


def play_batch(
    spec: TrialSpec,
    seeds: npt.NDArray[np.int64],
    trials: npt.NDArray[np.int64],
    turn_angles: Array,
) -> list[TrialResult]:
    """Each trial played with its defender's TA given (``turn_angles[k]`` [rad]), to its verdict.

    The behaviour's own rule is not asked; everything before the decision is as in
    :func:`decisions_batch`, so this is the rest of the trial that one observed.
    """
    return _InterceptBatch(spec, trials, seeds, turn_angles).run()


@dataclass(frozen=True)
class _Setting:
    """What every trial of the batch shares."""

    drill: InterceptDrill
    plan: LaunchPlan
    pitch: Pitch
    dt_s: float
    max_ticks: int
    choose: Chooser | None  # None: the still defender


class _InterceptBatch:
    """One batch of trials from placement to their verdicts (module docstring)."""

    def __init__(
        self,
        spec: TrialSpec,
        trials: npt.NDArray[np.int64],
        seeds: npt.NDArray[np.int64] | None = None,
        turn_angles: Array | None = None,
    ) -> None:
        """Place every trial.

        Args:
            spec: What to run.
            trials: The trial indices.
            seeds: One experiment seed per trial (default: ``spec.seed`` for all).
            turn_angles: An external TA per trial, used instead of the behaviour's rule
                (:func:`play_batch`); None: the behaviour decides.
        """
        drill = make_drill(spec.drill, dict(spec.drill_options))
        assert isinstance(drill, InterceptDrill)
        options = field_options(spec, drill)
        facts = field_facts(spec.field_model, spec.preset, options)
        plan = drill.checked_plan(facts)
        self.setting = _Setting(
            drill=drill,
            plan=plan,
            pitch=facts.pitch,
            dt_s=facts.dt_s,
            max_ticks=round(drill.max_time_s / facts.dt_s),
            choose=_chooser(drill, facts) if turn_angles is None else _given_ta,
        )
        self.trials = trials
        k = len(trials)
        self.turn_angles = np.zeros(k) if turn_angles is None else np.asarray(turn_angles)
        self.stop_at_decision = False
        self.decisions = np.full((k, 3), np.nan)  # (BD, BA, previous BD) at the trigger
        seed = spec.seed if seeds is None else seeds
        movement = StreamBatch.for_trials(seed, trials, "movement")
        self.server: BatchArena = make_batch_arena(
            spec.field_model, spec.preset, (SHOOTER, DEFENDER), movement, options
        )
        self.policy = StreamBatch.for_trials(seed, trials, "policy")
        self.out: dict[int, TrialResult] = {}
        self.rows = np.arange(k)  # each array row's position in `trials`
        self.alive = np.ones(k, dtype=bool)  # rows whose trial has no verdict yet
        self._place(StreamBatch.for_trials(seed, trials, "placement"))
        self._init_minds(k)

    # ------------------------------------------------------------------ set-up

    def _place(self, placement: StreamBatch) -> None:
        """InterceptDrill.setup and .place, for every trial."""
        drill, plan = self.setting.drill, self.setting.plan
        u = placement.take(2)
        low, high = plan.min_distance_m, plan.max_distance_m
        distance = low + (high - low) * u[:, 0]
        low, high = -drill.sector_rad, drill.sector_rad
        bearing = low + (high - low) * u[:, 1]
        dx, dy = plan.defender_x_m, 0.0
        ux, uy = np.cos(bearing), np.sin(bearing)
        bx, by = dx - distance * ux, dy - distance * uy
        aim = bearing + drill.aim_offset_rad
        gap = plan.shooter_gap_m
        server = self.server
        if plan.launch is Launch.COACH:
            speed = plan.launch_speed_mps
            server.move_ball(bx, by, speed * np.cos(aim), speed * np.sin(aim))
        else:
            assert plan.aimable_kick, "the Soccer Server's kick takes a direction"
            server.move_ball(bx, by)
        server.move_player(_SHOOTER_ROW, bx - gap * ux, by - gap * uy, bearing)
        server.move_player(_DEFENDER_ROW, dx, dy, bearing + math.pi)
        self._init_judge()

    def _init_judge(self) -> None:
        """The coach's _Judge and GoalWatch state at the start of every trial."""
        s = self.server
        pitch = self.setting.pitch
        x0, y0 = s.x[:, 0].copy(), s.y[:, 0].copy()
        ddx, ddy = s.x[:, _DEFENDER_ROW] - x0, s.y[:, _DEFENDER_ROW] - y0
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

    def _init_minds(self, k: int) -> None:
        """The shooter's and the defender's state (AimedShooterMind, DefenderMind)."""
        self.shooter_waits = np.full(k, self.setting.plan.launch is Launch.SHOOTER)
        self.kick_due = np.zeros(k, dtype=bool)
        self.kick_dir = np.zeros(k)
        self.queue_kind = np.zeros((k, 2), dtype=np.int8)
        self.queue_arg = np.zeros((k, 2))
        self.queue_next = np.zeros(k, dtype=np.intp)
        self.triggered = np.zeros(k, dtype=bool)
        self.ta = np.zeros(k)
        self.prev_bd = np.full(k, np.nan)
        self.prev_x = np.full(k, np.nan)
        self.prev_y = np.full(k, np.nan)
        self.heading = np.zeros(k)  # the defender's reckoned heading
        self.pending_turn = np.zeros(k)  # commanded, not yet in a percept
        self.example = np.full((k, 4), np.nan)
        self.inputs: tuple[Array, ...] = ()  # (BD, BA, previous BD, x, y) of the last percepts

    # ------------------------------------------------------------------ the loop

    def run(self) -> list[TrialResult]:
        """Step every trial to its verdict (TrialLoop.run, for all trials at once)."""
        setting = self.setting
        while self.alive.any():
            if self.server.cycle >= setting.max_ticks:
                self._time_out()
                break
            self._send_commands()
            self.server.step()
            if self.server.sees_now():
                self._shooter_sees()
                self._defender_sees()
            self._judge()
            if self.alive.sum() < COMPACT_SHARE * len(self.alive):
                self._compact()
        return [self.out[i] for i in range(len(self.trials)) if i in self.out]

    def _send_commands(self) -> None:
        """Each player's next queued body command (the arena's plans, one per cycle)."""
        s = self.server
        if self.kick_due.any():
            s.kick(_SHOOTER_ROW, self.setting.plan.kick_power, self.kick_dir, self.kick_due)
            self.kick_due[:] = False
        col = np.minimum(self.queue_next, 1)
        at = np.arange(len(col))
        kind = np.where(self.queue_next < 2, self.queue_kind[at, col], _NONE)
        arg = self.queue_arg[at, col]
        if (kind == _TURN).any():
            s.turn(_DEFENDER_ROW, arg, kind == _TURN)
        if (kind == _DASH).any():
            s.dash(_DEFENDER_ROW, DASH_POWER, 0.0, kind == _DASH)
        self.queue_next += kind != _NONE

    def _shooter_sees(self) -> None:
        """AimedShooterMind: kick at the first percept toward the defender as seen, plus aim."""
        waits = self.shooter_waits
        if not waits.any():
            return
        shown, _, angle = self.server.see(_SHOOTER_ROW, _DEFENDER_ROW)
        aim = np.where(shown, angle, 0.0) + self.setting.drill.aim_offset_rad
        self.kick_dir = np.where(waits, aim, self.kick_dir)
        self.kick_due |= waits
        self.shooter_waits[:] = False

    def _defender_sees(self) -> None:
        """DefenderMind.act on every trial's percept (its module docstring)."""
        choose = self.setting.choose
        if choose is None:  # still: never acts
            return
        ball, bd, ba = self.server.see(_DEFENDER_ROW, 0)
        kinds = np.zeros((len(ba), 2), dtype=np.int8)
        args = np.zeros((len(ba), 2))
        kinds[~ball & self.triggered, 0] = _DASH  # ball not seen: dash once triggered
        self.heading = np.where(ball, self.heading + self.pending_turn, self.heading)
        self.pending_turn = np.where(ball, 0.0, self.pending_turn)
        h = self.heading + ba
        x, y = bd * np.cos(h), bd * np.sin(h)
        previous_bd = np.where(np.isnan(self.prev_bd), bd, self.prev_bd)
        self.inputs = (bd, ba, previous_bd, x, y)
        before = self.triggered.copy()
        far = ball & ~before & (bd > self.setting.plan.trigger_distance_m)
        new = ball & ~before & ~far
        again = ball & before & (self.setting.drill.ta_mode is TaMode.EVERY_SEE)
        if self.stop_at_decision and new.any():  # decisions_batch: note it, leave the trial
            hit = new & self.alive
            self.decisions[self.rows[hit]] = np.stack((bd, ba, previous_bd), axis=1)[hit]
            self.alive &= ~hit
            self.triggered |= new  # a left trial still steps until compaction: no second note
            new = np.zeros_like(new)
        if new.any() or again.any():
            ta = choose(self, new | again)
            clip = TA_CLIP_RAD
            ta = np.where(ta > clip, clip, np.where(ta < -clip, -clip, ta))
            self.ta = np.where(new | again, ta, self.ta)
            self.example[new] = np.stack((bd, ba, previous_bd, self.ta), axis=1)[new]
            self.triggered |= new
        self.prev_bd = np.where(ball, bd, self.prev_bd)
        self.prev_x = np.where(ball, x, self.prev_x)
        self.prev_y = np.where(ball, y, self.prev_y)
        acting = ball & self.triggered
        angle = wrap_angle(np.where(acting, ba + self.ta, ba))
        turns = (far | acting) & ~(np.abs(angle) < self.setting.plan.turn_tolerance_rad)
        self.pending_turn = np.where(turns, angle, self.pending_turn)
        kinds[turns, 0], args[turns, 0] = _TURN, angle[turns]
        dash_first = acting & ~turns
        kinds[dash_first, 0] = _DASH
        kinds[acting & turns, 1] = _DASH
        self.queue_kind, self.queue_arg = kinds, args
        self.queue_next = np.zeros(len(ba), dtype=np.intp)

    # ------------------------------------------------------------------ the coach

    def _judge(self) -> None:
        """InterceptDrill.judge (the _Judge and GoalWatch rules, in order) for every trial."""
        s, j, pitch = self.server, self.j, self.setting.pitch
        newly = self.triggered & np.isnan(j["trig_t"])
        if newly.any():
            j["trig_t"] = np.where(newly, s.cycle * self.setting.dt_s, j["trig_t"])
            j["trig_x"] = np.where(newly, s.x[:, _DEFENDER_ROW], j["trig_x"])
            j["trig_y"] = np.where(newly, s.y[:, _DEFENDER_ROW], j["trig_y"])
        k = 1.0 / self.setting.dt_s  # BodyState's m/tick -> m/s
        x, y, vx, vy = s.x[:, 0], s.y[:, 0], s.vx[:, 0] * k, s.vy[:, 0] * k
        verdict = np.full(len(x), -1)
        open_ = self.alive.copy()

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
        self._finish(verdict >= 0, verdict)

    def _goal_line(
        self,
        x: Array,
        y: Array,
        decide: Callable[[Mask, npt.NDArray[np.int_] | int], None],
        not_in: Callable[[Mask, str], None],
    ) -> None:
        """GoalWatch.step: a referee's goal, else the one goal-line rule where the ball is out."""
        s, j, pitch = self.server, self.j, self.setting.pitch
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

    def _time_out(self) -> None:
        """InterceptDrill.timeout for every trial still running."""
        codes = np.where(self.deflected, _DEFLECTED_STOPPED, _STOPPED_SHORT)
        self._finish(self.alive.copy(), codes)

    def _finish(self, ended: Mask, codes: npt.NDArray[np.int_]) -> None:
        """Write the results of the trials `ended` (TrialResult, as run_trial builds it)."""
        rows = np.flatnonzero(ended)
        if not rows.size:
            return
        s, j, plan = self.server, self.j, self.setting.plan
        ticks = s.cycle
        time_s = ticks * self.setting.dt_s
        t0 = j["trig_t"][rows]
        seconds = time_s - t0  # the one-trial judge's float operations, elementwise
        dx = s.x[rows, _DEFENDER_ROW] - j["trig_x"][rows]
        dy = s.y[rows, _DEFENDER_ROW] - j["trig_y"][rows]
        travel = _hypots(dx, dy) / plan.unit_m
        positions = self.rows[rows]
        columns = zip(
            positions.tolist(),
            self.trials[positions].tolist(),
            codes[rows].tolist(),
            self.example[rows].tolist(),
            np.isnan(t0).tolist(),
            travel.tolist(),
            seconds.tolist(),
            (seconds / plan.sensor_period_s).tolist(),
            strict=True,
        )
        out, verdicts = self.out, _VERDICTS
        for position, trial, code, example, untriggered, units, secs, updates in columns:
            label, reason = verdicts[code]
            data = () if example[0] != example[0] else tuple(example)  # NaN: no decision
            measures = () if untriggered else (
                ("defender_travel_units", units),
                ("trigger_to_end_s", secs),
                ("updates_after_trigger", updates),
            )  # fmt: skip
            out[position] = TrialResult(trial, label, reason, ticks, time_s, data, measures)
        self.alive[rows] = False

    def _compact(self) -> None:
        """Drop the finished trials' rows from every array (module docstring)."""
        keep = np.flatnonzero(self.alive)
        self.server.keep(keep)
        self.policy = self.policy.subset(keep)
        for name in _PER_TRIAL:
            setattr(self, name, getattr(self, name)[keep])
        self.j = {name: values[keep] for name, values in self.j.items()}
        self.scores = (self.scores[0][keep], self.scores[1][keep])


_PER_TRIAL = (
    "rows", "alive", "shooter_waits", "kick_due", "kick_dir", "queue_kind", "queue_arg",
    "queue_next", "triggered", "ta", "prev_bd", "prev_x", "prev_y", "heading", "pending_turn",
    "example", "approaching", "deflected", "turn_angles",
)  # fmt: skip
"""The per-trial state arrays of :class:`_InterceptBatch` (compacted together)."""


def _hypots(a: Array, b: Array) -> Array:
    """``math.hypot`` elementwise, as the one-trial judge does.

    numpy's hypot differs in the last bit; this runs once per trial or on rare events only.
    """
    return np.array([math.hypot(u, v) for u, v in zip(a.tolist(), b.tolist(), strict=True)])


# ----------------------------------------------------------------------------- TA rules

Chooser = Callable[[_InterceptBatch, Mask], Array]
"""TA [rad] for the rows of a mask (other rows: anything), from the batch's present inputs."""

_NETS: dict[tuple[str, int, int, float], BatchTurnFunction] = {}


def _chooser(drill: InterceptDrill, facts: FieldFacts) -> Chooser | None:
    """The behaviour's TA rule over a batch; None for ``still`` (the defender never acts)."""
    kind = drill.behaviour
    if kind is Behaviour.STILL:
        return None
    if kind is Behaviour.STRAIGHT:
        return lambda batch, rows: np.zeros(len(rows))
    if kind is Behaviour.RANDOM:
        return _random_ta
    if kind is Behaviour.NET:
        factor = drill.distance_factor(facts)
        key = (*file_key(drill.model), factor)
        if key not in _NETS:
            _NETS[key] = load_batch_turn_function(drill.model, factor)
        net = _NETS[key]
        return lambda batch, rows: net(*batch.inputs[:3])
    if kind is Behaviour.LOOKUP:
        table = load_lookup_table(drill.model)
        return lambda batch, rows: table.predict(batch.inputs[1])
    return _analytic_ta


def _given_ta(batch: _InterceptBatch, rows: Mask) -> Array:
    """The TA given from outside for each trial (an environment's actions)."""
    return batch.turn_angles


def _random_ta(batch: _InterceptBatch, rows: Mask) -> Array:
    """RandomPolicy: one uniform draw from each chosen trial's "policy" stream."""
    ta = np.zeros(len(rows))
    chosen = np.flatnonzero(rows)
    low, high = -RANDOM_TA_HALF_RANGE_RAD, RANDOM_TA_HALF_RANGE_RAD
    ta[chosen] = low + (high - low) * batch.policy.take(1, chosen)[:, 0]
    return ta


def _analytic_ta(batch: _InterceptBatch, rows: Mask) -> Array:
    """AnalyticPolicy itself on each chosen trial (once per trial: the one implementation)."""
    policy = AnalyticPolicy()
    bd, ba, previous_bd, x, y = batch.inputs
    ta = np.zeros(len(rows))
    for row in np.flatnonzero(rows).tolist():
        px, py = float(batch.prev_x[row]), float(batch.prev_y[row])
        previous = None if math.isnan(px) else (px, py)
        ta[row] = policy(
            float(bd[row]), float(ba[row]), float(previous_bd[row]), previous,
            (float(x[row]), float(y[row])),
        )  # fmt: skip
    return ta
