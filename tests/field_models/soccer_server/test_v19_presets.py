"""The rcssserver 19 presets: a version-19 client's synchronised sees, and async ones (issue 28)."""

from __future__ import annotations

import math

import pytest

from field_models.presets import PresetError
from field_models.registry import field_facts
from field_models.soccer_server.arena import see_schedule
from field_models.soccer_server.cycle_rules import dash_rate
from field_models.soccer_server.params import load_server_preset
from field_models.soccer_server.sensing_params import SENSING_19


def test_rcssserver_19_sees_every_two_cycles_with_a_120_degree_view() -> None:
    synch, asynch = load_server_preset("rcssserver_19"), load_server_preset("rcssserver_19_async")
    assert synch.sensing.view_half_angle_rad == pytest.approx(math.radians(60.0))
    assert list(see_schedule(synch.sensing)[1:9]) == [False, True] * 4
    assert field_facts("soccer_server", "rcssserver_19").sensor_period_s == 0.2
    assert synch.dynamics == asynch.dynamics  # only the sensing differs
    assert synch.sensing == asynch.sensing.replace(
        send_step_ms=200, view_half_angle_rad=math.radians(60.0)
    )


def test_rcssserver_19_async_is_the_servers_own_parameters_with_sees_every_150_ms() -> None:
    asynch = load_server_preset("rcssserver_19_async")
    assert (asynch.name, asynch.era) == ("rcssserver_19_async", "19")
    assert asynch.sensing == SENSING_19
    # 1, 3, 4, 6, 7, ...: gaps of 1 and 2 cycles (specs/soccer_server.md §3.1)
    assert list(see_schedule(asynch.sensing)[1:9]) == [True, False, True] * 2 + [True, False]


def test_the_old_synch_name_is_refused_in_one_line_naming_the_presets() -> None:
    with pytest.raises(
        PresetError, match=r"unknown preset .*rcssserver_19_synch.*rcssserver_19_async"
    ):
        load_server_preset("rcssserver_19_synch")


def test_facts_give_the_servers_directed_dash_rates() -> None:
    facts = field_facts("soccer_server", "rcssserver_19")
    assert facts.dash_rates == (0.4, 0.7)
    assert facts.dash_angle_step_rad == pytest.approx(math.radians(1.0))
    for degrees in range(-180, 181, 5):
        direction = math.radians(degrees)
        assert facts.dash_factor(direction) == pytest.approx(dash_rate(direction, 0.4, 0.7))
    paper = field_facts("soccer_server", "soccer_server_1996")
    assert paper.dash_rates is None and paper.dash_factor(0.0) == 1.0
    assert paper.dash_factor(0.5) == 0.0


@pytest.mark.parametrize(
    ("preset", "top_mps"),
    [("soccer_server_1996", 100 * 0.016 / 0.1), ("rcssserver_19", 27.0)],
)
def test_a_kicks_top_speed_is_the_strongest_kick_within_the_balls_caps(
    preset: str, top_mps: float
) -> None:
    # 1996: no ball speed or acceleration cap (32 m/cycle, inf), so maxpower x kick_power_rate
    # bounds it; today the 2.7 m/cycle² acceleration cap equals that product.
    kick = field_facts("soccer_server", preset).kick
    assert kick is not None
    assert kick.max_speed_mps == pytest.approx(top_mps)
    assert kick.power_for(top_mps * 1.01) is None
    assert kick.power_for(top_mps) == pytest.approx(100.0)
