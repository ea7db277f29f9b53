"""The set play of Figure 15: its skills, its coach, and plays on both field models, by seed."""

from __future__ import annotations

import math

import pytest

from field_models.arena import BallLaw
from field_models.protocol import (
    Heard,
    Kick,
    Percept,
    PlayerRef,
    SeenBall,
    SeenLandmark,
    Turn,
)
from field_models.registry import field_facts
from robotsoccer.drills import make_drill
from robotsoccer.drills.setplay import STAGES
from robotsoccer.drills.setplay_kicks import (
    CoachKicks,
    ball_sense,
    coach_kicks,
    kick_powers,
    kick_reach,
    pass_speed,
)
from robotsoccer.runs.pool import run_trials
from robotsoccer.runs.runner import TrialSpec, build_trial, run_trial
from robotsoccer.skills.ball_sense import BallSense, Heading
from robotsoccer.skills.ball_tracker import BallTracker, blocking_side
from robotsoccer.skills.cycle import CycleDefenderMind
from robotsoccer.skills.setplay import (
    WINGER_CUE,
    arrives,
    chase,
    dribble,
    opponent_in_path,
    reach_entry,
    shoot,
)
from robotsoccer.skills.setplay_cycle import CycleAttacker

ME = PlayerRef("left", 1)
SERVER = ("soccer_server", "soccer_server_1996")
ROBOTS = ("robot_physics", "small_size_1997")
ARC = ("robot_physics", "small_size_1997_arc")
# The server's kick: 0.16 m/s per unit of power; a ball slows by 4% a cycle of 0.1 s.
SENSE = BallSense(BallLaw("geometric", 0.1, 0.96), 0.16, 100.0, 0.885, 1.735, 0.25)


def percept(
    ball: tuple[float, float] | None,
    *,
    goal: float | None = None,
    heard: tuple[str, ...] = (),
    tick: int = 10,
    observed: int | None = None,
) -> Percept:
    marks = () if goal is None else (SeenLandmark("g r", 30.0, goal),)
    seen = None if ball is None else SeenBall(ball[0], ball[1])
    return Percept(
        ME, tick, tick if observed is None else observed, seen, (), tuple(Heard(t) for t in heard),
        marks,
    )  # fmt: skip


def test_the_skills_chase_dribble_and_shoot_by_the_ball_and_goal() -> None:
    assert type(chase(percept(None))[0]).__name__ == "Turn"
    assert type(chase(percept((5.0, 0.5)))[0]).__name__ == "Turn"
    assert type(chase(percept((5.0, 0.0)))[0]).__name__ == "Dash"
    kick = dribble(percept((1.0, 0.0)), 0.3, 1.5, 20.0)[0]
    assert isinstance(kick, Kick) and kick.direction_rad == pytest.approx(0.3)
    assert type(dribble(percept((3.0, 0.0)), 0.3, 1.5, 20.0)[0]).__name__ == "Dash"
    assert type(shoot(percept((1.0, 0.0)), True, 1.5, 100.0)[0]).__name__ == "Turn"
    shot = shoot(percept((1.0, 0.0), goal=-0.2), True, 1.5, 100.0)[0]
    assert isinstance(shot, Kick) and shot.direction_rad == pytest.approx(-0.2)
    assert not opponent_in_path(percept((1.0, 0.0)), 0.0, 10.0)
    assert WINGER_CUE == "wing"


def test_a_kick_is_compensated_for_the_way_the_ball_rolls() -> None:
    tracker = BallTracker(SENSE)
    tracker.rest(10)
    kick = tracker.kick_to(percept((1.2, 0.0)), 8.0, 0.0)
    assert kick is not None and kick.power == pytest.approx(50.0)
    tracker.note([kick], 10)  # the ball now runs at 8 m/s straight ahead
    assert tracker.velocity(percept((1.5, 0.0), tick=11)) == pytest.approx((7.68, 0.0))
    sideways = tracker.kick_to(percept((1.5, 0.0), tick=11), 7.68, math.pi / 2)
    assert sideways is not None  # the kick that turns the ball by 90° at the same speed
    assert sideways.direction_rad == pytest.approx(3 * math.pi / 4)
    assert sideways.power == pytest.approx(7.68 * math.sqrt(2) / 0.16)
    fastest = tracker.kick_to(percept((1.5, 0.0), tick=11), 30.0, math.pi / 2)
    assert fastest is not None and fastest.power == pytest.approx(100.0)  # the top power
    stop = tracker.stop(percept((1.5, 0.0), tick=11), 0.1)
    assert stop is not None and abs(stop.direction_rad) == pytest.approx(math.pi)
    assert stop.power == pytest.approx(7.68 / 0.16)


def test_a_turn_rotates_the_tracked_ball_and_the_body_stops_it() -> None:
    tracker = BallTracker(SENSE)
    tracker.rest(0)
    tracker.note([Kick(10.0, 0.0), Turn(math.pi / 2)], 0)  # 1.6 m/s ahead, a left turn
    vx, vy = tracker.velocity(percept((1.5, -math.pi / 2), tick=0))
    assert (vx, vy) == pytest.approx((0.0, -1.6), abs=1e-9)
    assert tracker.velocity(percept((0.9, 0.0), tick=0)) != (0.0, 0.0)  # sampled before it
    assert tracker.velocity(percept((0.9, 0.0), tick=1)) == (0.0, 0.0)  # at the body: stopped


def test_a_kick_back_through_the_body_taps_the_ball_aside_first() -> None:
    tracker = BallTracker(SENSE)
    tracker.rest(0)
    tap, real = tracker.aim(percept((0.9, 0.0), tick=0), 16.0, math.pi)
    assert not real and tap is not None and abs(tap.direction_rad) == pytest.approx(math.pi / 2)
    kick, real = tracker.aim(percept((0.9, 0.0), tick=0), 16.0, 0.5)
    assert real and kick is not None and kick.direction_rad == pytest.approx(0.5)


def test_a_pass_announced_runs_at_the_receiver_and_it_waits_in_its_path() -> None:
    tracker = BallTracker(SENSE)
    tracker.launched(percept((10.0, 0.0), tick=0), 10.0, 0)
    assert tracker.velocity(percept((10.0, 0.0), tick=0)) == pytest.approx((-10.0, 0.0))
    assert not arrives(percept((10.0, 0.0), tick=0), tracker)  # a second away
    assert arrives(percept((3.0, 0.1), tick=0), tracker)  # passes within reach soon


def test_the_heading_turns_stale_percepts_and_recalls_a_missed_ball() -> None:
    heading = Heading(settle_ticks=5, recall_ticks=10)
    heading.view(percept((1.0, 0.0), tick=0))
    heading.note([Turn(0.5)], tick=0)
    stale = heading.view(percept((1.0, 0.2), tick=3, observed=2))
    assert stale.ball is not None and stale.ball.angle_rad == pytest.approx(-0.3)
    fresh = heading.view(percept((1.0, 0.2), tick=8, observed=6))
    assert fresh.ball is not None and fresh.ball.angle_rad == pytest.approx(0.2)
    missed = heading.view(percept(None, tick=12, observed=12))
    assert missed.ball is not None and missed.ball.angle_rad == pytest.approx(0.2)
    assert heading.view(percept(None, tick=30, observed=30)).ball is None


def test_the_drill_refuses_bad_options() -> None:
    with pytest.raises(ValueError, match="model file"):
        make_drill("setplay", {"chooser": "tree"})
    with pytest.raises(ValueError, match="max_time_s"):
        make_drill("setplay", {"max_time_s": 0.0})


@pytest.mark.parametrize("field", [SERVER, ROBOTS])
def test_the_field_numbers_let_the_players_kick_and_stop_beside_the_ball(
    field: tuple[str, str],
) -> None:
    facts = field_facts(*field)
    drill = make_drill("setplay", {})
    plan = drill.plan(facts)  # type: ignore[attr-defined]
    sense = ball_sense(facts, plan)
    assert facts.touch_distance_m < sense.reach_m < kick_reach(facts)
    powers = kick_powers(facts, plan)
    assert 0.0 < powers.dribble < powers.passing <= powers.shot == 100.0
    assert 0.0 < sense.approach_power <= 100.0
    # The coach kicks exactly where the players have no aimable kick (the 1997 robots).
    assert (coach_kicks(facts, plan) is None) == (facts.kick is not None and facts.kick.aimable)


@pytest.mark.parametrize("field", [SERVER, ROBOTS])
def test_a_play_runs_and_repeats_by_seed(field: tuple[str, str]) -> None:
    spec = TrialSpec(drill="setplay", field_model=field[0], preset=field[1], seed=3)
    first = [run_trial(spec, i) for i in range(3)]
    assert [run_trial(spec, i) for i in range(3)] == first
    for result in first:
        assert result.label in ("GOAL", "SHOT", "INTERCEPTED", "OUT", "TIMEOUT")
        measures = dict(result.measures)
        assert 0 <= measures["passes"] <= len(STAGES) and measures["goal"] in (0.0, 1.0)
        assert measures["goal"] <= measures["shot"] or result.label == "GOAL"
        assert (measures["first_receiver"] > 0) == (measures["passes"] > 0)


def test_the_starter_passes_on_the_server() -> None:
    # The first pass (starter to a first receiver) completes in most server plays: at least
    # one of five fixed plays must show it.
    spec = TrialSpec(drill="setplay", field_model=SERVER[0], preset=SERVER[1], seed=0)
    passes = [run_trial(spec, i).measure("passes") for i in range(5)]
    assert max(passes) >= 1.0


def test_results_do_not_depend_on_the_number_of_workers() -> None:
    spec = TrialSpec(drill="setplay", field_model=SERVER[0], preset=SERVER[1], seed=1)
    alone = run_trials(spec, 4, workers=1, progress=False)
    assert run_trials(spec, 4, workers=2, chunk_size=1, progress=False) == alone


# ----------------------------------------------------------------------------- the robots

GOALS = (("g l", -1.37, 0.0), ("g r", 1.37, 0.0))
# A 30 Hz camera 50 ms late on a 240 Hz tick, fitting the ball over 4 sightings.
CAMERA = BallSense(
    BallLaw("constant", 1 / 240, 1.0, 0.0), 0.0205, 100.0, 0.0589, 0.081, 1 / 30,
    turn_settle_ticks=9, landmarks=GOALS, track_window=4,
)  # fmt: skip


def seen_from(
    me: tuple[float, float, float], ball: tuple[float, float], tick: int, lag: int = 12
) -> Percept:
    """What a robot at pose `me` (x, y, heading) sees of `ball` and the goals (no noise)."""

    def polar(x: float, y: float) -> tuple[float, float]:
        dx, dy = x - me[0], y - me[1]
        return math.hypot(dx, dy), math.atan2(dy, dx) - me[2]

    marks = tuple(SeenLandmark(name, *polar(x, y)) for name, x, y in GOALS)
    return Percept(ME, tick, tick - lag, SeenBall(*polar(*ball)), (), (), marks)


def test_the_camera_fit_gives_the_balls_velocity_in_the_turned_body_frame() -> None:
    # A robot at (0.2, 0.1) facing 90° watches a ball rolling at (1, -0.5) m/s; its body
    # frame is the field's turned by -90°, so the ball moves at (-0.5, -1) there.
    tracker = BallTracker(CAMERA)
    me = (0.2, 0.1, math.pi / 2)
    for k in range(5):
        tick = 20 + 8 * k
        t = (tick - 12) / 240
        raw = seen_from(me, (-0.3 + 1.0 * t, 0.4 - 0.5 * t), tick)
        tracker.observe(raw)
        velocity = tracker.velocity(raw)
    assert tracker.fitted(raw) is not None
    assert velocity == pytest.approx((-0.5, -1.0), abs=1e-6)
    # Its own kick makes it forget the fit until a full window after the kick can show.
    tracker.note([Kick(10.0, 0.0)], tick)
    later = seen_from(me, (0.0, 0.0), tick + 8)
    tracker.observe(later)
    assert tracker.fitted(later) is None


def test_the_ball_comes_into_reach_at_the_reach_circle_not_at_the_body() -> None:
    tracker = BallTracker(CAMERA)
    tracker.launched(percept((0.2, 0.0), tick=0), 1.2, 0)  # 1.2 m/s straight at the player
    # Reach 0.081 m: from 0.12 m the ball enters it in 32.5 ms, within a 33.3 ms period.
    entry = reach_entry(percept((0.12, 0.0), tick=0), tracker, 1.0)
    assert entry is not None and entry == pytest.approx((0.081, 0.0), abs=1e-3)
    assert reach_entry(percept((0.13, 0.0), tick=0), tracker, 1.0) is None  # 40.8 ms away
    assert reach_entry(percept((0.12, 1.2), tick=0), tracker, 1.0) is None  # passes wide


def test_a_first_time_kick_is_bent_round_the_body_not_tapped() -> None:
    tracker = BallTracker(CAMERA)
    tracker.launched(percept((0.2, 0.0), tick=20), 1.2, 20)
    ball = percept((0.081, 0.3), tick=20)
    # Straight back through the body: a ball at rest would be tapped aside first.
    tap, real = tracker.aim(ball, 1.2, math.pi)
    assert tap is not None
    assert not real
    at = (0.081 * math.cos(0.3), 0.081 * math.sin(0.3))
    kick, real = tracker.aim(ball, 1.2, math.pi, first_time=at)
    assert real and kick is not None
    tracker.note([kick], 20)
    vx, vy = tracker.velocity(percept((0.081, 0.3), tick=20))
    out = math.atan2(vy, vx)
    assert blocking_side(CAMERA, 0.081, 0.3, out) is None  # it clears the body
    assert 0.0 < abs(math.remainder(out - math.pi, 2 * math.pi)) <= math.radians(45.0) + 1e-6


class _Table:
    """Just enough of an arena for the coach's kicks: one player and the ball."""

    def __init__(self, player_x: float) -> None:
        self.tick = 0
        self.ball = (0.0, 0.0, 0.0, -1.0, 0.0)  # at the origin, rolling at 1 m/s toward -x
        self.player_x = player_x

    def ball_state(self) -> tuple[float, float, float, float, float]:
        return self.ball

    def player_state(self, ref: PlayerRef) -> object:
        class State:
            x, y, heading = self.player_x, 0.0, math.pi

        return State()

    def place_ball(self, x: float, y: float, vx: float = 0.0, vy: float = 0.0) -> None:
        self.ball = (x, y, 0.0, vx, vy)


def test_a_coach_kick_stays_armed_for_the_ball_to_come_then_lapses() -> None:
    kicks = CoachKicks(0.02, 4.0, armed_ticks=7)
    table = _Table(player_x=-0.2)  # 0.2 m away: out of a 0.08 m reach
    kicks.arm(ME, Kick(50.0, 0.0), 0)
    kicks.apply(table, 0.08)  # type: ignore[arg-type]
    assert kicks.fired == 0 and ME in kicks.pending
    table.player_x, table.tick = -0.07, 5  # the ball came into reach within the period
    kicks.apply(table, 0.08)  # type: ignore[arg-type]
    # The kick (1 m/s along its heading, pi: toward -x) adds to the ball's 1 m/s that way.
    assert kicks.fired == 1 and table.ball[3] == pytest.approx(-2.0) and not kicks.pending
    kicks.arm(ME, Kick(50.0, 0.0), 10)
    table.player_x, table.tick = -0.5, 17  # never came: dropped at the period's end
    kicks.apply(table, 0.08)  # type: ignore[arg-type]
    assert kicks.fired == 1 and not kicks.pending


def test_robot_passes_go_at_the_robots_top_speed_and_the_server_keeps_layer_1s_launch() -> None:
    robots, server = field_facts(*ARC), field_facts(*SERVER)
    drill = make_drill("setplay", {})
    for facts in (robots, server):
        plan = drill.plan(facts)  # type: ignore[attr-defined]
        sense = ball_sense(facts, plan)
        speed = sense.speed(kick_powers(facts, plan).passing)
        expected = pass_speed(facts) if coach_kicks(facts, plan) else plan.launch_speed_mps
        assert speed == pytest.approx(expected)
        assert (sense.track_window > 0) == (facts is robots)  # the camera fit: robots only
    assert pass_speed(robots) == pytest.approx(robots.player_top_speed_mps)
    plan = drill.plan(robots)  # type: ignore[attr-defined]
    with pytest.raises(ValueError, match="pass_speed_mps must be in"):
        kick_powers(robots, plan, 9.0)


def test_the_defenders_option_is_checked() -> None:
    with pytest.raises(ValueError, match="behaviour"):
        make_drill("setplay", {"defenders": "fast"})
    drill = make_drill("setplay", {"defenders": "straight"})
    assert drill.defenders == "straight"  # type: ignore[attr-defined]


def test_robot_plays_do_not_depend_on_the_number_of_workers() -> None:
    spec = TrialSpec(drill="setplay", field_model=ARC[0], preset=ARC[1], seed=2)
    alone = run_trials(spec, 3, workers=1, progress=False)
    assert run_trials(spec, 3, workers=2, chunk_size=1, progress=False) == alone


# ----------------------------------------------------------------------------- the client


def _setplay(preset: str, *options: tuple[str, str], model: str = "soccer_server") -> TrialSpec:
    return TrialSpec("setplay", model, preset=preset, seed=4, drill_options=options)


def test_the_client_is_checked_and_see_is_the_default() -> None:
    with pytest.raises(ValueError, match=r"^unknown client 'udp' \(known: see, cycle\)$"):
        make_drill("setplay", {"client": "udp"})
    plain = _setplay("soccer_server_1996")
    see = _setplay("soccer_server_1996", ("client", "see"))
    assert [run_trial(plain, i) for i in range(3)] == [run_trial(see, i) for i in range(3)]


def test_the_robots_refuse_the_per_cycle_client() -> None:
    spec = _setplay("small_size_1997", ("client", "cycle"), model="robot_physics")
    rngs, drill, arena = build_trial(spec, 0)
    with pytest.raises(ValueError, match=r"^client=cycle is the Soccer Server's per-cycle client"):
        drill.setup(arena, rngs)


@pytest.mark.parametrize("preset", ["soccer_server_1996", "rcssserver_19"])
def test_a_play_on_the_per_cycle_client_runs_to_a_verdict(preset: str) -> None:
    spec = _setplay(preset, ("client", "cycle"))
    rngs, drill, arena = build_trial(spec, 0)
    drill.setup(arena, rngs)
    minds = drill.minds(arena, rngs)
    for ref, mind in minds.items():
        kind = CycleAttacker if ref.team == "left" else CycleDefenderMind
        assert isinstance(mind, kind), ref
    results = [run_trial(spec, i) for i in range(3)]
    assert [run_trial(spec, i) for i in range(3)] == results
    for result in results:
        assert result.label in ("GOAL", "SHOT", "INTERCEPTED", "OUT")  # a verdict, not TIMEOUT
    see = [run_trial(_setplay(preset), i) for i in range(3)]
    assert see != results  # the client changes the plays
