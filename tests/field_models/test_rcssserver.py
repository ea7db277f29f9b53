"""The rcssserver field model: a Soccer Server over UDP behind the Arena interface.

The conformance suite runs on it in ``tests/field_models/test_conformance.py`` (the ``served``
preset: our model served in-process; the ``binary`` preset when ``RCSSSERVER`` names a real
rcssserver, skipped otherwise). These tests cover what is particular to the wire.
"""

from __future__ import annotations

import math
import os
import threading

import pytest

from field_models.protocol import LEFT, RIGHT, Dash, PlayerRef
from field_models.registry import DEFAULT_OPTIONS, entry, make_arena
from field_models.seeding import TrialRngs


def test_a_trial_with_gaps_in_the_numbers_connects_and_closes_its_server() -> None:
    players = (PlayerRef(LEFT, 2), PlayerRef(RIGHT, 1))
    before = threading.active_count()
    arena = make_arena("rcssserver", "served", players, TrialRngs.for_trial(0, 0))
    arena.place_player(players[0], -5.0, 0.0, 0.0)
    arena.place_player(players[1], 5.0, 0.0, math.pi)
    arena.place_ball(0.0, 3.0)
    assert set(arena.truth().players) == set(players)  # the filler (left 1) said bye
    seen = []
    for _ in range(10):
        for percept in arena.step():
            seen.append(percept)
            arena.submit(percept.player, (Dash(50.0),))
    assert {p.player for p in seen} == set(players)
    assert arena.player_state(players[0]).x > -5.0  # dashed toward +x
    arena.close()  # type: ignore[attr-defined]
    assert threading.active_count() == before


def test_the_binary_preset_says_why_it_cannot_run_without_rcssserver() -> None:
    if os.environ.get("RCSSSERVER"):
        pytest.skip("RCSSSERVER is set: the conformance suite runs the real server")
    module = entry("rcssserver")
    preset = module.load("binary", DEFAULT_OPTIONS)
    with pytest.raises(RuntimeError, match="RCSSSERVER"):
        make_arena("rcssserver", "binary", (PlayerRef(LEFT, 1),), TrialRngs.for_trial(0, 0))
    assert "RCSSSERVER" in (module.unavailable(preset) or "")  # type: ignore[attr-defined]
