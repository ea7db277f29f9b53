"""The set play's kicks on a field: what the attackers know of ball and kick, and the coach's.

:func:`ball_sense` gives the set-play minds (:mod:`robotsoccer.skills.setplay`) the field's
ball and kick as they may know them; :func:`kick_powers` the dribble, pass and shot powers
(the dribble by the matches' rule, :func:`~robotsoccer.skills.motion.dribble_power`; the
approach by :func:`~robotsoccer.skills.motion.stop_speed`; :func:`pass_speed`). Where the
players have no aimable kick (the 1997 robots), the coach carries out their kicks
(:class:`CoachKicks`, fed by :class:`CoachKickRelay`), as :mod:`robotsoccer.drills.setplay`'s
docstring describes ("Kicks", "Speeds"). Distances in drill units where named so, else metres;
speeds m/s.
"""

from __future__ import annotations

import math

from field_models.arena import Arena, FieldFacts
from field_models.protocol import Action, Kick, Mind, Percept, PlayerRef
from robotsoccer.drills.intercept_plan import LaunchPlan
from robotsoccer.skills.ball_sense import BallSense
from robotsoccer.skills.lead import velocity_window
from robotsoccer.skills.motion import dribble_power, stop_speed
from robotsoccer.skills.setplay import KickPowers

KICK_MARGIN_UNITS = 1.0
"""Kick reach beyond touching where the coach kicks for the players (the server's margin)."""
ARMED_PERIODS = 1
"""A coach's kick stays armed this many sensor periods (to the player's next decision)."""
RECALL_PERIODS = 2
"""A ball the sensor misses is taken to be where it was last seen for this many periods."""
SAFE_REACH_SHARE = 0.85
"""The players kick when the ball seems within this share of their kick margin beyond
touching (sensor noise)."""


def kick_reach(facts: FieldFacts) -> float:
    """Kick reach: the field's kick, else touching plus :data:`KICK_MARGIN_UNITS` [m]."""
    if facts.kick is not None:
        return facts.kick.reach_m
    return facts.touch_distance_m + KICK_MARGIN_UNITS * facts.unit_m


def coach_kicks(facts: FieldFacts, plan: LaunchPlan) -> CoachKicks | None:
    """The coach's kicks for the attackers where they have no aimable kick; else None."""
    if facts.kick is not None and facts.kick.aimable:
        return None
    armed = ARMED_PERIODS * round(facts.sensor_period_s / facts.dt_s) - 1
    return CoachKicks(plan.launch_speed_mps / plan.kick_power, facts.ball_max_speed_mps, armed)


def ball_sense(facts: FieldFacts, plan: LaunchPlan) -> BallSense:
    """What the attackers know of the ball and their kick (the coach's kick where they lack one)."""
    kick = facts.kick
    if kick is not None and kick.aimable:
        per_power = kick.speed_per_power_mps
    else:
        per_power = plan.launch_speed_mps / plan.kick_power
    touch = facts.touch_distance_m
    reach = touch + SAFE_REACH_SHARE * (kick_reach(facts) - touch)
    period_ticks = round(facts.sensor_period_s / facts.dt_s)
    # A server command runs in the next cycle; a robot's turn runs over about a camera
    # period after the link (the host's timed turn, §2), so it shows a period later.
    settle = 1 if facts.sensor_latency_s is None else 1 + period_ticks
    margin = kick_reach(facts) - touch
    top = facts.player_top_speed_mps
    # A camera (a sensor with latency that gives positions: the robots) lets a player fit the
    # ball's velocity to its sightings, as layer 1's lead defender does; the 1996 server's see
    # gives none to fit, and there the ball is dead-reckoned as before.
    camera = facts.sensor_latency_s is not None and bool(facts.landmarks)
    return BallSense(
        facts.ball,
        per_power,
        100.0,
        touch,
        reach,
        facts.sensor_period_s,
        top_speed_mps=top,
        approach_power=100.0 * min(1.0, stop_speed(facts, margin) / top),
        turn_settle_ticks=settle,
        recall_ticks=RECALL_PERIODS * period_ticks,
        landmarks=facts.landmarks if camera else (),
        track_window=velocity_window(facts.sensor_period_s) if camera else 0,
    )


def kick_powers(
    facts: FieldFacts, plan: LaunchPlan, pass_speed_mps: float | None = None
) -> KickPowers:
    """Dribble, pass and shot powers: full power for shots; passes at `pass_speed_mps`.

    Passes default to layer 1's launch where the players have an aimable kick (the Soccer
    Server) and to :func:`pass_speed` where the coach kicks for them (the robots).

    Raises:
        ValueError: No kick sends the ball :data:`~robotsoccer.skills.motion.DRIBBLE_UNITS`
            in the dribble's time, or the pass speed is beyond the top kick.
    """
    sense = ball_sense(facts, plan)
    # The matches' dribble rule: a carrier must catch up with its ball at its last approach
    # speed, from which it can stop beside it (the robots' slow wheels): half that at most.
    margin = sense.reach_m - sense.touch_m
    dribble = dribble_power(facts, margin, sense.speed_per_power_mps, sense.max_power)
    passing = plan.kick_power
    if pass_speed_mps is None and coach_kicks(facts, plan) is not None:
        pass_speed_mps = pass_speed(facts)
    if pass_speed_mps is not None:
        top = sense.speed(sense.max_power)
        if not 0.0 < pass_speed_mps <= top:
            raise ValueError(
                f"pass_speed_mps must be in (0, {top:.3g}] m/s, got {pass_speed_mps!r}"
            )
        passing = pass_speed_mps / sense.speed_per_power_mps
    return KickPowers(dribble=dribble, passing=passing, shot=sense.max_power)


def pass_speed(facts: FieldFacts) -> float:
    """A pass's speed [m/s] where the coach kicks for the players (the robots).

    The robot's top speed (1.2 m/s on ``small_size_1997``): about what a 1997 robot without a
    kicker gives the ball by driving through it, and the top of the range of ball speeds
    layer 1's lead net was trained on there (0.6-1.2 m/s, :mod:`robotsoccer.drills.intercept`'s
    robot drill), so the learned skill meets passes it knows. Layer 1's launch (2.05 m/s on
    that table) is a shot's speed: a receiver cannot turn such a ball toward the winger with
    one kick of at most that speed.
    """
    return facts.player_top_speed_mps


class CoachKicks:
    """Kicks the coach carries out for players without an aimable kick (module docstring).

    A kick stays armed for `armed_ticks` after the tick it was sent on (a robot's next decision
    comes a camera period later and replaces it): it fires at the first tick its player is
    within kick reach of the ball, as a kicker that fires when the ball reaches it would; one
    whose ball never comes is dropped.

    Args:
        speed_per_power_mps: Ball speed a kick adds per unit of power [m/s].
        max_speed_mps: The ball's top speed [m/s].
        armed_ticks: Ticks a kick waits for the ball after the one it was sent on.
    """

    def __init__(
        self, speed_per_power_mps: float, max_speed_mps: float, armed_ticks: int = 0
    ) -> None:
        self.speed_per_power_mps = speed_per_power_mps
        self.max_speed_mps = max_speed_mps
        self.armed_ticks = armed_ticks
        self.pending: dict[PlayerRef, tuple[Kick, int]] = {}
        self.fired = 0
        """Kicks carried out so far."""

    def arm(self, ref: PlayerRef, kick: Kick, tick: int) -> None:
        """`ref` sends `kick` at `tick` (it replaces one of its own still armed)."""
        self.pending[ref] = (kick, tick + self.armed_ticks)

    def apply(self, arena: Arena, reach_m: float) -> None:
        """Carry out the armed kicks of players within `reach_m` of the ball; drop stale ones."""
        for ref, (kick, until) in list(self.pending.items()):
            x, y, _, vx, vy = arena.ball_state()
            p = arena.player_state(ref)
            if (p.x - x) ** 2 + (p.y - y) ** 2 > reach_m * reach_m:
                if arena.tick >= until:
                    del self.pending[ref]  # a kick that misses the ball, as on the server
                continue
            del self.pending[ref]
            self.fired += 1
            speed = max(0.0, min(100.0, kick.power)) * self.speed_per_power_mps
            direction = p.heading + kick.direction_rad
            vx += speed * math.cos(direction)
            vy += speed * math.sin(direction)
            top = math.hypot(vx, vy)
            if top > self.max_speed_mps:
                vx, vy = vx * self.max_speed_mps / top, vy * self.max_speed_mps / top
            arena.place_ball(x, y, vx, vy)


class CoachKickRelay:
    """A mind whose kicks go to the coach (:class:`CoachKicks`) instead of its robot."""

    def __init__(self, mind: Mind, ref: PlayerRef, kicks: CoachKicks) -> None:
        self.mind = mind
        self.ref = ref
        self.kicks = kicks

    @property
    def done(self) -> bool:
        """The wrapped mind's ``done``."""
        return bool(getattr(self.mind, "done", False))

    def act(self, percept: Percept) -> tuple[Action, ...]:
        """The mind's actions without its kicks, which are handed to the coach."""
        actions = self.mind.act(percept)
        kept: list[Action] = []
        for action in actions:
            if isinstance(action, Kick):
                self.kicks.arm(self.ref, action, percept.tick)
            else:
                kept.append(action)
        return tuple(kept)
