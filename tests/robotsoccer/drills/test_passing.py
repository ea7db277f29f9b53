"""The pass drill (paper §6) on both field models: placement, conversation, labels, data."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from field_models.arena import BallLaw
from learning.pass_features import ATTRIBUTE_NAMES, HALF, PASS_SCHEMA
from learning.pass_tree_file import save_pass_tree
from learning.pass_tree_grow import fit_pass_tree
from robotsoccer.drills import make_drill
from robotsoccer.drills.passing import DEFENDERS, ELSEWHERE, PASSER, RECEIVERS, PassDrill
from robotsoccer.runs.pool import run_trials
from robotsoccer.runs.runner import TrialSpec, build_trial, play, run_trial
from robotsoccer.skills.pass_messages import (
    announce_text,
    announced_number,
    parse_report,
    report_text,
)
from robotsoccer.skills.passing import PassPhysics, analytic_margin

HEAD = 4
FIELDS = ["soccer_server", "robot_physics"]


def spec(field_model: str, **options: str) -> TrialSpec:
    return TrialSpec(drill="pass", field_model=field_model).with_options(**options)


@pytest.mark.parametrize("field_model", FIELDS)
def test_a_trial_passes_to_a_receiver_and_records_174_attributes(field_model: str) -> None:
    results = [run_trial(spec(field_model), i) for i in range(12)]
    for r in results:
        assert r.label in PassDrill.labels
        assert len(r.data) == HEAD + len(ATTRIBUTE_NAMES), r
        receiver, confidence, candidates, reports = r.data[:HEAD]
        assert int(receiver) in {ref.number for ref in RECEIVERS}
        assert math.isnan(confidence)  # a random chooser has no tree
        assert 1 <= candidates <= 3
        assert reports >= 1
        x = np.array(r.data[HEAD:])
        assert not np.isnan(x[0])  # the passer saw its receiver: distance known
    assert {"SUCCESS", "FAILURE"} <= {r.label for r in results}
    # Most reports get through the field's hearing limits (one message per two server cycles).
    assert np.mean([r.data[3] for r in results]) >= 2.5
    heard = [not np.all(np.isnan(np.array(r.data[HEAD + HALF :]))) for r in results]
    assert np.mean(heard) >= 0.75  # the chosen receiver's half arrived in most trials


def test_placement_follows_figure_9() -> None:
    rngs, drill, arena = build_trial(spec("soccer_server"), 3)
    drill.setup(arena, rngs)
    ball = arena.ball_state()
    passer = arena.player_state(PASSER)
    assert passer.x < ball.x and abs(passer.y - ball.y) < 1e-9  # behind the ball, facing +x
    assert -30.0 <= ball.x <= -10.0 and -12.0 <= ball.y <= 12.0
    for ref in (*RECEIVERS, *DEFENDERS):
        p = arena.player_state(ref)
        assert 8.0 <= p.x - ball.x <= 30.0 and abs(p.y - ball.y) <= 15.0
    refs = [PASSER, *RECEIVERS, *DEFENDERS, *ELSEWHERE]
    xy = np.array([[arena.player_state(r).x, arena.player_state(r).y] for r in refs])
    gaps = np.hypot(*(xy[:, None, :] - xy[None, :, :]).transpose(2, 0, 1))
    assert gaps[~np.eye(len(refs), dtype=bool)].min() >= 3.0


def test_on_rcssserver_19_most_reports_are_too_long_and_the_receiver_half_is_unknown() -> None:
    # 10 characters carry a report of at most one seen player (codec: "v" + 4 + 5 per player).
    s = TrialSpec(drill="pass", field_model="soccer_server", preset="rcssserver_19_async")
    unknown = 0
    for index in range(6):
        r = run_trial(s, index)
        assert len(r.data) == HEAD + len(ATTRIBUTE_NAMES)
        unknown += bool(np.all(np.isnan(np.array(r.data[HEAD + HALF :]))))
    assert unknown >= 4


def test_results_are_identical_whatever_the_worker_count(tmp_path: Path) -> None:
    s = spec("soccer_server")
    one = run_trials(s, 12, workers=1, results_path=tmp_path / "a.csv")
    two = run_trials(s, 12, workers=2, results_path=tmp_path / "b.csv")
    assert [(r.label, r.ticks) for r in one] == [(r.label, r.ticks) for r in two]
    for a, b in zip(one, two, strict=True):
        np.testing.assert_array_equal(np.array(a.data), np.array(b.data))


def _scene(field_model: str, receiver_xy: tuple[float, float], defender_xy: tuple[float, float]):
    """A trial re-placed by hand: receiver 2 and defender 1 where given, the rest far away."""
    rngs, drill, arena = build_trial(spec(field_model, chooser="closest"), 0)
    drill.setup(arena, rngs)
    unit = arena.facts.unit_m
    arena.place_ball(0.0, 0.0)
    gap = 0.5 * (arena.facts.touch_distance_m + arena.facts.kick.reach_m)
    arena.place_player(PASSER, -gap, 0.0, 0.0)
    far = [(-30.0, 25.0), (-30.0, -25.0), (40.0, 25.0), (40.0, -25.0), (-45.0, 0.0), (45.0, 30.0),
           (45.0, -30.0), (-45.0, 30.0), (-45.0, -30.0)]  # fmt: skip
    others = [r for r in (*RECEIVERS[1:], *DEFENDERS[1:], *ELSEWHERE)]
    for ref, (x, y) in zip(others, far, strict=False):
        arena.place_player(ref, x * unit, y * unit, math.pi)
    rx, ry = receiver_xy
    arena.place_player(RECEIVERS[0], rx * unit, ry * unit, math.pi)
    dx, dy = defender_xy
    arena.place_player(DEFENDERS[0], dx * unit, dy * unit, math.pi)
    minds = drill.minds(arena, rngs)
    return drill, arena, play(arena, drill, minds)


def test_an_open_receiver_takes_the_pass() -> None:
    drill, _, verdict = _scene("soccer_server", (15.0, 0.0), (0.0, 30.0))
    assert drill.passer is not None and drill.passer.chosen == RECEIVERS[0].number
    assert verdict.label == "SUCCESS", verdict


def test_a_defender_on_the_line_takes_the_pass() -> None:
    _, _, verdict = _scene("soccer_server", (25.0, 0.0), (8.0, 0.5))
    assert verdict.label == "FAILURE", verdict


def test_the_messages_round_trip() -> None:
    assert announced_number(announce_text(3)) == 3
    assert announced_number("pass") is None and announced_number("k3") is None
    short = parse_report(report_text(4, None, 17.25))
    assert short is not None and short.number == 4 and short.passer_distance_units == 17.2
    assert np.all(np.isnan(short.half))
    assert parse_report("hello") is None and parse_report("r02zz!") is None


def test_the_analytic_margin_sees_a_defender_on_the_line() -> None:
    # The 1996 server: 2.7 m per 0.1 s cycle at power 100 (27 m/s), decay 0.94 per cycle.
    physics = PassPhysics(BallLaw("geometric", 0.1, decay_per_tick=0.94), 27.0, 1.0, 1.085)
    receiver = (20.0, 0.0)
    blocked = analytic_margin(physics, receiver, [(10.0, 0.05)])
    open_ = analytic_margin(physics, receiver, [(20.0, math.radians(90.0))])
    assert blocked < 0.0 < open_
    assert analytic_margin(physics, receiver, []) == math.inf
    slow = PassPhysics(physics.ball, 2.7, 1.0, 1.085)  # the ball stops after 4.5 m: anyone wins
    assert analytic_margin(slow, receiver, [(20.0, math.radians(90.0))]) < 0.0


def _tree_file(tmp_path: Path, field_model: str) -> Path:
    rng = np.random.default_rng(0)
    x = rng.uniform(0, 30, (60, len(ATTRIBUTE_NAMES)))
    y = np.where(x[:, 0] < 15, "SUCCESS", "FAILURE")
    tree = fit_pass_tree(x, y, ATTRIBUTE_NAMES, schema=PASS_SCHEMA)
    origin = {"field_model": field_model, "preset": "soccer_server_1996"}
    return save_pass_tree(tree, tmp_path / "tree.json", origin)


def test_a_tree_from_another_field_is_refused_unless_it_is_a_transfer(tmp_path: Path) -> None:
    path = _tree_file(tmp_path, "soccer_server")
    s = spec("robot_physics", chooser="tree", model=str(path))
    with pytest.raises(ValueError, match="transfer=true"):
        run_trial(s, 0)
    r = run_trial(s.with_options(transfer="true"), 0)
    assert len(r.data) == HEAD + len(ATTRIBUTE_NAMES) and 0.0 <= r.data[1] <= 1.0


def test_the_tree_chooser_records_its_confidence(tmp_path: Path) -> None:
    path = _tree_file(tmp_path, "soccer_server")
    r = run_trial(spec("soccer_server", chooser="tree", model=str(path)), 1)
    assert 0.0 <= r.data[1] <= 1.0


def test_bad_options_are_refused() -> None:
    with pytest.raises(ValueError, match="chooser"):
        make_drill("pass", {"chooser": "oracle"})
    with pytest.raises(ValueError, match="model file"):
        make_drill("pass", {"chooser": "tree"})
    with pytest.raises(ValueError, match="defenders"):
        make_drill("pass", {"defenders": "asleep"})


def test_a_receiver_reports_without_a_player_beyond_the_messages_range() -> None:
    # A set play's defender that lost the ball runs on (layer 1's rule), far off the field: the
    # report leaves out what its message cannot carry instead of failing.
    from field_models.protocol import Heard, Percept, PlayerRef, SeenBall, SeenPlayer
    from learning.pass_codec import MAX_DISTANCE
    from robotsoccer.skills.pass_messages import INTENT
    from robotsoccer.skills.pass_receivers import ReceiverMind

    class Still:
        def act(self, percept: Percept) -> tuple[()]:
            return ()

    def report(far_m: float | None) -> str:
        mind = ReceiverMind(
            2, Still(), unit_m=1.0, sensor_period_s=0.25, dt_s=0.1, slot=0, say_max_chars=None
        )
        passer = SeenPlayer(15.0, 0.0, "left", 1)
        others: tuple[SeenPlayer, ...] = (SeenPlayer(20.0, 0.5, "right", 3),)
        if far_m is not None:
            others += (SeenPlayer(far_m, -0.5, "right", 4),)
        seen = Percept(
            PlayerRef("left", 2), 10, 10, SeenBall(14.0, 0.0), (passer, *others), (Heard(INTENT),)
        )
        (say,) = mind.act(seen)
        return say.text  # type: ignore[attr-defined,no-any-return]

    assert report(MAX_DISTANCE + 50.0) == report(None)  # left out, as if not seen
    assert report(30.0) != report(None)  # a player in range is reported


# ----------------------------------------------------------------------------- the client


def test_the_client_is_checked_and_see_is_the_default() -> None:
    with pytest.raises(ValueError, match=r"^unknown client 'udp' \(known: see, cycle\)$"):
        make_drill("pass", {"client": "udp"})
    plain, see = spec("soccer_server"), spec("soccer_server", client="see")
    # Rows, not results: the data hold nan (no tree), which equals nothing.
    rows = [run_trial(plain, i).csv_row() for i in range(3)]
    assert rows == [run_trial(see, i).csv_row() for i in range(3)]


def test_the_robots_refuse_the_per_cycle_client() -> None:
    rngs, drill, arena = build_trial(spec("robot_physics", client="cycle"), 0)
    with pytest.raises(ValueError, match=r"^client=cycle is the Soccer Server's per-cycle client"):
        drill.setup(arena, rngs)


def test_a_lead_net_is_refused_on_the_per_cycle_client(tmp_path: Path) -> None:
    from tests.robotsoccer.drills.test_match import lead_net_file

    net = lead_net_file(tmp_path)
    with pytest.raises(ValueError, match=r"^client 'cycle' plays the turn decision"):
        make_drill("pass", {"interceptor": "net", "net": str(net), "client": "cycle"})


def test_a_pass_on_the_per_cycle_client_reaches_a_verdict() -> None:
    from robotsoccer.skills.cycle import CycleDefenderMind
    from robotsoccer.skills.pass_receivers import ReceiverMind, WaitingInterceptorMind

    s = spec("soccer_server", client="cycle")
    rngs, drill, arena = build_trial(s, 0)
    drill.setup(arena, rngs)
    minds = drill.minds(arena, rngs)
    for ref in RECEIVERS:
        mind = minds[ref]
        assert isinstance(mind, ReceiverMind)
        assert isinstance(mind.interceptor, CycleDefenderMind)
    for ref in DEFENDERS:
        mind = minds[ref]
        assert isinstance(mind, WaitingInterceptorMind)
        assert isinstance(mind.interceptor, CycleDefenderMind)
    results = [run_trial(s, i) for i in range(8)]
    rows = [r.csv_row() for r in results]
    assert [run_trial(s, i).csv_row() for i in range(8)] == rows
    for result in results:
        assert result.label in ("SUCCESS", "FAILURE", "MISS")
        assert "time ran out" not in result.reason  # a player took the ball
    see = [run_trial(spec("soccer_server"), i) for i in range(8)]
    assert [r.data[0] for r in see] == [r.data[0] for r in results]  # the passer is the same
    assert [r.csv_row() for r in see] != rows  # the receivers' and defenders' client counts
