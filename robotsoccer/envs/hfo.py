"""Half-field offense in HFO's shape, as a PettingZoo parallel environment on any field model.

Hausknecht et al.'s HFO (2016) is the standard multi-agent RoboCup benchmark: attackers try to
score on one half against defenders and a goalie. :class:`HalfFieldOffenseEnv`
(``half_field_offense_env("soccer_server")``) poses it on our field models, with the match's
team minds (:mod:`robotsoccer.skills.team`) for every player not controlled, on the loop,
observations, actions and rewards of :class:`~robotsoccer.envs.play.PlayParallelEnv` (see
there: steps, ``"commands"``/``"primitives"``/``"macro"`` actions, percept vectors, reward
terms, seeds).

**Players.** ``offense`` attackers (default 2: ``left_1`` …) attack the goal at +x against
``defense`` defenders (default 1) and a goalie (``goalie=True``): ``right_1`` keeps goal,
``right_2`` … defend. ``controlled``: ``"offense"`` (default), ``"defense"``, ``"all"`` or a
list of agent names; the rest are baseline team minds.

**Start** (trial k's ``placement`` stream; distances in units, Soccer Server metres): the ball
at x in :data:`BALL_X_UNITS`, y in ±:data:`BALL_Y_UNITS`; attacker 1 just behind it, facing
the goal; the other attackers at x in [ball x - 5, ball x + 15], |y| <= 20; the defenders at x
in :data:`DEFENDER_X_UNITS`, |y| <= 15, facing the attackers; the goalie on its goal line's
centre, :data:`GOALIE_INSET_UNITS` in. Formation homes (where GO_HOME goes, shifted with the
ball): :data:`ATTACK_HOME_X_UNITS` and :data:`DEFENCE_HOME_X_UNITS` from the centre line.

**Ends** (the coach judges every tick on the truth; HFO's status names, in
``infos[agent]["status"]``, ``IN_GAME`` before):

* ``GOAL``: the ball wholly over the goal line between the posts (the project's one goal-line
  rule, :class:`~robotsoccer.drills.base.GoalWatch`);
* ``CAPTURED_BY_DEFENSE``: a defender or the goalie has the ball within its control reach
  (:func:`~robotsoccer.drills.layered.control_reach`), checked as the match's referee checks
  touches;
* ``OUT_OF_BOUNDS``: the ball over a side line or the end line wide of the goal, or back over
  the centre line (out of the half);
* ``OUT_OF_TIME``: the time limit (``max_time_s``), or no player touched the ball for
  ``untouched_time_s`` (HFO's ``untouched-time``). This one is a truncation; the others
  terminate.

Time limits are in sensor periods of the field (:data:`MAX_TIME_PERIODS`,
:data:`UNTOUCHED_PERIODS`), HFO's 1000 and 100 server cycles on the 1996 Soccer Server's see
period of 250 ms; on the robots' 30 Hz camera they are the same number of decisions.

**The ball holder's choice** is what the layer-3 learners learn: with ``action="macro"`` the
attacker with the ball in reach has the mask ``{AUTO, GO_HOME, SHOOT, DRIBBLE, PASS_k}`` for
the teammates it sees (:mod:`robotsoccer.envs.macros`); :mod:`robotsoccer.envs.hfo_eval`
measures goal rates of such choices on fixed episodes.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Sequence
from typing import Any

from field_models.arena import Arena, FieldFacts
from field_models.protocol import LEFT, RIGHT, Crossing, Mind, PlayerRef
from field_models.registry import FIELD_MODELS
from field_models.seeding import TrialRngs
from robotsoccer.drills.base import Drill, GoalWatch, Verdict
from robotsoccer.drills.layered import control_reach
from robotsoccer.drills.match import MatchDrill
from robotsoccer.drills.referee import TOUCH_PERIOD_S
from robotsoccer.envs.agents import controlled_players, play_spec
from robotsoccer.envs.play import PlayParallelEnv
from robotsoccer.runs.spec import resolve_with
from robotsoccer.skills.team import TeamMind
from robotsoccer.skills.team_setup import TeamSetup

GOAL = "GOAL"
CAPTURED = "CAPTURED_BY_DEFENSE"
OUT_OF_BOUNDS = "OUT_OF_BOUNDS"
OUT_OF_TIME = "OUT_OF_TIME"
IN_GAME = "IN_GAME"
OUTCOMES = (GOAL, CAPTURED, OUT_OF_BOUNDS, OUT_OF_TIME)
"""HFO's episode outcomes (module docstring)."""
MAX_TIME_PERIODS = 400
UNTOUCHED_PERIODS = 40
"""Default time limits in sensor periods (module docstring)."""
BALL_X_UNITS = (0.0, 20.0)
BALL_Y_UNITS = 15.0
ATTACKER_SPREAD_UNITS = ((-5.0, 15.0), 20.0)
DEFENDER_X_UNITS = (27.5, 42.5)
DEFENDER_Y_UNITS = 15.0
GOALIE_INSET_UNITS = 2.0
"""Start positions (module docstring) [units]."""
ATTACK_HOME_X_UNITS = 20.0
DEFENCE_HOME_X_UNITS = 25.0
HOME_SPREAD_UNITS = 12.0
"""Formation homes: x from the centre line toward the attacked goal, y spread [units]."""
EDGE_UNITS = 3.0
"""Players start at least this far inside the side lines [units]."""
MAX_SIDE = 5
"""The most attackers, and defenders, a side may have."""


@dataclasses.dataclass(frozen=True)
class HfoTask:
    """What half-field offense poses: the sides and the episode's limits (module docstring).

    Attributes:
        offense: Attackers, 1 … :data:`MAX_SIDE`.
        defense: Defenders besides the goalie, 0 … :data:`MAX_SIDE`.
        goalie: Whether the defence has a goalie (``right_1``).
        max_time_s: The time limit [s] (None: :data:`MAX_TIME_PERIODS` sensor periods).
        untouched_time_s: Ends an episode whose ball nobody touched this long [s] (None:
            :data:`UNTOUCHED_PERIODS` sensor periods).

    Raises:
        ValueError: Counts out of range, no goalie and no defender, a time that is not a
            finite number > 0.
    """

    offense: int = 2
    defense: int = 1
    goalie: bool = True
    max_time_s: float | None = None
    untouched_time_s: float | None = None

    def __post_init__(self) -> None:
        _count("offense", self.offense, 1)
        _count("defense", self.defense, 0)
        if not isinstance(self.goalie, bool):
            raise ValueError(f"goalie must be True or False, got {self.goalie!r}")
        if self.defense == 0 and not self.goalie:
            raise ValueError("the defence needs a goalie or at least one defender")
        for name in ("max_time_s", "untouched_time_s"):
            value = getattr(self, name)
            ok = value is None or (
                isinstance(value, int | float) and math.isfinite(value) and value > 0
            )
            if not ok:
                raise ValueError(f"{name} must be None or a finite number > 0, got {value!r}")


HFO_FIELDS = tuple(f.name for f in dataclasses.fields(HfoTask))
"""The task's names: the environment's keywords that go to its record."""


class HfoDrill:
    """The half-field offense as a drill: placement, team minds, the judge (module docstring).

    Args:
        task: The sides and the limits (:class:`HfoTask`).
    """

    name: str = "hfo"
    labels: tuple[str, ...] = OUTCOMES

    def __init__(self, task: HfoTask) -> None:
        self.offense, self.defense, self.goalie = task.offense, task.defense, task.goalie
        self.max_time_s = task.max_time_s if task.max_time_s is not None else math.inf
        self.untouched_time_s = task.untouched_time_s
        self.score = [0, 0]
        self.last_touch: PlayerRef | None = None
        self._goals: GoalWatch | None = None
        self._touched_tick = 0
        self._untouched_ticks = 0
        self._touch_every = 1
        self._control2 = 0.0

    def players(self) -> tuple[PlayerRef, ...]:
        """Attackers (left 1 …), then the goalie (right 1) and the defenders."""
        defence = self.defense + (1 if self.goalie else 0)
        return (*(PlayerRef(LEFT, k) for k in range(1, self.offense + 1)),
                *(PlayerRef(RIGHT, k) for k in range(1, defence + 1)))  # fmt: skip

    def field_settings(self, facts: FieldFacts) -> dict[str, float]:
        """Percepts with every landmark (the minds localise): set by the environment."""
        return {}

    def inputs(self) -> tuple[str, ...]:
        """No model files."""
        return ()

    def setup(self, arena: Arena, rngs: TrialRngs) -> None:
        """Place ball and players (module docstring)."""
        facts = arena.facts
        unit, pitch = facts.unit_m, facts.pitch
        hl, hw = pitch.half_length_m / unit, pitch.half_width_m / unit
        edge = hw - EDGE_UNITS
        rng = rngs["placement"]
        bx = rng.uniform(*BALL_X_UNITS)
        by = rng.uniform(-BALL_Y_UNITS, BALL_Y_UNITS)
        arena.place_ball(bx * unit, by * unit)
        behind = facts.touch_distance_m + 0.3 * unit
        (dx_low, dx_high), spread = ATTACKER_SPREAD_UNITS
        for ref in arena.players:
            if ref.team == LEFT and ref.number == 1:
                arena.place_player(ref, bx * unit - behind, by * unit, 0.0)
                continue
            if ref.team == LEFT:
                x = rng.uniform(bx + dx_low, bx + dx_high)
                y = rng.uniform(-spread, spread)
                heading = 0.0
            elif self.goalie and ref.number == 1:
                x, y, heading = hl - GOALIE_INSET_UNITS, 0.0, math.pi
            else:
                x = rng.uniform(*DEFENDER_X_UNITS)
                y = rng.uniform(-DEFENDER_Y_UNITS, DEFENDER_Y_UNITS)
                heading = math.pi
            y = max(-edge, min(y, edge))
            arena.place_player(ref, x * unit, y * unit, heading)
        self._goals = GoalWatch(arena, (bx * unit, by * unit))
        self._touch_every = max(1, math.floor(TOUCH_PERIOD_S / facts.dt_s))
        reach = control_reach(facts)
        self._control2 = reach * reach
        periods = facts.sensor_period_s
        if not math.isfinite(self.max_time_s):
            self.max_time_s = MAX_TIME_PERIODS * periods
        untouched = self.untouched_time_s or UNTOUCHED_PERIODS * periods
        self._untouched_ticks = max(1, round(untouched / facts.dt_s))

    def minds(self, arena: Arena, rngs: TrialRngs) -> dict[PlayerRef, Mind]:
        """The baseline team mind for every player, on HFO's homes."""
        facts = arena.facts
        minds: dict[PlayerRef, Mind] = {}
        for team in (LEFT, RIGHT):
            numbers = [r.number for r in arena.players if r.team == team]
            if not numbers:
                continue
            setup = self.team_setup(facts, team, numbers)
            for number in numbers:
                minds[PlayerRef(team, number)] = TeamMind(number, setup)
        return minds

    def team_setup(self, facts: FieldFacts, team: str, numbers: list[int]) -> TeamSetup:
        """The match's plan for one team on this field, with HFO's homes and goalie."""
        base = MatchDrill(left="baseline", right="baseline").team_setup(facts, 2, team)
        unit = facts.unit_m
        sign = 1.0 if team == LEFT else -1.0
        x = ATTACK_HOME_X_UNITS if team == LEFT else -DEFENCE_HOME_X_UNITS
        goalie = 1 if team == RIGHT and self.goalie else None
        field = [n for n in numbers if n != goalie]
        home: dict[int, tuple[float, float]] = {}
        for i, number in enumerate(field):
            share = 0.0 if len(field) == 1 else 2.0 * i / (len(field) - 1) - 1.0
            home[number] = (sign * x * unit, sign * share * HOME_SPREAD_UNITS * unit)
        if goalie is not None:
            home[goalie] = (facts.pitch.half_length_m - GOALIE_INSET_UNITS * unit, 0.0)
        return dataclasses.replace(base, home=home, goalie=goalie)

    def judge(self, arena: Arena) -> Verdict | None:
        """The episode's end after this tick, or None (module docstring)."""
        goals = self._goals
        assert goals is not None, "judge() before setup()"
        tick = arena.tick
        x, y, *_ = arena.ball_state()
        crossing = goals.step(arena, x, y)
        if crossing is Crossing.RIGHT_GOAL:
            self.score[0] += 1
            return Verdict(GOAL, f"goal at tick {tick}")
        if tick % self._touch_every == 0:
            touch = self._touch(arena, x, y)
            if touch is not None:
                self.last_touch, self._touched_tick = touch, tick
                if touch.team == RIGHT:
                    return Verdict(CAPTURED, f"{touch} has the ball")
        pitch = arena.facts.pitch
        if crossing is not Crossing.NONE or x < 0.0:
            return Verdict(OUT_OF_BOUNDS, "over an end line" if x > 0.0 else "out of the half")
        if abs(y) > pitch.half_width_m + pitch.ball_radius_m:
            return Verdict(OUT_OF_BOUNDS, "over a side line")
        if tick - self._touched_tick >= self._untouched_ticks:
            return Verdict(OUT_OF_TIME, "ball untouched")
        return None

    def _touch(self, arena: Arena, x: float, y: float) -> PlayerRef | None:
        """The player nearest the ball within control reach (the referee's touch), or None."""
        best, best_d2 = None, self._control2
        for ref in arena.players:
            p = arena.player_state(ref)
            d2 = (p.x - x) ** 2 + (p.y - y) ** 2
            if d2 <= best_d2:
                best, best_d2 = ref, d2
        return best

    def timeout(self, arena: Arena) -> Verdict:
        """The time limit: OUT_OF_TIME."""
        return Verdict(OUT_OF_TIME, "time limit")

    def data(self) -> tuple[float, ...]:
        """Nothing to learn from."""
        return ()

    def measures(self) -> dict[str, float]:
        """Goals of the offense."""
        return {"goals": float(self.score[0])}


class HalfFieldOffenseEnv(PlayParallelEnv):
    """Half-field offense (module docstring).

    Args:
        field_model: A registered field model (default: the first registered).
        preset: Its preset; None: the model's default.
        task: The sides and the limits (:class:`HfoTask`); None: built from the keywords that
            name its fields (``offense``, ``defense``, ``goalie``, ``max_time_s``,
            ``untouched_time_s``), HFO's 2 v 1 and a goalie where they leave one out.
        controlled: ``"offense"``, ``"defense"``, ``"all"`` or a list of agent names.
        **options: The task's fields by name, where `task` is not given; and ``action``,
            ``reward_weights``, ``perfect_perception``, ``turn_step_rad``, ``render_mode``
            (:class:`~robotsoccer.envs.play.PlayParallelEnv`).

    Raises:
        ValueError: A bad task (:class:`HfoTask`), both a record and the task's keywords, an
            unknown agent, action mode, reward term or render mode.
    """

    metadata: dict[str, Any] = {  # noqa: RUF012
        **PlayParallelEnv.metadata,
        "name": "robotsoccer_hfo_v0",
    }

    def __init__(
        self,
        field_model: str = FIELD_MODELS[0],
        preset: str | None = None,
        task: HfoTask | None = None,
        *,
        controlled: str | Sequence[str] = "offense",
        **options: Any,
    ) -> None:
        given = {name: options.pop(name) for name in HFO_FIELDS if name in options}
        if task is not None and given:
            raise ValueError("give half-field offense a task record or keywords, not both")
        self.task = task if task is not None else HfoTask(**given)
        self.counts = (self.task.offense, self.task.defense, self.task.goalie)
        # HFO's own drill, not a registered one: the environment makes each episode's.
        spec = play_spec("hfo", field_model, preset, options)
        resolved = resolve_with(spec, self._new_drill())
        teams = {"offense": LEFT, "defense": RIGHT}
        chosen = controlled_players(controlled, resolved.players, teams)
        super().__init__(resolved, chosen, **options)

    def _new_drill(self) -> Drill:
        return HfoDrill(self.task)

    def _score(self, drill: Drill) -> tuple[int, int]:
        hfo = _hfo(drill)
        return (hfo.score[0], hfo.score[1])

    def _holder(self, drill: Drill) -> PlayerRef | None:
        return _hfo(drill).last_touch

    def _end_info(self, verdict: Verdict) -> tuple[bool, dict[str, Any]]:
        info = {"status": verdict.label, "label": verdict.label, "reason": verdict.reason}
        return verdict.label == OUT_OF_TIME, info

    def _step_info(self, drill: Drill) -> dict[str, Any]:
        return {"status": IN_GAME}


def half_field_offense_env(
    field_model: str = FIELD_MODELS[0], preset: str | None = None, **options: Any
) -> HalfFieldOffenseEnv:
    """Half-field offense as a PettingZoo parallel environment (:class:`HalfFieldOffenseEnv`)."""
    return HalfFieldOffenseEnv(field_model, preset, **options)


def _hfo(drill: Drill) -> HfoDrill:
    assert isinstance(drill, HfoDrill)
    return drill


def _count(name: str, value: object, low: int) -> None:
    if isinstance(value, bool) or not isinstance(value, int) or not low <= value <= MAX_SIDE:
        raise ValueError(f"{name} must be a whole number in {low}..{MAX_SIDE}, got {value!r}")
