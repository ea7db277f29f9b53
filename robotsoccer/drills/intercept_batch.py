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

The coach's rules and the results they give are
:class:`~robotsoccer.drills.intercept_batch_coach.BatchCoach`; this module places the trials,
plays the shooter and the defender, and steps the batch.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from field_models.arena import FieldFacts
from field_models.batch_arena import BatchArena
from field_models.protocol import Pitch, wrap_angle
from field_models.registry import batch_reason as field_batch_reason
from field_models.registry import make_batch_arena
from field_models.seeding import StreamBatch
from learning.interception_file import BatchTurnFunction, load_batch_turn_function
from robotsoccer.drills.intercept import InterceptDrill
from robotsoccer.drills.intercept_batch_coach import DEFENDER_ROW, SHOOTER_ROW, BatchCoach
from robotsoccer.drills.intercept_options import ClientKind, Decision, Launch, Shot
from robotsoccer.drills.intercept_plan import DEFENDER, SHOOTER, LaunchPlan
from robotsoccer.runs.runner import TrialResult, TrialSpec, resolve
from robotsoccer.skills.intercept import (
    DASH_POWER,
    TA_CLIP_RAD,
    Behaviour,
    TaMode,
    file_key,
    load_lookup_table,
)
from robotsoccer.skills.turn_policies import RANDOM_TA_HALF_RANGE_RAD, AnalyticPolicy

Array = npt.NDArray[np.float64]
Mask = npt.NDArray[np.bool_]

DEFAULT_BATCH = 8192
"""Trials stepped together by default: large enough that numpy's per-call cost is spread thin,
small enough that the arrays stay in cache (``robotsoccer bench``: trials/s against size)."""
COMPACT_SHARE = 0.75
"""The batch drops its finished trials once fewer than this share of its rows still run."""

_NONE, _TURN, _DASH = 0, 1, 2


def batch_reason(spec: TrialSpec) -> str | None:
    """Why `spec`'s trials cannot run batched (None: they can).

    Raises:
        ValueError: The drill's options are invalid (as the one-trial path raises).
    """
    if spec.drill != "intercept":
        return f"the batch engine runs the intercept drill, not {spec.drill!r}"
    resolved = resolve(spec)
    drill = resolved.new_drill()
    assert isinstance(drill, InterceptDrill)
    if drill.defender_kick:
        return "the defender's clearing kick reads landmarks, which the batch does not see"
    if drill.client is not ClientKind.SEE:
        return "the batch plays the see-triggered client"
    if drill.decision is not Decision.TURN:
        return "the batch plays the paper's turn-angle decision, not the lead"
    if drill.shot is not Shot.DEFENDER:
        return "the batch aims every shot at the defender"
    reason = field_batch_reason(spec.field_model, spec.preset, resolved.options)
    if reason is not None:
        return reason
    if drill.plan_for(resolved.facts).decision_period_s:
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
        resolved = resolve(spec)
        drill = resolved.new_drill()
        assert isinstance(drill, InterceptDrill)
        options, facts = resolved.options, resolved.facts
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
        server.move_player(SHOOTER_ROW, bx - gap * ux, by - gap * uy, bearing)
        server.move_player(DEFENDER_ROW, dx, dy, bearing + math.pi)
        self.coach = BatchCoach(server, self.setting.pitch, self.setting.dt_s, plan)

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
            s.kick(SHOOTER_ROW, self.setting.plan.kick_power, self.kick_dir, self.kick_due)
            self.kick_due[:] = False
        col = np.minimum(self.queue_next, 1)
        at = np.arange(len(col))
        kind = np.where(self.queue_next < 2, self.queue_kind[at, col], _NONE)
        arg = self.queue_arg[at, col]
        if (kind == _TURN).any():
            s.turn(DEFENDER_ROW, arg, kind == _TURN)
        if (kind == _DASH).any():
            s.dash(DEFENDER_ROW, DASH_POWER, 0.0, kind == _DASH)
        self.queue_next += kind != _NONE

    def _shooter_sees(self) -> None:
        """AimedShooterMind: kick at the first percept toward the defender as seen, plus aim."""
        waits = self.shooter_waits
        if not waits.any():
            return
        shown, _, angle = self.server.see(SHOOTER_ROW, DEFENDER_ROW)
        aim = np.where(shown, angle, 0.0) + self.setting.drill.aim_offset_rad
        self.kick_dir = np.where(waits, aim, self.kick_dir)
        self.kick_due |= waits
        self.shooter_waits[:] = False

    def _defender_sees(self) -> None:
        """DefenderMind.act on every trial's percept (its module docstring)."""
        choose = self.setting.choose
        if choose is None:  # still: never acts
            return
        ball, bd, ba = self.server.see(DEFENDER_ROW, 0)
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
        """InterceptDrill.judge for every trial (:class:`BatchCoach`); end those it decides."""
        verdict = self.coach.judge(self.triggered, self.alive)
        self._finish(verdict >= 0, verdict)

    def _time_out(self) -> None:
        """InterceptDrill.timeout for every trial still running."""
        self._finish(self.alive.copy(), self.coach.time_out_codes())

    def _finish(self, ended: Mask, codes: npt.NDArray[np.int_]) -> None:
        """Write the results of the trials `ended` and take them out of the running."""
        rows = np.flatnonzero(ended)
        if not rows.size:
            return
        self.out.update(self.coach.results(rows, codes, self.rows, self.trials, self.example))
        self.alive[rows] = False

    def _compact(self) -> None:
        """Drop the finished trials' rows from every array (module docstring)."""
        keep = np.flatnonzero(self.alive)
        self.server.keep(keep)
        self.policy = self.policy.subset(keep)
        for name in _PER_TRIAL:
            setattr(self, name, getattr(self, name)[keep])
        self.coach.keep(keep)


_PER_TRIAL = (
    "rows", "alive", "shooter_waits", "kick_due", "kick_dir", "queue_kind", "queue_arg",
    "queue_next", "triggered", "ta", "prev_bd", "prev_x", "prev_y", "heading", "pending_turn",
    "example", "turn_angles",
)  # fmt: skip
"""The per-trial state arrays of :class:`_InterceptBatch` (compacted together; the coach's
own with :meth:`~robotsoccer.drills.intercept_batch_coach.BatchCoach.keep`)."""


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
