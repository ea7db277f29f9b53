"""Layer 3 on the field: destinations, their features from the tree, the kick, the rewards."""

from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import pytest

from field_models.protocol import (
    LEFT,
    RIGHT,
    Kick,
    Percept,
    PlayerRef,
    SeenBall,
    SeenLandmark,
    SeenPlayer,
)
from learning.tpot import FAILURE, MISS, N_ACTIONS, SUCCESS, TpotTable
from robotsoccer.skills.layer3 import DESTINATIONS, TpotBallPolicy, TpotSettings, destination_xy
from robotsoccer.skills.localise import Pose
from robotsoccer.skills.passing import open_play_attributes
from robotsoccer.skills.setplay import KickPowers
from robotsoccer.skills.team_setup import TeamSetup
from tests.robotsoccer.skills.test_team import setup as team_setup

HALF_L, HALF_W = 52.5, 34.0


class Fixed:
    """An evaluator whose confidence is fixed."""

    def __init__(self, confidence: float) -> None:
        self.confidence = confidence

    def success_confidence(self, x: np.ndarray) -> float:
        assert x.shape == (174,)
        return self.confidence


def plan(attack_right: bool = True) -> TeamSetup:
    """The team's plan the policies play by: the pitch, 30 m passes at power 80, 25 m shots."""
    powers = KickPowers(dribble=20.0, passing=80.0, shot=100.0)
    return replace(team_setup(), attack_right=attack_right, powers=powers)


def policy(
    confidence: float, *, attack_right: bool = True, learn: bool = False, window: str = "choice"
) -> TpotBallPolicy:
    settings = TpotSettings(learn=learn, window=window)
    return TpotBallPolicy(
        TpotTable.empty(11),
        plan(attack_right),
        Fixed(confidence),
        np.random.default_rng(0),
        settings,
    )


def percept(*players: SeenPlayer, team: str = LEFT, tick: int = 10) -> Percept:
    return Percept(PlayerRef(team, 7), tick, tick, SeenBall(0.5, 0.0), players)


def test_destinations_are_eight_and_mirror_for_the_team_attacking_left() -> None:
    assert len(DESTINATIONS) == N_ACTIONS
    for a in range(N_ACTIONS):
        x, y = destination_xy(a, True, HALF_L, HALF_W)
        assert (-x, -y) == destination_xy(a, False, HALF_L, HALF_W)
        assert 0.0 <= x <= HALF_L and abs(y) < HALF_W  # level or ahead, inside the touchlines
    assert destination_xy(0, True, HALF_L, HALF_W) == (HALF_L, 0.0)


@pytest.mark.parametrize(("confidence", "verdict"), [(0.9, SUCCESS), (0.2, FAILURE)])
def test_a_teammate_toward_a_destination_gets_the_tree_s_verdict_the_rest_miss(
    confidence: float, verdict: int
) -> None:
    # At the centre spot facing +x: the goal (destination 0) dead ahead; a teammate 10 m away,
    # 5 degrees to the left, is a pass toward it; one 3 m away is too near to count.
    mate = SeenPlayer(10.0, math.radians(5.0), LEFT, 9)
    near = SeenPlayer(3.0, 0.0, LEFT, 8)
    foe = SeenPlayer(8.0, 0.0, RIGHT, 4)
    options = policy(confidence).options(percept(mate, near, foe), Pose(0.0, 0.0, 0.0))
    assert options.features[0] == verdict
    assert options.directions[0] == pytest.approx(math.radians(5.0))  # kick to the mate
    assert options.features[5] == verdict  # centre ahead: the same direction from the spot
    for a in (1, 2, 3, 4, 6, 7):
        assert options.features[a] == MISS
    # a destination with no one toward it is kicked at the point itself
    x, y = destination_xy(6, True, HALF_L, HALF_W)
    assert options.directions[6] == pytest.approx(math.atan2(y, x))


def test_the_choice_is_a_pass_kick_and_its_reward_comes_from_the_ball_s_advance() -> None:
    mate = SeenPlayer(10.0, 0.0, LEFT, 9)
    p = policy(0.9, learn=True)
    p.table.q[6, SUCCESS, 5] = 0.3  # player 7 has learned that "centre ahead" pays
    decided = p.decide(7, percept(mate), Pose(0.0, 0.0, 0.0), (0.0, 0.0))
    assert decided is not None
    intent, actions = decided
    assert intent == "tpot centre ahead"
    assert actions == (Kick(80.0, 0.0),)
    p.observe(7, 11, (26.25, 0.0))  # the ball seen half way to the opponents' goal
    p.observe(7, 12, None)  # not seen: no sample
    p.finish(20)
    (e,) = p.experiences
    assert (e.number, e.feature, e.action) == (7, SUCCESS, 5)
    assert e.reward == pytest.approx(26.25 / 52.5)  # the mean sample: half way to the goal
    assert p.choices[5] == 1


def test_a_goal_fixes_every_pending_reward_and_the_horizon_fixes_one() -> None:
    p = policy(0.9, attack_right=False, learn=True)
    p.decide(7, percept(tick=0), Pose(10.0, 0.0, math.pi), (10.0, 0.0))
    p.decide(3, percept(tick=0), Pose(20.0, 0.0, math.pi), (20.0, 0.0))
    p.goal(False, 100)  # conceded 10 s later (dt 0.1 s)
    assert [e.reward for e in p.experiences] == pytest.approx([-0.75, -0.75])
    p.decide(7, percept(tick=200), Pose(0.0, 0.0, math.pi), (0.0, 0.0))
    p.observe(7, 210, (-52.5, 0.0))  # attacking -x: the ball at the opponents' goal line
    p.observe(7, 200 + 300, (52.5, 0.0))  # 30 s later: the horizon fixed it before this sample
    assert p.experiences[-1].reward == pytest.approx(1.0)
    p.finish(600)
    assert len(p.experiences) == 3


def _two_choices_then_the_ball_lost(window: str) -> list[float]:
    """Player 7 kicks at tick 0 (ball at the centre spot), sees the ball half way to the
    opponents' goal, has it again at tick 20 and kicks, then sees it at its own goal line."""
    p = policy(0.9, learn=True, window=window)
    p.decide(7, percept(tick=0), Pose(0.0, 0.0, 0.0), (0.0, 0.0))
    p.observe(7, 10, (26.25, 0.0))
    p.decide(7, percept(tick=20), Pose(26.25, 0.0, 0.0), (26.25, 0.0))
    p.observe(7, 30, (-52.5, 0.0))
    p.finish(40)
    assert [e.number for e in p.experiences] == [7, 7]
    return [e.reward for e in p.experiences]


def test_the_choice_window_closes_at_the_next_choice_the_horizon_window_does_not() -> None:
    # The first kick's ball went half way up; after the second kick it was lost to the own goal
    # line. Closed at the next choice the first kick earns +0.5 (only the half-way sighting);
    # over the fixed window it also sees the loss: mean x (26.25 - 52.5) / 2 = -13.125 m, a
    # quarter of the way back to the own goal line.
    assert _two_choices_then_the_ball_lost("choice") == pytest.approx([0.5, -1.0])
    # horizon: fixed at full time in order of the actions; the second kick's reward is the same
    assert _two_choices_then_the_ball_lost("horizon") == pytest.approx([-0.25, -1.0])


def test_a_stop_closes_only_the_horizon_window_s_rewards_and_the_horizon_each_its_own() -> None:
    for window, fixed in (("choice", 0), ("horizon", 1)):
        p = policy(0.9, learn=True, window=window)
        p.decide(7, percept(tick=0), Pose(0.0, 0.0, 0.0), (0.0, 0.0))
        p.observe(7, 10, (26.25, 0.0))
        p.stopped(15)  # the referee's restart call
        assert len(p.experiences) == fixed
    p = policy(0.9, learn=True, window="horizon")
    p.decide(7, percept(tick=0), Pose(0.0, 0.0, 0.0), (0.0, 0.0))
    p.decide(7, percept(tick=100), Pose(0.0, 0.0, 0.0), (0.0, 0.0))
    p.observe(7, 300, (52.5, 0.0))  # 30 s after the first kick: it closes, the second does not
    assert len(p.experiences) == 1 and p.experiences[0].reward == 0.0
    p.observe(7, 350, (52.5, 0.0))
    p.goal(True, 360)  # 26 s after the second kick: a goal within its window
    assert p.experiences[1].reward == pytest.approx(30.0 / 56.0)
    with pytest.raises(ValueError, match="window must be one of choice, horizon"):
        policy(0.9, window="episode")


def test_without_a_pose_the_policy_leaves_the_decision_to_the_layered_rule() -> None:
    assert policy(0.9).decide(7, percept(), None, (0.0, 0.0)) is None


class Recording:
    """A ball policy that records what the mind asks and tells it."""

    def __init__(self) -> None:
        self.asked = 0
        self.seen: list[tuple[int, int, tuple[float, float] | None]] = []

    def decide(
        self, number: int, percept: Percept, pose: Pose | None, ball_xy: tuple[float, float] | None
    ) -> tuple[str, tuple[Kick, ...]]:
        self.asked += 1
        return ("tpot test", (Kick(42.0, 0.25),))

    def observe(self, number: int, tick: int, ball_xy: tuple[float, float] | None) -> None:
        self.seen.append((number, tick, ball_xy))


def test_the_mind_asks_its_ball_policy_only_where_it_would_pass_and_once_a_spell() -> None:
    from robotsoccer.skills.team import TeamMind
    from tests.robotsoccer.skills.test_team import percept as team_percept
    from tests.robotsoccer.skills.test_team import setup

    ball = SeenBall(0.5, 0.0)
    free = Recording()
    mind = TeamMind(7, setup(), ball_policy=free)
    mind.act(team_percept(-20.0, 0.0, 0.0, ball=ball))  # nobody in the path: it dribbles
    assert mind.intent == "dribble" and free.asked == 0
    assert free.seen == [(7, 10, pytest.approx((-19.5, 0.0)))]
    blocked = Recording()
    mind = TeamMind(7, setup(), ball_policy=blocked)
    foe = SeenPlayer(5.0, 0.0, RIGHT, 3)
    for tick in (10, 11):  # the ball still in reach at the next percept: the same kick
        (kick,) = mind.act(team_percept(-20.0, 0.0, 0.0, ball=ball, players=(foe,), tick=tick))
        assert kick == Kick(42.0, 0.25) and mind.intent == "tpot test"
    assert blocked.asked == 1 and mind.passes == 1


def every_policy(
    confidence: float, threshold: float = 0.5, **extra: bool | float | str
) -> TpotBallPolicy:
    """A policy with TPOT-RL's own rule: shoot and keep among the destinations."""
    settings = TpotSettings(threshold=threshold, every_ball=True, **extra)  # type: ignore[arg-type]
    return TpotBallPolicy(
        TpotTable.empty(11), plan(), Fixed(confidence), np.random.default_rng(0), settings
    )


def test_with_every_ball_the_goal_is_a_shot_judged_by_range_and_path() -> None:
    p = every_policy(0.9)
    near_goal = Pose(35.0, 0.0, 0.0)  # 17.5 m from the goal, facing it
    assert p.options(percept(), near_goal).features[0] == SUCCESS
    foe = SeenPlayer(5.0, math.radians(10.0), RIGHT, 1)  # in the path, within 8 m
    assert p.options(percept(foe), near_goal).features[0] == FAILURE
    assert p.options(percept(), Pose(0.0, 0.0, 0.0)).features[0] == MISS  # 52.5 m: out of range
    intent, kick = p.kick(0, p.options(percept(), near_goal))
    assert intent == "tpot shoot" and kick == Kick(100.0, 0.0)


def test_with_every_ball_a_destination_without_a_teammate_is_kept_and_the_cut_splits() -> None:
    mate = SeenPlayer(10.0, math.radians(5.0), LEFT, 9)
    options = every_policy(0.93, threshold=0.95).options(percept(mate), Pose(0.0, 0.0, 0.0))
    assert options.features[5] == FAILURE  # 0.93 below the study's cut: FAILURE occurs
    assert (
        every_policy(0.97, threshold=0.95).options(percept(mate), Pose(0.0, 0.0, 0.0)).features[5]
        == SUCCESS
    )
    p = every_policy(0.97, threshold=0.95)
    intent, kick = p.kick(6, options)  # midfield left: nobody there, a dribble toward it
    x, y = destination_xy(6, True, HALF_L, HALF_W)
    assert intent == "tpot keep midfield left"
    assert kick == Kick(20.0, pytest.approx(math.atan2(y, x)))
    intent, kick = p.kick(5, options)  # the teammate's destination: the pass
    assert intent == "tpot centre ahead" and kick.power == 80.0


def test_a_policy_refuses_a_table_of_other_actions() -> None:
    with pytest.raises(ValueError, match="3 actions"):
        TpotBallPolicy(TpotTable.empty(11, actions=3), plan(), Fixed(0.9), np.random.default_rng(0))


class EveryBall(Recording):
    """A recording policy with TPOT-RL's own rule."""

    every_ball = True


def test_with_every_ball_the_mind_asks_on_every_spell_even_free_or_in_range() -> None:
    from robotsoccer.skills.team import TeamMind
    from tests.robotsoccer.skills.test_team import percept as team_percept
    from tests.robotsoccer.skills.test_team import setup

    ball = SeenBall(0.5, 0.0)
    policy = EveryBall()
    mind = TeamMind(7, setup(), ball_policy=policy)
    mind.act(team_percept(-20.0, 0.0, 0.0, ball=ball))  # free: the layered rule would dribble
    assert policy.asked == 1 and mind.intent == "tpot test"
    mind = TeamMind(7, setup(), ball_policy=policy)
    mind.act(team_percept(40.0, 0.0, 0.0, ball=ball))  # in range: the layered rule would shoot
    assert policy.asked == 2 and mind.intent == "tpot test" and mind.shots == 0


def test_the_shot_range_guard_makes_the_goal_an_advance_toward_it_out_of_range() -> None:
    guarded = every_policy(0.97, threshold=0.95, shot_guard=True)
    far = Pose(0.0, 0.0, 0.0)  # 52.5 m from the goal: beyond the 25 m range
    options = guarded.options(percept(), far)
    assert not options.shot and options.features[0] == MISS
    intent, kick = guarded.kick(0, options)  # no teammate toward the goal: dribble toward it
    assert intent == "tpot keep goal" and kick == Kick(20.0, pytest.approx(0.0))
    mate = SeenPlayer(15.0, math.radians(5.0), LEFT, 9)  # ahead, toward the goal
    options = guarded.options(percept(mate), far)
    assert options.features[0] == SUCCESS  # the tree's verdict on the pass toward the goal
    intent, kick = guarded.kick(0, options)
    assert intent == "tpot goal" and kick == Kick(80.0, pytest.approx(math.radians(5.0)))
    # Unguarded, the same choice is a long shot (the first every-ball studies).
    unguarded = every_policy(0.97, threshold=0.95)
    assert unguarded.kick(0, unguarded.options(percept(mate), far))[0] == "tpot shoot"
    # In range the guard changes nothing: a shot, judged by the path.
    near = Pose(35.0, 0.0, 0.0)
    options = guarded.options(percept(), near)
    assert options.shot and options.features[0] == SUCCESS
    assert guarded.kick(0, options) == ("tpot shoot", Kick(100.0, pytest.approx(0.0)))


def test_the_guard_and_the_mind_share_one_range_rule_the_seen_goal_first() -> None:
    from robotsoccer.skills.team_setup import goal_direction, in_shooting_range

    pose = Pose(20.0, 0.0, 0.0)  # 32.5 m by the pose: out of range
    seen_near = Percept(
        PlayerRef(LEFT, 7), 10, 10, SeenBall(0.5, 0.0), landmarks=(SeenLandmark("g r", 24.0, 0.1),)
    )
    goal = goal_direction(seen_near, pose, True, (HALF_L, 0.0))
    assert goal == (24.0, 0.1) and in_shooting_range(goal, 25.0)  # the flag's reading wins
    assert not in_shooting_range(goal_direction(percept(), pose, True, (HALF_L, 0.0)), 25.0)
    assert not in_shooting_range(None, 25.0)
    guarded = every_policy(0.9, shot_guard=True)
    assert guarded.options(seen_near, pose).shot  # the guard reads the same flag
    assert not guarded.options(percept(), pose).shot


def test_the_guard_needs_every_ball_and_the_loss_penalty_its_bounds() -> None:
    with pytest.raises(ValueError, match="every_ball"):
        TpotSettings(shot_guard=True)
    with pytest.raises(ValueError, match="loss_penalty"):
        every_policy(0.9, loss_penalty=1.5)


def test_an_opponent_touch_closes_rewards_with_the_loss_penalty_only_when_one_is_set() -> None:
    p = every_policy(0.9, learn=True, window="horizon", loss_penalty=0.5)
    p.decide(7, percept(tick=0), Pose(0.0, 0.0, 0.0), (0.0, 0.0))
    p.observe(7, 10, (26.25, 0.0))  # half way to the opponents' goal
    p.lost(100)  # an opponent touched it 10 s after the kick
    p.observe(7, 110, (-52.5, 0.0))  # what happens after the loss is not this kick's
    # advance 0.5 less 0.5 * (1 - 10/30)
    assert [e.reward for e in p.experiences] == pytest.approx([0.5 - 0.5 * (2.0 / 3.0)])
    p.decide(7, percept(tick=200), Pose(-40.0, 0.0, 0.0), (-40.0, 0.0))
    p.observe(7, 201, (-52.5, 0.0))
    p.lost(200)  # lost at once, the ball back at the own goal line: clipped at -1
    assert p.experiences[-1].reward == pytest.approx(-1.0)
    # Without a penalty a touch closes nothing (the earlier studies' reward).
    q = every_policy(0.9, learn=True, window="horizon")
    q.decide(7, percept(tick=0), Pose(0.0, 0.0, 0.0), (0.0, 0.0))
    q.observe(7, 10, (26.25, 0.0))
    q.lost(100)
    assert q.experiences == []
    q.finish(110)
    assert [e.reward for e in q.experiences] == pytest.approx([0.5])


class _Rows:
    """An evaluator that keeps every attribute row it is asked about."""

    def __init__(self) -> None:
        self.rows: list[np.ndarray] = []

    def success_confidence(self, x: np.ndarray) -> float:
        self.rows.append(x)
        return 0.9


@pytest.mark.parametrize("half", ["unknown", "estimated"])
def test_layer3_asks_its_tree_as_the_team_does_the_receivers_half_included(half: str) -> None:
    mate = SeenPlayer(10.0, math.radians(5.0), LEFT, 9)
    foe = SeenPlayer(8.0, math.radians(10.0), RIGHT, 4)
    seen = percept(mate, foe)
    tree = _Rows()
    setup = replace(plan(), receiver_half=half)
    TpotBallPolicy(TpotTable.empty(11), setup, tree, np.random.default_rng(0)).options(
        seen, Pose(0.0, 0.0, 0.0)
    )
    (row,) = tree.rows
    np.testing.assert_array_equal(row, open_play_attributes(seen, 0, 1.0, half))
    receiver_half = row[len(row) // 2 :]
    assert np.isnan(receiver_half).all() == (half == "unknown")
