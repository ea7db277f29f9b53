"""A whole match as a PettingZoo parallel environment, on any field model.

:class:`MatchParallelEnv` (``match_parallel_env("soccer_server")``) plays the match of
:class:`~robotsoccer.drills.match.MatchDrill` (its referee, its two halves, its formations)
with some or all players as agents, on the loop, observations, actions, rewards and seeds of
:class:`~robotsoccer.envs.play.PlayParallelEnv` (see there).

**Agents** are players, named ``left_1`` … ``left_N``, ``right_1`` … (``controlled``: ``"all"``
by default, ``"left"``, ``"right"``, or a list of agent names). Players not controlled are
played by the match's team minds (``left=`` and ``right=``: ``"baseline"``, or ``"layered"``
with ``net=`` and ``tree=``), so a user can control one team, or a few players. With the
``AUTO`` macro for every agent, every agent is its team mind and an episode is the match
drill's trial of the same seed and index.

**Ends.** Full time terminates every agent (``infos`` carry the match's label, LEFT_WIN, DRAW
or RIGHT_WIN, and its score line, and the referee's ``play_mode`` at every step); ``agents``
then empties. Shorter matches: ``half_time_s``.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

from field_models.arena import FieldOptions
from field_models.protocol import PlayerRef
from field_models.registry import FIELD_MODELS, field_facts
from robotsoccer.drills.base import Drill
from robotsoccer.drills.match import MatchDrill
from robotsoccer.drills.match_options import HALF_TIME_S
from robotsoccer.envs.agents import controlled_players
from robotsoccer.envs.play import PlayParallelEnv


class MatchParallelEnv(PlayParallelEnv):
    """A whole match with some or all players as agents (module docstring).

    Args:
        field_model: A registered field model (default: the first registered).
        preset: Its preset; None: the model's default.
        players: Players per side (0: the match's default for the field, 11 on an open field,
            5 on the robots' table; else one of the match's formation sizes).
        left: The left team's minds for its players not controlled (``baseline``, ``layered``).
        right: The right team's.
        net: Layer 1's net, for a layered team.
        tree: Layer 2's pass tree, for a layered team.
        half_time_s: One half [s] (default: rcssserver's 300 s).
        controlled: ``"all"``, ``"left"``, ``"right"`` or a list of agent names.
        steady_turns: The team minds' steady turns (:class:`~robotsoccer.drills.match.MatchDrill`).
        **options: ``action``, ``reward_weights``, ``perfect_perception``, ``turn_step_rad``,
            ``render_mode`` (:class:`PlayParallelEnv`).

    Raises:
        ValueError: Any option the match refuses, an unknown agent name in `controlled`.
    """

    metadata: dict[str, Any] = {  # noqa: RUF012
        **PlayParallelEnv.metadata,
        "name": "robotsoccer_match_v0",
    }

    def __init__(
        self,
        field_model: str = FIELD_MODELS[0],
        preset: str | None = None,
        *,
        players: int = 0,
        left: str = "baseline",
        right: str = "baseline",
        net: str = "",
        tree: str = "",
        half_time_s: float = HALF_TIME_S,
        controlled: str | Sequence[str] = "all",
        steady_turns: bool = False,
        **options: Any,
    ) -> None:
        def drill() -> MatchDrill:
            return MatchDrill(
                left=left, right=right, net=net, tree=tree, players=players,
                half_time_s=half_time_s, steady_turns=steady_turns,
            )  # fmt: skip

        self._make_drill = drill
        probe = drill()  # its own checks, once, before anything is built
        perfect = bool(options.get("perfect_perception", False))
        facts = field_facts(field_model, preset, FieldOptions(perfect_perception=perfect,
                                                              all_landmarks=True))  # fmt: skip
        everyone = probe.players_for(facts)
        super().__init__(field_model, preset, everyone, controlled_players(controlled, everyone),
                         **options)  # fmt: skip

    def _new_drill(self) -> Drill:
        return self._make_drill()

    def _score(self, drill: Drill) -> tuple[int, int]:
        referee = _match(drill).referee
        return (0, 0) if referee is None else (referee.score[0], referee.score[1])

    def _holder(self, drill: Drill) -> PlayerRef | None:
        referee = _match(drill).referee
        return None if referee is None else referee.last_touch

    def _step_info(self, drill: Drill) -> dict[str, Any]:
        referee = _match(drill).referee
        return {"play_mode": "" if referee is None else referee.play_mode}


def match_parallel_env(
    field_model: str = FIELD_MODELS[0], preset: str | None = None, **options: Any
) -> MatchParallelEnv:
    """A whole match as a PettingZoo parallel environment (:class:`MatchParallelEnv`)."""
    return MatchParallelEnv(field_model, preset, **options)


def _match(drill: Drill) -> MatchDrill:
    assert isinstance(drill, MatchDrill)
    return drill
