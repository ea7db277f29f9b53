"""The set play of the paper's Figure 15 (§7) on any field model; labels by how the play ended.

**Set-up** in drill units (Soccer Server metres; ``unit_m`` on another field), the left team
attacking the goal at +x. The paper shows the play in a figure without numbers, so the spots
are ours (:data:`SPOTS`); each player is moved by up to :data:`JITTER_UNITS` in x and y from
the trial's ``"placement"`` stream and faces the ball:

* the starter (left 1) behind the ball at (-5, 0);
* two receivers (left 2, 3) ahead on either side, each with a defender beside it;
* a defender (right 1) in the starter's path;
* the winger (left 4) up the left wing, uncovered, with a defender (right 4) in its path to
  goal;
* two last receivers (left 5, 6) near the goal, each with a defender beside it, and a goalie
  (right 7).

**The play** (:mod:`robotsoccer.skills.setplay`): the starter dribbles toward the goal until it
sees an opponent within :data:`BLOCKED_UNITS` in its path, then passes by the tree to one of its
two nearest teammates (left 2, 3) after the say/hear exchange of layer 2. The chosen receiver
intercepts with the layer-1 net and kicks to the winger; the winger collects the ball, dribbles
the same way and passes by the tree to left 5 or 6; that receiver intercepts and shoots.
Defenders and goalie are layer 1's interception (the same net), triggered by the ball's
distance as in the drill of §5.

**The coach.** At every tick the first player within control distance of the ball (kick
reach, or touching plus a quarter unit without a kick) holds it. An attacker other than the
last one to hold it completes a pass. The play ends:

* GOAL: the left team scores;
* SHOT: a shot was kicked and did not score (the goalie or a defender took it, it went out,
  or it stopped);
* INTERCEPTED: a defender held the ball before any shot;
* OUT: the ball left the field before any shot;
* TIMEOUT: :attr:`SetPlayDrill.max_time_s` ran out (by default :data:`TIME_LIMIT_ARRIVALS`
  times layer 1's arrival time on the field).

**Measures** per play: ``passes`` completed (0–3), ``shot`` and ``goal`` (0 or 1), and the
first pass's receiver.
"""

from __future__ import annotations

import math

from field_models.arena import Arena, FieldFacts
from field_models.protocol import LEFT, RIGHT, Crossing, Mind, PlayerRef
from field_models.seeding import TrialRngs
from robotsoccer.drills.base import GoalWatch, Verdict
from robotsoccer.drills.intercept import LaunchPlan
from robotsoccer.drills.passing import (
    STOPPED_SPEED_PER_LENGTH,
    LayeredDrill,
    control_reach,
    load_evaluator,
)
from robotsoccer.options import choice, flag
from robotsoccer.skills.intercept import (
    Behaviour,
    DefenderMind,
    check_behaviour,
    make_policy,
    transfer_distance_factor,
)
from robotsoccer.skills.passing import Chooser, PasserMind, ReceiverMind
from robotsoccer.skills.setplay import CarrierMind, KickPowers, SetPlayReceiverMind

STARTER = PlayerRef(LEFT, 1)
FIRST_RECEIVERS = (PlayerRef(LEFT, 2), PlayerRef(LEFT, 3))
WINGER = PlayerRef(LEFT, 4)
LAST_RECEIVERS = (PlayerRef(LEFT, 5), PlayerRef(LEFT, 6))
DEFENDERS = tuple(PlayerRef(RIGHT, n) for n in range(1, 8))
GOALIE = DEFENDERS[-1]
SPOTS: dict[PlayerRef, tuple[float, float]] = {
    STARTER: (-5.0, 0.0),
    FIRST_RECEIVERS[0]: (20.0, 12.0),
    FIRST_RECEIVERS[1]: (20.0, -12.0),
    WINGER: (28.0, 22.0),
    LAST_RECEIVERS[0]: (42.0, 12.0),
    LAST_RECEIVERS[1]: (44.0, 2.0),
    DEFENDERS[0]: (28.0, 0.0),
    DEFENDERS[1]: (25.0, 6.0),
    DEFENDERS[2]: (25.0, -6.0),
    DEFENDERS[3]: (38.0, 16.0),
    DEFENDERS[4]: (46.0, 8.0),
    DEFENDERS[5]: (47.0, -3.0),
    GOALIE: (50.5, 0.0),
}
"""Where each player stands before its jitter [units] (module docstring; ours)."""
PLAYERS = tuple(SPOTS)
JITTER_UNITS = 2.0
BALL_AHEAD_UNITS = 1.0
"""The ball starts this far beyond the starter's touching distance, toward +x."""
BLOCKED_UNITS = 22.0
"""An opponent this close in the path ends a dribble (the paper's "predetermined distance")."""
DRIBBLE_UNITS = 4.0
DRIBBLE_TIME_S = 2.0
"""A dribble kick sends the ball this far in this time (on a field with an aimable kick)."""
TIME_LIMIT_ARRIVALS = 40.0
SAFE_REACH_SHARE = 0.85
"""The players kick when the ball seems within this share of their reach (sensor noise)."""


class SetPlayDrill(LayeredDrill):
    """Figure 15's set play (module docstring).

    Args:
        chooser: How the passers pick (``tree``, ``random``, ``closest``, ``analytic``).
        model: The pass tree file for ``tree``.
        interceptor: Layer 1's behaviour for receivers, winger and defenders.
        net: The interception net for ``net``.
        max_time_s: The play's time limit [s]; None: 40 arrival times of layer 1's drill.
        transfer: Accept a tree or net trained on another field model or preset.

    Raises:
        ValueError: An unknown chooser or interceptor, a missing model file, a limit <= 0.
    """

    name: str = "setplay"
    labels: tuple[str, ...] = ("GOAL", "SHOT", "INTERCEPTED", "OUT", "TIMEOUT")

    def __init__(
        self,
        chooser: Chooser | str = Chooser.CLOSEST,
        model: str = "",
        interceptor: Behaviour | str = Behaviour.STRAIGHT,
        net: str = "",
        max_time_s: float | None = None,
        transfer: bool | str = False,
    ) -> None:
        self.chooser = choice(Chooser, chooser, "chooser")
        if self.chooser in (Chooser.TREE, Chooser.BOOST) and not model:
            raise ValueError(
                f"chooser {self.chooser.value!r} needs a model file (option model=...)"
            )
        self.model = model
        self.interceptor = check_behaviour(interceptor, net)
        self.net = net
        if max_time_s is not None and not max_time_s > 0.0:
            raise ValueError(f"max_time_s must be > 0, got {max_time_s!r}")
        self._max_time_s = max_time_s
        self.max_time_s = max_time_s or 60.0
        self.transfer = flag("transfer", transfer)
        self._judge: _SetPlayJudge | None = None
        self._checked: FieldFacts | None = None

    def players(self) -> tuple[PlayerRef, ...]:
        """Six attackers and seven defenders (the goalie last)."""
        return PLAYERS

    def setup(self, arena: Arena, rngs: TrialRngs) -> None:
        """Place the ball and the players (module docstring)."""
        facts = arena.facts
        self._check_origins(facts)
        if self._max_time_s is None:
            self.max_time_s = TIME_LIMIT_ARRIVALS * self.plan(facts).arrival_time_s
        unit = facts.unit_m
        pitch = facts.pitch
        rng = rngs["placement"]
        x_lim = pitch.half_length_m - 2.0 * pitch.player_radius_m
        y_lim = pitch.half_width_m - 2.0 * pitch.player_radius_m
        spots: dict[PlayerRef, tuple[float, float]] = {}
        for ref, (sx, sy) in SPOTS.items():
            dx, dy = (float(rng.uniform(-JITTER_UNITS, JITTER_UNITS)) for _ in range(2))
            x = min(max((sx + dx) * unit, -x_lim), x_lim)
            y = min(max((sy + dy) * unit, -y_lim), y_lim)
            spots[ref] = (x, y)
        sx, sy = spots[STARTER]
        bx = sx + facts.touch_distance_m + BALL_AHEAD_UNITS * unit
        arena.place_ball(bx, sy)
        for ref, (x, y) in spots.items():
            heading = 0.0 if ref == STARTER else math.atan2(sy - y, bx - x)
            arena.place_player(ref, x, y, heading)
        self._judge = _SetPlayJudge(arena, (bx, sy))

    def minds(self, arena: Arena, rngs: TrialRngs) -> dict[PlayerRef, Mind]:
        """Every player's mind (module docstring)."""
        facts = arena.facts
        plan = self.plan(facts)
        rng = rngs["policy"]
        tree = load_evaluator(self.model)[0] if self.model else None
        # Minds kick inside a safe share of the reach: a sensor's distance may read short.
        reach = SAFE_REACH_SHARE * control_reach(facts)
        powers = _powers(facts, plan)
        factor = 1.0
        if self.transfer and self.net and self.interceptor is Behaviour.NET:
            factor = transfer_distance_factor(self.net, facts)

        def interceptor(kickable: float | None = None) -> DefenderMind:
            return DefenderMind(
                make_policy(self.interceptor, rng, self.net, factor),
                plan.trigger_distance_m,
                kickable_distance_m=kickable,
                turn_tolerance_rad=plan.turn_tolerance_rad,
            )

        def passer(receivers: tuple[PlayerRef, ...]) -> PasserMind:
            return PasserMind(
                [r.number for r in receivers],
                self.chooser,
                rng,
                unit_m=facts.unit_m,
                sensor_period_s=facts.sensor_period_s,
                dt_s=facts.dt_s,
                kick_power=powers.passing,
                tree=tree,
            )

        def receiver(ref: PlayerRef, slot: int) -> ReceiverMind:
            return ReceiverMind(
                ref.number,
                interceptor(),
                unit_m=facts.unit_m,
                sensor_period_s=facts.sensor_period_s,
                dt_s=facts.dt_s,
                slot=slot,
                say_max_chars=facts.say_max_chars,
            )

        blocked = BLOCKED_UNITS * facts.unit_m

        def carrier(receivers: tuple[PlayerRef, ...], collect: DefenderMind | None) -> CarrierMind:
            return CarrierMind(
                passer(receivers),
                collect,
                attack_right=True,
                reach_m=reach,
                blocked_distance_m=blocked,
                powers=powers,
            )

        def kicker(ref: PlayerRef, slot: int, to: int | None) -> SetPlayReceiverMind:
            return SetPlayReceiverMind(
                receiver(ref, slot),
                to,
                attack_right=True,
                reach_m=reach,
                powers=powers,
                armed=to is not None,
            )

        minds: dict[PlayerRef, Mind] = {
            STARTER: carrier(FIRST_RECEIVERS, None),
            WINGER: carrier(LAST_RECEIVERS, interceptor()),
        }
        for slot, ref in enumerate(FIRST_RECEIVERS):
            minds[ref] = kicker(ref, slot, WINGER.number)
        for slot, ref in enumerate(LAST_RECEIVERS):
            minds[ref] = kicker(ref, slot, None)
        kickable = facts.kick.reach_m if facts.kick is not None else None
        for ref in DEFENDERS:
            minds[ref] = interceptor(kickable)
        assert self._judge is not None
        self._judge.minds = minds
        return minds

    def judge(self, arena: Arena) -> Verdict | None:
        """GOAL, SHOT, INTERCEPTED, OUT or carry on (module docstring)."""
        if self._judge is None:
            raise RuntimeError("judge() before setup()")
        return self._judge.judge(arena)

    def timeout(self, arena: Arena) -> Verdict:
        """Out of time."""
        judge = self._judge
        if judge is not None and judge.shot_tick is not None:
            return Verdict("SHOT", "the shot did not score in time")
        return Verdict("TIMEOUT", f"no result within {self.max_time_s:g} s")

    def data(self) -> tuple[float, ...]:
        """Nothing to learn from: the play only measures."""
        return ()

    def measures(self) -> dict[str, float]:
        """Passes completed, shot and goal (0 or 1), the first pass's receiver."""
        judge = self._judge
        if judge is None:
            return {}
        return {
            "passes": float(judge.passes),
            "shot": float(judge.shot_tick is not None),
            "goal": float(judge.goal),
            "first_receiver": float(judge.first_receiver),
        }


def _powers(facts: FieldFacts, plan: LaunchPlan) -> KickPowers:
    """Dribble, pass and shot powers: layer 1's launch for passes and shots."""
    kick = facts.kick
    full = 100.0
    if kick is None or not kick.aimable:
        return KickPowers(dribble=40.0, passing=full, shot=full)
    speed = facts.ball.speed_to_cover(DRIBBLE_UNITS * facts.unit_m, DRIBBLE_TIME_S)
    power = kick.power_for(speed) if speed is not None else None
    if power is None:
        raise ValueError(f"{facts.preset}: no kick sends the ball {DRIBBLE_UNITS:g} units")
    return KickPowers(dribble=power, passing=plan.kick_power, shot=full)


class _SetPlayJudge:
    """The coach's rule for one play (module docstring)."""

    def __init__(self, arena: Arena, ball: tuple[float, float]) -> None:
        facts = arena.facts
        pitch = facts.pitch
        reach = control_reach(facts)
        self.reach2 = reach * reach
        self.half_length = pitch.half_length_m
        self.half_width = pitch.half_width_m
        self.eps2 = (STOPPED_SPEED_PER_LENGTH * pitch.length_m) ** 2
        self.goals = GoalWatch(arena, ball)
        self.minds: dict[PlayerRef, Mind] = {}
        self.holder: PlayerRef | None = STARTER
        self.passes = 0
        self.first_receiver = 0
        self.shot_tick: int | None = None
        self.goal = False

    def _shot(self) -> int | None:
        for ref in LAST_RECEIVERS:
            mind = self.minds.get(ref)
            if isinstance(mind, SetPlayReceiverMind) and mind.kicked_tick is not None:
                return mind.kicked_tick
        return None

    def judge(self, arena: Arena) -> Verdict | None:
        """The verdict of this tick, or None."""
        x, y, _, vx, vy = arena.ball_state()
        crossing = self.goals.step(arena, x, y)
        if self.shot_tick is None:
            self.shot_tick = self._shot()
        if crossing is Crossing.RIGHT_GOAL:
            self.goal = True
            return Verdict("GOAL", f"goal after {self.passes} passes")
        taken = self._holder(arena, x, y)
        if taken is not None and taken != self.holder:
            if taken.team == RIGHT:
                label = "SHOT" if self.shot_tick is not None else "INTERCEPTED"
                return Verdict(label, f"{taken} took the ball after {self.passes} passes")
            if self.holder is not None and self.holder.team == LEFT:
                self.passes += 1
                if self.passes == 1:
                    self.first_receiver = taken.number
            self.holder = taken
        if abs(x) > self.half_length or abs(y) > self.half_width or crossing is not Crossing.NONE:
            label = "SHOT" if self.shot_tick is not None else "OUT"
            return Verdict(label, f"the ball left the field after {self.passes} passes")
        if self.shot_tick is not None and vx * vx + vy * vy < self.eps2:
            return Verdict("SHOT", "the shot stopped short")
        return None

    def _holder(self, arena: Arena, x: float, y: float) -> PlayerRef | None:
        """The first player (in :data:`PLAYERS` order) within control distance, or None."""
        for ref in PLAYERS:
            p = arena.player_state(ref)
            if (p.x - x) ** 2 + (p.y - y) ** 2 <= self.reach2:
                return ref
        return None
