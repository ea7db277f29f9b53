"""The 174 pass attributes of layer 2 (paper §6, Figure 14) and the say-message view codec."""

from __future__ import annotations

import math
import re
import subprocess
import sys
from collections.abc import Callable

import numpy as np
import numpy.typing as npt
import pytest

from learning.pass_codec import (
    ANGLE_STEP_DEG,
    DISTANCE_STEP,
    MAX_DISTANCE,
    decode_view,
    encode_view,
    view_message_length,
)
from learning.pass_features import (
    ATTRIBUTE_NAMES,
    COUNT_REGIONS,
    HALF,
    PASS_SCHEMA,
    PASSER_NAMES,
    RECEIVER_NAMES,
    pass_attributes,
    passer_attributes,
    receiver_attributes,
    unknown_half,
)

FIGURE_14_NAMES = (
    "passer opponents ang6",
    "passer opponent1 angle",
    "passer teammates ang6",
    "passer teammates ang5",
    "passer receiver distance",
    "passer players dist8 ang12",
    "passer players dist4 ang12",
    "passer opponents dist12 ang8",
    "passer opponents dist12 ang4",
    "passer opponents dist12 ang12",
    "passer opponents dist4 ang12",
    "passer opponents dist4 ang8",
    "passer teammates dist8 ang8",
    "passer opponent1 distance",
    "passer opponent2 distance",
    "passer teammate1 distance",
    "receiver teammates dist8 ang12",
    "receiver players dist8 ang12",
    "receiver opponent3 angle",
)

F64 = npt.NDArray[np.float64]


def _view(*players: tuple[float, float, int]) -> tuple[F64, F64, npt.NDArray[np.int8]]:
    """(distance, angle_deg, team) tuples -> the three view arrays."""
    if not players:
        return np.empty(0), np.empty(0), np.empty(0, dtype=np.int8)
    d, a, t = zip(*players, strict=True)
    return np.array(d, dtype=float), np.array(a, dtype=float), np.array(t, dtype=np.int8)


def _passer(receiver: tuple[float, float], *players: tuple[float, float, int]) -> dict[str, float]:
    values = passer_attributes(*receiver, *_view(*players))
    assert values.shape == (HALF,)
    return dict(zip(PASSER_NAMES, values.tolist(), strict=True))


def _receiver(passer: tuple[float, float], *players: tuple[float, float, int]) -> dict[str, float]:
    values = receiver_attributes(*passer, *_view(*players))
    assert values.shape == (HALF,)
    return dict(zip(RECEIVER_NAMES, values.tolist(), strict=True))


def _xy(distance: float, angle_deg: float) -> tuple[float, float]:
    return distance * math.cos(math.radians(angle_deg)), distance * math.sin(
        math.radians(angle_deg)
    )


def _cosine_law(d: float, offset_deg: float, target: float) -> float:
    return math.sqrt(d * d + target * target - 2 * d * target * math.cos(math.radians(offset_deg)))


# ----------------------------------------------------------------------------- names


def test_schema_lengths_and_unique_names() -> None:
    assert PASS_SCHEMA == "pass-attributes/1"
    assert HALF == 87
    assert len(PASSER_NAMES) == len(RECEIVER_NAMES) == 87
    assert len(ATTRIBUTE_NAMES) == 174
    assert ATTRIBUTE_NAMES == PASSER_NAMES + RECEIVER_NAMES
    assert len(set(ATTRIBUTE_NAMES)) == 174
    assert all(name.startswith("passer ") for name in PASSER_NAMES)
    assert all(name.startswith("receiver ") for name in RECEIVER_NAMES)


@pytest.mark.parametrize("name", FIGURE_14_NAMES)
def test_figure_14_names_exist(name: str) -> None:
    assert name in ATTRIBUTE_NAMES


def test_name_order_follows_the_paper_list() -> None:
    assert PASSER_NAMES[:6] == (
        "passer receiver distance",
        "passer receiver angle",
        "passer teammate1 distance",
        "passer teammate1 angle",
        "passer teammate2 distance",
        "passer teammate2 angle",
    )
    assert PASSER_NAMES[19] == "passer teammate9 angle"
    assert PASSER_NAMES[20] == "passer opponent1 distance"
    assert PASSER_NAMES[41] == "passer opponent11 angle"
    # Counts: kind-major, the 9 dist x ang regions (distance-major) then ang1..ang6.
    assert PASSER_NAMES[42:46] == (
        "passer teammates dist4 ang4",
        "passer teammates dist4 ang8",
        "passer teammates dist4 ang12",
        "passer teammates dist8 ang4",
    )
    assert PASSER_NAMES[50] == "passer teammates dist12 ang12"
    assert PASSER_NAMES[51] == "passer teammates ang1"
    assert PASSER_NAMES[56] == "passer teammates ang6"
    assert PASSER_NAMES[57] == "passer opponents dist4 ang4"
    assert PASSER_NAMES[72] == "passer players dist4 ang4"
    assert PASSER_NAMES[-1] == "passer players ang6"
    assert RECEIVER_NAMES[0] == "receiver teammate1 distance"
    assert RECEIVER_NAMES[19] == "receiver teammate10 angle"
    assert RECEIVER_NAMES[20] == "receiver opponent1 distance"
    assert RECEIVER_NAMES[41] == "receiver opponent11 angle"
    assert RECEIVER_NAMES[42] == "receiver teammates dist4 ang4"
    assert RECEIVER_NAMES[-1] == "receiver players ang6"
    assert COUNT_REGIONS == (
        (4, 4), (4, 8), (4, 12), (8, 4), (8, 8), (8, 12), (12, 4), (12, 8), (12, 12),
        (None, 1), (None, 2), (None, 3), (None, 4), (None, 5), (None, 6),
    )  # fmt: skip


# ----------------------------------------------------------------------------- passer's half

# Receiver 20 units straight ahead. Distances to the receiver by the law of cosines:
# A opponent (18, 3°): sqrt(18² + 20² - 2·18·20·cos 3°) = 2.233 -> every dist region, ang3..ang6
# B teammate (10, 30°): offset 30 -> in no region
# C unknown team (22, -5.5°): 2.838 -> dist4/8/12 x ang8/ang12, ang6
# D opponent (12, 10°): 8.443 -> dist12 ang12 only
# E opponent (5, 100°): offset 100 -> in no region
SCENE = (
    (18.0, 3.0, -1),  # A
    (10.0, 30.0, 1),  # B
    (22.0, -5.5, 0),  # C
    (12.0, 10.0, -1),  # D
    (5.0, 100.0, -1),  # E
)


def test_hand_built_scene_distances_by_the_law_of_cosines() -> None:
    # The hand values the counts below rely on.
    assert _cosine_law(18.0, 3.0, 20.0) == pytest.approx(2.233, abs=1e-3)
    assert _cosine_law(22.0, 5.5, 20.0) == pytest.approx(2.838, abs=1e-3)
    assert _cosine_law(12.0, 10.0, 20.0) == pytest.approx(8.443, abs=1e-3)


def test_hand_built_scene_lists() -> None:
    p = _passer((20.0, 0.0), *SCENE)
    assert p["passer receiver distance"] == 20.0
    assert p["passer receiver angle"] == 0.0
    # Only B is a teammate; C's team is unknown, so it is in no list.
    assert (p["passer teammate1 distance"], p["passer teammate1 angle"]) == (10.0, 30.0)
    assert math.isnan(p["passer teammate2 distance"])
    assert math.isnan(p["passer teammate9 angle"])
    # Opponents by angle from the receiver: A (3°), D (10°), E (100°).
    assert (p["passer opponent1 distance"], p["passer opponent1 angle"]) == (18.0, 3.0)
    assert (p["passer opponent2 distance"], p["passer opponent2 angle"]) == (12.0, 10.0)
    assert (p["passer opponent3 distance"], p["passer opponent3 angle"]) == (5.0, 100.0)
    assert math.isnan(p["passer opponent4 distance"])
    assert math.isnan(p["passer opponent11 angle"])


def test_hand_built_scene_counts() -> None:
    p = _passer((20.0, 0.0), *SCENE)
    expected = {
        # Figure 14's root: an opponent within 6° of the receiver -> the tree predicts FAILURE.
        "passer opponents ang6": 1,
        "passer opponents ang3": 1,  # A at exactly 3°: the bounds are inclusive
        "passer opponents ang2": 0,
        "passer opponents ang1": 0,
        "passer opponents dist4 ang4": 1,
        "passer opponents dist4 ang12": 1,
        "passer opponents dist8 ang8": 1,
        "passer opponents dist12 ang8": 1,
        "passer opponents dist12 ang12": 2,  # A and D
        "passer teammates ang6": 0,
        "passer teammates dist12 ang12": 0,
        "passer players dist4 ang4": 1,  # A (C is 5.5° off)
        "passer players dist4 ang8": 2,  # A, C
        "passer players dist8 ang12": 2,  # A, C (D is 8.44 from the receiver)
        "passer players dist12 ang12": 3,  # A, C, D
        "passer players ang6": 2,  # A, C
        "passer players ang5": 1,
        "passer players ang1": 0,
    }
    assert {name: p[name] for name in expected} == expected
    counts = [p[name] for name in PASSER_NAMES[42:]]
    assert all(c == int(c) and c >= 0 for c in counts)


def test_empty_view_has_zero_counts_and_unknown_lists() -> None:
    p = _passer((15.0, -20.0))
    assert p["passer receiver distance"] == 15.0
    assert p["passer receiver angle"] == -20.0
    lists = [p[name] for name in PASSER_NAMES[2:42]]
    assert all(math.isnan(v) for v in lists)
    assert [p[name] for name in PASSER_NAMES[42:]] == [0.0] * 45


def test_passer_lists_sort_by_angle_offset_and_keep_the_first_nine_and_eleven() -> None:
    # 12 teammates and 13 opponents at offsets 1..12 / 0.5..12.5 on alternating sides, given in
    # reverse order, with distances that do not follow the offsets.
    teammates = [(30.0 - i, (i + 1.0) * (-1) ** i, 1) for i in range(12)][::-1]
    opponents = [(5.0 + i % 4, (i + 0.5) * (-1) ** (i + 1), -1) for i in range(13)][::-1]
    values = passer_attributes(20.0, 0.0, *_view(*teammates, *opponents))
    mate_angles = values[3:20:2]
    mate_distances = values[2:20:2]
    np.testing.assert_array_equal(mate_angles, np.arange(1.0, 10.0))
    np.testing.assert_array_equal(mate_distances, 30.0 - np.arange(9.0))
    opp_angles = values[21:42:2]
    np.testing.assert_array_equal(opp_angles, np.arange(11.0) + 0.5)
    np.testing.assert_array_equal(values[20:42:2], 5.0 + np.arange(11.0) % 4)
    # Counts see every player, listed or not.
    p = dict(zip(PASSER_NAMES, values.tolist(), strict=True))
    assert p["passer teammates ang6"] == 6
    assert p["passer opponents ang6"] == 6  # 0.5 .. 5.5
    assert p["passer players ang6"] == 12


def test_angles_wrap_across_plus_minus_180() -> None:
    # Receiver behind-left at 175°; a teammate at -178° is 7° from it, one at 170° is 5°.
    p = _passer((20.0, 175.0), (20.0, -178.0, 1), (20.0, 170.0, 1), (20.0, -175.0, -1))
    assert p["passer teammate1 angle"] == pytest.approx(5.0)
    assert p["passer teammate2 angle"] == pytest.approx(7.0)
    assert p["passer opponent1 angle"] == pytest.approx(10.0)
    assert p["passer teammates ang6"] == 1
    assert p["passer teammates dist4 ang8"] == 2  # 20·2·sin(3.5°) = 2.44 < 4
    # The receiver's own angle is the one signed attribute, wrapped to [-180, 180).
    assert _passer((20.0, 190.0))["passer receiver angle"] == pytest.approx(-170.0)
    assert _passer((20.0, -540.0))["passer receiver angle"] == pytest.approx(-180.0)
    # Any reference direction gives the same attributes: turning the whole view changes only
    # the receiver's angle.
    base = passer_attributes(20.0, 0.0, *_view(*SCENE))
    d, a, t = _view(*SCENE)
    turned = passer_attributes(20.0, 0.0 + 270.0, d, a + 270.0, t)
    np.testing.assert_allclose(turned[2:], base[2:], atol=1e-9)


def test_offsets_are_absolute_and_at_most_180() -> None:
    rng = np.random.default_rng(3)
    d = rng.uniform(0.0, 60.0, 12)
    a = rng.uniform(-720.0, 720.0, 12)
    t = np.where(rng.random(12) < 0.5, 1, -1).astype(np.int8)
    values = passer_attributes(20.0, 33.0, d, a, t)
    angles = values[3:42:2]
    angles = angles[~np.isnan(angles)]
    assert angles.size == min(np.sum(t == 1), 9) + min(np.sum(t == -1), 11) >= 10
    assert np.all((angles >= 0.0) & (angles <= 180.0))


# ----------------------------------------------------------------------------- receiver's half


def test_receiver_half_hand_built() -> None:
    # The receiver faces the passer, 20 units away. A teammate 5 units off to the left, an
    # opponent 3 units behind (-170° wraps to 170° from the passer), an opponent 25 units away
    # 2° from the passer (5.06 from it by the law of cosines), one of unknown team beside the
    # passer.
    r = _receiver(
        (20.0, 0.0),
        (5.0, 90.0, 1),
        (3.0, -170.0, -1),
        (25.0, 2.0, -1),
        (21.0, -1.0, 0),
    )
    assert _cosine_law(25.0, 2.0, 20.0) == pytest.approx(5.06, abs=1e-2)
    assert _cosine_law(21.0, 1.0, 20.0) == pytest.approx(1.06, abs=1e-2)
    # Teammates by distance, the passer itself included at angle 0.
    assert (r["receiver teammate1 distance"], r["receiver teammate1 angle"]) == (5.0, 90.0)
    assert (r["receiver teammate2 distance"], r["receiver teammate2 angle"]) == (20.0, 0.0)
    assert math.isnan(r["receiver teammate3 distance"])
    assert (r["receiver opponent1 distance"], r["receiver opponent1 angle"]) == (3.0, 170.0)
    assert (r["receiver opponent2 distance"], r["receiver opponent2 angle"]) == (25.0, 2.0)
    assert math.isnan(r["receiver opponent3 angle"])
    # Counts around the passer; the passer itself is not counted.
    assert r["receiver teammates dist8 ang12"] == 0
    assert r["receiver teammates ang1"] == 0
    assert r["receiver opponents dist4 ang4"] == 0
    assert r["receiver opponents dist8 ang4"] == 1
    assert r["receiver opponents ang2"] == 1
    assert r["receiver opponents ang1"] == 0
    assert r["receiver players dist4 ang4"] == 1  # the unknown-team player
    assert r["receiver players dist8 ang12"] == 2
    assert r["receiver players ang1"] == 1


def test_receiver_lists_sort_by_distance_and_keep_ten_and_eleven() -> None:
    mates = [(float(k), 45.0 + k, 1) for k in (12, 3, 30, 7, 1, 18, 25, 9, 14, 2, 40, 5)]
    opps = [(float(k), -30.0 - k, -1) for k in (50, 4, 6, 11, 13, 8, 22, 19, 16, 10, 21, 17, 15)]
    values = receiver_attributes(10.0, 0.0, *_view(*opps, *mates))
    mate_d = values[0:20:2]
    # The 10 nearest of the 12 teammates and the passer (10.0, angle 0).
    np.testing.assert_array_equal(mate_d, [1, 2, 3, 5, 7, 9, 10, 12, 14, 18])
    assert values[2 * 6 + 1] == 0.0  # the passer's entry
    np.testing.assert_allclose(values[1:20:2][mate_d != 10.0], 45.0 + mate_d[mate_d != 10.0])
    opp_d = values[20:42:2]
    np.testing.assert_array_equal(opp_d, [4, 6, 8, 10, 11, 13, 15, 16, 17, 19, 21])
    np.testing.assert_allclose(values[21:42:2], 30.0 + opp_d)


def test_passer_ahead_of_a_teammate_at_the_same_distance() -> None:
    r = _receiver((8.0, 0.0), (8.0, 40.0, 1))
    assert r["receiver teammate1 angle"] == 0.0
    assert r["receiver teammate2 angle"] == 40.0


def test_counts_agree_with_a_cartesian_reference() -> None:
    # Random scenes against a slow reference in x, y (no law of cosines, no vectorising).
    rng = np.random.default_rng(7)
    for _ in range(200):
        k = int(rng.integers(0, 14))
        d = rng.uniform(0.0, 40.0, k)
        a = rng.uniform(-180.0, 180.0, k)
        t = rng.integers(-1, 2, k).astype(np.int8)
        target_d, target_a = float(rng.uniform(2.0, 30.0)), float(rng.uniform(-180, 180))
        # Cluster some players near the target so that the small regions are not all empty.
        near = rng.random(k) < 0.5
        a[near] = target_a + rng.uniform(-14.0, 14.0, near.sum())
        d[near] = np.maximum(target_d + rng.uniform(-10.0, 10.0, near.sum()), 0.1)
        tx, ty = _xy(target_d, target_a)
        expected = []
        for kind in (1, -1, None):
            for max_d, max_a in COUNT_REGIONS:
                n = 0
                for di, ai, ti in zip(d, a, t, strict=True):
                    x, y = _xy(di, ai)
                    # The offset: the angle between the two position vectors.
                    off = math.degrees(math.atan2(abs(x * ty - y * tx), x * tx + y * ty))
                    n += (kind is None or ti == kind) and (
                        off <= max_a and (max_d is None or math.hypot(x - tx, y - ty) <= max_d)
                    )
                expected.append(n)
        got = passer_attributes(target_d, target_a, d, a, t)[42:]
        np.testing.assert_array_equal(got, expected)
        got = receiver_attributes(target_d, target_a, d, a, t)[42:]
        np.testing.assert_array_equal(got, expected)


def test_unknown_distance_counts_only_in_the_angle_regions() -> None:
    p = _passer((20.0, 0.0), (math.nan, 2.0, -1))
    assert p["passer opponents ang2"] == 1
    assert p["passer opponents dist12 ang12"] == 0
    assert math.isnan(p["passer opponent1 distance"])
    assert p["passer opponent1 angle"] == 2.0


def test_team_arrays_may_be_lists_of_ints() -> None:
    d, a, t = _view(*SCENE)
    np.testing.assert_array_equal(
        passer_attributes(20.0, 0.0, d.tolist(), a.tolist(), [int(x) for x in t]),
        passer_attributes(20.0, 0.0, d, a, t),
    )


@pytest.mark.parametrize("builder", [passer_attributes, receiver_attributes])
def test_bad_input_is_refused(builder: Callable[..., F64]) -> None:
    d, a, t = _view(*SCENE)
    with pytest.raises(ValueError, match="seen"):
        builder(math.nan, 0.0, d, a, t)
    with pytest.raises(ValueError, match="seen"):
        builder(20.0, math.inf, d, a, t)
    with pytest.raises(ValueError, match="shapes"):
        builder(20.0, 0.0, d, a[:-1], t)
    for bad in (np.array([1, 2, 0, 1, 1], dtype=np.int8), [1, 0, -2, 1, 1], [1, 0, 0.5, 1, 1]):
        with pytest.raises(ValueError, match="team"):
            builder(20.0, 0.0, d, a, bad)
    bad8 = t.copy()
    bad8[2] = -128
    with pytest.raises(ValueError, match="team"):
        builder(20.0, 0.0, d, a, bad8)


# ----------------------------------------------------------------------------- the 174


def test_pass_attributes_joins_the_halves() -> None:
    passer = passer_attributes(20.0, 0.0, *_view(*SCENE))
    receiver = receiver_attributes(20.0, 180.0, *_view((5.0, 10.0, 1)))
    both = pass_attributes(passer, receiver)
    assert both.shape == (174,)
    np.testing.assert_array_equal(both[:87], passer)
    np.testing.assert_array_equal(both[87:], receiver)
    assert both[ATTRIBUTE_NAMES.index("receiver teammate1 distance")] == 5.0
    unheard = pass_attributes(passer, unknown_half())
    assert unknown_half().shape == (87,)
    assert np.isnan(unheard[87:]).all()
    assert not np.isnan(unheard[42:87]).any()
    with pytest.raises(ValueError, match="shape"):
        pass_attributes(passer[:-1], receiver)
    with pytest.raises(ValueError, match="shape"):
        pass_attributes(passer, both)


def test_learning_stays_free_of_the_simulators_and_heavy_libraries() -> None:
    code = (
        "import sys, learning.pass_features; "
        "print(sorted(m for m in ('robotsoccer', 'field_models', 'pymunk', 'rerun', 'torch', "
        "'sklearn') if m in sys.modules))"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "[]"


# ----------------------------------------------------------------------------- the say codec

# The Soccer Server's say alphabet without space, parentheses and quotes.
SAY_SAFE = re.compile(r"[-0-9a-zA-Z.+*/?<>_]*")


def _random_view(
    rng: np.random.Generator, k: int
) -> tuple[float, float, F64, F64, npt.NDArray[np.int8]]:
    return (
        float(rng.uniform(0.0, 60.0)),
        float(rng.uniform(-180.0, 180.0)),
        rng.uniform(0.0, 120.0, k),
        rng.uniform(-180.0, 180.0, k),
        rng.integers(-1, 2, k).astype(np.int8),
    )


def _angle_error(a: npt.ArrayLike, b: npt.ArrayLike) -> F64:
    return np.abs((np.asarray(a, dtype=float) - np.asarray(b, dtype=float) + 180.0) % 360.0 - 180.0)


def test_view_message_length() -> None:
    assert view_message_length(0) == 5
    assert view_message_length(1) == 10  # rcssserver 19's say_msg_size: the passer and one more
    assert view_message_length(21) == 110
    assert view_message_length(101) <= 512 < view_message_length(102)  # the 1998 server
    with pytest.raises(ValueError):
        view_message_length(-1)


@pytest.mark.parametrize("k", [0, 1, 5, 21])
def test_codec_round_trip_within_the_quantisation_step(k: int) -> None:
    rng = np.random.default_rng(k)
    for _ in range(50):
        view = _random_view(rng, k)
        text = encode_view(*view)
        assert len(text) == view_message_length(k)
        assert SAY_SAFE.fullmatch(text)
        pd, pa, d, a, t = decode_view(text)
        assert abs(pd - view[0]) <= DISTANCE_STEP / 2 + 1e-9
        assert _angle_error(pa, view[1]) <= ANGLE_STEP_DEG / 2 + 1e-9
        assert np.all(np.abs(d - view[2]) <= DISTANCE_STEP / 2 + 1e-9)
        assert np.all(_angle_error(a, view[3]) <= ANGLE_STEP_DEG / 2 + 1e-9)
        assert np.all((a >= -180.0) & (a < 180.0))
        np.testing.assert_array_equal(t, view[4])
        assert t.dtype == np.int8
        # Decoded values are on the grid, so a second round trip is exact.
        assert encode_view(pd, pa, d, a, t) == text


def test_codec_edges() -> None:
    angles = [-180.0, 179.99, -0.01, 0.0, 360.0, math.nan]
    text = encode_view(0.0, -0.01, [MAX_DISTANCE, 0.0, 1.0, 2.0, 3.0, math.nan], angles, [1] * 6)
    pd, pa, d, a, t = decode_view(text)
    assert pd == 0.0
    assert pa == 0.0  # -0.01 rounds to the code of 0°: the angle codes wrap around
    assert d[0] == pytest.approx(MAX_DISTANCE)
    assert a[3] == a[4] == 0.0  # straight at the passer is on the grid
    assert np.all(_angle_error(a[:5], angles[:5]) <= ANGLE_STEP_DEG / 2 + 1e-9)
    assert np.all((a[:5] >= -180.0) & (a[:5] < 180.0))
    assert math.isnan(d[5]) and math.isnan(a[5])
    assert t.tolist() == [1] * 6
    empty = encode_view(20.0, 0.0, [], [], [])
    assert len(empty) == 5
    pd, pa, d, a, t = decode_view(empty)
    assert (pd, pa, d.size, a.size, t.size) == (20.0, 0.0, 0, 0, 0)


@pytest.mark.parametrize(
    "text",
    [
        "",
        "v",
        "v123",
        "w1234",
        "v1234abcd",  # 4 characters of a player
        "v1234abcdx",  # x is no team character
        "v12 4",
        "v1234(bcdt",
        "v12é4",
        "(say v1234)",
    ],
)
def test_decode_rejects_garbage(text: str) -> None:
    with pytest.raises(ValueError):
        decode_view(text)


def test_decode_rejects_non_text() -> None:
    with pytest.raises(ValueError):
        decode_view(b"v1234")  # type: ignore[arg-type]


def test_encode_refuses_what_it_cannot_carry() -> None:
    with pytest.raises(ValueError, match="distances"):
        encode_view(20.0, 0.0, [MAX_DISTANCE + 0.1], [0.0], [1])
    with pytest.raises(ValueError, match="distances"):
        encode_view(-1.0, 0.0, [], [], [])
    with pytest.raises(ValueError, match="angles"):
        encode_view(20.0, 0.0, [3.0], [math.inf], [1])
    with pytest.raises(ValueError, match="team"):
        encode_view(20.0, 0.0, [3.0], [0.0], np.array([3], dtype=np.int8))


def test_receiver_half_survives_the_say_codec() -> None:
    # Players kept away from the region boundaries, so quantisation cannot change a count.
    rng = np.random.default_rng(11)
    bounds_a = np.array([1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 8.0, 12.0])
    bounds_d = np.array([4.0, 8.0, 12.0])
    for _ in range(100):
        pd, pa = float(rng.uniform(5.0, 30.0)), float(rng.uniform(-180.0, 180.0))
        d = np.concatenate((rng.uniform(0.5, 50.0, 8), pd + rng.uniform(-4.5, 6.0, 6)))
        a = np.concatenate((rng.uniform(-180.0, 180.0, 8), pa + rng.uniform(-13.0, 13.0, 6)))
        t = rng.integers(-1, 2, d.size).astype(np.int8)
        off = _angle_error(a, pa)
        to_passer = np.sqrt(d**2 + pd**2 - 2 * d * pd * np.cos(np.radians(off)))
        clear = (np.abs(off[:, None] - bounds_a).min(axis=1) > 0.2) & (
            np.abs(to_passer[:, None] - bounds_d).min(axis=1) > 0.2
        )
        # ... and apart in distance, so quantisation cannot swap two players in a list.
        sorted_d = np.sort(np.append(d[clear], pd))
        apart = np.abs(d[:, None] - sorted_d).min(
            axis=1, initial=np.inf, where=d[:, None] != sorted_d
        )
        d, a, t = d[clear & (apart > 0.1)], a[clear & (apart > 0.1)], t[clear & (apart > 0.1)]
        direct = receiver_attributes(pd, pa, d, a, t)
        heard = receiver_attributes(*decode_view(encode_view(pd, pa, d, a, t)))
        np.testing.assert_array_equal(heard[42:], direct[42:])
        np.testing.assert_array_equal(np.isnan(heard), np.isnan(direct))
        lists_d, lists_a = slice(0, 42, 2), slice(1, 42, 2)
        np.testing.assert_allclose(heard[lists_d], direct[lists_d], rtol=0, atol=DISTANCE_STEP)
        np.testing.assert_allclose(heard[lists_a], direct[lists_a], rtol=0, atol=ANGLE_STEP_DEG)
