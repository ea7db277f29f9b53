"""Score in a small-sided match: ``robotsoccer/Score-v0`` on either field model.

A task of the per-step control environments (:class:`~robotsoccer.envs.control.ControlEnv`:
steps, options, seeds and bad input are described there): one learning player in a
small-sided match, everyone else driven by the baseline team minds under the match's referee
(:class:`ScoreEnv`).
"""

from __future__ import annotations

import math
from typing import Any, ClassVar

from field_models.arena import Arena, FieldFacts
from field_models.protocol import LEFT, Mind, PlayerRef
from field_models.registry import FIELD_MODELS, has_preset
from field_models.seeding import TrialRngs
from robotsoccer.drills.match import MatchDrill
from robotsoccer.drills.match_setup import KICKER
from robotsoccer.envs.control import ControlEnv

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
        return MatchDrill(left="baseline", right="baseline", players=self.players_per_side,
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
