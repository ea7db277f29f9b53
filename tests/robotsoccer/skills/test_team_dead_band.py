"""The team minds' dead band (issue 28 item 5: robots that do not turn back and forth)."""

from __future__ import annotations

import dataclasses
import math

import pytest

from field_models.protocol import LEFT, RIGHT, Dash, Percept, Turn
from robotsoccer.drills.match import MatchDrill
from robotsoccer.drills.match_options import dead_band_teams
from robotsoccer.runs.runner import DrillOption, TrialLoop, TrialSpec, build_trial, run_trial
from robotsoccer.skills.reversals import TurnReversals
from robotsoccer.skills.team import TeamMind
from robotsoccer.skills.team_setup import REVERSE_HOLD_TICKS, TeamSetup

DEG = math.pi / 180.0


def _spec(preset: str, *extra: tuple[str, DrillOption]) -> TrialSpec:
    options: tuple[tuple[str, DrillOption], ...] = (
        ("left", "baseline"),
        ("right", "baseline"),
        ("half_time_s", 5.0),
        *extra,
    )
    return TrialSpec("match", "robot_physics", preset, drill_options=options)


def _minds(spec: TrialSpec) -> dict[str, list[TeamMind]]:
    rngs, drill, arena = build_trial(spec, 0)
    drill.setup(arena, rngs)
    minds = drill.minds(arena, rngs)
    out: dict[str, list[TeamMind]] = {LEFT: [], RIGHT: []}
    for ref, mind in minds.items():
        assert isinstance(mind, TeamMind)
        out[ref.team].append(mind)
    return out


def _setup(dead_band: bool) -> TeamSetup:
    mind = _minds(_spec("small_size_1997", ("dead_band", dead_band)))[LEFT][0]
    return mind.setup


def test_the_option_takes_both_one_team_or_none_and_refuses_the_rest() -> None:
    assert dead_band_teams(True) == dead_band_teams("TRUE") == {LEFT, RIGHT}
    assert dead_band_teams(False) == dead_band_teams("false") == frozenset()
    assert dead_band_teams("left") == {LEFT} and dead_band_teams("right") == {RIGHT}
    with pytest.raises(ValueError, match="dead_band must be one of false, true, left, right"):
        MatchDrill(left="baseline", right="baseline", dead_band="both")
    with pytest.raises(ValueError, match="dead_band must be one of"):
        dead_band_teams(1)  # type: ignore[arg-type]


def test_one_team_alone_gets_the_dead_band() -> None:
    minds = _minds(_spec("small_size_1997", ("dead_band", "right")))
    assert all(not m.setup.dead_band for m in minds[LEFT])
    assert all(m.setup.dead_band for m in minds[RIGHT])


def test_off_is_the_default_and_changes_nothing() -> None:
    plain = _spec("small_size_1997_arc")
    assert run_trial(plain, 0) == run_trial(_spec("small_size_1997_arc", ("dead_band", False)), 0)
    assert _setup(False).reverse_hold_ticks() == REVERSE_HOLD_TICKS


def test_the_turn_back_hold_lasts_the_server_s_ten_cycles_in_seconds() -> None:
    setup = _setup(True)
    assert setup.reverse_hold_ticks() * setup.dt_s == pytest.approx(1.0, abs=setup.dt_s)
    server = dataclasses.replace(setup, dt_s=0.1)
    assert server.reverse_hold_ticks() == REVERSE_HOLD_TICKS


def test_the_arrival_power_stops_the_player_where_it_was_going() -> None:
    setup = _setup(True)
    accel = setup.spin_accel_radps2 * setup.player_radius_m
    lag = setup.latency_s + setup.sensor_period_s
    assert setup.arrive_power(0.0) == 0.0
    assert setup.arrive_power(10.0) == 100.0
    d = 0.1
    v = setup.arrive_power(d) / 100.0 * setup.top_speed_mps
    assert v * lag + v * v / (2.0 * accel) == pytest.approx(d)
    assert setup.arrive_power(0.05) < setup.arrive_power(0.1)


def _mind() -> TeamMind:
    return _minds(_spec("small_size_1997", ("dead_band", True)))[LEFT][1]


def test_a_player_drives_on_while_on_course_and_backs_to_a_point_behind() -> None:
    mind = _mind()
    tolerance = mind.setup.home_tolerance_m
    # 1 m away, 30° off: it would miss by 0.5 m, so it turns, and drives as it does.
    far = mind._drive_to(30 * DEG, 1.0, tolerance, 80.0)
    assert far == (Turn(30 * DEG), Dash(80.0))
    # 5 cm away, 40° off: it passes within 3.2 cm of the point, under the 5.2 cm tolerance.
    near = mind._drive_to(40 * DEG, 0.05, tolerance, 80.0)
    assert len(near) == 1 and isinstance(near[0], Dash) and 0.0 < near[0].power < 80.0
    # Behind (170°): straight back, no turn; at 140° a 40° turn the other way, not 140°.
    assert mind._drive_to(170 * DEG, 1.0, tolerance, 80.0) == (Dash(-80.0),)
    back = mind._drive_to(140 * DEG, 1.0, tolerance, 80.0)
    assert isinstance(back[0], Turn) and back[0].angle_rad == pytest.approx(-40 * DEG)
    assert back[1] == Dash(-80.0)
    # Backing, it keeps backing at 100° (the switch waits 30° past the side) ...
    still = mind._drive_to(100 * DEG, 1.0, tolerance, 80.0)
    assert isinstance(still[-1], Dash) and still[-1].power < 0.0
    # ... and drives forwards again once the point is well ahead of its side.
    ahead = mind._drive_to(50 * DEG, 1.0, tolerance, 80.0)
    assert isinstance(ahead[-1], Dash) and ahead[-1].power > 0.0


def test_a_small_turn_back_within_a_second_is_left_out_a_large_one_is_not() -> None:
    mind = _mind()
    ticks = mind.setup.reverse_hold_ticks()
    mind._last_turn = (100, 30 * DEG)
    assert mind._steady(100 + ticks, (Turn(-90 * DEG), Dash(80.0))) == (Dash(80.0),)
    assert mind._steady(100 + ticks, (Turn(-130 * DEG),)) == (Turn(-130 * DEG),)
    mind._last_turn = (100, 30 * DEG)
    assert mind._steady(101 + ticks, (Turn(-90 * DEG),)) == (Turn(-90 * DEG),)


def _reversals(spec: TrialSpec) -> int:
    rngs, drill, arena = build_trial(spec, 0)
    drill.setup(arena, rngs)
    minds = drill.minds(arena, rngs)
    counter = TurnReversals()
    every = round(0.1 / arena.facts.dt_s)  # the Soccer Server's cycle, as the script samples

    def observe(a: object, percepts: list[Percept]) -> None:
        if arena.tick % every == 0:
            for ref in minds:
                counter.sample(ref, arena.player_state(ref).heading)

    TrialLoop(arena, drill, minds, observe).run()
    return counter.count


@pytest.mark.parametrize("preset", ["small_size_1997", "small_size_1997_arc"])
def test_robots_with_the_dead_band_turn_back_and_forth_less(preset: str) -> None:
    default = _reversals(_spec(preset))
    banded = _reversals(_spec(preset, ("dead_band", True)))
    assert banded < 0.6 * default
