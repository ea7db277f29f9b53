"""Per-step control environments on either field model: go to the ball, and score.

Where :class:`~robotsoccer.envs.intercept.InterceptEnv` poses one decision per trial, these
give a policy the body every step, as robot-soccer RL users expect (rSoccer's ``VSS-v0``):

* ``robotsoccer/GoToBall-v0`` (:class:`GoToBallEnv`): one player alone with a still ball. It
  must reach the ball and face a target point (module :class:`GoToBallEnv` docstring).
* ``robotsoccer/Score-v0`` (:class:`ScoreEnv`): one learning player in a small-sided match
  (3 v 3 by default, on the robots the ``vss`` preset), everyone else driven by the baseline
  team minds (:mod:`robotsoccer.skills.team`) under the match's referee. The episode ends on a
  goal, on the ball leaving play (the referee's next call: a throw-in, goal kick or corner on
  an open field, a drop ball for a ball stuck on the walled table) or on the time limit.

Both run on every field model (``field_model=...``): the Soccer Server twin takes the same
task in that field's own commands. Actions, observations and reward weights are documented
in :mod:`robotsoccer.envs.control_spaces`.

**One step** is ``frames_per_step`` percepts of the learning player (default one: a camera
frame on the robots, a see on the Soccer Server). The action is sent when the step starts and
held (sent again every command period) until the step ends; the field runs tick by tick, the
other players' minds act on their own percepts, and the coach judges every tick on the truth.
The observation is built from the learner's last percept.

**Options.** ``perfect_perception`` (the sensor without noise, misses or latency) and
``ideal_actuation`` (on the robots: no link latency, loss or rate limit and no watchdog; the
Soccer Server's commands already act in the next cycle, unlost) switch the imperfections off;
``privileged`` adds the true state to the observation; ``max_time_s`` the time limit (a
truncation); ``reward_weights`` replaces any of the task's weights (an unknown term is
refused); ``render_mode`` ``"rgb_array"`` or ``"human"`` (:mod:`robotsoccer.envs.rendering`).

**Seeds** follow :class:`~robotsoccer.envs.intercept.InterceptEnv`: ``reset(seed=s)`` starts
the episode stream of experiment seed `s`, episode k drawing every random number from trial
k's named streams (:mod:`field_models.seeding`), so the same seed and actions give the same
episode in any process. ``reset()`` continues the stream; the first one without a seed draws
one from the OS.

**Bad input.** ``step`` before ``reset`` (or after the end) raises RuntimeError; an action of
the wrong shape or type, or with NaN or infinity, a ValueError naming it; Box actions outside
their bounds are clipped to them. An unknown action kind, preset or ``reset`` option is
refused in one line.
"""

from __future__ import annotations

import math
from typing import Any, ClassVar

import gymnasium as gym
from gymnasium import spaces

from field_models.arena import Arena, FieldFacts, FieldOptions, WheelDrive
from field_models.protocol import LEFT, Mind, Percept, PlayerRef, wrap_angle
from field_models.registry import FIELD_MODELS, field_facts, has_preset, make_arena
from field_models.seeding import TrialRngs
from robotsoccer.drills.match import KICKER, MatchDrill
from robotsoccer.drills.passing import control_reach
from robotsoccer.envs.control_spaces import (
    ACTION_KINDS,
    COMMAND_PERIOD_S,
    DEFAULT_TURN_STEP_RAD,
    Held,
    ObservationBuilder,
    action_space,
    decode_action,
    reward_weights,
    state_space,
    state_vector,
)
from robotsoccer.envs.rendering import RENDER_MODES, ArenaView

SKIP_LIMIT = 100
"""reset() gives up after this many episodes in a row that end before the first step."""
TIME_OUT = "TIME_OUT"
"""The label of an episode cut by the time limit (a truncation)."""


class ControlEnv(gym.Env[Any, Any]):
    """What both tasks share: the episode loop, actions, observations, rewards, frames.

    A task fills in the class attributes and the ``_task_*`` hooks. Arguments as in the
    module docstring; `field_model` any registered one (default: the first), `preset` None
    for the task's default.
    """

    # Gymnasium's class attribute.
    metadata: dict[str, Any] = {"render_modes": RENDER_MODES, "render_fps": 30}  # noqa: RUF012
    default_weights: ClassVar[dict[str, float]] = {}
    sparse_term: ClassVar[str] = ""

    def __init__(
        self,
        field_model: str = FIELD_MODELS[0],
        preset: str | None = None,
        *,
        action: str | None = None,
        frames_per_step: int = 1,
        perfect_perception: bool = False,
        ideal_actuation: bool = False,
        privileged: bool = False,
        max_time_s: float | None = None,
        reward_weights: dict[str, float] | None = None,
        turn_step_rad: float = DEFAULT_TURN_STEP_RAD,
        render_mode: str | None = None,
        render_width: int = 480,
    ) -> None:
        if not isinstance(frames_per_step, int) or frames_per_step < 1:
            raise ValueError(f"frames_per_step must be a whole number >= 1: {frames_per_step!r}")
        if max_time_s is not None and not (math.isfinite(max_time_s) and max_time_s > 0.0):
            raise ValueError(f"max_time_s must be a finite number > 0, got {max_time_s!r}")
        self.field_model = field_model
        self.preset = preset or self._default_preset(field_model)
        self.field_options = FieldOptions(perfect_perception=perfect_perception, all_landmarks=True)
        self.facts: FieldFacts = field_facts(field_model, self.preset, self.field_options)
        self.players = self._task_players(self.facts)
        probe = self._build_arena(TrialRngs(0, 0))
        drives = isinstance(probe, WheelDrive)
        self.action_kind = action or ("wheels" if drives else "commands")
        if self.action_kind not in ACTION_KINDS:
            raise ValueError(f"unknown action {action!r} (kinds: {', '.join(ACTION_KINDS)})")
        if self.action_kind == "wheels" and not drives:
            raise ValueError(f"action 'wheels' needs a field that drives wheels, not {field_model}")
        self.frames_per_step = frames_per_step
        self.ideal_actuation = ideal_actuation
        self.privileged = privileged
        self.turn_step_rad = float(turn_step_rad)
        self.weights = reward_weights_for(self, reward_weights)
        facts = self.facts
        self.max_time_s = max_time_s or self._default_max_time_s(facts)
        self.max_ticks = max(1, round(self.max_time_s / facts.dt_s))
        period = min(facts.sensor_period_s, COMMAND_PERIOD_S)
        self.command_ticks = max(1, round(period / facts.dt_s))
        self.builder = ObservationBuilder(facts, *self._task_slots())
        self.action_space = action_space(self.action_kind)
        self.observation_space: spaces.Space[Any] = self.builder.space
        if privileged:
            self.observation_space = spaces.Dict(
                {"observation": self.builder.space, "state": state_space(len(self.players))}
            )
        self.render_mode = render_mode
        self._view = ArenaView(render_mode, render_width, title=type(self).__name__)
        self._experiment_seed: int | None = None
        self._next_episode = 0
        self._arena: Arena | None = None
        self._percept: Percept | None = None
        self._minds: dict[PlayerRef, Mind] = {}
        self._held: Held | None = None
        self._running = False

    # ------------------------------------------------------------------ Gymnasium API

    def reset(
        self, *, seed: int | None = None, options: dict[str, Any] | None = None
    ) -> tuple[Any, dict[str, Any]]:
        """Start the next episode of the stream and run it to the learner's first percept.

        Raises:
            ValueError: Any `options` (none are taken).
        """
        super().reset(seed=seed)
        if options:
            raise ValueError(f"unknown reset options {sorted(options)} (none are taken)")
        if seed is not None:
            self._experiment_seed, self._next_episode = int(seed), 0
        elif self._experiment_seed is None:
            self._experiment_seed = int(self.np_random.integers(2**31 - 1))
        for _ in range(SKIP_LIMIT):
            episode = self._next_episode
            self._next_episode += 1
            if self._start(TrialRngs(self._experiment_seed, episode)):
                self._running = True
                info = {"episode": episode, "seed": self._experiment_seed}
                if self.render_mode == "human":
                    self.render()
                return self._observation(), info
        raise RuntimeError(f"{SKIP_LIMIT} episodes in a row ended before their first step")

    def step(self, action: Any) -> tuple[Any, float, bool, bool, dict[str, Any]]:
        """Hold `action` for one step (module docstring); the reward and its terms in info."""
        arena = self._arena
        if arena is None or not self._running:
            raise RuntimeError("step() before reset(), or after the episode ended: call reset()")
        held = decode_action(self.action_kind, action, self.facts.player_top_speed_mps,
                             self.turn_step_rad)  # fmt: skip
        self._held = held
        self._send(held)
        before = self._task_potentials(arena)
        label, sparse = self._advance(self.frames_per_step)
        after = self._task_potentials(arena)
        weights = self.weights
        terms = {name: weights[name] * (after[name] - value) for name, value in before.items()}
        terms["time"] = -weights["time"]
        terms[self.sparse_term] = weights[self.sparse_term] * sparse
        truncated = label == TIME_OUT
        terminated = label is not None and not truncated
        self._running = label is None
        info: dict[str, Any] = {"reward_terms": terms, "tick": arena.tick, "label": label or ""}
        info |= self._task_info(label)
        if self.render_mode == "human":
            self.render()
        reward = float(sum(terms.values()))
        return self._observation(), reward, terminated, truncated, info

    def render(self) -> Any:
        """The present frame: an RGB array (``"rgb_array"``), or logged to rerun (``"human"``)."""
        return self._view.render(self._arena)

    def close(self) -> None:
        """Close the viewer's recording."""
        self._view.close()

    # ------------------------------------------------------------------ the episode

    def _build_arena(self, rngs: TrialRngs) -> Arena:
        return make_arena(self.field_model, self.preset, self.players, rngs, self.field_options)

    def _start(self, rngs: TrialRngs) -> bool:
        """Build and place episode `rngs`, run to the first percept; False: it ended first."""
        arena = self._arena = self._build_arena(rngs)
        if self.ideal_actuation and isinstance(arena, WheelDrive):
            arena.ideal_actuation()
        self._minds = self._task_setup(arena, rngs)
        arena.listen(frozenset(self._minds) | {self.learner})
        self.builder.reset()
        self._held = None
        self._percept = None
        label, _ = self._advance(1)
        return label is None

    def _advance(self, frames: int) -> tuple[str | None, float]:
        """Step ticks until the learner got `frames` percepts or the episode ended.

        Returns the end's label and sparse reward, or (None, 0) when the step just ends.
        """
        arena = self._arena
        assert arena is not None
        learner, minds, held = self.learner, self._minds, self._held
        start, period, seen = arena.tick, self.command_ticks, 0
        while True:
            percepts = arena.step()
            tick = arena.tick
            got = None
            for percept in percepts:
                player = percept.player
                if player is learner or player == learner:
                    got = percept
                    continue
                mind = minds.get(player)
                if mind is not None:
                    arena.submit(player, mind.act(percept))
            if got is not None:
                self._percept = got
            outcome = self._task_judge(arena)
            if outcome is not None:
                return outcome
            if tick >= self.max_ticks:
                return TIME_OUT, 0.0
            if got is not None:
                seen += 1
                if seen >= frames:
                    return None, 0.0
            if held is not None and (got is not None or (tick - start) % period == 0):
                self._send(held)

    def _send(self, held: Held) -> None:
        """Send the held action to the learner through the field's actuation path."""
        arena = self._arena
        assert arena is not None
        if self.action_kind == "wheels":
            assert isinstance(arena, WheelDrive)
            left, right = held
            arena.submit_wheels(self.learner, float(left), float(right))  # type: ignore[arg-type]
        else:
            arena.submit(self.learner, held)  # type: ignore[arg-type]

    def _observation(self) -> Any:
        arena, percept = self._arena, self._percept
        assert arena is not None and percept is not None
        left = max(0.0, 1.0 - arena.tick / self.max_ticks)
        vector = self.builder.build(percept, self._task_target(), left, self.facts.dt_s)
        if not self.privileged:
            return vector
        return {"observation": vector, "state": state_vector(arena.truth(), self.players,
                                                             self.facts)}  # fmt: skip

    # ------------------------------------------------------------------ the task's part

    learner: PlayerRef

    def _default_preset(self, field_model: str) -> str:
        """The preset used when none is named."""
        return field_facts(field_model).preset

    def _default_max_time_s(self, facts: FieldFacts) -> float:
        raise NotImplementedError

    def _task_players(self, facts: FieldFacts) -> tuple[PlayerRef, ...]:
        raise NotImplementedError

    def _task_slots(self) -> tuple[int, int]:
        """Teammate and opponent slots of the observation."""
        return (0, 0)

    def _task_setup(self, arena: Arena, rngs: TrialRngs) -> dict[PlayerRef, Mind]:
        """Place everything for a new episode; the other players' minds."""
        raise NotImplementedError

    def _task_judge(self, arena: Arena) -> tuple[str, float] | None:
        """After each tick: (label, sparse reward) when the episode ends, else None."""
        raise NotImplementedError

    def _task_potentials(self, arena: Arena) -> dict[str, float]:
        """The shaping potentials: each term's reward is its weight × the potential's gain."""
        raise NotImplementedError

    def _task_target(self) -> tuple[float, float]:
        """The field point of the observation's ``target`` entries [m]."""
        raise NotImplementedError

    def _task_info(self, label: str | None) -> dict[str, Any]:
        return {}


def reward_weights_for(env: ControlEnv, given: dict[str, float] | None) -> dict[str, float]:
    """The task's default weights with `given` ones replacing them (unknown terms refused)."""
    return reward_weights(type(env).default_weights, given)


# ----------------------------------------------------------------------------- go to the ball

GO_PLAYER = PlayerRef(LEFT, 1)
MARGIN_UNITS = 5.0
"""Ball, player and target are placed at least this far inside the lines [units]."""
DISTANCE_UNITS = (8.0, 30.0)
"""The player starts this far from the ball [units] (uniform)."""
TARGET_MIN_UNITS = 10.0
"""The target point lies at least this far from the ball [units]."""
REACH_UNITS = 1.5
"""At the ball: within the field's control reach, or touching plus this much [units]."""
FACE_TOLERANCE_RAD = math.radians(20.0)
"""Facing the target: its direction within this of the heading."""
GO_TIME_PERIODS = 200
"""The default time limit, in sensor periods (6.7 s on the robots, 50 s on the server)."""


class GoToBallEnv(ControlEnv):
    """Go to the ball and face a target point (``robotsoccer/GoToBall-v0``).

    **Placement** (the episode's "placement" stream): the ball uniformly inside the lines
    less :data:`MARGIN_UNITS`; the player :data:`DISTANCE_UNITS` from it in a uniform
    direction, facing a uniform heading; the target point uniformly inside, at least
    :data:`TARGET_MIN_UNITS` from the ball. The ball lies still.

    **Success** (the coach, on the truth, every tick): the ball within reach
    (:data:`REACH_UNITS`) and the target within :data:`FACE_TOLERANCE_RAD` of the heading.
    The episode then terminates with ``info["is_success"]`` True.

    **Rewards** (weights: ``reward_weights``): ``success`` 1 at the success; ``approach``
    the fall of the player-ball distance over L (weight 1); ``facing`` the gain of
    cos(heading error to the target) × exp(-distance / (2·reach)), i.e. of facing the target
    near the ball (weight 0.2); ``time`` a cost per step (weight 0.001). The shaped terms are
    differences of potentials, so they do not change which policy is best.
    """

    default_weights: ClassVar[dict[str, float]] = {
        "success": 1.0,
        "approach": 1.0,
        "facing": 0.2,
        "time": 0.001,
    }
    sparse_term: ClassVar[str] = "success"
    learner = GO_PLAYER

    def _default_max_time_s(self, facts: FieldFacts) -> float:
        return GO_TIME_PERIODS * facts.sensor_period_s

    def _task_players(self, facts: FieldFacts) -> tuple[PlayerRef, ...]:
        unit = facts.unit_m
        self.reach_m = max(control_reach(facts), facts.touch_distance_m + REACH_UNITS * unit)
        self.target_xy = (0.0, 0.0)
        return (GO_PLAYER,)

    def _task_setup(self, arena: Arena, rngs: TrialRngs) -> dict[PlayerRef, Mind]:
        facts = arena.facts
        unit, pitch = facts.unit_m, facts.pitch
        hx = pitch.half_length_m - MARGIN_UNITS * unit
        hy = pitch.half_width_m - MARGIN_UNITS * unit
        rng = rngs["placement"]
        bx, by = rng.uniform(-hx, hx), rng.uniform(-hy, hy)
        px, py = bx, by
        for _ in range(100):  # redraw until the player starts inside (a fixed number of draws)
            d = rng.uniform(*DISTANCE_UNITS) * unit
            a = rng.uniform(-math.pi, math.pi)
            px, py = bx + d * math.cos(a), by + d * math.sin(a)
            if abs(px) <= hx and abs(py) <= hy:
                break
        px, py = max(-hx, min(px, hx)), max(-hy, min(py, hy))
        tx, ty = bx, by
        for _ in range(100):
            tx, ty = rng.uniform(-hx, hx), rng.uniform(-hy, hy)
            if math.hypot(tx - bx, ty - by) >= TARGET_MIN_UNITS * unit:
                break
        self.target_xy = (tx, ty)
        arena.place_ball(bx, by)
        arena.place_player(GO_PLAYER, px, py, rng.uniform(-math.pi, math.pi))
        return {}

    def _errors(self, arena: Arena) -> tuple[float, float]:
        """(player-ball distance [m], heading error to the target [rad]) on the truth."""
        p = arena.player_state(GO_PLAYER)
        b = arena.ball_state()
        tx, ty = self.target_xy
        error = wrap_angle(math.atan2(ty - p.y, tx - p.x) - p.heading)
        return math.hypot(b.x - p.x, b.y - p.y), error

    def _task_judge(self, arena: Arena) -> tuple[str, float] | None:
        distance, error = self._errors(arena)
        if distance <= self.reach_m and abs(error) <= FACE_TOLERANCE_RAD:
            return "SUCCESS", 1.0
        return None

    def _task_potentials(self, arena: Arena) -> dict[str, float]:
        distance, error = self._errors(arena)
        near = math.exp(-distance / (2.0 * self.reach_m))
        return {"approach": -distance / self.facts.pitch.length_m, "facing": math.cos(error) * near}

    def _task_target(self) -> tuple[float, float]:
        return self.target_xy

    def _task_info(self, label: str | None) -> dict[str, Any]:
        return {"is_success": label == "SUCCESS"}


# ----------------------------------------------------------------------------- score

SCORE_PRESET = "vss"
"""Score's preset where the field model ships one of that name (the robots' 3 v 3 table)."""
SCORE_TIME_S = 60.0
"""Score's default time limit [s]."""


class ScoreEnv(ControlEnv):
    """Score in a small-sided match (``robotsoccer/Score-v0``).

    Extra arguments: ``players_per_side`` (default 3; any size the match drill has a formation
    for) and ``learner_number`` (default: the left team's kick-off taker). The learner plays
    for the left team, attacking the goal at +x; the left team kicks off
    (:class:`~robotsoccer.drills.match.MatchDrill` with two baseline teams, its referee
    included).

    **Ends**: a goal (``GOAL_FOR`` / ``GOAL_AGAINST``), the ball out of play (the referee's
    call as the label: ``kick_in_l``, ``goal_kick_r``, ``corner_kick_l``, ``drop_ball``...),
    or the time limit (truncation, ``TIME_OUT``).

    **Rewards** (weights: ``reward_weights``): ``goal`` +1 for a goal for, -1 against;
    ``ball_to_goal`` the fall of the ball's distance to the opponents' goal over L (weight
    0.2); ``to_ball`` the fall of the learner's distance to the ball over L (weight 0.05);
    ``time`` a cost per step (weight 0). Shaped terms are differences of potentials.
    """

    default_weights: ClassVar[dict[str, float]] = {
        "goal": 1.0,
        "ball_to_goal": 0.2,
        "to_ball": 0.05,
        "time": 0.0,
    }
    sparse_term: ClassVar[str] = "goal"

    def __init__(
        self,
        field_model: str = FIELD_MODELS[0],
        preset: str | None = None,
        *,
        players_per_side: int = 3,
        learner_number: int | None = None,
        **options: Any,
    ) -> None:
        if players_per_side not in KICKER:
            sizes = ", ".join(str(n) for n in sorted(KICKER))
            raise ValueError(f"players_per_side must be one of {sizes}, got {players_per_side!r}")
        number = KICKER[players_per_side] if learner_number is None else learner_number
        if not isinstance(number, int) or not 1 <= number <= players_per_side:
            raise ValueError(f"learner_number must be in 1..{players_per_side}, got {number!r}")
        self.players_per_side = players_per_side
        self.learner = PlayerRef(LEFT, number)
        self._drill: MatchDrill | None = None
        super().__init__(field_model, preset, **options)

    def _default_preset(self, field_model: str) -> str:
        if has_preset(field_model, SCORE_PRESET):
            return SCORE_PRESET
        return super()._default_preset(field_model)

    def _default_max_time_s(self, facts: FieldFacts) -> float:
        return SCORE_TIME_S

    def _new_drill(self) -> MatchDrill:
        # Halves longer than any episode: the referee never calls half time in one.
        half = 2.0 * (getattr(self, "max_time_s", None) or SCORE_TIME_S) + 1.0
        return MatchDrill("baseline", "baseline", players=self.players_per_side,
                          half_time_s=half)  # fmt: skip

    def _task_players(self, facts: FieldFacts) -> tuple[PlayerRef, ...]:
        return self._new_drill().players_for(facts)

    def _task_slots(self) -> tuple[int, int]:
        return (self.players_per_side - 1, self.players_per_side)

    def _task_setup(self, arena: Arena, rngs: TrialRngs) -> dict[PlayerRef, Mind]:
        drill = self._drill = self._new_drill()
        drill.setup(arena, rngs)
        minds = drill.minds(arena, rngs)
        del minds[self.learner]
        drill.drain_events()
        return minds

    def _task_judge(self, arena: Arena) -> tuple[str, float] | None:
        drill = self._drill
        assert drill is not None
        drill.judge(arena)
        referee = drill.referee
        assert referee is not None
        if not referee.events:
            return None
        for event in referee.drain():
            if event.text.startswith("goal_l"):
                return "GOAL_FOR", 1.0
            if event.text.startswith("goal_r"):
                return "GOAL_AGAINST", -1.0
            if event.text != "play_on":
                return event.text, 0.0
        return None

    def _task_potentials(self, arena: Arena) -> dict[str, float]:
        b = arena.ball_state()
        p = arena.player_state(self.learner)
        gx, length = self.facts.pitch.half_length_m, self.facts.pitch.length_m
        return {
            "ball_to_goal": -math.hypot(gx - b.x, b.y) / length,
            "to_ball": -math.hypot(b.x - p.x, b.y - p.y) / length,
        }

    def _task_target(self) -> tuple[float, float]:
        return (self.facts.pitch.half_length_m, 0.0)

    def _task_info(self, label: str | None) -> dict[str, Any]:
        referee = self._drill.referee if self._drill is not None else None
        return {"score": tuple(referee.score) if referee is not None else (0, 0)}
