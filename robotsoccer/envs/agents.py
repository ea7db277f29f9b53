"""Agent names of the play environments, which players a ``controlled=`` option names.

And the spec a play environment resolves (:func:`play_spec`): its drill on the field.
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

from field_models.arena import FieldOptions
from field_models.protocol import LEFT, RIGHT, PlayerRef
from robotsoccer.runs.spec import TrialSpec


def agent_name(ref: PlayerRef) -> str:
    """A player's agent name, ``left_3``."""
    return f"{ref.team}_{ref.number}"


def controlled_players(
    controlled: str | Sequence[str],
    everyone: tuple[PlayerRef, ...],
    teams: dict[str, str] | None = None,
) -> tuple[PlayerRef, ...]:
    """The controlled players of `controlled`: ``"all"``, a team, or a list of agent names.

    A team is ``"left"`` or ``"right"``, or a name in `teams` (``"offense"``: left).

    Raises:
        ValueError: An unknown name.
    """
    names = {"left": LEFT, "right": RIGHT, **(teams or {})}
    if isinstance(controlled, str):
        if controlled == "all":
            return everyone
        if controlled in names:
            return tuple(p for p in everyone if p.team == names[controlled])
        choices = ", ".join(["all", *names])
        raise ValueError(
            f"controlled must be {choices} or a list of agent names, got {controlled!r}"
        )
    by_name = {agent_name(p): p for p in everyone}
    wanted = list(controlled)
    unknown = [a for a in wanted if a not in by_name]
    if unknown:
        raise ValueError(f"unknown agents {unknown} in controlled (players: {list(by_name)})")
    return tuple(p for p in everyone if agent_name(p) in wanted)


def play_spec(
    drill: str, field_model: str, preset: str | None, options: dict[str, Any]
) -> TrialSpec:
    """The spec a play environment resolves: `drill` on the field, every landmark seen.

    Takes ``perfect_perception`` (the sensor without noise, misses or latency) out of
    `options`, the environment's keywords, and leaves the rest to
    :class:`~robotsoccer.envs.play.PlayParallelEnv`.
    """
    perfect = bool(options.pop("perfect_perception", False))
    field = FieldOptions(perfect_perception=perfect, all_landmarks=True)
    return TrialSpec(drill=drill, field_model=field_model, preset=preset, field=field)
