"""The set play of the paper's Figure 15 (§7) on any field model; labels by how the play ended.

**Set-up** in drill units (Soccer Server metres; ``unit_m`` on another field), the left team
attacking the goal at +x. The paper shows the play in a figure without numbers, so the spots
are ours (:data:`SPOTS`); each player is moved by up to :data:`JITTER_UNITS` in x and y from
the trial's ``"placement"`` stream and faces the ball:

* the starter (left 1) behind the ball at (-5, 0), the ball at rest;
* a defender (right 1) in the starter's path, and two receivers (left 2, 3) ahead on either
  side, each with a defender (right 2, 3) beside it, a little nearer the goal. The receivers
  lie within 40° of straight ahead from where the starter stops, so it can see both at once
  (the server's view cone is 45° each side), and no defender is within layer 1's trigger
  distance of the ball while the starter asks (they start for the ball when it comes within
  14 units, §5);
* the winger (left 4) up the left wing, uncovered, with a defender (right 4) in its path to
  goal, far enough that the winger collects and dribbles before it sees it within
  :data:`BLOCKED_UNITS`;
* two last receivers (left 5, 6) near the goal, each with a defender (right 5, 6) beside it,
  and a goalie (right 7) in front of the goal.

**On the robots** (:data:`ROBOT_SPOTS`) the same spots in units of the table (1 unit =
2.74 m / 105 = 2.6 cm), but the winger stands level with the first receivers, at (26, 25)
instead of (32, 25). A receiver kicks the ball on first time (below), and a ball turned by
less than about 50° from its track runs back into the receiver's own body (it meets the ball
about 3 units from its centre, and the body with the ball clears 2.3 units). Seen from the
receiver on the winger's side (left 2, the tree's usual choice), the winger at (32, 25) lies
about 16° off the first pass's track (from where the starter stops, about (8, 0)); at (26, 25)
about 36°, which the kick reaches by bending round the body. README "The set play (measured)"
gives the plays of both spots.

**The play** (:mod:`robotsoccer.skills.setplay`): the starter dribbles toward the goal until it
sees an opponent within :data:`BLOCKED_UNITS` in its path (the paper's "predetermined
distance"), stops the ball, turns until both its receivers (left 2, 3) are in view and passes
by the tree to one of them after the say/hear exchange of layer 2. The chosen receiver
intercepts with layer 1 and at once kicks to the winger (who calls for the ball from the
announcement on, so the receiver knows where it is without looking); the winger collects the
ball with layer 1, dribbles the same way and passes by the tree to left 5 or 6; that receiver
intercepts and shoots. Defenders and goalie are layer 1's interception (the same behaviour
and net), triggered by the ball's distance as in the drill of §5.

**Speeds.** A dribble kick sends the ball :data:`DRIBBLE_UNITS` in :data:`DRIBBLE_PERIODS`
sensor periods, but no faster than half the speed a player comes up to the ball at; that
speed is the one it can stop from, after seeing the ball its sensor latency late, within half
its kick margin (:func:`stop_speed`; it matters on the robots, whose wheels brake slowly
and whose camera lags). Passes are layer 1's launch on the Soccer Server and the robot's top
speed on the robots (:func:`pass_speed`), shots full power.

**Defenders** (option ``defenders``): ``same`` (the default) gives the defenders and goalie
the attackers' layer 1, as the paper's set play does (§7: "the defenders are all equipped with
the same ball-interception skill as the receivers"); a behaviour name gives them that one
whatever the attackers use (``straight``: the baseline's defenders facing layered attackers).
The winger, uncovered, starts its layer 1 on the cue wherever the ball is on the robots; on
the Soccer Server it keeps the drill's trigger distance.

**Kicks.** Where the players have an aimable kick (the Soccer Server), they kick. Where they
do not (the 1997 robots pushed the ball), the coach stands in for the kicker, as layer 1 and
layer 2's drills launch the ball on that field: a ``Kick`` a set-play attacker sends is not
passed to the robot but carried out by the coach, at the first tick within
:data:`ARMED_PERIODS` sensor period of the one it was sent on at which that player is within
kick reach of the ball (a kicker that fires when the ball reaches it; the robot's next
decision comes a camera period later, so a receiver can kick a pass on first time: it sends
the kick as it sees the ball about to come into reach): the ball's velocity gains the kick's
speed (its power times
:attr:`~robotsoccer.drills.intercept.LaunchPlan.launch_speed_mps` / the plan's power, layer
1's launch at full power) along the player's heading plus the kick's direction, as the
server's kick adds to the ball's velocity. The kick reach there is touching plus
:data:`KICK_MARGIN_UNITS` (the server's ``kickable_margin``, 1 unit). Defenders keep the
field's own behaviour (robots without a kicker block).

**The coach.** At every tick the player nearest the ball, if within kick reach, holds it. The
play's passes are completed in order (:data:`STAGES`): the first when a first receiver (left 2
or 3) holds the ball, the second when the winger then holds it, the third when a last receiver
(left 5 or 6) then holds it; other attackers touching the ball count no pass. The play ends:

* GOAL: the left team scores;
* SHOT: a shot was kicked and did not score (the goalie or a defender took it, it went out,
  or it stopped);
* INTERCEPTED: a defender held the ball before any shot;
* OUT: the ball left the field before any shot;
* TIMEOUT: :attr:`SetPlayDrill.max_time_s` ran out (by default :data:`TIME_LIMIT_ARRIVALS`
  times layer 1's arrival time on the field).

**Measures** per play: ``passes`` completed (0–3), ``shot`` and ``goal`` (0 or 1), and the
first pass's receiver (0 without a pass).
"""

from __future__ import annotations

import dataclasses
import math

from field_models.arena import Arena, FieldFacts
from field_models.protocol import LEFT, RIGHT, Action, Crossing, Kick, Mind, Percept, PlayerRef
from field_models.seeding import TrialRngs
from robotsoccer.drills.base import GoalWatch, Verdict
from robotsoccer.drills.intercept_plan import LaunchPlan
from robotsoccer.drills.passing import (
    STOPPED_SPEED_PER_LENGTH,
    LayeredDrill,
    load_evaluator,
)
from robotsoccer.options import choice, duration, flag
from robotsoccer.skills.intercept import (
    Behaviour,
    check_behaviour,
)
from robotsoccer.skills.lead import velocity_window
from robotsoccer.skills.passing import Chooser, PasserMind, ReceiverMind
from robotsoccer.skills.setplay import BallSense, CarrierMind, KickPowers, SetPlayReceiverMind

STARTER = PlayerRef(LEFT, 1)
FIRST_RECEIVERS = (PlayerRef(LEFT, 2), PlayerRef(LEFT, 3))
WINGER = PlayerRef(LEFT, 4)
LAST_RECEIVERS = (PlayerRef(LEFT, 5), PlayerRef(LEFT, 6))
DEFENDERS = tuple(PlayerRef(RIGHT, n) for n in range(1, 8))
GOALIE = DEFENDERS[-1]
SPOTS: dict[PlayerRef, tuple[float, float]] = {
    STARTER: (-5.0, 0.0),
    FIRST_RECEIVERS[0]: (22.0, 11.0),
    FIRST_RECEIVERS[1]: (22.0, -11.0),
    WINGER: (32.0, 25.0),
    LAST_RECEIVERS[0]: (43.0, 15.0),
    LAST_RECEIVERS[1]: (41.0, 3.0),
    DEFENDERS[0]: (29.0, 0.0),
    DEFENDERS[1]: (27.0, 6.0),
    DEFENDERS[2]: (27.0, -6.0),
    DEFENDERS[3]: (46.0, 11.0),
    DEFENDERS[4]: (47.0, 18.0),
    DEFENDERS[5]: (45.0, -1.0),
    GOALIE: (50.5, 0.0),
}
"""Where each player stands before its jitter [units] (module docstring; ours)."""
ROBOT_SPOTS: dict[PlayerRef, tuple[float, float]] = {**SPOTS, WINGER: (26.0, 25.0)}
"""The robots' spots: the winger stands level with the first receivers (module docstring)."""
PLAYERS = tuple(SPOTS)
STAGES = (FIRST_RECEIVERS, (WINGER,), LAST_RECEIVERS)
"""Who completes the play's first, second and third pass."""
JITTER_UNITS = 2.0
BALL_AHEAD_UNITS = 1.0
"""The ball starts this far beyond the starter's touching distance, toward +x."""
BLOCKED_UNITS = 22.0
"""An opponent this close in the path ends a dribble (the paper's "predetermined distance");
more than layer 1's trigger distance (14 units), so the one in the path does not start for the
ball while the carrier asks."""
DRIBBLE_UNITS = 4.0
DRIBBLE_PERIODS = 8.0
"""A dribble kick sends the ball this far in this many sensor periods (2 s on the server)."""
KICK_MARGIN_UNITS = 1.0
"""Kick reach beyond touching where the coach kicks for the players (the server's margin)."""
ARMED_PERIODS = 1
"""A coach's kick stays armed this many sensor periods (to the player's next decision)."""
TIME_LIMIT_ARRIVALS = 40.0
RECALL_PERIODS = 2
"""A ball the sensor misses is taken to be where it was last seen for this many periods."""
SAFE_REACH_SHARE = 0.85
"""The players kick when the ball seems within this share of their kick margin beyond
touching (sensor noise)."""


class SetPlayDrill(LayeredDrill):
    """Figure 15's set play (module docstring).

    Args:
        chooser: How the passers pick (``tree``, ``random``, ``closest``, ``analytic``).
        model: The pass tree file for ``tree``.
        interceptor: Layer 1's behaviour for receivers, winger and defenders.
        net: The interception net for ``net``.
        max_time_s: The play's time limit [s]; None: 40 arrival times of layer 1's drill.
        transfer: Accept a tree or net trained on another field model or preset.
        pass_speed_mps: The passes' speed [m/s]; None: the field's (:func:`kick_powers`).
        defenders: The defenders' and goalie's interception: ``same`` as the attackers'
            `interceptor` (the paper's set play, §7: "the defenders are all equipped with the
            same ball-interception skill as the receivers"), or a behaviour of their own
            (``straight``: the field's baseline defenders, whatever the attackers use).

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
        pass_speed_mps: float | str | None = None,
        defenders: Behaviour | str = "same",
    ) -> None:
        self.chooser = choice(Chooser, chooser, "chooser")
        if self.chooser in (Chooser.TREE, Chooser.BOOST) and not model:
            raise ValueError(
                f"chooser {self.chooser.value!r} needs a model file (option model=...)"
            )
        self.model = model
        self.interceptor = check_behaviour(interceptor, net)
        self.net = net
        if max_time_s is not None:
            max_time_s = duration("max_time_s", max_time_s)
        self._max_time_s = max_time_s
        self.max_time_s = max_time_s or 60.0
        self.transfer = flag("transfer", transfer)
        self.pass_speed_mps = None if pass_speed_mps is None else float(pass_speed_mps)
        self.defenders = defenders if defenders == "same" else check_behaviour(defenders, net)
        self._judge: _SetPlayJudge | None = None
        self._checked: FieldFacts | None = None

    def players(self) -> tuple[PlayerRef, ...]:
        """Six attackers and seven defenders (the goalie last)."""
        return PLAYERS

    def setup(self, arena: Arena, rngs: TrialRngs) -> None:
        """Place the ball and the players (module docstring)."""
        facts = arena.facts
        self._check_origins(facts)
        plan = self.plan(facts)
        if self._max_time_s is None:
            self.max_time_s = TIME_LIMIT_ARRIVALS * plan.arrival_time_s
        unit = facts.unit_m
        pitch = facts.pitch
        rng = rngs["placement"]
        x_lim = pitch.half_length_m - 2.0 * pitch.player_radius_m
        y_lim = pitch.half_width_m - 2.0 * pitch.player_radius_m
        spots: dict[PlayerRef, tuple[float, float]] = {}
        spots_units = SPOTS if coach_kicks(facts, plan) is None else ROBOT_SPOTS
        for ref, (sx, sy) in spots_units.items():
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
        self._judge = _SetPlayJudge(arena, (bx, sy), coach_kicks(facts, plan))

    def minds(self, arena: Arena, rngs: TrialRngs) -> dict[PlayerRef, Mind]:
        """Every player's mind (module docstring)."""
        facts = arena.facts
        plan = self.plan(facts)
        rng = rngs["policy"]
        tree = load_evaluator(self.model)[0] if self.model else None
        sense = ball_sense(facts, plan)
        powers = kick_powers(facts, plan, self.pass_speed_mps)

        def interceptor(kickable: float | None = None) -> Mind:
            return self.interceptor_for(facts, plan, rng, self.interceptor, kickable)

        def passer(receivers: tuple[PlayerRef, ...]) -> PasserMind:
            return PasserMind(
                [r.number for r in receivers],
                self.chooser,
                rng,
                unit_m=facts.unit_m,
                sensor_period_s=facts.sensor_period_s,
                dt_s=facts.dt_s,
                kick_power=None,  # the carrier kicks the pass itself (skills module docstring)
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

        def carrier(receivers: tuple[PlayerRef, ...], collect: Mind | None) -> CarrierMind:
            return CarrierMind(
                passer(receivers),
                collect,
                sense=sense,
                attack_right=True,
                blocked_distance_m=blocked,
                powers=powers,
                calls_after=() if collect is None else tuple(r.number for r in FIRST_RECEIVERS),
            )

        def kicker(ref: PlayerRef, slot: int, to: int | None) -> SetPlayReceiverMind:
            return SetPlayReceiverMind(
                receiver(ref, slot),
                to,
                sense=sense,
                attack_right=True,
                powers=powers,
                armed=to is not None,
                goal_half_width_m=0.5 * facts.pitch.goal_width_m,
            )

        # The winger collects a kick on that may pass it anywhere (§7: "since the winger is not
        # covered, it can easily collect the ball"): its layer 1 starts at once on the cue,
        # wherever the ball is, rather than waiting for it within the drill's trigger distance.
        # On the Soccer Server (no camera) it keeps the drill's trigger, as before.
        collect = interceptor()
        if sense.track_window > 0:
            reach_all = facts.pitch.length_m
            anywhere = dataclasses.replace(
                plan, trigger_distance_m=reach_all, max_distance_m=reach_all
            )
            collect = self.interceptor_for(facts, anywhere, rng, self.interceptor)
        minds: dict[PlayerRef, Mind] = {
            STARTER: carrier(FIRST_RECEIVERS, None),
            WINGER: carrier(LAST_RECEIVERS, collect),
        }
        for slot, ref in enumerate(FIRST_RECEIVERS):
            minds[ref] = kicker(ref, slot, WINGER.number)
        for slot, ref in enumerate(LAST_RECEIVERS):
            minds[ref] = kicker(ref, slot, None)
        kickable = facts.kick.reach_m if facts.kick is not None else None
        defence = self.interceptor if self.defenders == "same" else Behaviour(self.defenders)
        for ref in DEFENDERS:
            minds[ref] = self.interceptor_for(facts, plan, rng, defence, kickable)
        assert self._judge is not None
        self._judge.minds = dict(minds)
        if self._judge.kicks is not None:
            for ref in (STARTER, WINGER, *FIRST_RECEIVERS, *LAST_RECEIVERS):
                minds[ref] = _CoachKickRelay(minds[ref], ref, self._judge.kicks)
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


def stop_speed(facts: FieldFacts, distance_m: float) -> float:
    """The speed [m/s] a player can stop from within half of `distance_m`.

    It sees the ball the sensor latency late and then brakes at its acceleration a: the
    speed v with v·latency + v²/(2a) = distance / 2.
    """
    a, lag = facts.player_accel_mps2, facts.sensor_latency_s or 0.0
    return a * (math.sqrt(lag * lag + distance_m / a) - lag)


def kick_powers(
    facts: FieldFacts, plan: LaunchPlan, pass_speed_mps: float | None = None
) -> KickPowers:
    """Dribble, pass and shot powers: full power for shots; passes at `pass_speed_mps`.

    Passes default to layer 1's launch where the players have an aimable kick (the Soccer
    Server) and to :func:`pass_speed` where the coach kicks for them (the robots).

    Raises:
        ValueError: No kick sends the ball :data:`DRIBBLE_UNITS` in the dribble's time, or
            the pass speed is beyond the top kick.
    """
    sense = ball_sense(facts, plan)
    time_s = DRIBBLE_PERIODS * facts.sensor_period_s
    speed = facts.ball.speed_to_cover(DRIBBLE_UNITS * facts.unit_m, time_s)
    if speed is None or speed > sense.speed(sense.max_power):
        raise ValueError(f"{facts.preset}: no kick sends the ball {DRIBBLE_UNITS:g} units")
    # A carrier must catch up with its ball at its last approach speed, from which it can stop
    # beside it (the robots' slow wheels): half that speed at most.
    speed = min(speed, 0.5 * stop_speed(facts, sense.reach_m - sense.touch_m))
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
    return KickPowers(
        dribble=speed / sense.speed_per_power_mps, passing=passing, shot=sense.max_power
    )


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


class _CoachKickRelay:
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


class _SetPlayJudge:
    """The coach's rule for one play (module docstring)."""

    def __init__(self, arena: Arena, ball: tuple[float, float], kicks: CoachKicks | None) -> None:
        facts = arena.facts
        pitch = facts.pitch
        self.reach = kick_reach(facts)
        self.reach2 = self.reach * self.reach
        self.half_length = pitch.half_length_m
        self.half_width = pitch.half_width_m
        self.eps2 = (STOPPED_SPEED_PER_LENGTH * pitch.length_m) ** 2
        self.goals = GoalWatch(arena, ball)
        self.kicks = kicks
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
        if self.kicks is not None and self.kicks.pending:
            self.kicks.apply(arena, self.reach)
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
            if self.passes < len(STAGES) and taken in STAGES[self.passes]:
                self.passes += 1  # the play's next pass (module docstring)
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
        """The player nearest the ball among those within kick reach, or None."""
        best, best_d2 = None, self.reach2
        for ref in PLAYERS:
            p = arena.player_state(ref)
            d2 = (p.x - x) ** 2 + (p.y - y) ** 2
            if d2 <= best_d2:
                best, best_d2 = ref, d2
        return best
