"""The one interface the runner, coaches, skills and recordings see, whatever the field model.

An *arena* is a field model together with its sensing and actuation: on the robots, the pymunk
world plus overhead camera, central host, link and firmware; on the Soccer Server model, the
server's dynamics plus its see/hear messages and command queue. The runner drives it tick by
tick (DESIGN.md §2):

    percepts = arena.step()              # one tick; percepts that reached clients now
    for p in percepts:
        arena.submit(p.player, mind.act(p))   # acted on from the next tick

Coaches use the truth side (place objects, read exact state); skills only ever get percepts.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Protocol

from field_models.protocol import Action, BodyState, Percept, Pitch, PlayerRef, Truth


@dataclass(frozen=True, slots=True)
class ArenaEvent:
    """Something worth a line in a recording or trace: a command sent, a packet lost, a goal.

    Attributes:
        tick: When it happened.
        channel: Short category, e.g. ``"command"``, ``"link"``, ``"referee"``, ``"message"``.
        text: Human-readable description.
        player: The player it concerns, if any.
    """

    tick: int
    channel: str
    text: str
    player: PlayerRef | None = None


class Arena(Protocol):
    """A field model with sensing and actuation, stepped one integer tick at a time."""

    model_name: str
    """``"robot_physics"`` or ``"soccer_server"``."""
    dt_s: float
    """Length of one tick [s]."""

    @property
    def tick(self) -> int:
        """Ticks stepped since the trial began."""
        ...

    pitch: Pitch
    """Field geometry."""
    players: tuple[PlayerRef, ...]
    """Players on the field, in a fixed order."""

    # --- coach side: truth ---------------------------------------------------------------
    def place_player(self, ref: PlayerRef, x: float, y: float, heading: float) -> None:
        """Put a player at rest at (x, y) [m] facing `heading` [rad]."""
        ...

    def place_ball(self, x: float, y: float, vx: float = 0.0, vy: float = 0.0) -> None:
        """Put the ball at (x, y) [m] with velocity (vx, vy) [m/s]."""
        ...

    def ball_state(self) -> BodyState:
        """The ball's exact state (coach only)."""
        ...

    def player_state(self, ref: PlayerRef) -> BodyState:
        """A player's exact state (coach only)."""
        ...

    def truth(self) -> Truth:
        """Exact state of everything (coach and recordings only)."""
        ...

    # --- client side: percepts and actions -------------------------------------------------
    def step(self) -> list[Percept]:
        """Advance one tick; return the percepts that reach their clients at the new tick."""
        ...

    def listen(self, refs: frozenset[PlayerRef]) -> None:
        """Build percepts only for these players from now on (default: every player).

        The runner calls it with the players whose minds still think; a field model may then
        skip sensing the others (a speed-up: their percepts would go unread).
        """
        ...

    def submit(self, ref: PlayerRef, actions: tuple[Action, ...]) -> None:
        """Hand a client's actions to the actuation path (acted on from the next tick)."""
        ...

    def drain_events(self) -> list[ArenaEvent]:
        """Events since the last call (commands, losses, referee messages), oldest first."""
        ...
