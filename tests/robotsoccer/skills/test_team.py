"""Team minds: localisation from landmarks, the chaser rule, kicks on the ball, turn holds."""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable

import numpy as np
import numpy.typing as npt
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
from learning.pass_features import (
    HALF,
    estimated_receiver_half,
    pass_attributes,
    passer_attributes,
    unknown_half,
)
from robotsoccer.skills.localise import Localiser
from robotsoccer.skills.passing import view_arrays
from robotsoccer.skills.setplay import KickPowers
from robotsoccer.skills.team import TeamMind
from robotsoccer.skills.team_setup import TeamSetup

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


class _Recorder:
    """A pass evaluator that keeps every attribute row it is asked about."""

    def __init__(self, confidence: Callable[[npt.NDArray[np.float64]], float]) -> None:
        self.rows: list[npt.NDArray[np.float64]] = []
        self.confidence = confidence

    def success_confidence(self, x: npt.NDArray[np.float64]) -> float:
        self.rows.append(np.array(x))
        return self.confidence(x)


BLOCKED = (
    SeenPlayer(5.0, 0.0, RIGHT, 3),
    SeenPlayer(12.0, 0.6, LEFT, 9),
    SeenPlayer(25.0, -0.4, LEFT, 10),
)


def _passer_half(index: int) -> npt.NDArray[np.float64]:
    seen = BLOCKED[index]
    dist, ang, team = view_arrays([s for s in BLOCKED if s is not seen], LEFT, 1.0)
    return passer_attributes(seen.distance_m, math.degrees(seen.angle_rad), dist, ang, team)


def test_the_layered_passer_asks_the_tree_with_the_receivers_half_unknown_by_default() -> None:
    tree = _Recorder(lambda x: 0.9)
    mind = TeamMind(7, setup(), evaluator=tree)
    (kick,) = mind.act(percept(-20.0, 0.0, 0.0, ball=SeenBall(0.5, 0.0), players=BLOCKED))
    # Every answer equal: the first passable teammate in the percept's list.
    assert mind.intent == "pass 9" and isinstance(kick, Kick)
    expected = [pass_attributes(_passer_half(i), unknown_half()) for i in (1, 2)]
    assert len(tree.rows) == 2
    for got, want in zip(tree.rows, expected, strict=True):
        np.testing.assert_array_equal(got, want)


def test_with_the_estimated_half_the_tree_sees_the_receivers_surroundings() -> None:
    # Estimated, mate 9 (12 m, 34°) would see the opponent 8.4 m from it and mate 10 (25 m,
    # -23°) 20.5 m from it. A tree that likes a receiver whose nearest opponent is over 15 m
    # away picks 10; with the half unknown it cannot tell them apart and the first, 9, goes.
    def likes_space(x: npt.NDArray[np.float64]) -> float:
        return 0.9 if x[HALF + 20] > 15.0 else 0.6  # "receiver opponent1 distance"

    blind = TeamMind(7, setup(), evaluator=_Recorder(likes_space))
    blind.act(percept(-20.0, 0.0, 0.0, ball=SeenBall(0.5, 0.0), players=BLOCKED))
    assert blind.intent == "pass 9"
    tree = _Recorder(likes_space)
    mind = TeamMind(7, dataclasses.replace(setup(), receiver_half="estimated"), evaluator=tree)
    (kick,) = mind.act(percept(-20.0, 0.0, 0.0, ball=SeenBall(0.5, 0.0), players=BLOCKED))
    assert mind.intent == "pass 10" and isinstance(kick, Kick)
    assert kick.direction_rad == pytest.approx(-0.4)
    for index, got in zip((1, 2), tree.rows, strict=True):
        seen = BLOCKED[index]
        dist, ang, team = view_arrays([s for s in BLOCKED if s is not seen], LEFT, 1.0)
        theirs = estimated_receiver_half(
            seen.distance_m, math.degrees(seen.angle_rad), dist, ang, team
        )
        np.testing.assert_array_equal(got, pass_attributes(_passer_half(index), theirs))
        assert not np.isnan(got[HALF:]).all()


def test_a_bad_receiver_half_is_refused() -> None:
    with pytest.raises(ValueError, match="receiver_half: expected one of unknown, estimated"):
        dataclasses.replace(setup(), receiver_half="heard")


def test_after_a_turn_it_waits_for_a_percept_that_shows_it() -> None:
    slow = dataclasses.replace(setup(), latency_s=0.5)
    mind = TeamMind(7, slow)
    first = mind.act(percept(0.0, 0.0, 0.0, ball=SeenBall(20.0, 1.0), tick=10))
    assert isinstance(first[0], Turn)
    # A later percept sampled before the turn could show: nothing new is decided.
    assert mind.act(percept(0.0, 0.0, 0.0, ball=SeenBall(20.0, 1.0), tick=12, observed=11)) == ()
    later = mind.act(percept(0.0, 0.0, 1.0, ball=SeenBall(20.0, 0.0), tick=30, observed=29))
    assert later == (Dash(100.0),)


# ---------------------------------------------------------------------- pushing teams (robots)


def pushing(**changes: float) -> TeamSetup:
    """The plan of a team that pushes the ball, seen by an overhead camera (the robots)."""
    base = dataclasses.replace(
        setup(),
        sensor_period_s=0.1,  # a velocity fit over two sightings
        push_kick=True,
        sees_all_round=True,
        player_radius_m=0.5,
        goal_width_m=14.0,
        lead_from_m=5.0,
        lead_trigger_m=30.0,
        goalie_depth_m=4.0,
        turn_tolerance_rad=0.05,
    )
    return dataclasses.replace(base, **changes)


def ball_at(x: float, y: float, heading: float, bx: float, by: float) -> SeenBall:
    """The ball at (bx, by) as a player at (x, y) facing `heading` sees it."""
    return SeenBall(math.hypot(bx - x, by - y), wrap_angle(math.atan2(by - y, bx - x) - heading))


def rolling(
    mind: TeamMind, x: float, y: float, heading: float, track: list[tuple[float, float]]
) -> tuple:
    """Show `mind` the ball at each point of `track`, one percept a tick; the last decision."""
    actions: tuple = ()
    for i, (bx, by) in enumerate(track):
        tick = 10 + i
        actions = mind.act(percept(x, y, heading, ball=ball_at(x, y, heading, bx, by), tick=tick))
    return actions


def test_a_pusher_goal_side_of_the_ball_goes_round_it_not_through_it() -> None:
    mind = TeamMind(7, pushing())
    # It stands between the ball and the goal it attacks (+x), facing the ball.
    (turn, dash) = rolling(mind, 10.0, 0.0, math.pi, [(5.0, 0.0), (5.0, 0.0)])
    assert mind.intent == "approach" and dash == Dash(100.0)
    # Round the ball on its own side: to (5, 2 * (radius + reach)), not at the ball (angle 0).
    assert isinstance(turn, Turn)
    assert turn.angle_rad == pytest.approx(wrap_angle(math.atan2(3.0, -5.0) - math.pi))


def test_a_pusher_behind_the_ball_runs_through_it_and_pushes_it_goalward() -> None:
    mind = TeamMind(7, pushing())
    assert rolling(mind, 0.0, 0.0, 0.0, [(5.0, 0.0), (5.0, 0.0)]) == (Dash(100.0),)
    assert mind.intent == "chase"
    on_ball = TeamMind(7, pushing())
    (kick,) = rolling(on_ball, -20.0, 0.0, 0.0, [(-19.5, 0.0), (-19.5, 0.0)])
    assert on_ball.intent == "dribble" and isinstance(kick, Kick)


def test_a_ball_rolling_at_a_player_toward_its_own_end_is_met_straight_or_with_the_lead() -> None:
    track = [(-10.0, 5.0), (-11.0, 5.0)]  # 10 m/s toward its own goal (-x)
    straight = TeamMind(7, pushing())
    (turn, dash) = rolling(straight, -20.0, 0.0, 0.0, track)
    assert straight.intent == "meet" and dash == Dash(100.0)
    assert isinstance(turn, Turn) and turn.angle_rad == pytest.approx(math.atan2(5.0, 9.0))
    led = TeamMind(7, pushing(), lead=lambda bd, angle, previous: 0.5)
    (turn, _) = rolling(led, -20.0, 0.0, 0.0, track)
    # The lead aims 0.5 s ahead along the ball's track: at (-16, 5).
    assert led.intent == "intercept"
    assert isinstance(turn, Turn) and turn.angle_rad == pytest.approx(math.atan2(5.0, 4.0))


def test_the_lead_is_asked_only_of_a_free_ball_from_its_drill_range() -> None:
    track = [(-10.0, 5.0), (-11.0, 5.0)]
    mind = TeamMind(7, pushing(), lead=lambda bd, angle, previous: 0.5)
    for i, (bx, by) in enumerate(track):
        ball = ball_at(-20.0, 0.0, 0.0, bx, by)
        near = SeenPlayer(ball.distance_m + 0.5, ball.angle_rad, RIGHT, 4)  # pushing it on
        actions = mind.act(percept(-20.0, 0.0, 0.0, ball=ball, players=(near,), tick=10 + i))
    assert mind.intent == "intercept"
    (turn, _) = actions
    assert isinstance(turn, Turn) and turn.angle_rad == pytest.approx(math.atan2(5.0, 9.0))
    close = TeamMind(7, pushing(lead_from_m=20.0), lead=lambda bd, angle, previous: 0.5)
    (turn, _) = rolling(close, -20.0, 0.0, 0.0, track)
    assert isinstance(turn, Turn) and turn.angle_rad == pytest.approx(math.atan2(5.0, 9.0))


def test_a_ball_rolling_at_a_player_toward_the_other_end_is_played_from_behind() -> None:
    mind = TeamMind(7, pushing())
    rolling(mind, 0.0, 0.0, math.pi, [(-10.0, 0.0), (-9.0, 0.0)])  # toward +x, at the player
    assert mind.intent == "approach"


def test_a_goalie_cuts_its_turn_hold_short_for_a_shot_at_its_goal() -> None:
    goal_x = -52.5 + 4.0
    track = [(-30.0, 2.0), (-31.0, 2.0), (-32.0, 2.0)]  # on target, rolling at the goalie

    def play(sees_all_round: bool) -> tuple:
        mind = TeamMind(1, pushing(latency_s=5.0, sees_all_round=sees_all_round))
        # Far from its spot and facing away: it turns to go there, and holds for the turn.
        first = mind.act(percept(goal_x + 8.0, 6.0, 0.0, ball=ball_at(goal_x + 8, 6, 0, 0, 20)))
        assert isinstance(first[0], Turn)
        return rolling(mind, goal_x, 0.0, 0.0, track), mind

    actions, mind = play(True)
    assert mind.intent == "meet" and actions and actions[-1] == Dash(100.0)
    actions, _ = play(False)
    assert actions == ()  # the paper's client holds on until its turn shows


def test_under_an_overhead_camera_a_missed_ball_is_no_reason_to_turn() -> None:
    seen = TeamMind(7, pushing())
    seen.act(percept(0.0, 0.0, 0.0, ball=SeenBall(10.0, 0.0), tick=10))
    assert seen.act(percept(0.0, 0.0, 0.0, tick=11)) == ()
    cone = TeamMind(7, setup())
    cone.act(percept(0.0, 0.0, 0.0, ball=SeenBall(10.0, 0.0), tick=10))
    assert isinstance(cone.act(percept(0.0, 0.0, 0.0, tick=11))[0], Turn)
