"""The rcssserver_19_synch preset: what a version-19 client's synchronised sees give (issue 28)."""

from __future__ import annotations

import math

import pytest

from field_models.registry import field_facts
from field_models.soccer_server.arena import see_schedule
from field_models.soccer_server.params import load_server_preset


def test_a_see_every_two_cycles_with_a_120_degree_view() -> None:
    synch, asynch = load_server_preset("rcssserver_19_synch"), load_server_preset("rcssserver_19")
    assert synch.sensing.view_half_angle_rad == pytest.approx(math.radians(60.0))
    assert list(see_schedule(synch.sensing)[1:9]) == [False, True] * 4
    assert field_facts("soccer_server", "rcssserver_19_synch").sensor_period_s == 0.2
    assert synch.dynamics == asynch.dynamics  # only the sensing differs
