"""The robots' arena drives wheels for a per-step controller (WheelDrive), ideally if asked."""

from __future__ import annotations

import math

from field_models.arena import WheelDrive
from field_models.protocol import LEFT, PlayerRef
from field_models.registry import make_arena
from field_models.seeding import TrialRngs

ME = PlayerRef(LEFT, 1)


def drive(ideal: bool) -> tuple[float, int, int]:
    """Heading change, link packets lost and the first moving tick after wheels (0.1, 0.3)."""
    arena = make_arena("robot_physics", None, (ME,), TrialRngs(0, 0))
    assert isinstance(arena, WheelDrive)
    if ideal:
        arena.ideal_actuation()
    arena.place_player(ME, 0.0, 0.0, 0.0)
    first_moving = -1
    for tick in range(240):
        if tick % 8 == 0:
            arena.submit_wheels(ME, 0.1, 0.3)
        arena.step()
        if first_moving < 0 and arena.player_state(ME).speed > 0.0:
            first_moving = arena.tick
    lost = arena.link.lost  # type: ignore[attr-defined]
    return arena.player_state(ME).heading, lost, first_moving


def test_wheels_turn_the_robot_left_through_the_link() -> None:
    heading, _, first = drive(ideal=False)
    assert 0.5 < heading < math.pi  # right wheel faster: a left turn (2.7 rad/s for 1 s)
    assert first > 3  # the link's latency


def test_ideal_actuation_acts_at_once_and_loses_nothing() -> None:
    heading, lost, first = drive(ideal=True)
    assert lost == 0 and first <= 2 and heading > 0.5


def test_the_soccer_server_arena_has_no_wheels() -> None:
    arena = make_arena("soccer_server", None, (ME,), TrialRngs(0, 0))
    assert not isinstance(arena, WheelDrive)
