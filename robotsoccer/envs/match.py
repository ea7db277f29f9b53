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
from dataclasses import fields
from typing import Any

from field_models.protocol import PlayerRef
from field_models.registry import FIELD_MODELS
from robotsoccer.drills.base import Drill
from robotsoccer.drills.match import MatchDrill
from robotsoccer.drills.match_options import MatchOptions
from robotsoccer.envs.agents import controlled_players, play_spec
from robotsoccer.envs.play import PlayParallelEnv
from robotsoccer.runs.spec import resolve

MATCH_FIELDS = tuple(f.name for f in fields(MatchOptions))
"""The match's option names: the keywords that go to its options record."""


class MatchParallelEnv(PlayParallelEnv):
    """A whole match with some or all players as agents (module docstring).

    Args:
        field_model: A registered field model (default: the first registered).
        preset: Its preset; None: the model's default.
        match: The match's options (:class:`~robotsoccer.drills.match_options.MatchOptions`);
            None: built from the keywords that name its fields, with both teams ``baseline``
            where they leave a team out.
        controlled: ``"all"``, ``"left"``, ``"right"`` or a list of agent names.
        **options: The match's options by name, where `match` is not given: ``players`` (0:
            the match's default for the field, 11 on an open field, 5 on the robots' table;
            else one of the match's formation sizes), ``left`` and ``right`` (the minds of the
            players not controlled: ``baseline``, or ``layered`` with ``net`` and ``tree``),
            ``half_time_s`` (default: rcssserver's 300 s), ``steady_turns``, ...; and
            ``perfect_perception``, ``action``, ``reward_weights``, ``turn_step_rad``,
            ``render_mode`` (:class:`PlayParallelEnv`).

    Raises:
        ValueError: Any option the match refuses, both a record and the match's keywords, an
            unknown agent name in `controlled`.
    """

    metadata: dict[str, Any] = {  # noqa: RUF012
        **PlayParallelEnv.metadata,
        "name": "robotsoccer_match_v0",
    }

    def __init__(
        self,
        field_model: str = FIELD_MODELS[0],
        preset: str | None = None,
        match: MatchOptions | None = None,
        *,
        controlled: str | Sequence[str] = "all",
        **options: Any,
    ) -> None:
        given = {name: options.pop(name) for name in MATCH_FIELDS if name in options}
        if match is not None and given:
            raise ValueError("give the match environment an options record or keywords, not both")
        if match is None:  # its own checks, once, before anything is built
            match = MatchOptions(**{"left": "baseline", "right": "baseline", **given})
        drill_options = {name: getattr(match, name) for name in MATCH_FIELDS}
        spec = play_spec("match", field_model, preset, options).with_options(**drill_options)
        resolved = resolve(spec)
        everyone = resolved.players
        super().__init__(resolved, controlled_players(controlled, everyone), **options)

    def _new_drill(self) -> Drill:
        return self.resolved.new_drill()

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
