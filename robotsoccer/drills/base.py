"""What a drill is: the coach's side of a trial (who plays, where they start, how it ends)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Protocol

from field_models.arena import Arena
from field_models.protocol import Mind, PlayerRef
from field_models.seeding import TrialRngs


@dataclass(frozen=True, slots=True)
class Verdict:
    """How a trial ended: its label and a short reason for the recording."""

    label: str
    reason: str = ""


class Drill(Protocol):
    """A coach-run trial: places objects, gives the players their minds, ends and labels the trial.

    The coach reads truth through the arena; the minds it hands out see only percepts.
    """

    name: str
    labels: tuple[str, ...]
    """Every label `judge` can return, in report order."""
    max_time_s: float
    """A trial still running after this long is judged by `timeout`."""

    def players(self) -> tuple[PlayerRef, ...]:
        """The players on the field, in a fixed order."""
        ...

    def arena_settings(self, field_model: str, preset: str) -> dict[str, float]:
        """Arena overrides the drill needs on this field (e.g. a scaled noise period), or {}.

        The runner applies them when it builds the arena; a TrialSpec's own override wins.
        """
        ...

    def setup(self, arena: Arena, rngs: TrialRngs) -> None:
        """Place players and ball for a new trial (the "placement" stream is for this)."""
        ...

    def minds(self, arena: Arena, rngs: TrialRngs) -> dict[PlayerRef, Mind]:
        """The client minds of the players that think (others stand still)."""
        ...

    def judge(self, arena: Arena) -> Verdict | None:
        """Called after every tick: a verdict ends the trial, None lets it run on."""
        ...

    def timeout(self, arena: Arena) -> Verdict:
        """The verdict when `max_time_s` runs out."""
        ...

    def data(self) -> tuple[float, ...]:
        """What the trial recorded for learning (empty when the drill records nothing)."""
        ...
