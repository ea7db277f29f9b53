"""The interception defender and shooter minds: behaviours, TA timing, recording, model files."""

from __future__ import annotations

import math
import subprocess
import sys
from pathlib import Path

import numpy as np
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
)
from learning.datasets import Provenance, write_npz
from learning.features import FeatureSchema, ModelFileError
from learning.interception_file import MODEL_FORMAT, MODEL_FORMAT_VERSION, PARAM_NAMES
from learning.lookup import LookupTable
from robotsoccer.skills.intercept import (
    AimedShooterMind,
    DefenderMind,
    load_lookup_table,
    load_net_function,
    make_policy,
    trained_domain,
)
from robotsoccer.skills.turn_policies import (
    RANDOM_TA_HALF_RANGE_RAD,
    AnalyticPolicy,
    LookupPolicy,
    NetPolicy,
    RandomPolicy,
    straight_policy,
)

ME = PlayerRef(RIGHT, 1)
SHOOTER = PlayerRef(LEFT, 1)
TRIGGER = 14.0
DEG = math.pi / 180.0


def percept(
    tick: int,
    distance: float | None,
    angle_deg: float = 0.0,
    landmarks: tuple[SeenLandmark, ...] = (),
) -> Percept:
    ball = None if distance is None else SeenBall(distance, angle_deg * DEG)
    return Percept(ME, tick, tick, ball, (), (), landmarks)


def polar(x: float, y: float) -> tuple[float, float]:
    """(distance, angle in degrees) of a point in the player's frame."""
    return math.hypot(x, y), math.degrees(math.atan2(y, x))


class Sequence:
    """A scripted TA policy: returns 0.1, 0.2, ... rad on successive calls, recording its inputs."""

    def __init__(self) -> None:
        self.calls: list[tuple[float, float, float]] = []

    def __call__(self, bd: float, ba: float, prev: float, prev_xy: object, xy: object) -> float:
        self.calls.append((bd, ba, prev))
        return 0.1 * len(self.calls)


def net_file(
    path: Path, seed: int = 0, hidden: int = 4, preset: str = "p", field: str = "soccer_server"
) -> Path:
    """A valid interception-net file written without torch (random weights)."""
    rng = np.random.default_rng(seed)
    arrays = {
        "hidden.weight": rng.normal(0.0, 1.0, (hidden, 3)),
        "hidden.bias": rng.normal(0.0, 0.5, hidden),
        "output.weight": rng.normal(0.0, 0.5, (1, hidden)),
        "output.bias": rng.normal(0.0, 0.1, 1),
        "input_mean": np.array([11.0, 0.01, 12.5]),
        "input_scale": np.array([1.7, 0.05, 1.9]),
        "loss_history": np.linspace(1.0, 0.1, 5),
    }
    params = dict.fromkeys(PARAM_NAMES)
    params.update(
        hidden=hidden,
        optimizer="adam",
        weight_decay=0.001,
        epochs=5,
        random_state=0,
        distance_scale_m=1.0,
    )
    meta = {
        "format": MODEL_FORMAT,
        "format_version": MODEL_FORMAT_VERSION,
        "schema": FeatureSchema().to_dict(),
        "hyperparameters": params,
        "provenance": Provenance(field, preset, 1, 0.05, "random", 10).to_dict(),
        "n_train": 10,
    }
    return write_npz(path, arrays, meta)


# ----------------------------------------------------------------------------- the procedure


def test_watches_the_ball_until_the_trigger_then_turns_and_dashes() -> None:
    policy = Sequence()
    mind = DefenderMind(policy, TRIGGER)
    assert mind.act(percept(2, 24.0, 3.0)) == (Turn(3.0 * DEG),)
    assert mind.act(percept(5, 18.0, -2.0)) == (Turn(-2.0 * DEG),)
    assert policy.calls == [] and mind.example is None and not mind.triggered
    actions = mind.act(percept(7, 13.5, 1.0))
    assert policy.calls == [(13.5, 1.0 * DEG, 18.0)]  # previous BD: the previous sighting
    assert mind.example == (13.5, 1.0 * DEG, 18.0, 0.1)
    assert actions == (Turn(1.0 * DEG + 0.1), Dash(100.0))


def test_hold_keeps_the_first_ta_and_every_see_recomputes_it() -> None:
    held, fresh = Sequence(), Sequence()
    hold = DefenderMind(held, TRIGGER, ta_mode="hold")
    every = DefenderMind(fresh, TRIGGER, ta_mode="every_see")
    for mind in (hold, every):
        mind.act(percept(2, 20.0))
        mind.act(percept(5, 13.0, 2.0))
    assert hold.act(percept(7, 9.0, -4.0)) == (Turn(-4.0 * DEG + 0.1), Dash(100.0))
    assert every.act(percept(7, 9.0, -4.0)) == (Turn(-4.0 * DEG + 0.2), Dash(100.0))
    assert len(held.calls) == 1 and fresh.calls[1] == (9.0, -4.0 * DEG, 13.0)
    assert hold.example == every.example == (13.0, 2.0 * DEG, 20.0, 0.1)  # the first is recorded


def test_ball_not_seen_dashes_only_once_triggered() -> None:
    mind = DefenderMind(straight_policy, TRIGGER)
    assert mind.act(percept(2, None)) == ()
    mind.act(percept(5, 12.0))
    assert mind.act(percept(7, None)) == (Dash(100.0),)


def test_first_sighting_within_range_uses_its_own_distance_as_previous() -> None:
    mind = DefenderMind(straight_policy, TRIGGER)
    mind.act(percept(2, None))
    mind.act(percept(5, 12.0, 1.0))
    assert mind.example == (12.0, 1.0 * DEG, 12.0, 0.0)


def test_still_never_acts_and_records_nothing() -> None:
    mind = DefenderMind(None, TRIGGER, kickable_distance_m=2.0)
    assert all(mind.act(percept(t, d)) == () for t, d in ((2, 20.0), (5, 10.0), (7, 1.0)))
    assert mind.example is None


def test_ta_is_clipped_to_ninety_degrees() -> None:
    mind = DefenderMind(lambda *args: 2.5, TRIGGER)
    mind.act(percept(5, 10.0))
    assert mind.example is not None and mind.example[3] == pytest.approx(math.pi / 2)
    mind = DefenderMind(lambda *args: -2.5, TRIGGER)
    mind.act(percept(5, 10.0))
    assert mind.example is not None and mind.example[3] == pytest.approx(-math.pi / 2)


def test_turns_below_the_tolerance_are_left_out() -> None:
    mind = DefenderMind(straight_policy, TRIGGER, turn_tolerance_rad=3.0 * DEG)
    assert mind.act(percept(2, 20.0, 2.0)) == ()
    assert mind.act(percept(5, 20.0, 4.0)) == (Turn(4.0 * DEG),)
    assert mind.act(percept(7, 10.0, -2.9)) == (Dash(100.0),)
    assert mind.act(percept(10, 8.0, 3.5)) == (Turn(3.5 * DEG), Dash(100.0))


@pytest.mark.parametrize(
    ("landmarks", "direction_deg"),
    [
        ((SeenLandmark("g r", 5.0, 150.0 * DEG), SeenLandmark("g l", 99.0, 3.0 * DEG)), -30.0),
        ((SeenLandmark("g r", 5.0, -170.0 * DEG),), 10.0),
        ((SeenLandmark("g l", 99.0, 3.0 * DEG),), 3.0),
        ((), 0.0),
    ],
)
def test_kickable_ball_is_cleared_away_from_the_own_goal(
    landmarks: tuple[SeenLandmark, ...], direction_deg: float
) -> None:
    mind = DefenderMind(straight_policy, TRIGGER, kickable_distance_m=1.885)
    mind.act(percept(5, 12.0))
    (kick,) = mind.act(percept(7, 1.8, 40.0, landmarks))
    assert isinstance(kick, Kick) and kick.power == 100.0
    assert kick.direction_rad == pytest.approx(direction_deg * DEG)
    assert mind.act(percept(10, 1.9, 0.0)) == (Turn(0.0), Dash(100.0))  # just out of reach


def test_kick_at_the_trigger_still_records_the_example() -> None:
    mind = DefenderMind(straight_policy, TRIGGER, kickable_distance_m=1.885)
    mind.act(percept(2, 16.0))
    assert mind.act(percept(5, 1.5)) == (Kick(100.0, 0.0),)
    assert mind.example == (1.5, 0.0, 16.0, 0.0)


# ----------------------------------------------------------------------------- behaviours


def test_straight_and_random_policies() -> None:
    assert straight_policy(10.0, 0.3, 11.0, (1.0, 2.0), (3.0, 4.0)) == 0.0
    random = RandomPolicy(np.random.default_rng(5))
    draws = np.array([random(10.0, 0.0, 11.0, None, (10.0, 0.0)) for _ in range(2000)])
    assert np.all(np.abs(draws) <= RANDOM_TA_HALF_RANGE_RAD)
    edge = 0.9 * RANDOM_TA_HALF_RANGE_RAD
    assert draws.min() < -edge < edge < draws.max()
    again = RandomPolicy(np.random.default_rng(5))
    assert again(1.0, 0.0, 1.0, None, (1.0, 0.0)) == draws[0]


def test_lookup_behaviour_gives_the_hand_interpolated_ta(tmp_path: Path) -> None:
    # TA = -3 x BA on the paper's grid (degrees), saved and loaded as a behaviour would be.
    grid = [a * DEG for a in range(-7, 8)]
    path = LookupTable(grid, [-3.0 * a for a in grid]).save(tmp_path / "table.json")
    mind = DefenderMind(make_policy("lookup", np.random.default_rng(0), str(path)), TRIGGER)
    mind.act(percept(2, 20.0, 0.0))
    # BA = 2.5°: between grid entries 2° (-6°) and 3° (-9°) -> -7.5°.
    turn, dash = mind.act(percept(5, 13.0, 2.5))
    assert isinstance(turn, Turn) and turn.angle_rad == pytest.approx((2.5 - 7.5) * DEG)
    assert dash == Dash(100.0)
    assert mind.example is not None and mind.example[3] == pytest.approx(-7.5 * DEG)
    # Beyond the grid the end value holds: BA = 12° -> TA = -21°.
    assert LookupPolicy(load_lookup_table(path))(9.0, 12.0 * DEG, 10.0, None, (0.0, 0.0)) == (
        pytest.approx(-21.0 * DEG)
    )


def test_analytic_behaviour_gives_the_hand_computed_ta_standing() -> None:
    # The defender stands facing +x. The ball was at (16, 0), now at (12, 3): motion (-4, 3),
    # x3 from (16, 0) ends at (4, 9). TA = atan2(9, 4) - atan2(3, 12) = 66.04° - 14.04° = 52.00°.
    mind = DefenderMind(AnalyticPolicy(), TRIGGER)
    assert mind.act(percept(2, 16.0, 0.0)) == (Turn(0.0),)
    bd, ba = polar(12.0, 3.0)
    turn, dash = mind.act(percept(5, bd, ba))
    assert mind.example is not None
    assert math.degrees(mind.example[3]) == pytest.approx(52.0013, abs=1e-4)
    assert isinstance(turn, Turn) and turn.angle_rad == pytest.approx(66.0375 * DEG, abs=1e-6)
    assert dash == Dash(100.0)


def test_analytic_behaviour_reckons_the_turn_it_commanded() -> None:
    # Field frame = the defender's initial heading. The ball is first seen 10° left at 16 m; the
    # defender turns 10° to face it. Then the ball is at (12, 3) in the field frame, seen from
    # the turned body at 12.37 m, 14.04° - 10° = 4.04°. The two sightings must be compared in
    # one frame: TA = direction of (p_prev + 3 (p_now - p_prev)) minus direction of p_now.
    prev = (16.0 * math.cos(10 * DEG), 16.0 * math.sin(10 * DEG))
    now = (12.0, 3.0)
    end = (prev[0] + 3.0 * (now[0] - prev[0]), prev[1] + 3.0 * (now[1] - prev[1]))
    expected = math.atan2(end[1], end[0]) - math.atan2(now[1], now[0])
    mind = DefenderMind(AnalyticPolicy(), TRIGGER)
    assert mind.act(percept(2, 16.0, 10.0)) == (Turn(10.0 * DEG),)
    bd, ba = polar(*now)
    mind.act(percept(5, bd, ba - 10.0))
    assert mind.example is not None and mind.example[3] == pytest.approx(expected, abs=1e-12)
    naive = AnalyticPolicy()(bd, 0.0, 16.0, polar_xy(16.0, 10.0), polar_xy(bd, ba - 10.0))
    assert abs(naive - expected) > 5 * DEG  # forgetting the turn would be badly wrong


def polar_xy(distance: float, angle_deg: float) -> tuple[float, float]:
    return distance * math.cos(angle_deg * DEG), distance * math.sin(angle_deg * DEG)


def test_analytic_turn_counts_only_from_percepts_observed_after_it() -> None:
    # A robot percept observed before the turn was commanded still shows the old heading.
    mind = DefenderMind(AnalyticPolicy(), TRIGGER)
    mind.act(Percept(ME, 24, 12, SeenBall(16.0, 10.0 * DEG)))  # turns 10° at tick 24
    late = Percept(ME, 32, 20, SeenBall(15.0, 10.0 * DEG))  # observed at 20 < 24: old heading
    mind.act(late)
    assert mind._heading_at(20) == 0.0 and mind._heading_at(25) == pytest.approx(10.0 * DEG)


def test_analytic_without_a_previous_sighting_goes_straight() -> None:
    assert AnalyticPolicy()(10.0, 0.2, 10.0, None, (9.8, 1.98)) == 0.0


def test_net_behaviour_equals_the_models_predict(tmp_path: Path) -> None:
    from learning.interception import InterceptionModel

    path = net_file(tmp_path / "net.npz", seed=3)
    policy = make_policy("net", np.random.default_rng(0), str(path))
    assert isinstance(policy, NetPolicy)
    rng = np.random.default_rng(1)
    rows = np.stack(
        [rng.uniform(5, 15, 40), rng.uniform(-0.3, 0.3, 40), rng.uniform(6, 18, 40)], axis=1
    )
    expected = InterceptionModel.load(path).predict(rows)
    got = [policy(bd, ba, prev, None, (0.0, 0.0)) for bd, ba, prev in rows.tolist()]
    assert np.max(np.abs(np.array(got) - expected)) < 1e-12
    mind = DefenderMind(policy, TRIGGER)
    mind.act(percept(2, 16.0))
    mind.act(percept(5, 12.0, 2.0))
    assert mind.example is not None
    model_ta = InterceptionModel.load(path).predict([[12.0, 2.0 * DEG, 16.0]])[0]
    assert mind.example[3] == pytest.approx(model_ta, abs=1e-12)


def test_model_files_are_read_once_per_path(tmp_path: Path) -> None:
    path = net_file(tmp_path / "net.npz")
    assert load_net_function(path) is load_net_function(str(path))
    table = LookupTable([-0.1, 0.1], [0.0, 0.0]).save(tmp_path / "t.json")
    assert load_lookup_table(table) is load_lookup_table(table)


def test_bad_behaviours_and_files_are_refused(tmp_path: Path) -> None:
    rng = np.random.default_rng(0)
    with pytest.raises(ValueError, match="unknown behaviour"):
        make_policy("teleport", rng)
    with pytest.raises(ValueError, match="needs a model file"):
        make_policy("net", rng)
    with pytest.raises(ModelFileError, match="not found"):
        make_policy("net", rng, str(tmp_path / "none.npz"))
    with pytest.raises(ModelFileError):
        make_policy("lookup", rng, str(net_file(tmp_path / "net.npz")))
    with pytest.raises(ValueError, match="ta_mode"):
        DefenderMind(straight_policy, TRIGGER, ta_mode="sometimes")
    assert make_policy("still", rng) is None


def test_loading_a_net_for_the_skill_does_not_import_torch(tmp_path: Path) -> None:
    path = net_file(tmp_path / "net.npz", preset="soccer_server_1996")
    code = (
        "import sys\n"
        "from robotsoccer.runs.runner import TrialSpec, run_trial\n"
        "from robotsoccer.skills.intercept import load_net_function\n"
        f"f = load_net_function({str(path)!r})\n"
        "assert isinstance(f(12.0, 0.01, 13.0), float)\n"
        "spec = TrialSpec(drill='intercept', field_model='soccer_server',\n"
        "    preset='soccer_server_1996').with_options(behaviour='net', transfer=True, model="
        f"{str(path)!r})\n"
        "result = run_trial(spec, 0)\n"
        "assert len(result.data) == 4, result\n"
        "assert 'torch' not in sys.modules, 'torch was imported'\n"
        "print('ok')\n"
    )
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60)
    assert done.returncode == 0, done.stderr
    assert done.stdout.strip() == "ok"


# ----------------------------------------------------------------------------- shooter


def test_shooter_kicks_once_at_the_seen_defender_plus_the_offset() -> None:
    mind = AimedShooterMind(ME, 100.0, aim_offset_rad=4.0 * DEG)
    seen = (SeenPlayer(3.0, 0.5, LEFT, 2), SeenPlayer(25.0, -1.0 * DEG, RIGHT, 1))
    first = Percept(SHOOTER, 2, 2, SeenBall(1.4, 0.0), seen)
    assert mind.act(first) == (Kick(100.0, 3.0 * DEG),)
    assert mind.act(first) == ()


def test_shooter_without_the_defenders_number_aims_at_the_unknown_player() -> None:
    mind = AimedShooterMind(ME, 80.0)
    far = Percept(SHOOTER, 2, 2, None, (SeenPlayer(28.0, 2.0 * DEG, None, None),))
    assert mind.act(far) == (Kick(80.0, 2.0 * DEG),)
    blind = AimedShooterMind(ME, 80.0, aim_offset_rad=0.1)
    assert blind.act(Percept(SHOOTER, 2, 2, None)) == (Kick(80.0, 0.1),)


def test_a_net_from_another_field_sees_distances_in_drill_units(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    from field_models.registry import field_facts
    from robotsoccer.drills.intercept import InterceptDrill
    from robotsoccer.skills import intercept as skills

    path = str(net_file(tmp_path / "net.npz"))
    server, robots = field_facts("soccer_server"), field_facts("robot_physics")
    monkeypatch.setattr(skills, "model_origin", lambda _: ("robot_physics", "small_size_1997"))
    assert skills.transfer_distance_factor(path, robots) == 1.0
    factor = skills.transfer_distance_factor(path, server)
    assert factor == pytest.approx(server.unit_m / robots.unit_m)
    # k units here enter the net as k units of its field: f(BD) here = f(BD / factor) there
    here, there = load_net_function(path, factor), load_net_function(path)
    assert here(14.0, 0.1, 16.0) == pytest.approx(there(14.0 / factor, 0.1, 16.0 / factor))
    drill = InterceptDrill(behaviour="net", model=path, transfer=True)
    assert drill.distance_factor(server) == pytest.approx(factor)
    assert InterceptDrill(behaviour="net", model=path).distance_factor(server) == 1.0


def test_the_trained_domain_asks_the_net_inside_and_runs_straight_outside(tmp_path: Path) -> None:
    # net_file's scaler: BD 11.0 ± 1.7 m, BA 0.01 ± 0.05 rad, previous BD 12.5 ± 1.9 m.
    path = net_file(tmp_path / "net.npz", seed=3)
    net = make_policy("net", np.random.default_rng(0), str(path))
    assert net is not None
    guarded = trained_domain(net, path)
    inside = (11.0 + 2.9 * 1.7, 0.01 - 2.9 * 0.05, 12.5)
    assert guarded(*inside, None, (0.0, 0.0)) == net(*inside, None, (0.0, 0.0)) != 0.0
    for outside in ((11.0 + 3.1 * 1.7, 0.01, 12.5), (11.0, 0.2, 12.5), (11.0, 0.01, 6.0)):
        assert guarded(*outside, None, (0.0, 0.0)) == 0.0
    assert (guarded.asked, guarded.outside) == (4, 3)


def test_the_trained_domain_scales_with_the_distance_factor(tmp_path: Path) -> None:
    path = net_file(tmp_path / "net.npz", seed=3)
    net = make_policy("net", np.random.default_rng(0), str(path), 2.0)
    assert net is not None
    guarded = trained_domain(net, path, 2.0)
    assert guarded.mean == pytest.approx((22.0, 0.01, 25.0))
    assert guarded.spread == pytest.approx((3.4, 0.05, 3.8))
    assert guarded.inside(22.0 + 2.9 * 3.4, 0.0, 25.0)
    assert not guarded.inside(11.0, 0.0, 12.5)  # the training field's distances, unscaled
