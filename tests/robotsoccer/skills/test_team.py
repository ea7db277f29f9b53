"""Team minds: localisation from landmarks, the chaser rule, kicks on the ball, turn holds."""

from __future__ import annotations

import dataclasses
import math

import pytest

from field_models.protocol import (
    LEFT,
    RIGHT,
    Dash,
    Kick,
    Percept,
    PlayerRef,
    SeenBall,
    SeenLandmark,
    SeenPlayer,
    Turn,
    wrap_angle,
)
from robotsoccer.skills.setplay import KickPowers
from robotsoccer.skills.team import Localiser, TeamMind, TeamSetup

MARKS = (("g l", -52.5, 0.0), ("g r", 52.5, 0.0), ("f c t", 0.0, 34.0))
ME = PlayerRef(LEFT, 7)


def seen_mark(name: str, x: float, y: float, heading: float) -> SeenLandmark:
    """The landmark `name` as a player at (x, y) facing `heading` sees it."""
    where = {n: (mx, my) for n, mx, my in MARKS}[name]
    dx, dy = where[0] - x, where[1] - y
    return SeenLandmark(name, math.hypot(dx, dy), wrap_angle(math.atan2(dy, dx) - heading))


def percept(
    x: float,
    y: float,
    heading: float,
    marks: tuple[str, ...] = ("g l", "g r"),
    ball: SeenBall | None = None,
    players: tuple[SeenPlayer, ...] = (),
    tick: int = 10,
    observed: int | None = None,
) -> Percept:
    """A percept of ME at that pose with these landmarks (exact)."""
    seen = tuple(seen_mark(n, x, y, heading) for n in marks)
    obs = tick if observed is None else observed
    return Percept(ME, tick, obs, ball, players, (), seen)


@pytest.mark.parametrize("pose", [(10.0, -5.0, 0.3), (-30.0, 20.0, -2.8), (0.0, 0.0, math.pi / 2)])
def test_two_landmarks_give_the_exact_pose(pose: tuple[float, float, float]) -> None:
    x, y, heading = pose
    got = Localiser(MARKS).update(percept(x, y, heading, ("g l", "g r", "f c t")))
    assert got is not None
    assert got.x == pytest.approx(x, abs=1e-9)
    assert got.y == pytest.approx(y, abs=1e-9)
    assert wrap_angle(got.heading - heading) == pytest.approx(0.0, abs=1e-9)


def test_one_landmark_keeps_the_heading_and_none_keeps_the_pose() -> None:
    localiser = Localiser(MARKS)
    localiser.update(percept(5.0, 5.0, 0.5))
    moved = localiser.update(percept(8.0, 5.0, 0.5, ("g r",)))
    assert moved is not None and moved.x == pytest.approx(8.0)
    assert moved.heading == pytest.approx(0.5)
    assert localiser.update(percept(0.0, 0.0, 0.0, ())) is moved
    assert Localiser(MARKS).update(percept(0.0, 0.0, 0.0, ("g r",))) is None


def setup(reach: float = 1.0) -> TeamSetup:
    return TeamSetup(
        attack_right=True,
        home={n: (-10.0 * n, 0.0) for n in range(1, 12)},
        goalie=1,
        landmarks=MARKS,
        unit_m=1.0,
        reach_m=reach,
        blocked_m=8.0,
        shoot_range_m=25.0,
        pass_range_m=30.0,
        trigger_distance_m=14.0,
        goalie_zone_m=16.5,
        home_tolerance_m=2.0,
        powers=KickPowers(dribble=20.0, passing=60.0, shot=100.0),
        half_length_m=52.5,
        half_width_m=34.0,
        dt_s=0.1,
        latency_s=0.0,
        spin_accel_radps2=1e6,
    )


def test_a_player_with_a_teammate_nearer_the_ball_goes_home() -> None:
    ball = SeenBall(10.0, 0.0)
    mate = SeenPlayer(10.5, 0.05, LEFT, 8)  # about 0.7 m from the ball
    mind = TeamMind(7, setup())
    mind.act(percept(0.0, 0.0, 0.0, ball=ball, players=(mate,)))
    assert not mind.chasing and mind.intent == "home"
    alone = TeamMind(7, setup())
    actions = alone.act(percept(0.0, 0.0, 0.0, ball=ball))
    assert alone.chasing and actions == (Dash(100.0),)


def test_on_the_ball_it_shoots_near_the_goal_and_dribbles_far_from_it() -> None:
    near = TeamMind(7, setup())
    actions = near.act(percept(40.0, 3.0, 0.0, ball=SeenBall(0.5, 0.0)))
    assert near.intent == "shoot" and near.shots == 1
    (kick,) = actions
    assert isinstance(kick, Kick) and kick.power == 100.0
    assert kick.direction_rad == pytest.approx(math.atan2(-3.0, 12.5), abs=1e-9)
    far = TeamMind(7, setup())
    (dribble,) = far.act(percept(-20.0, 0.0, 0.0, ball=SeenBall(0.5, 0.0)))
    assert far.intent == "dribble" and isinstance(dribble, Kick) and dribble.power == 20.0


def test_blocked_the_baseline_passes_to_the_closest_teammate_ahead() -> None:
    opponent = SeenPlayer(5.0, 0.0, RIGHT, 3)
    near_mate = SeenPlayer(12.0, 0.6, LEFT, 9)
    far_mate = SeenPlayer(25.0, -0.4, LEFT, 10)
    mind = TeamMind(7, setup())
    ball = SeenBall(0.5, 0.0)
    (kick,) = mind.act(percept(-20.0, 0.0, 0.0, ball=ball, players=(opponent, near_mate, far_mate)))
    assert mind.intent == "pass 9" and isinstance(kick, Kick)
    assert kick.direction_rad == pytest.approx(0.6) and kick.power == 60.0


def test_after_a_turn_it_waits_for_a_percept_that_shows_it() -> None:
    slow = dataclasses.replace(setup(), latency_s=0.5)
    mind = TeamMind(7, slow)
    first = mind.act(percept(0.0, 0.0, 0.0, ball=SeenBall(20.0, 1.0), tick=10))
    assert isinstance(first[0], Turn)
    # A later percept sampled before the turn could show: nothing new is decided.
    assert mind.act(percept(0.0, 0.0, 0.0, ball=SeenBall(20.0, 1.0), tick=12, observed=11)) == ()
    later = mind.act(percept(0.0, 0.0, 1.0, ball=SeenBall(20.0, 0.0), tick=30, observed=29))
    assert later == (Dash(100.0),)
