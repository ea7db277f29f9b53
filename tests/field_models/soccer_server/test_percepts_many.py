"""A cycle's percepts at once equal the one-player route, bit for bit; whole trials too."""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Sequence
from typing import Any

import numpy as np
import pytest

from field_models import fpmath
from field_models.protocol import LEFT, RIGHT, Heard, Percept, PlayerRef
from field_models.seeding import Rng, TrialRngs
from field_models.soccer_server import arena as arena_module
from field_models.soccer_server import percepts_many
from field_models.soccer_server.percepts import percept_from_state
from field_models.soccer_server.percepts_many import percepts_of
from field_models.soccer_server.sensing import Bodies, LandmarkMode
from field_models.soccer_server.sensing_params import SENSING_19, SENSING_1996, SensingParams
from robotsoccer.runs.runner import TrialSpec, run_trial

PLAYERS = tuple(PlayerRef(LEFT, n) for n in range(1, 7)) + tuple(
    PlayerRef(RIGHT, n) for n in range(1, 7)
)
SENSINGS = {
    "1996": SENSING_1996,
    "19": SENSING_19,
    "8": SENSING_19.replace(protocol_version=8, team_far_length_m=40.0, team_too_far_length_m=60.0),
    "rounded": SENSING_1996.replace(direction_mode="round"),
    "low": SENSING_19.replace(view_quality="low"),
    "wide": SENSING_1996.replace(view_width="wide"),
    "perfect": SENSING_19.replace(perfect=True),
    "perfect_1996": SENSING_1996.replace(perfect=True),
}
MODES: tuple[LandmarkMode, ...] = ("goals", "all", "none")


def bits(value: Any) -> Any:
    """A value with every float replaced by its exact hex form (so -0.0 and 0.0 differ)."""
    if isinstance(value, float):
        return value.hex()
    if isinstance(value, tuple | list):
        return tuple(bits(v) for v in value)
    if dataclasses.is_dataclass(value):
        fields = (getattr(value, f.name) for f in dataclasses.fields(value))
        return (type(value).__name__, *(bits(v) for v in fields))
    return value


def one_at_a_time(
    observers: Sequence[int],
    bodies: Bodies,
    players: tuple[PlayerRef, ...],
    params: SensingParams,
    rng: Rng,
    time: int,
    heard: Sequence[tuple[Heard, ...]],
    landmarks: LandmarkMode = "goals",
) -> list[Percept]:
    """The reference: ``percept_from_state`` for each observer in turn."""
    return [
        percept_from_state(
            row, bodies, players, time, params, rng, heard=heard[k], landmarks=landmarks
        )
        for k, row in enumerate(observers)
    ]


def random_state(g: np.random.Generator, kind: int) -> Bodies:
    """Ball and 12 players: spread over the pitch, crowded, or with some on one spot."""
    n = len(PLAYERS) + 1
    spread = (56.0, 37.0) if kind == 0 else (4.0, 4.0)
    x = g.uniform(-spread[0], spread[0], n)
    y = g.uniform(-spread[1], spread[1], n)
    if kind == 2:  # two players on one spot, the ball on a third (offsets of exactly zero)
        x[3], y[3] = x[2], y[2]
        x[0], y[0] = x[5], y[5]
    heading = g.uniform(-math.pi, math.pi, n)
    heading[1] = math.pi if kind == 2 else heading[1]
    return Bodies(
        x.tolist(), y.tolist(), g.uniform(-2, 2, n).tolist(), g.uniform(-2, 2, n).tolist(),
        heading.tolist(),
    )  # fmt: skip


@pytest.mark.parametrize("era", sorted(SENSINGS))
def test_a_cycle_of_percepts_equals_one_see_at_a_time_bit_for_bit(era: str) -> None:
    params = SENSINGS[era]
    g = np.random.default_rng(list(SENSINGS).index(era))
    heard = (Heard("hello", PLAYERS[0], 0.5, 3),)
    for case in range(120):
        bodies = random_state(g, case % 3)
        count = int(g.integers(1, len(PLAYERS) + 1))
        observers = sorted(g.choice(np.arange(1, len(PLAYERS) + 1), count, replace=False).tolist())
        heards = [heard if k % 2 else () for k in range(count)]
        mode = MODES[case % 3]
        rng_a, rng_b = (TrialRngs.for_trial(case, 7)["sensing"] for _ in range(2))
        want = one_at_a_time(observers, bodies, PLAYERS, params, rng_a, 40, heards, mode)
        got = percepts_of(observers, bodies, PLAYERS, params, rng_b, 40, heards, mode)
        assert bits(got) == bits(want), (era, case)
        assert rng_a.random() == rng_b.random()  # both read the same share of the stream


def on_the_boundaries(params: SensingParams) -> Bodies:
    """Observer row 1 at the origin facing +x; the others on a cone edge, on whole degrees (and
    halves), on the axes, and at distances whose log index lies on a half (§3.2, §3.3)."""
    half = params.half_angle_rad
    q = params.quantize_step
    places = [
        (5.0, 5.0),  # 45°: the normal cone's edge (atan2(1, 1) is pi/4 to the last bit)
        (10.0 * math.cos(half), -10.0 * math.sin(half)),
        (math.exp(30.5 * q) - 1e-10, 0.0),  # on the x axis, log index 30.5
        (0.0, math.exp(25.5 * q)),
        (-7.0, 0.0),  # behind, on the axis: ±180°, not felt
        (-2.0, -0.0),  # felt (within 3 m) at ±180°
        (8.0 * math.cos(math.radians(12.0)), 8.0 * math.sin(math.radians(12.0))),
        (8.0 * math.cos(math.radians(-30.5)), 8.0 * math.sin(math.radians(-30.5))),
        (9.0 * math.cos(math.radians(44.0)), 9.0 * math.sin(math.radians(44.0))),
        (3.0, 0.0),
        (20.0, 20.0),
    ]
    x = [1.0, 0.0] + [p[0] for p in places]
    y = [-1.0, 0.0] + [p[1] for p in places]
    zeros = [0.0] * len(x)
    return Bodies(x, y, zeros, zeros, zeros)


@pytest.mark.parametrize("era", ["1996", "rounded", "19", "wide"])
def test_angles_and_distances_on_a_boundary_take_the_exact_scalar_rule(
    era: str, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.setattr(percepts_many, "ARRAY_PAIRS_MIN", 0)  # one observer: arrays all the same
    params = SENSINGS[era]
    bodies = on_the_boundaries(params)
    calls = []
    scalar = fpmath.atan2

    def counted(y: float, x: float) -> float:
        calls.append((y, x))
        return scalar(y, x)

    monkeypatch.setattr(fpmath, "atan2", counted)
    got = percepts_of([1], bodies, PLAYERS, params, np.random.default_rng(3), 5, [()], "all")
    assert calls  # the fast kernel's answer was not trusted near a boundary
    monkeypatch.setattr(fpmath, "atan2", scalar)
    want = one_at_a_time([1], bodies, PLAYERS, params, np.random.default_rng(3), 5, [()], "all")
    assert bits(got) == bits(want)
    assert len(got[0].players) >= 5


def _perturbed(scale: float) -> tuple[Any, Any]:
    """numpy's atan2 and log, each result moved by up to `scale` of itself (a CPU of its own)."""
    g = np.random.default_rng(11)

    def atan2(y: Any, x: Any) -> Any:
        out = np.arctan2(y, x)
        return out * (1.0 + scale * g.uniform(-1.0, 1.0, np.shape(out)))

    def log(x: Any) -> Any:
        out = np.log(x)
        return out + np.abs(out) * scale * g.uniform(-1.0, 1.0, np.shape(out))

    return atan2, log


def _mismatches(monkeypatch: pytest.MonkeyPatch, scale: float) -> int:
    atan2, log = _perturbed(scale)
    monkeypatch.setattr(percepts_many, "ARRAY_PAIRS_MIN", 0)
    monkeypatch.setattr(percepts_many, "_numpy_atan2", atan2)
    monkeypatch.setattr(percepts_many, "_numpy_log", log)
    g = np.random.default_rng(8)
    wrong = 0
    for case in range(150):
        params = (
            SENSING_1996,
            SENSING_19.replace(direction_mode="round"),
            SENSING_1996.replace(quantize_step=1e-5),  # the smallest step: indices near 10^6
        )[case % 3]
        bodies = on_the_boundaries(params) if case < 4 else random_state(g, case % 3)
        observers = [1, 4, 9] if case >= 4 else [1]
        rng_a, rng_b = np.random.default_rng(case), np.random.default_rng(case)
        want = one_at_a_time(observers, bodies, PLAYERS, params, rng_a, 1, [()] * len(observers))
        got = percepts_of(observers, bodies, PLAYERS, params, rng_b, 1, [()] * len(observers))
        wrong += bits(got) != bits(want)
    return wrong


def test_kernels_that_round_otherwise_still_give_the_same_percepts(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    """numpy's kernels may differ from fdlibm's in the last bits on another CPU; within the
    safety margin that changes nothing, while errors far beyond it do show (the check works)."""
    assert _mismatches(monkeypatch, 1e-13) == 0
    assert _mismatches(monkeypatch, 1e-4) > 0


def test_the_check_would_see_a_sign_of_zero() -> None:
    assert bits(0.0) != bits(-0.0) and bits((1.0, None)) == bits([1.0, None])


def test_small_cycles_take_the_one_see_route_and_agree_either_way(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    bodies = random_state(np.random.default_rng(9), 1)
    two = [(), ()]
    calls = []
    monkeypatch.setattr(percepts_many, "_Builder", lambda *a: calls.append(a))
    percepts_of([2, 5], bodies, PLAYERS, SENSING_1996, np.random.default_rng(1), 4, two)
    assert not calls  # 2 observers x 14 objects: below ARRAY_PAIRS_MIN
    monkeypatch.undo()
    monkeypatch.setattr(percepts_many, "ARRAY_PAIRS_MIN", 0)
    got = percepts_of([2, 5], bodies, PLAYERS, SENSING_1996, np.random.default_rng(1), 4, two)
    want = one_at_a_time([2, 5], bodies, PLAYERS, SENSING_1996, np.random.default_rng(1), 4, two)
    assert bits(got) == bits(want)


def test_a_numpy_generator_works_too_and_no_observers_draw_nothing() -> None:
    bodies = random_state(np.random.default_rng(5), 1)
    want = one_at_a_time([2, 9], bodies, PLAYERS, SENSING_19, np.random.default_rng(1), 8, [(), ()])
    got = percepts_of([2, 9], bodies, PLAYERS, SENSING_19, np.random.default_rng(1), 8, [(), ()])
    assert bits(got) == bits(want)
    rng = np.random.default_rng(2)
    assert percepts_of([], bodies, PLAYERS, SENSING_19, rng, 8, []) == []
    assert rng.random() == np.random.default_rng(2).random()


def test_bad_input_is_refused_in_one_line() -> None:
    bodies = random_state(np.random.default_rng(0), 0)
    rng = np.random.default_rng(0)
    with pytest.raises(ValueError, match=r"outside|inside"):
        percepts_of([0], bodies, PLAYERS, SENSING_19, rng, 1, [()])
    with pytest.raises(ValueError, match="heard"):
        percepts_of([1, 2], bodies, PLAYERS, SENSING_19, rng, 1, [()])
    with pytest.raises(ValueError, match="landmarks"):
        percepts_of([1], bodies, PLAYERS, SENSING_19, rng, 1, [()], "flags")  # type: ignore[arg-type]


def _pass_trials(
    monkeypatch: pytest.MonkeyPatch, build: Any, count: int
) -> tuple[list[str], list[Any]]:
    """`count` pass trials on the server with the arena's percepts built by `build`."""
    seen: list[Any] = []

    def recording(*args: Any) -> list[Percept]:
        percepts: list[Percept] = build(*args)
        seen.append(bits(percepts))
        return percepts

    monkeypatch.setattr(arena_module, "percepts_of", recording)
    spec = TrialSpec(drill="pass", field_model="soccer_server", seed=4)
    rows = [run_trial(spec, i).csv_row() for i in range(count)]
    return rows, seen


def test_whole_pass_trials_are_identical_percept_for_percept(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    rows, seen = _pass_trials(monkeypatch, percepts_of, 12)
    ref_rows, ref_seen = _pass_trials(monkeypatch, one_at_a_time, 12)
    assert len(seen) > 100 and seen == ref_seen
    assert rows == ref_rows


def test_layouts_are_looked_up_by_the_players_and_marks_they_were_built_for() -> None:
    bodies = random_state(np.random.default_rng(12), 1)
    swapped = tuple(PlayerRef(RIGHT if p.team == LEFT else LEFT, p.number) for p in PLAYERS)
    observers, heard = [1, 3, 4, 7], [()] * 4
    for players in (PLAYERS, swapped, PLAYERS, tuple(swapped)):
        for mode in MODES:
            want = one_at_a_time(
                observers, bodies, players, SENSING_1996, np.random.default_rng(2), 3, heard, mode
            )
            got = percepts_of(
                observers, bodies, players, SENSING_1996, np.random.default_rng(2), 3, heard, mode
            )
            assert bits(got) == bits(want)
            assert [p.player for p in got] == [players[row - 1] for row in observers]
    key = (id(PLAYERS), (1, 3, 4, 7))
    assert any(k[:2] == key for k in percepts_many._LAYOUTS)
