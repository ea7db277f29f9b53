"""A cycle's percepts at once equal the one-player route, bit for bit; whole trials too."""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Sequence
from typing import Any

import numpy as np
import pytest

from field_models.protocol import LEFT, RIGHT, Heard, Percept, PlayerRef
from field_models.seeding import Rng, TrialRngs
from field_models.soccer_server import arena as arena_module
from field_models.soccer_server.percepts import percept_from_state
from field_models.soccer_server.percepts_many import Bodies, percepts_of
from field_models.soccer_server.sensing import LandmarkMode
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
            row, *bodies, players, time, params, rng, tick=time, heard=heard[k], landmarks=landmarks
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


def test_the_check_would_see_a_sign_of_zero() -> None:
    assert bits(0.0) != bits(-0.0) and bits((1.0, None)) == bits([1.0, None])


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
