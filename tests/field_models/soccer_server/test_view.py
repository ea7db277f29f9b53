"""Soccer Server view cone, identity, landmarks, lines, see timing, hearing (spec §3, §2.6)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from field_models.protocol import PlayerRef
from field_models.soccer_server.hearing import (
    HearInfo,
    HearingBudget,
    deliver_says,
    hearers,
    say_allowed,
)
from field_models.soccer_server.landmarks import FLAGS_1996, FLAGS_FULL, landmarks_for
from field_models.soccer_server.messages import render_see
from field_models.soccer_server.see_timing import SeeTimer
from field_models.soccer_server.sensing import Bodies, SeeInfo, SeenObject, observe
from field_models.soccer_server.sensing_params import SENSING_19, SENSING_1996, SensingParams

ME = PlayerRef("left", 1)
MATE = PlayerRef("left", 2)
OPP = PlayerRef("right", 1)


def see_one(
    ox: float,
    oy: float,
    heading: float,
    obj_x: float,
    obj_y: float,
    params: SensingParams = SENSING_19,
    seed: int = 0,
    other: PlayerRef = OPP,
    landmarks: str = "none",
) -> SeeInfo:
    """Observer row 1 at (ox, oy); the ball AND another player (row 2) at (obj_x, obj_y)."""
    return observe(
        1,
        Bodies(
            [obj_x, ox, obj_x],
            [obj_y, oy, obj_y],
            [0.0, 0.0, 0.0],
            [0.0, 0.0, 0.0],
            [0.0, heading, 0.0],
        ),
        (ME, other),
        7,
        params,
        np.random.default_rng(seed),
        landmarks=landmarks,
    )


def at_angle(deg: float, dist: float) -> tuple[float, float]:
    """A point at `dist` and CCW angle `deg` from the origin."""
    return dist * math.cos(math.radians(deg)), dist * math.sin(math.radians(deg))


# ----------------------------------------------------------------------------- view cone


@pytest.mark.parametrize("deg", [44.9, -44.9, 0.0, 30.0])
def test_objects_inside_45_degrees_are_seen(deg: float) -> None:
    info = see_one(0.0, 0.0, 0.0, *at_angle(deg, 10.0))
    assert info.find("b") is not None
    assert info.find("p") is not None


@pytest.mark.parametrize("deg", [45.1, -45.1, 90.0, 179.0, -135.0])
def test_objects_outside_45_degrees_are_absent(deg: float) -> None:
    info = see_one(0.0, 0.0, 0.0, *at_angle(deg, 10.0))
    assert info.objects == ()


def test_cone_follows_the_heading() -> None:
    # Facing up (+90 deg): an object at +80 deg is in view, one at 0 deg is not.
    assert see_one(0.0, 0.0, math.pi / 2, *at_angle(80.0, 10.0)).find("b") is not None
    assert see_one(0.0, 0.0, math.pi / 2, *at_angle(0.0, 10.0)).objects == ()


def test_close_objects_behind_are_felt_within_visible_distance() -> None:
    info = see_one(0.0, 0.0, 0.0, *at_angle(180.0, 2.0))
    assert [o.name for o in info.objects] == ["B", "P"]
    ball = info.objects[0]
    assert ball.distance == 2.0 and ball.direction in (180, -180)
    assert ball.dist_change is None and ball.team is None
    assert see_one(0.0, 0.0, 0.0, *at_angle(180.0, 3.1)).objects == ()
    flags = see_one(-52.0, 33.0, 0.0, 0.0, 0.0, landmarks="all")
    # (f l t) at (-52.5, 34): 1.118 m away at 116.57 deg CCW = -117 in the server's sign.
    assert SeenObject("F", 1.1, -117) in flags.objects


def test_direction_sign_and_truncation_by_era() -> None:
    # Ball to the player's left at -26.57 deg server sign (spec §8.9 geometry, mirrored).
    x, y = 10.0, 5.0  # our frame: up-left of the direction of view
    rounded = see_one(0.0, 0.0, 0.0, x, y).find("b")
    truncated = see_one(0.0, 0.0, 0.0, x, y, params=SENSING_1996).find("b")
    assert rounded is not None and truncated is not None
    assert rounded.direction == -27
    assert truncated.direction == -26
    right = see_one(0.0, 0.0, 0.0, 10.0, -5.0).find("b")
    assert right is not None and right.direction == 27


def test_spec_measured_see_message_protocol_8_and_4() -> None:
    # spec §3.7/§8.9: player at server (-10, 5) = ours (-10, -5), facing 0, ball at the centre.
    def msg(params: SensingParams) -> str:
        info = observe(
            1,
            Bodies([0.0, -10.0], [0.0, -5.0], [0.0, 0.0], [0.0, 0.0], [0.0, 0.0]),
            (ME,),
            0,
            params,
            np.random.default_rng(1),
        )
        return render_see(info, params.protocol_version)

    p8 = msg(SENSING_19.replace(protocol_version=8))
    assert p8.startswith("(see 0 ((f c) 11.1 -27 0 0) ((f r t) 73.7 -32)")
    for part in ("((f g r b) 62.8 2)", "((g r) 62.8 -5)", "((f p r c) 46.1 -6)"):
        assert part in p8
    assert "((f r 0) 67.4 -4)" in p8
    assert p8.endswith("((b) 11 -27 0 0) ((l r) 62.8 90))")
    p4 = msg(SENSING_19.replace(protocol_version=4, direction_mode="truncate"))
    assert p4.startswith("(see 0 ((flag c) 11.1 -26 0 0) ((flag r t) 73.7 -31)")
    for part in ("((flag g r b) 62.8 1)", "((goal r) 62.8 -4)", "((flag p r c) 46.1 -6)"):
        assert part in p4
    assert p4.endswith("((ball) 11 -26 0 0) ((line r) 62.8 90))")


def test_landmark_modes_give_the_same_ball_players_and_goals() -> None:
    rng_state = np.random.default_rng(5)
    xs = rng_state.uniform(-40, 40, 4).tolist()
    ys = rng_state.uniform(-30, 30, 4).tolist()
    vs = rng_state.uniform(-1, 1, 4).tolist()
    hs = rng_state.uniform(-3, 3, 4).tolist()
    players = (ME, MATE, OPP)
    goals_seen = 0
    for seed in range(40):
        hs[2] = (seed % 8) * math.pi / 4 - math.pi  # look all around
        infos = {
            mode: observe(
                2,
                Bodies(xs, ys, vs, vs, hs),
                players,
                3,
                SENSING_19,
                np.random.default_rng(seed),
                landmarks=mode,
            )
            for mode in ("all", "goals", "none")
        }
        movable = ("b", "p", "B", "P")
        keep_goals = (*movable, "g l", "g r", "G")
        full = infos["all"].objects
        assert tuple(o for o in full if o.name in movable) == infos["none"].objects
        assert tuple(o for o in full if o.name in keep_goals) == tuple(
            o for o in infos["goals"].objects
        )
        goals_seen += sum(o.name in ("g l", "g r") for o in full)
    assert goals_seen > 0
    with pytest.raises(ValueError, match="landmarks"):
        observe(
            1,
            Bodies(xs, ys, vs, vs, hs),
            players,
            3,
            SENSING_19,
            np.random.default_rng(0),
            landmarks="flags",
        )


def test_observer_row_is_checked() -> None:
    with pytest.raises(ValueError, match="observer row"):
        observe(
            0,
            Bodies([0.0, 1.0], [0.0, 0.0], [0.0] * 2, [0.0] * 2, [0.0] * 2),
            (ME,),
            0,
            SENSING_19,
            np.random.default_rng(0),
        )


# ----------------------------------------------------------------------------- identity


def identity_counts(dist: float, params: SensingParams, n: int = 4000) -> dict[str, int]:
    """How often a player straight ahead at `dist` shows team+number, team only, or nothing."""
    counts = {"full": 0, "team": 0, "none": 0}
    rng = np.random.default_rng(11)
    for _ in range(n):
        info = observe(
            1,
            Bodies([0.0, 0.0, dist], [50.0, 0.0, 0.0], [0.0] * 3, [0.0] * 3, [0.0] * 3),
            (ME, OPP),
            0,
            params,
            rng,
            landmarks="none",
        )
        p = info.find("p")
        assert p is not None
        key = "full" if p.unum is not None else "team" if p.team is not None else "none"
        counts[key] += 1
    return counts


def test_number_always_shown_up_to_unum_far_length() -> None:
    assert identity_counts(15.0, SENSING_19, 500) == {"full": 500, "team": 0, "none": 0}


def test_number_fades_linearly_between_20_and_40_m() -> None:
    # d = 30 m is reported 30.0: number shown with probability (40 - 30) / 20 = 0.5.
    n = 4000
    counts = identity_counts(30.0, SENSING_19, n)
    assert counts["none"] == 0
    assert abs(counts["full"] / n - 0.5) < 4 * math.sqrt(0.25 / n)
    # d = 25 m is reported 24.5 (log step): probability (40 - 24.5) / 20 = 0.775.
    counts = identity_counts(25.0, SENSING_19, n)
    p = 0.775
    assert abs(counts["full"] / n - p) < 4 * math.sqrt(p * (1 - p) / n)


def test_team_fades_between_40_and_60_m_in_1996_and_never_today() -> None:
    n = 4000
    # d = 50 m is reported 49.4: no number (>= 40); team shown with 1 - (49.4 - 40)/20 = 0.53.
    counts = identity_counts(50.0, SENSING_1996, n)
    assert counts["full"] == 0
    p = 1 - (49.4 - 40.0) / 20.0
    assert abs(counts["team"] / n - p) < 4 * math.sqrt(p * (1 - p) / n)
    assert identity_counts(65.0, SENSING_1996, 300) == {"full": 0, "team": 0, "none": 300}
    assert identity_counts(65.0, SENSING_19, 300) == {"full": 0, "team": 300, "none": 0}


def test_ball_changes_are_sent_with_falling_probability() -> None:
    rng = np.random.default_rng(3)
    n = 4000
    with_changes = 0
    for _ in range(n):
        info = observe(
            1,
            Bodies([30.0, 0.0], [0.0, 0.0], [0.1, 0.0], [0.0, 0.0], [0.0, 0.0]),
            (ME,),
            0,
            SENSING_19,
            rng,
            landmarks="none",
        )
        ball = info.find("b")
        assert ball is not None and ball.distance == 30.0
        with_changes += ball.dist_change is not None
    assert abs(with_changes / n - 0.5) < 4 * math.sqrt(0.25 / n)
    far = observe(
        1,
        Bodies([45.0, 0.0], [0.0, 0.0], [0.1, 0.0], [0.0, 0.0], [0.0, 0.0]),
        (ME,),
        0,
        SENSING_19,
        rng,
        landmarks="none",
    ).find("b")
    assert far is not None and far.dist_change is None


def test_1996_sees_carry_no_changes_and_no_body_direction() -> None:
    info = see_one(0.0, 0.0, 0.0, 5.0, 0.0, params=SENSING_1996, other=MATE)
    assert info.find("b") == SeenObject("b", 5.0, 0)
    assert info.find("p") == SeenObject("p", 5.0, 0, team="left", unum=2)


def test_today_player_entry_has_changes_body_and_head() -> None:
    info = observe(
        1,
        Bodies(
            [9.0, 0.0, 5.0],
            [9.0, 0.0, 0.0],
            [0.0, 0.0, 0.0],
            [0.0, 0.0, 0.2],
            [0.0, 0.0, math.radians(30.0)],
        ),
        (ME, MATE),
        0,
        SENSING_19,
        np.random.default_rng(0),
        landmarks="none",
    )
    p = info.find("p")
    # Teammate 5 m ahead moving up at 0.2 m/cycle, body at +30 deg CCW -> server -30.
    assert p == SeenObject("p", 5.0, 0, 0.0, -2.3, "left", 2, -30, -30)


def test_low_quality_gives_directions_only() -> None:
    low = SENSING_19.replace(view_quality="low")
    info = see_one(0.0, 0.0, 0.0, 10.0, 0.0, params=low, landmarks="all")
    assert all(o.distance is None for o in info.objects)
    assert info.find("b") == SeenObject("b", None, 0)


# ----------------------------------------------------------------------------- landmarks, lines


def test_landmark_sets_and_positions_in_our_frame() -> None:
    assert len(FLAGS_FULL) == 55
    assert len({f.name for f in FLAGS_FULL}) == 55
    assert len(FLAGS_1996) == 13
    by_name = {f.name: (f.x, f.y) for f in FLAGS_FULL}
    assert by_name["f r t"] == (52.5, 34.0)  # server (52.5, -34): y flips
    assert by_name["f t l 10"] == (-10.0, 39.0)
    assert by_name["f b r 50"] == (50.0, -39.0)
    assert by_name["f l t 30"] == (-57.5, 30.0)
    assert by_name["f g r b"] == (52.5, -7.01)
    assert by_name["f p l t"] == (-36.0, 20.16)
    assert landmarks_for("1996") == FLAGS_1996
    with pytest.raises(ValueError):
        landmarks_for("2000")


def lines_seen(x: float, y: float, heading_deg: float) -> list[SeenObject]:
    info = observe(
        1,
        Bodies([0.0, x], [0.0, y], [0.0] * 2, [0.0] * 2, [0.0, math.radians(heading_deg)]),
        (ME,),
        0,
        SENSING_19,
        np.random.default_rng(0),
    )
    return [o for o in info.objects if o.name.startswith("l ")]


def test_lines_are_hit_by_the_line_of_sight() -> None:
    # Facing the right goal line squarely from the centre: 52.5 m, 90 deg.
    assert lines_seen(0.0, 0.0, 0.0) == [SeenObject("l r", 52.5, 90)]
    # Facing up (our +y) = the server's top line "l t" at 34 m (reported 34.1: log step).
    assert lines_seen(0.0, 0.0, 90.0) == [SeenObject("l t", 34.1, 90)]
    # 30 deg CCW off the right line's normal: the server reports -60 (its sign).
    (line,) = lines_seen(0.0, 0.0, 30.0)
    assert line.name == "l r" and line.direction == -60
    assert line.distance == pytest.approx(52.5 / math.cos(math.radians(30.0)), rel=0.01)


def test_at_most_one_line_inside_two_outside() -> None:
    rng = np.random.default_rng(2)
    for _ in range(300):
        x, y = rng.uniform(-52, 52), rng.uniform(-33.9, 33.9)
        assert len(lines_seen(float(x), float(y), float(rng.uniform(-180, 180)))) <= 1
    # Outside the top-right corner looking back across the pitch: the sight ray crosses the
    # right goal line (y = 32.5) and then the far (bottom) touchline; the server reports both.
    assert [o.name for o in lines_seen(60.0, 40.0, -135.0)] == ["l r", "l b"]


def test_sight_parallel_to_a_line_misses_it() -> None:
    assert [o.name for o in lines_seen(0.0, 0.0, 90.0)] == ["l t"]
    assert lines_seen(0.0, 40.0, 0.0) == []  # outside, looking along the touchline


# ----------------------------------------------------------------------------- see timing


def test_see_timer_150ms_alternates_one_and_two_cycles() -> None:
    timer = SeeTimer(SENSING_19)
    assert timer.see_cycles(0, 12) == [1, 3, 4, 6, 7, 9, 10, 12]
    # 300 s of play, one see per 150 ms; the 2000th fires at t = 300000 ms, in cycle 3000.
    assert sum(timer.sees_in_cycle(c) for c in range(3000)) == 1999
    assert timer.sees_in_cycle(3000) == 1


def test_see_timer_250ms_and_figure_4s_500ms() -> None:
    assert SeeTimer(SENSING_1996).see_cycles(0, 12) == [2, 5, 7, 10, 12]
    fig4 = SeeTimer(SENSING_1996.replace(send_step_ms=500))
    assert fig4.see_cycles(0, 30) == [5, 10, 15, 20, 25, 30]
    assert fig4.see_cycles(120, 150) == [120, 125, 130, 135, 140, 145, 150]


def test_see_timer_view_modes_and_phase() -> None:
    narrow_low = SeeTimer(SENSING_19.replace(view_width="narrow", view_quality="low"))
    # Every 37.5 ms, on the 10 ms timer: sees up to t = 29990 ms are k <= 29990 / 37.5.
    assert sum(narrow_low.sees_in_cycle(c) for c in range(300)) == 799
    assert max(narrow_low.sees_in_cycle(c) for c in range(300)) == 3
    wide = SeeTimer(SENSING_19.replace(view_width="wide"))
    assert wide.see_cycles(0, 9) == [3, 6, 9]
    shifted = SeeTimer(SENSING_19, phase=2)
    assert shifted.see_cycles(0, 6) == [2, 3, 5, 6]
    with pytest.raises(ValueError, match="phase"):
        SeeTimer(SENSING_19, phase=4)


# ----------------------------------------------------------------------------- hearing


def test_hearing_range_and_length() -> None:
    xs, ys = [0.0, 0.0, 49.9, 50.1], [0.0, 0.0, 0.0, 0.0]
    assert hearers(1, xs, ys, SENSING_19) == [1, 2]
    assert say_allowed("pass to 7", SENSING_19)
    assert not say_allowed("shoot the ball", SENSING_19)  # 14 > 10 characters today
    assert say_allowed("shoot the ball", SENSING_1996)
    assert not say_allowed('say "hi"', SENSING_1996)
    assert not say_allowed("", SENSING_1996)


def test_deliver_says_directions_and_forms() -> None:
    players = (ME, MATE, OPP)
    xs, ys = [0.0, 0.0, 10.0, 0.0], [0.0, 0.0, 0.0, -10.0]
    hs = [0.0, 0.0, math.pi, 0.0]
    out = deliver_says([(2, "go")], xs, ys, hs, players, 12, SENSING_19)
    assert out[2] == [HearInfo(12, "self", "go")]
    # Row 1 (facing +x) hears row 2 straight ahead; row 3 hears it 45 deg to its left (our
    # frame), which is -45 in the server's sign.
    assert out[1][0] == (12, "player", "go", 0, "our", 2)
    assert out[3][0] == (12, "player", "go", -45, "opp", None)
    old = deliver_says([(2, "go")], xs, ys, hs, players, 12, SENSING_1996)
    assert old[3][0] == (12, "player", "go", -45, None, None)


def test_hearing_capacity_per_era() -> None:
    players = (ME, MATE, OPP)
    xs, ys, hs = [0.0, 0.0, 1.0, 2.0], [0.0] * 4, [0.0] * 4
    says = [(2, "a"), (3, "b"), (2, "c")]
    # Today: one message per cycle from each team; over capacity the short form.
    budgets = {row: HearingBudget(SENSING_19) for row in (1, 2, 3)}
    heard = deliver_says(says, xs, ys, hs, players, 0, SENSING_19, budgets)[1]
    assert [(h.text, h.team) for h in heard] == [("a", "our"), ("b", "opp"), (None, "our")]
    # 1998: one common counter (hear_max 2, decay 2): one message per cycle, nothing after.
    budgets = {row: HearingBudget(SENSING_1996) for row in (1, 2, 3)}
    heard = deliver_says(says, xs, ys, hs, players, 0, SENSING_1996, budgets)[1]
    assert [h.text for h in heard] == ["a"]
    budgets[1].new_cycle()
    assert budgets[1].teammates == 1  # regains hear_inc = 1 < hear_decay = 2
    budgets[1].new_cycle()
    assert budgets[1].take(same_team=False)
