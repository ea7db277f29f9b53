"""The paper's pass drill (§6, Figures 9–13) on any field model; labels SUCCESS, FAILURE, MISS.

**Placement** (Figure 9), in *units* (Soccer Server metres; on another field one unit is its
``unit_m``, as in layer 1). The paper draws the region but gives no numbers, so these are ours
(drill constants, below):

* the ball is at x in [-30, -10], y in [-12, 12]; the passer stands behind it (toward its own
  goal), touching distance plus half its kick reach away, facing +x;
* the 3 receivers (left 2–4) and 4 defenders (right 1–4) are uniform in the region ahead of
  the ball: 8–30 units further along x, within ±15 units of the ball's y, inside the pitch;
* 2 more players of each team (left 5–6, right 5–6) are uniform on the whole pitch;
* no two players closer than :data:`MIN_SEPARATION_UNITS` (or two player diameters on a field
  whose players are bigger), and none within 4 units of the ball;
* every player but the passer faces a random direction within ±90° of the ball.

**The conversation and the minds** are in :mod:`robotsoccer.skills.passing`. Receivers and
defenders use layer 1's interception (``interceptor``, ``net`` with the run's own net file) with
layer 1's trigger distance and turn tolerance on this field
(:func:`robotsoccer.drills.intercept_plan.launch_plan`). The pass itself is layer 1's launch:
the same kick power on the Soccer Server. On a field without an aimable kick (the 1997 robots),
the coach launches the ball at the plan's launch speed along the direction the passer chose,
one tick after its announcement.

**Client** (option ``client``, issue 28): ``see`` (the default, the paper's client: receivers
and defenders decide at each see, "turn, then dash") or ``cycle``, the Soccer Server's per-cycle
client: their layer 1 is the per-cycle defender
(:meth:`~robotsoccer.drills.layered.LayeredDrill.cycle_interceptor_for`, the same TA rule, as
the set play's defenders), so that a tree is trained against the client the team plays on. The
passer is the same on both. Refused on the robots, whose host already acts on every tick, and
with a lead net (the per-cycle client plays the turn decision).

**The coach's labels.** From the pass on, at every tick, the first player other than the passer
within *control* distance of the ball (its kick reach, or touching plus a quarter unit on a field
without a kick) decides the trial:

* the chosen receiver: SUCCESS (the paper's receiver then plays it back; taking control is
  what we judge);
* an opponent: FAILURE (the paper's defender clears it);
* another teammate: MISS (no receiver or defender got it);
* the ball leaves the pitch, stops, or time runs out: MISS.

**Data** per trial (:meth:`PassDrill.data`): the chosen receiver's number, the tree's success
confidence (nan without a tree), the numbers of candidates found and reports heard, then the 174
attributes (:data:`learning.pass_features.ATTRIBUTE_NAMES`).
"""

from __future__ import annotations

import math
from typing import Any, NamedTuple

from field_models.arena import Arena, FieldFacts
from field_models.protocol import LEFT, RIGHT, Mind, PlayerRef
from field_models.seeding import Rng, TrialRngs
from robotsoccer.drills.base import Verdict
from robotsoccer.drills.intercept_options import ClientKind
from robotsoccer.drills.intercept_plan import LaunchPlan
from robotsoccer.drills.layered import CYCLE_ON_ROBOTS, LayeredDrill, control_reach, load_evaluator
from robotsoccer.drills.layered_options import PassOptions
from robotsoccer.skills.pass_receivers import ReceiverMind, WaitingInterceptorMind
from robotsoccer.skills.passing import Chooser, PasserMind, PassPhysics

PASSER = PlayerRef(LEFT, 1)
RECEIVERS = (PlayerRef(LEFT, 2), PlayerRef(LEFT, 3), PlayerRef(LEFT, 4))
DEFENDERS = tuple(PlayerRef(RIGHT, n) for n in (1, 2, 3, 4))
ELSEWHERE = (PlayerRef(LEFT, 5), PlayerRef(LEFT, 6), PlayerRef(RIGHT, 5), PlayerRef(RIGHT, 6))
PLAYERS = (PASSER, *RECEIVERS, ELSEWHERE[0], ELSEWHERE[1], *DEFENDERS, ELSEWHERE[2], ELSEWHERE[3])

BALL_X_UNITS = (-30.0, -10.0)
BALL_Y_UNITS = (-12.0, 12.0)
REGION_AHEAD_UNITS = (8.0, 30.0)
"""The region of Figure 9 starts and ends this far ahead of the ball (ours: no numbers given)."""
REGION_HALF_WIDTH_UNITS = 15.0
MIN_SEPARATION_UNITS = 3.0
BALL_CLEARANCE_UNITS = 4.0
STOPPED_SPEED_PER_LENGTH = 1e-3
"""The ball has stopped below this share of the pitch length per second."""


class _Spacing(NamedTuple):
    """How a placed player keeps clear: of the players placed so far and of the ball [m]."""

    taken: list[tuple[float, float]]
    separation: float
    ball: tuple[float, float]
    clear: float


class PassDrill(LayeredDrill):
    """The paper's Figure 9–13 trial (module docstring).

    Built from a :class:`~robotsoccer.drills.layered_options.PassOptions` record, or from its
    fields as keywords (the registry's ``make_drill`` and a command line's ``--option
    NAME=VALUE`` give them so); :data:`OPTIONS` names the record, whose fields are the drill's
    option names.

    Args:
        options: The drill's options; None: built from `keywords`.
        **keywords: The options' fields by name, where `options` is not given.

    Raises:
        ValueError: A bad option (:class:`~robotsoccer.drills.layered_options.PassOptions`),
            both a record and keywords, or (at set-up) a model from another field.
    """

    name: str = "pass"
    labels: tuple[str, ...] = ("SUCCESS", "FAILURE", "MISS")
    OPTIONS = PassOptions

    def __init__(self, options: PassOptions | None = None, /, **keywords: Any) -> None:
        if options is not None and keywords:
            raise ValueError("give the pass drill an options record or keywords, not both")
        self.options = o = options if options is not None else PassOptions(**keywords)
        self.chooser, self.model = o.chooser, o.model
        self.interceptor, self.net = o.interceptor, o.net
        self.defenders_still = o.defenders == "still"
        self.max_time_s = o.max_time_s
        self.transfer = o.transfer
        self.use_reports = o.receiver_half == "use"
        self.client = o.client
        self.passer: PasserMind | None = None
        self._judge: _PassJudge | None = None
        self._checked: FieldFacts | None = None

    def players(self) -> tuple[PlayerRef, ...]:
        """The passer, its 3 receivers and 2 more teammates; 4 defenders and 2 more opponents."""
        return PLAYERS

    def setup(self, arena: Arena, rngs: TrialRngs) -> None:
        """Place ball and players (module docstring)."""
        facts = arena.facts
        if self.client is ClientKind.CYCLE and facts.walled:
            raise ValueError(CYCLE_ON_ROBOTS)
        self._check_origins(facts)
        plan = self.plan(facts)
        rng = rngs["placement"]
        unit = facts.unit_m
        pitch = facts.pitch
        bx = float(rng.uniform(*BALL_X_UNITS)) * unit
        by = float(rng.uniform(*BALL_Y_UNITS)) * unit
        arena.place_ball(bx, by)
        reach = facts.kick.reach_m if facts.kick is not None else facts.touch_distance_m
        gap = 0.5 * (facts.touch_distance_m + reach)
        arena.place_player(PASSER, bx - gap, by, 0.0)
        separation = max(MIN_SEPARATION_UNITS * unit, 4.0 * pitch.player_radius_m)
        taken = [(bx - gap, by)]
        clear = BALL_CLEARANCE_UNITS * unit
        x_lim = pitch.half_length_m - 2.0 * pitch.player_radius_m
        y_lim = pitch.half_width_m - 2.0 * pitch.player_radius_m
        region_x = (
            bx + REGION_AHEAD_UNITS[0] * unit,
            min(bx + REGION_AHEAD_UNITS[1] * unit, x_lim),
        )
        half = REGION_HALF_WIDTH_UNITS * unit
        region_y = (max(by - half, -y_lim), min(by + half, y_lim))
        spacing = _Spacing(taken, separation, (bx, by), clear)
        for ref in (*RECEIVERS, *DEFENDERS):
            self._place(arena, rng, ref, (region_x, region_y), spacing)
        for ref in ELSEWHERE:
            self._place(arena, rng, ref, ((-x_lim, x_lim), (-y_lim, y_lim)), spacing)
        self._judge = _PassJudge(arena, plan)
        self.passer = None

    @staticmethod
    def _place(
        arena: Arena,
        rng: Rng,
        ref: PlayerRef,
        box: tuple[tuple[float, float], tuple[float, float]],
        spacing: _Spacing,
    ) -> None:
        """Place `ref` uniformly in the box ((x low, x high), (y low, y high)), spaced out."""
        (xs, ys), (taken, separation, ball, clear) = box, spacing
        for _ in range(1000):
            x, y = float(rng.uniform(*xs)), float(rng.uniform(*ys))
            if math.hypot(x - ball[0], y - ball[1]) < clear:
                continue
            if all(math.hypot(x - px, y - py) >= separation for px, py in taken):
                break
        taken.append((x, y))
        to_ball = math.atan2(ball[1] - y, ball[0] - x)
        arena.place_player(ref, x, y, to_ball + float(rng.uniform(-0.5, 0.5)) * math.pi)

    def minds(self, arena: Arena, rngs: TrialRngs) -> dict[PlayerRef, Mind]:
        """The passer, the receivers and the defenders (the others stand still)."""
        facts = arena.facts
        plan = self.plan(facts)
        policy_rng = rngs["policy"]
        boost = self.chooser is Chooser.BOOST
        tree = load_evaluator(self.model, boost=boost)[0] if self.model else None
        physics = PassPhysics(
            facts.ball,
            plan.launch_speed_mps,
            facts.player_top_speed_mps,
            facts.kick.reach_m if facts.kick is not None else facts.touch_distance_m,
        )
        aimable = facts.kick is not None and facts.kick.aimable
        passer = PasserMind(
            [r.number for r in RECEIVERS],
            self.chooser,
            policy_rng,
            facts,
            kick_power=plan.kick_power if aimable else None,
            tree=tree,
            physics=physics,
            use_reports=self.use_reports,
        )
        self.passer = passer
        assert self._judge is not None
        self._judge.passer = passer

        def interceptor() -> Mind:
            if self.client is ClientKind.CYCLE:
                return self.cycle_interceptor_for(facts, plan, policy_rng, self.interceptor)
            return self.interceptor_for(facts, plan, policy_rng, self.interceptor)

        minds: dict[PlayerRef, Mind] = {PASSER: passer}
        for slot, ref in enumerate(RECEIVERS):
            minds[ref] = ReceiverMind(
                ref.number,
                interceptor(),
                unit_m=facts.unit_m,
                sensor_period_s=facts.sensor_period_s,
                dt_s=facts.dt_s,
                slot=slot,
                say_max_chars=facts.say_max_chars,
            )
        for ref in DEFENDERS:
            minds[ref] = WaitingInterceptorMind(interceptor(), still=self.defenders_still)
        return minds

    def judge(self, arena: Arena) -> Verdict | None:
        """SUCCESS, FAILURE, MISS or carry on (module docstring)."""
        if self._judge is None:
            raise RuntimeError("judge() before setup()")
        return self._judge.judge(arena)

    def timeout(self, arena: Arena) -> Verdict:
        """Out of time: a MISS."""
        passer = self.passer
        if passer is None or passer.chosen is None:
            return Verdict("MISS", "time ran out before the pass")
        return Verdict("MISS", "time ran out: nobody took the ball")

    def data(self) -> tuple[float, ...]:
        """(receiver, confidence, candidates, reports, *174 attributes), or () without a pass."""
        passer = self.passer
        if passer is None or passer.chosen is None or passer.attributes is None:
            return ()
        head = (float(passer.chosen), passer.confidence, passer.candidates, passer.reports)
        return (*map(float, head), *map(float, passer.attributes))

    def measures(self) -> dict[str, float]:
        """The pass's length [units] and how long it ran [s]."""
        judge = self._judge
        if judge is None or judge.launched_tick is None:
            return {}
        out = {"pass_time_s": (judge.end_tick - judge.launched_tick) * judge.dt_s}
        if judge.pass_length_m is not None:
            out["pass_distance_units"] = judge.pass_length_m / judge.unit_m
        return out


class _PassJudge:
    """The coach's labelling rule for one trial (module docstring)."""

    def __init__(self, arena: Arena, plan: LaunchPlan) -> None:
        facts = arena.facts
        pitch = facts.pitch
        self.dt_s = facts.dt_s
        self.unit_m = facts.unit_m
        self.plan = plan
        kick = facts.kick
        self.coach_launch = kick is None or not kick.aimable
        reach = control_reach(facts)
        self.reach2 = reach * reach
        self.half_length = pitch.half_length_m
        self.half_width = pitch.half_width_m
        self.eps2 = (STOPPED_SPEED_PER_LENGTH * pitch.length_m) ** 2
        self.passer: PasserMind | None = None
        self.launched_tick: int | None = None
        self.end_tick = 0
        self.pass_length_m: float | None = None
        self.chosen: PlayerRef | None = None  # the receiver, from the pass on
        self.order = [p for p in PLAYERS if p != PASSER]
        # A player cannot reach the ball sooner than their gap allows at this closing speed
        # (both at full speed, with room for a push), so the judge looks at each player only
        # from the first tick it could be within reach: far fewer truth reads per tick.
        self.closing_mps = 1.5 * (facts.ball_max_speed_mps + facts.player_top_speed_mps)
        self.reach = reach
        self.next_look = [0] * len(self.order)  # by place in `order` (no hashing per tick)
        self.score = arena.score()

    def judge(self, arena: Arena) -> Verdict | None:
        """The verdict of this tick, or None."""
        passer = self.passer
        if passer is None or passer.decided_tick is None:
            return None
        tick = arena.tick
        self.end_tick = tick
        if self.launched_tick is None:
            if tick <= passer.decided_tick:
                return None
            self._launch(arena, passer)
            return None
        if arena.score() != self.score:  # a referee that restarts at once hides the crossing
            return Verdict("MISS", "the ball went into a goal")
        x, y, _, vx, vy = arena.ball_state()
        chosen = self.chosen
        next_look = self.next_look
        for i, ref in enumerate(self.order):
            if tick < next_look[i]:
                continue
            p = arena.player_state(ref)
            d2 = (p.x - x) ** 2 + (p.y - y) ** 2
            if d2 <= self.reach2:
                return self._taken(ref, chosen)
            gap_s = (math.sqrt(d2) - self.reach) / self.closing_mps
            next_look[i] = tick + max(1, int(gap_s / self.dt_s))
        if abs(x) > self.half_length or abs(y) > self.half_width:
            return Verdict("MISS", "the ball left the field")
        if tick > self.launched_tick + 2 and vx * vx + vy * vy < self.eps2:
            return Verdict("MISS", "the ball stopped; nobody took it")
        return None

    def _launch(self, arena: Arena, passer: PasserMind) -> None:
        """Note the pass (and launch the ball on a field without an aimable kick)."""
        self.launched_tick = arena.tick
        p = arena.player_state(PASSER)
        if passer.chosen is not None:
            self.chosen = PlayerRef(LEFT, passer.chosen)
            r = arena.player_state(self.chosen)
            self.pass_length_m = math.hypot(r.x - p.x, r.y - p.y)
        if self.coach_launch:
            ball = arena.ball_state()
            direction = p.heading + (passer.pass_direction_rad or 0.0)
            speed = self.plan.launch_speed_mps
            arena.place_ball(
                ball.x, ball.y, speed * math.cos(direction), speed * math.sin(direction)
            )

    def _taken(self, ref: PlayerRef, chosen: PlayerRef | None) -> Verdict:
        if ref == chosen:
            return Verdict("SUCCESS", f"the receiver {ref} took the ball")
        if ref.team == RIGHT:
            return Verdict("FAILURE", f"the defender {ref} took the ball")
        return Verdict("MISS", f"the ball reached {ref}, not the receiver")
