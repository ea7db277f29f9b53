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

**Speeds.** A dribble kick sends the ball
:data:`~robotsoccer.skills.motion.DRIBBLE_UNITS` in
:data:`~robotsoccer.skills.motion.DRIBBLE_PERIODS` sensor periods, but no faster than
half the speed a player comes up to the ball at; that speed is the one it can stop from, after
seeing the ball its sensor latency late, within half its kick margin
(:func:`~robotsoccer.skills.motion.stop_speed`; it matters on the robots, whose wheels
brake slowly and whose camera lags): the matches' dribble rule too
(:func:`~robotsoccer.skills.motion.dribble_power`). Passes are layer 1's launch on the Soccer
Server and the robot's top speed on the robots
(:func:`~robotsoccer.drills.setplay_kicks.pass_speed`), shots full power.

**Defenders** (option ``defenders``): ``same`` (the default) gives the defenders and goalie
the attackers' layer 1, as the paper's set play does (§7: "the defenders are all equipped with
the same ball-interception skill as the receivers"); a behaviour name gives them that one
whatever the attackers use (``straight``: the baseline's defenders facing layered attackers).
The winger, uncovered, starts its layer 1 on the cue wherever the ball is on the robots; on
the Soccer Server it keeps the drill's trigger distance.

**Client** (option ``client``, issue 28 item 3): ``see`` (the default, the paper's client: one
decision per see, "turn, then dash") or ``cycle``, the Soccer Server's per-cycle client: the
defenders and goalie are layer 1's per-cycle defender (:class:`~robotsoccer.skills.cycle.
CycleDefenderMind`, the same TA rule, built as the interception drill's ``client=cycle``
builds it) and the attackers' decisions are carried on every cycle from a world model
(:mod:`robotsoccer.skills.setplay_cycle`), their layer 1 that defender's plan. It is refused on
the robots, whose host already acts on every tick, and with a lead net (the per-cycle client
plays the turn decision).

**Looking** (option ``look``, issue 28 item 3): ``body`` (the default, the paper's client: the
head is the body, a player turns its body to look) or ``neck``: every attacker, on either
client, reads its percepts with their directions from the body, points its head at the ball
(scanning with a wide view while it has none) and waits without turning its body to keep the
ball in view; a first receiver reports once its head faces the ball; a last receiver looks for
the goal with its head (:mod:`robotsoccer.skills.setplay_look`). Defenders and goalie keep
layer 1's drill minds. The robots have no neck (their camera sees all round, and their host
ignores neck and view actions, as in a match): there ``look=neck`` is accepted and the
attackers play as with ``body``.

**Kicks.** Where the players have an aimable kick (the Soccer Server), they kick. Where they do
not (the 1997 robots pushed the ball), the coach stands in for the kicker, as layer 1 and layer
2's drills launch the ball on that field: a ``Kick`` a set-play attacker sends is not passed to
the robot but carried out by the coach, at the first tick within
:data:`~robotsoccer.drills.setplay_kicks.ARMED_PERIODS` sensor period of the one it was sent on
at which that player is within kick reach of the ball (a kicker that fires when the ball reaches
it; the robot's next decision comes a camera period later, so a receiver can kick a pass on
first time: it sends the kick as it sees the ball about to come into reach): the ball's velocity
gains the kick's speed (its power times
:attr:`~robotsoccer.drills.intercept_plan.LaunchPlan.launch_speed_mps` / the plan's power, layer 1's
launch at full power) along the player's heading plus the kick's direction, as the server's kick
adds to the ball's velocity. The kick reach there is touching plus
:data:`~robotsoccer.drills.setplay_kicks.KICK_MARGIN_UNITS` (the server's ``kickable_margin``, 1
unit). Defenders keep the field's own behaviour (robots without a kicker block).

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

This module is the drill (set-up, minds, labels); the field's kick numbers and the coach's
kicks are :mod:`robotsoccer.drills.setplay_kicks`, the coach's verdict
:mod:`robotsoccer.drills.setplay_judge`.
"""

from __future__ import annotations

import dataclasses
import math
from typing import Any

from field_models.arena import Arena, FieldFacts
from field_models.protocol import LEFT, RIGHT, Mind, PlayerRef
from field_models.seeding import TrialRngs
from robotsoccer.drills.base import Verdict
from robotsoccer.drills.intercept_options import ClientKind
from robotsoccer.drills.layered import CYCLE_ON_ROBOTS, LayeredDrill, load_evaluator
from robotsoccer.drills.layered_options import SetPlayOptions
from robotsoccer.drills.setplay_judge import SetPlayJudge
from robotsoccer.drills.setplay_kicks import CoachKickRelay, ball_sense, coach_kicks, kick_powers
from robotsoccer.skills.cycle import CycleDefenderMind
from robotsoccer.skills.intercept import Behaviour
from robotsoccer.skills.pass_receivers import ReceiverMind
from robotsoccer.skills.passing import PasserMind
from robotsoccer.skills.setplay_carrier import CarrierMind
from robotsoccer.skills.setplay_cycle import CycleAttacker, CycleIntercept
from robotsoccer.skills.setplay_look import NeckAttacker
from robotsoccer.skills.setplay_receiver import SetPlayReceiverMind
from robotsoccer.skills.team_look import NeckLook

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
TIME_LIMIT_ARRIVALS = 40.0


class SetPlayDrill(LayeredDrill):
    """Figure 15's set play (module docstring).

    Built from a :class:`~robotsoccer.drills.layered_options.SetPlayOptions` record, or from
    its fields as keywords (the registry's ``make_drill`` and a command line's ``--option
    NAME=VALUE`` give them so); :data:`OPTIONS` names the record, whose fields are the drill's
    option names.

    Args:
        options: The drill's options; None: built from `keywords`.
        **keywords: The options' fields by name, where `options` is not given.

    Raises:
        ValueError: A bad option (:class:`~robotsoccer.drills.layered_options.SetPlayOptions`),
            or both a record and keywords.
    """

    name: str = "setplay"
    labels: tuple[str, ...] = ("GOAL", "SHOT", "INTERCEPTED", "OUT", "TIMEOUT")
    OPTIONS = SetPlayOptions

    def __init__(self, options: SetPlayOptions | None = None, /, **keywords: Any) -> None:
        if options is not None and keywords:
            raise ValueError("give the set play an options record or keywords, not both")
        self.options = o = options if options is not None else SetPlayOptions(**keywords)
        self.chooser, self.model = o.chooser, o.model
        self.interceptor, self.net = o.interceptor, o.net
        self._max_time_s = o.max_time_s
        self.max_time_s = o.max_time_s or 60.0
        self.transfer = o.transfer
        self.pass_speed_mps = o.pass_speed_mps
        self.defenders = o.defenders
        self.client = o.client
        self.look = o.look
        self._judge: SetPlayJudge | None = None
        self._checked: FieldFacts | None = None

    def players(self) -> tuple[PlayerRef, ...]:
        """Six attackers and seven defenders (the goalie last)."""
        return PLAYERS

    def setup(self, arena: Arena, rngs: TrialRngs) -> None:
        """Place the ball and the players (module docstring)."""
        facts = arena.facts
        if self.client is ClientKind.CYCLE and facts.walled:
            raise ValueError(CYCLE_ON_ROBOTS)
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
        self._judge = SetPlayJudge(
            arena,
            (bx, sy),
            coach_kicks(facts, plan),
            starter=STARTER,
            players=PLAYERS,
            stages=STAGES,
        )

    def minds(self, arena: Arena, rngs: TrialRngs) -> dict[PlayerRef, Mind]:
        """Every player's mind (module docstring)."""
        facts = arena.facts
        plan = self.plan(facts)
        rng = rngs["policy"]
        tree = load_evaluator(self.model)[0] if self.model else None
        sense = ball_sense(facts, plan)
        powers = kick_powers(facts, plan, self.pass_speed_mps)

        per_cycle = self.client is ClientKind.CYCLE
        # The per-cycle client's world models and layer-1 plans, by attacker.
        models: dict[PlayerRef, tuple[CycleDefenderMind, CycleIntercept | None]] = {}
        # Each attacker's head, looking with the neck (none on the robots: module docstring).
        heads: dict[PlayerRef, NeckLook] = {}

        def head(ref: PlayerRef) -> NeckLook | None:
            if self.look != "neck" or facts.walled:
                return None
            return heads.setdefault(ref, NeckLook())

        def interceptor(kickable: float | None = None) -> Mind:
            return self.interceptor_for(facts, plan, rng, self.interceptor, kickable)

        def meeting(ref: PlayerRef) -> Mind:
            """Layer 1 for the attacker `ref` (receiving or collecting a pass)."""
            if not per_cycle:
                return interceptor()
            model = self.cycle_interceptor_for(facts, plan, rng, self.interceptor)
            meet = CycleIntercept(model)
            models[ref] = (model, meet)
            return meet

        def passer(receivers: tuple[PlayerRef, ...]) -> PasserMind:
            return PasserMind(
                [r.number for r in receivers],
                self.chooser,
                rng,
                facts,
                kick_power=None,  # the carrier kicks the pass itself (skills module docstring)
                tree=tree,
            )

        def receiver(ref: PlayerRef, slot: int) -> ReceiverMind:
            return ReceiverMind(
                ref.number,
                meeting(ref),
                unit_m=facts.unit_m,
                sensor_period_s=facts.sensor_period_s,
                dt_s=facts.dt_s,
                slot=slot,
                say_max_chars=facts.say_max_chars,
                head=head(ref),
            )

        blocked = BLOCKED_UNITS * facts.unit_m

        def carrier(
            ref: PlayerRef, receivers: tuple[PlayerRef, ...], collect: Mind | None
        ) -> CarrierMind:
            return CarrierMind(
                passer(receivers),
                collect,
                sense=sense,
                attack_right=True,
                blocked_distance_m=blocked,
                powers=powers,
                calls_after=() if collect is None else tuple(r.number for r in FIRST_RECEIVERS),
                head=head(ref),
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
                head=head(ref),
            )

        # The winger collects a kick on that may pass it anywhere (§7: "since the winger is not
        # covered, it can easily collect the ball"): its layer 1 starts at once on the cue,
        # wherever the ball is, rather than waiting for it within the drill's trigger distance.
        # On the Soccer Server (no camera) it keeps the drill's trigger, as before.
        collect = meeting(WINGER)
        if sense.track_window > 0:
            reach_all = facts.pitch.length_m
            anywhere = dataclasses.replace(
                plan, trigger_distance_m=reach_all, max_distance_m=reach_all
            )
            collect = self.interceptor_for(facts, anywhere, rng, self.interceptor)
        minds: dict[PlayerRef, Mind] = {
            STARTER: carrier(STARTER, FIRST_RECEIVERS, None),
            WINGER: carrier(WINGER, LAST_RECEIVERS, collect),
        }
        for slot, ref in enumerate(FIRST_RECEIVERS):
            minds[ref] = kicker(ref, slot, WINGER.number)
        for slot, ref in enumerate(LAST_RECEIVERS):
            minds[ref] = kicker(ref, slot, None)
        kickable = facts.kick.reach_m if facts.kick is not None else None
        defence = self.interceptor if self.defenders == "same" else Behaviour(self.defenders)
        for ref in DEFENDERS:
            if per_cycle:
                minds[ref] = self.cycle_interceptor_for(facts, plan, rng, defence, kickable)
            else:
                minds[ref] = self.interceptor_for(facts, plan, rng, defence, kickable)
        assert self._judge is not None
        self._judge.minds = dict(minds)
        if per_cycle:
            # The starter never meets a ball with layer 1: its world model has no TA rule.
            models[STARTER] = (CycleDefenderMind(None, facts, plan.trigger_distance_m), None)
            for ref, (model, meet) in models.items():
                attacker = minds[ref]
                assert isinstance(attacker, CarrierMind | SetPlayReceiverMind)
                minds[ref] = CycleAttacker(attacker, model, meet, facts)
        for ref, look in heads.items():
            mind = minds[ref]
            client = mind if isinstance(mind, CycleAttacker) else None
            attacker = mind if client is None else client.mind
            assert isinstance(attacker, CarrierMind | SetPlayReceiverMind)
            minds[ref] = NeckAttacker(attacker, look, client)
        if self._judge.kicks is not None:
            for ref in (STARTER, WINGER, *FIRST_RECEIVERS, *LAST_RECEIVERS):
                minds[ref] = CoachKickRelay(minds[ref], ref, self._judge.kicks)
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
