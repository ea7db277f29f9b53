"""Layer 3 on the field: TPOT-RL's ball destinations, their features from layer 2, the rewards.

A :class:`TpotBallPolicy` is the optional ``ball_policy`` of a team's
:class:`~robotsoccer.skills.team.TeamMind`: one object per team, one table of Q-values with a
row per formation position (:mod:`learning.tpot`). The mind asks it where the layered team
would ask layer 2's tree (on the ball, an opponent in the path, or the goalie); everything else
is the layered team's play.

**Destinations** (:data:`DESTINATIONS`): 8 fixed points of the field, in the team's attack
frame, as shares of the half-length and half-width. TPOT-RL's destinations are places, not
teammates (Stone & Veloso 1999, Figure 1a): the opponents' goal, its two corners and two flank
points ahead, the centre of the opponents' half, and the two touchlines at midfield. All lie
level or ahead, as a pass forward or square is what a blocked player has; the flank points
sit inside the touchlines so a kick toward them does not aim the ball out.

**Features e(s, a)**: for destination ``a``, the teammates the player sees within
:data:`SECTOR_RAD` of its direction and within the layered team's pass distances are the
passes toward it. The tree's success confidence of the best of them (asked as the layered team
asks: the passer's half, the receiver's unknown or, with the match option ``receiver_half``,
estimated) gives SUCCESS when at least the layered team's pass threshold, FAILURE below it;
no such teammate gives MISS (the kick reaches no one, §6's third label).

**The kick**: toward the teammate judged when there is one (the pass the tree rated), else
toward the destination point, at the pass power.

**When it is asked** (``every_ball``). False (the first study's rule): only where the layered
team would ask the tree (blocked, or the goalie), so it decides a few times a game. True (Stone
& Veloso 1999's own rule: the player with the ball always chooses among the destinations): on
every spell on the ball, shooting range or not, so layer 3 owns the whole ball-holder decision.
Two destinations then change meaning so that the choice covers what the layered team does:

* the opponents' goal (action 0) is *shoot*: a kick at the shot power toward the goal's centre;
  its feature is SUCCESS within the team's shooting range with no opponent in the path
  (:func:`~robotsoccer.skills.setplay.opponent_in_path` within the blocked distance), FAILURE
  within range but blocked, MISS out of range (the shot reaches no one);
* a destination with no teammate toward it (MISS) is *keep*: a dribble toward that point at the
  dribble power, the player keeping the ball (the layered team's dribble is the dribble toward
  the goal, or the centre ahead).

**The shot-range guard** (``shot_guard``, with ``every_ball``): the goal destination is a shot
only where the layered team would shoot, by the teams' one rule
(:func:`~robotsoccer.skills.team_setup.in_shooting_range` on
:func:`~robotsoccer.skills.team_setup.goal_direction`: the goal's flag, else the pose, within
the team's shooting range); beyond it the destination means *advance toward the goal*, as the
hand-written team does out of range: a pass to the teammate the tree rates best within
:data:`SECTOR_RAD` of the goal's direction (SUCCESS or FAILURE), else a dribble toward the goal
(MISS, *keep*). Without it a choice of the goal from anywhere was a shot at the shot power
(the first every-ball studies: 84% of their goal choices were such long shots). The corners
and the other destinations are passes or keeps with or without the guard.

The SUCCESS cut (``threshold``) is then a study setting: with the layered team's 0.5 the tree
rated every pass it was asked about at least 0.5 (FAILURE never occurred, |U| = 2 in effect);
the study sets it where FAILURE does occur (:mod:`robotsoccer.experiments.team_study`).

**Rewards** (:func:`learning.tpot.reward`): after each action the player samples the ball's
x in the attack frame from its own sightings (its pose plus the ball's relative position).
The reward is fixed by a goal (the referee's call, which rcssserver sends to every client as a
``hear`` message; here the match drill relays it: :meth:`TpotBallPolicy.goal`), by
:data:`learning.tpot.HORIZON_S` passing, or by the end of the game
(:meth:`TpotBallPolicy.finish`); and, by the ``window`` option:

* :data:`~learning.tpot.WINDOW_CHOICE` (the first studies' rule): also by the player's next
  layer-3 action, so each player has at most one open reward;
* :data:`~learning.tpot.WINDOW_HORIZON` (Stone & Veloso 1999's fixed window after the action):
  not by the player's next action (its earlier actions stay open, each with its own window), but
  by play stopping (the referee's call of a restart: :meth:`TpotBallPolicy.stopped`), as the
  ball's place after a restart says nothing about the kick before it.

**Possession** (``loss_penalty`` > 0; 0 is the ball's advance alone, the earlier studies'):
the opponents' gaining the ball also closes a window: the match drill relays each new touch of
the ball by an opponent (the coach's possession rule, the one its possession share counts:
the player nearest the ball within control reach touched it; :meth:`TpotBallPolicy.lost`),
and the reward is then the ball's advance over the player's sightings up to that moment, less
:func:`learning.tpot.loss_penalty`, ``loss_penalty * (1 - t / HORIZON_S)`` for a loss t after
the action, clipped to ``[-1, +1]``. So a kick pays for the ground the team gains *while it keeps
the ball*, and a kick the opponents pick up at once costs up to ``loss_penalty`` (TPOT-RL's
reward is the team's over the window after the action; this adds the team's possession to it).
A goal within the window still fixes the reward alone.

While learning, each fixed reward becomes an :class:`~learning.tpot.Experience`; the table
itself changes only between games (the training runner applies the games' experiences in a
fixed order: results do not depend on how many workers played them).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from field_models.protocol import Action, Kick, Percept, SeenPlayer, wrap_angle
from learning.tpot import (
    FAILURE,
    HORIZON_S,
    MISS,
    N_ACTIONS,
    Q_MAX,
    REWARD_WINDOWS,
    SUCCESS,
    WINDOW_CHOICE,
    Experience,
    TpotTable,
    UniformSource,
    choose,
    loss_penalty,
    reward,
)
from robotsoccer.skills.localise import Pose
from robotsoccer.skills.passing import PassEvaluator, open_play_attributes
from robotsoccer.skills.setplay import opponent_in_path
from robotsoccer.skills.team_setup import TeamSetup, goal_direction, in_shooting_range

DESTINATIONS: tuple[tuple[str, float, float], ...] = (
    ("goal", 1.0, 0.0),
    ("corner left", 0.85, 0.75),
    ("corner right", 0.85, -0.75),
    ("flank left", 0.45, 0.8),
    ("flank right", 0.45, -0.8),
    ("centre ahead", 0.5, 0.0),
    ("midfield left", 0.0, 0.8),
    ("midfield right", 0.0, -0.8),
)
"""(name, x share of the half-length, y share of the half-width), attack frame (+x ahead, +y
to the left when attacking +x); module docstring."""
SECTOR_RAD = math.radians(20.0)
"""A teammate within this of a destination's direction is a pass toward it."""
MIN_PASS_UNITS = 6.0
"""Teammates nearer than this are not passes (the layered team's rule, ``team.py``)."""

SHOOT_ACTION = 0
"""The opponents' goal: with ``every_ball``, the shot (module docstring)."""

assert len(DESTINATIONS) == N_ACTIONS


def destination_xy(
    action: int, attack_right: bool, half_length_m: float, half_width_m: float
) -> tuple[float, float]:
    """Destination `action` in the field frame [m] for a team attacking +x or -x."""
    _, sx, sy = DESTINATIONS[action]
    sign = 1.0 if attack_right else -1.0
    return (sign * sx * half_length_m, sign * sy * half_width_m)


@dataclass(frozen=True, slots=True)
class Options:
    """What one destination offers: its feature and where the kick goes.

    Attributes:
        features: e(s, a) per destination.
        directions: Kick direction per destination, relative to the body [rad].
        shot: The goal destination is a shot now (``every_ball``, and in range under the
            shot-range guard).
    """

    features: tuple[int, ...]
    directions: tuple[float, ...]
    shot: bool = False


@dataclass(slots=True)
class _Pending:
    """An action whose reward is not fixed yet."""

    number: int
    feature: int
    action: int
    tick: int
    x0: float
    samples: list[float] = field(default_factory=list)


@dataclass(frozen=True, slots=True)
class TpotSettings:
    """How one team's layer 3 plays and learns: the study's settings (module docstring).

    Attributes:
        threshold: The tree's least success confidence for SUCCESS, in [0, 1].
        epsilon: Exploration rate (0: greedy, in play).
        learn: Record experiences (training games).
        every_ball: Decide on every spell on the ball, shoot and keep included (module
            docstring); False: only where the layered team would ask the tree.
        window: When a reward closes (module docstring): ``choice`` or ``horizon``.
        shot_guard: The goal destination is a shot only within the shooting range, else an
            advance toward the goal (``every_ball``; module docstring).
        loss_penalty: What the opponents' gaining the ball costs at once, >= 0 (0: the
            ball's advance alone; module docstring, "Possession").

    Raises:
        ValueError: An unknown window; a loss penalty outside [0, Q_MAX]; the guard without
            ``every_ball``.
    """

    threshold: float = 0.5
    epsilon: float = 0.0
    learn: bool = False
    every_ball: bool = False
    window: str = WINDOW_CHOICE
    shot_guard: bool = False
    loss_penalty: float = 0.0

    def __post_init__(self) -> None:
        loss = self.loss_penalty
        if not 0.0 <= loss <= Q_MAX:
            raise ValueError(f"loss_penalty must be in [0, {Q_MAX:g}], got {loss}")
        if self.shot_guard and not self.every_ball:
            raise ValueError("the shot-range guard needs every_ball (the goal is a shot only then)")
        if self.window not in REWARD_WINDOWS:
            known = ", ".join(REWARD_WINDOWS)
            raise ValueError(f"window must be one of {known}, got {self.window!r}")


class TpotBallPolicy:
    """One team's layer 3 (module docstring).

    Args:
        table: The Q-values (a row per uniform number).
        setup: The team's plan on this field: its attack direction, the pitch, its pass range
            and kick powers, its shooting range and blocked distance (``every_ball``), the
            tick.
        evaluator: Layer 2's tree.
        rng: The exploration's stream.
        settings: How it plays and learns (:class:`TpotSettings`; default: greedy, the
            first study's rules).

    Raises:
        ValueError: A table whose actions are not the :data:`DESTINATIONS`.

    Attributes:
        experiences: The fixed rewards, in the order fixed (when learning).
        choices: Actions taken per destination index.
    """

    def __init__(
        self,
        table: TpotTable,
        setup: TeamSetup,
        evaluator: PassEvaluator,
        rng: UniformSource,
        settings: TpotSettings = TpotSettings(),
    ) -> None:
        if table.actions != N_ACTIONS:
            raise ValueError(
                f"a table of {table.actions} actions, not the field's {N_ACTIONS} destinations"
            )
        self.table = table
        self.evaluator = evaluator
        self.rng = rng
        self.settings = settings
        # The plan's numbers and the settings the decisions read, by the module docstring's names.
        self.attack_right = setup.attack_right
        self.half_length_m, self.half_width_m = setup.half_length_m, setup.half_width_m
        self.unit_m, self.dt_s = setup.unit_m, setup.dt_s
        self.receiver_half = setup.receiver_half
        self.pass_range_m, self.pass_power = setup.pass_range_m, setup.powers.passing
        self.shoot_range_m, self.blocked_m = setup.shoot_range_m, setup.blocked_m
        self.shot_power, self.dribble_power = setup.powers.shot, setup.powers.dribble
        self.threshold, self.epsilon, self.learn = (
            settings.threshold,
            settings.epsilon,
            settings.learn,
        )
        self.every_ball, self.window = settings.every_ball, settings.window
        self.shot_guard, self.loss_penalty = settings.shot_guard, settings.loss_penalty
        self.experiences: list[Experience] = []
        self.choices = [0] * N_ACTIONS
        # Open rewards per player, oldest first (more than one only with the horizon window).
        self._pending: dict[int, list[_Pending]] = {}

    # ------------------------------------------------------------------ deciding

    def options(self, percept: Percept, pose: Pose) -> Options:
        """e(s, a) and the kick direction of every destination (module docstring)."""
        own = percept.player.team
        mates = [
            (i, s)
            for i, s in enumerate(percept.players)
            if s.team == own and MIN_PASS_UNITS * self.unit_m <= s.distance_m <= self.pass_range_m
        ]
        scores = {i: self._confidence(percept, i, s) for i, s in mates}
        features: list[int] = []
        directions: list[float] = []
        shot = self.every_ball
        for action in range(N_ACTIONS):
            dx, dy = destination_xy(
                action, self.attack_right, self.half_length_m, self.half_width_m
            )
            bearing = wrap_angle(math.atan2(dy - pose.y, dx - pose.x) - pose.heading)
            if self.every_ball and action == SHOOT_ACTION and self.shot_guard:
                goal = goal_direction(percept, pose, self.attack_right, (dx, dy))
                shot = goal is not None and in_shooting_range(goal, self.shoot_range_m)
                if goal is not None and shot:
                    blocked = opponent_in_path(percept, goal[1], self.blocked_m)
                    features.append(FAILURE if blocked else SUCCESS)
                    directions.append(goal[1])
                    continue
                # Out of range: an advance toward the goal, a pass or keep as below.
            elif self.every_ball and action == SHOOT_ACTION:
                features.append(self._shot_feature(percept, pose, dx, dy, bearing))
                directions.append(bearing)
                continue
            near = [
                (scores[i], s)
                for i, s in mates
                if abs(wrap_angle(s.angle_rad - bearing)) <= SECTOR_RAD
            ]
            if not near:
                features.append(MISS)
                directions.append(bearing)
                continue
            confidence, seen = max(near, key=lambda c: c[0])
            features.append(SUCCESS if confidence >= self.threshold else FAILURE)
            directions.append(seen.angle_rad)
        return Options(tuple(features), tuple(directions), shot)

    def _shot_feature(
        self, percept: Percept, pose: Pose, gx: float, gy: float, bearing: float
    ) -> int:
        """The shot's e(s, a): SUCCESS in range and open, FAILURE blocked, MISS out of range."""
        if math.hypot(gx - pose.x, gy - pose.y) > self.shoot_range_m:
            return MISS
        return FAILURE if opponent_in_path(percept, bearing, self.blocked_m) else SUCCESS

    def kick(self, action: int, options: Options) -> tuple[str, Kick]:
        """(intent, kick) of destination `action` (module docstring: shoot, pass, keep)."""
        name = DESTINATIONS[action][0]
        direction = options.directions[action]
        if action == SHOOT_ACTION and options.shot:
            return ("tpot shoot", Kick(self.shot_power, direction))
        if self.every_ball and options.features[action] == MISS:
            return (f"tpot keep {name}", Kick(self.dribble_power, direction))
        return (f"tpot {name}", Kick(self.pass_power, direction))

    def _confidence(self, percept: Percept, index: int, seen: SeenPlayer) -> float:
        """The tree's success confidence of a pass to `seen`, asked as the layered team asks."""
        x = open_play_attributes(percept, index, self.unit_m, self.receiver_half)
        return self.evaluator.success_confidence(x)

    def decide(
        self, number: int, percept: Percept, pose: Pose | None, ball_xy: tuple[float, float] | None
    ) -> tuple[str, tuple[Action, ...]] | None:
        """(intent, actions) of the kick toward the chosen destination; None without a pose."""
        if pose is None or ball_xy is None:
            return None
        options = self.options(percept, pose)
        action = choose(self.table, number, options.features, self.rng, self.epsilon)
        self.choices[action] += 1
        if self.learn:
            if self.window == WINDOW_CHOICE:
                self._fix(number, percept.tick)
            self._pending.setdefault(number, []).append(
                _Pending(
                    number, options.features[action], action, percept.tick, self._along(ball_xy)
                )
            )
        intent, kick = self.kick(action, options)
        return (intent, (kick,))

    # ------------------------------------------------------------------ rewards

    def observe(self, number: int, tick: int, ball_xy: tuple[float, float] | None) -> None:
        """A sighting of the ball by player `number` (None: not seen): a reward sample."""
        open_ = self._pending.get(number)
        if not open_:
            return
        along = None if ball_xy is None else self._along(ball_xy)
        keep: list[_Pending] = []
        for pending in open_:
            if (tick - pending.tick) * self.dt_s >= HORIZON_S:
                self._record(pending, 0, (tick - pending.tick) * self.dt_s)
                continue
            if along is not None:
                pending.samples.append(along)
            keep.append(pending)
        if keep:
            self._pending[number] = keep
        else:
            del self._pending[number]

    def goal(self, scored: bool, tick: int) -> None:
        """The referee's call: this team scored (True) or conceded; fixes every pending reward."""
        for number in sorted(self._pending):
            for pending in self._pending.pop(number):
                after = (tick - pending.tick) * self.dt_s
                self._record(pending, 1 if scored else -1, after)

    def lost(self, tick: int) -> None:
        """An opponent touched the ball at `tick` (the coach's possession rule).

        With a loss penalty this fixes every pending reward as lost (module docstring,
        "Possession"); without one it changes nothing.
        """
        if self.loss_penalty <= 0.0:
            return
        for number in sorted(self._pending):
            for pending in self._pending.pop(number):
                self._record(pending, 0, (tick - pending.tick) * self.dt_s, lost=True)

    def stopped(self, tick: int) -> None:
        """The referee stopped play (a restart); closes every reward with the horizon window.

        With the ``choice`` window a stop closes nothing (the first studies' rule, kept so their
        tables are reproduced).
        """
        if self.window != WINDOW_CHOICE:
            self.finish(tick)

    def finish(self, tick: int) -> None:
        """The game is over: fix every pending reward from what was seen."""
        for number in sorted(self._pending):
            self._fix(number, tick)

    def _fix(self, number: int, tick: int) -> None:
        for pending in self._pending.pop(number, []):
            self._record(pending, 0, (tick - pending.tick) * self.dt_s)

    def _record(self, pending: _Pending, goal: int, after_s: float, lost: bool = False) -> None:
        r = reward(
            pending.x0,
            pending.samples,
            goal=goal if after_s <= HORIZON_S else 0,
            goal_after_s=after_s,
            own_goal_x=-self.half_length_m,
            opponent_goal_x=self.half_length_m,
        )
        if lost:
            r = max(-Q_MAX, r - loss_penalty(self.loss_penalty, after_s))
        self.experiences.append(Experience(pending.number, pending.feature, pending.action, r))

    def _along(self, xy: tuple[float, float]) -> float:
        """A field-frame point's x in the attack frame [m]."""
        return xy[0] if self.attack_right else -xy[0]
