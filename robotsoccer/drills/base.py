"""What a drill is: the coach's side of a trial (who plays, where they start, how it ends)."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Protocol

from field_models.arena import Arena, FieldFacts
from field_models.protocol import Crossing, Mind, PlayerRef, end_line_crossing
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

    def field_settings(self, facts: FieldFacts) -> dict[str, float]:
        """Field settings the drill needs on this field (e.g. a scaled noise period), or {}.

        Keys are :class:`~field_models.arena.FieldOptions` names. The runner applies them
        when it builds the arena; a setting the TrialSpec gives itself wins.
        """
        ...

    def inputs(self) -> tuple[str, ...]:
        """Files the trials read (model files): a resumed run checks they did not change."""
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

    def measures(self) -> dict[str, float]:
        """What the coach measured in the trial, by name, for reports (may be empty)."""
        ...


class GoalWatch:
    """Follows the ball tick by tick for end-line crossings, and the field's referee for goals.

    The one goal-line rule is :func:`~field_models.protocol.end_line_crossing`; a field whose
    referee restarts play at once after a goal (the 1996 Soccer Server puts the ball back on the
    centre spot in the same cycle) never shows the crossing to a coach, so a change of
    :meth:`Arena.score <field_models.arena.Arena.score>` counts as the crossing it stands for.
    """

    def __init__(self, arena: Arena, ball: tuple[float, float]) -> None:
        self.pitch = arena.facts.pitch
        self.line = 0.5 * self.pitch.length_m + self.pitch.ball_radius_m
        self.last = ball
        self.score = arena.score()

    def step(self, arena: Arena, x: float, y: float) -> Crossing:
        """How the ball crossed an end line since the last call (NONE: it did not)."""
        lx, ly = self.last
        self.last = (x, y)
        score = arena.score()
        if score != self.score:
            left_scored = score[0] > self.score[0]
            self.score = score
            return Crossing.RIGHT_GOAL if left_scored else Crossing.LEFT_GOAL
        if -self.line <= x <= self.line:  # inside: no crossing to ask the rule about
            return _NONE
        return end_line_crossing(self.pitch, lx, ly, x, y)


_NONE = Crossing.NONE
