"""Batch mode equals one-at-a-time, seed for seed, noise included."""

from __future__ import annotations

import math

import numpy as np
import pytest

from field_models.protocol import LEFT, RIGHT, PlayerRef
from field_models.seeding import Stream, StreamBatch, TrialRngs
from field_models.soccer_server.batch import BatchSoccerServer
from field_models.soccer_server.cycle_rules import PLAY_MODES
from field_models.soccer_server.dynamics import SoccerServerModel
from field_models.soccer_server.params import load_server_preset

PLAYERS = (PlayerRef(LEFT, 1), PlayerRef(RIGHT, 1), PlayerRef(RIGHT, 2))
K = 12
CYCLES = 300  # crosses the single model's 256-cycle and the batch's 64-cycle blocks


def rngs(seed: int) -> list[np.random.Generator]:
    return [np.random.default_rng([seed, k]) for k in range(K)]


def place_all(
    singles: list[SoccerServerModel], batch: BatchSoccerServer, g: np.random.Generator
) -> None:
    """Ball and players close together (so kicks and collisions happen), same in both."""
    bx, by = g.uniform(-40.0, 40.0, K), g.uniform(-25.0, 25.0, K)
    for k, m in enumerate(singles):
        m.move_ball(bx[k], by[k], 10.0, -2.0)
    batch.move_ball(bx, by, 10.0, -2.0)
    for i in range(1, len(PLAYERS) + 1):
        px, py = bx + g.uniform(-1.5, 1.5, K), by + g.uniform(-1.5, 1.5, K)
        h = g.uniform(-4.0, 4.0, K)
        for k, m in enumerate(singles):
            m.move_player(i, px[k], py[k], h[k])
        batch.move_player(i, px, py, h)


def command_all(
    singles: list[SoccerServerModel],
    batch: BatchSoccerServer,
    kind: np.ndarray,
    a: np.ndarray,
    b: np.ndarray,
) -> None:
    """kind per (trial, player): 0 none, 1 dash, 2 turn, 3 kick, 4 dash then turn (ignored).

    Dashes of kind 1 take the direction `b` (clamped and rounded by the preset), kind 4 none.
    """
    for i in range(1, len(PLAYERS) + 1):
        kk, aa, bb = kind[:, i - 1], a[:, i - 1], b[:, i - 1]
        for k, m in enumerate(singles):
            if kk[k] == 1:
                m.dash(i, aa[k], bb[k])
            if kk[k] == 4:
                m.dash(i, aa[k])
            if kk[k] in (2, 4):
                m.turn(i, bb[k])
            if kk[k] == 3:
                m.kick(i, aa[k], bb[k])
        batch.dash(i, aa, bb, mask=kk == 1)
        batch.dash(i, aa, mask=kk == 4)
        batch.turn(i, bb, mask=(kk == 2) | (kk == 4))
        batch.kick(i, aa, bb, mask=kk == 3)


def assert_same(singles: list[SoccerServerModel], batch: BatchSoccerServer) -> None:
    for name in ("x", "y", "vx", "vy", "heading"):
        single = np.array([getattr(m, name) for m in singles])
        np.testing.assert_array_equal(getattr(batch, name), single)
    assert [m.play_mode for m in singles] == [batch.mode_name(k) for k in range(K)]
    assert [m.score_left for m in singles] == batch.score_left.tolist()
    assert [m.score_right for m in singles] == batch.score_right.tolist()


def count_kickable(singles: list[SoccerServerModel], kind: np.ndarray) -> int:
    """Kick commands of this cycle whose ball is within the kickable area."""
    count = 0
    for k, m in enumerate(singles):
        for i in np.flatnonzero(kind[k] == 3) + 1:
            reach = m.params.kickable_area_m
            count += math.hypot(m.x[0] - m.x[i], m.y[0] - m.y[i]) <= reach
    return count


def streams(seed: int) -> tuple[list[Stream], StreamBatch]:
    """The trials' counter-based "movement" streams, one by one and as one batch."""
    one = [TrialRngs.for_trial(seed, k)["movement"] for k in range(K)]
    return one, StreamBatch.for_trials(seed, np.arange(K), "movement")


@pytest.mark.parametrize("source", ["generators", "streams"])
@pytest.mark.parametrize("name", ["rcssserver_19_async", "soccer_server_1996"])
def test_batch_equals_single_models_seed_for_seed(name: str, source: str) -> None:
    preset = load_server_preset(name)
    if source == "streams":  # turn and kick draws are computed only when they happen
        one, many = streams(5)
        singles = [SoccerServerModel(preset, PLAYERS, s) for s in one]
        batch = BatchSoccerServer(preset, PLAYERS, many)
    else:
        singles = [SoccerServerModel(preset, PLAYERS, rng) for rng in rngs(5)]
        batch = BatchSoccerServer(preset, PLAYERS, rngs(5))
    g = np.random.default_rng(77)
    place_all(singles, batch, g)
    heard_single: list[list[tuple[int, str]]] = [[] for _ in range(K)]
    heard_batch: list[list[tuple[int, str]]] = [[] for _ in range(K)]
    kicks = 0
    for t in range(CYCLES):
        if t == 120:  # a shot at the right goal in every trial, then a few stopped trials
            for m in singles:
                m.move_ball(50.0, 0.0, 30.0, 0.0)
            batch.move_ball(50.0, 0.0, 30.0, 0.0)
        if t == 200:
            held = np.arange(K) % 3 == 0
            for trial in np.flatnonzero(held).tolist():
                singles[trial].change_mode("before_kick_off")
            batch.change_mode("before_kick_off", mask=held)
        shape = (K, len(PLAYERS))
        kind = g.integers(0, 5, shape)
        command_all(singles, batch, kind, g.uniform(-150, 150, shape), g.uniform(-4, 4, shape))
        kicks += count_kickable(singles, kind)
        for k, m in enumerate(singles):
            heard_single[k] += [(t, text) for text in m.step()]
        for k, text in batch.step():
            heard_batch[k].append((t, text))
        assert_same(singles, batch)
    assert heard_single == heard_batch
    assert any(any(text.startswith("goal_") for _, text in h) for h in heard_single)
    assert kicks >= 5  # kicks were taken, so their noise was compared too
    assert batch.cycle == CYCLES


def test_move_with_collision_and_state_accessors_match() -> None:
    preset = load_server_preset("rcssserver_19_async")
    singles = [SoccerServerModel(preset, PLAYERS, rng) for rng in rngs(9)]
    batch = BatchSoccerServer(preset, PLAYERS, rngs(9))
    for k, m in enumerate(singles):
        m.move_ball(1.0 * k, 0.0)
        m.move_player(1, 1.0 * k + 0.2, 0.1, 0.5)  # onto the ball: both pushed apart
    batch.move_ball(np.arange(K, dtype=float), 0.0)
    batch.move_player(1, np.arange(K) + 0.2, 0.1, 0.5)
    assert_same(singles, batch)
    first = singles[0]
    assert math.hypot(first.x[1] - first.x[0], first.y[1] - first.y[0]) >= 0.385
    assert batch.ball_state(3) == singles[3].ball_state()
    assert batch.player_state(3, 1) == singles[3].player_state(1)
    assert batch.row(PLAYERS[2]) == singles[0].row(PLAYERS[2]) == 3


def test_masked_commands_and_one_body_command_per_cycle() -> None:
    preset = load_server_preset("rcssserver_19_async").replace_dynamics(
        player_rand=0.0, ball_rand=0.0
    )
    batch = BatchSoccerServer(preset, PLAYERS, rngs(1))
    batch.move_player(1, -10.0, 0.0, 0.0)
    mask = np.arange(K) < 4
    accepted = batch.dash(1, 100.0, mask=mask)
    assert accepted.tolist() == mask.tolist()
    assert not batch.turn(1, 1.0, mask=mask).any()  # second body command of the cycle
    assert batch.turn(1, 1.0, mask=~mask).tolist() == (~mask).tolist()
    batch.step()
    assert batch.x[mask, 1] == pytest.approx(-9.4)
    assert batch.x[~mask, 1] == pytest.approx(-10.0)
    assert batch.heading[~mask, 1] == pytest.approx(1.0)
    assert batch.heading[mask, 1] == pytest.approx(0.0)


def test_change_mode_is_announced_per_trial() -> None:
    batch = BatchSoccerServer(load_server_preset("rcssserver_19_async"), PLAYERS, rngs(2))
    batch.change_mode("kick_off_l", mask=np.arange(K) == 2)
    assert batch.step() == [(2, "kick_off_l")]
    assert batch.mode_name(2) == "kick_off_l" and batch.mode_name(1) == "play_on"
    with pytest.raises(ValueError, match="unknown play mode"):
        batch.change_mode("half_time")
    assert "play_on" in PLAY_MODES


@pytest.mark.parametrize("name", ["rcssserver_19_async", "soccer_server_1996"])
def test_directed_dashes_equal_the_single_model(name: str) -> None:
    preset = load_server_preset(name).replace_dynamics(player_rand=0.0, ball_rand=0.0)
    directions = np.radians(np.linspace(-200.0, 200.0, K))  # beyond the range, off the step
    singles = [SoccerServerModel(preset, PLAYERS, rng) for rng in rngs(4)]
    batch = BatchSoccerServer(preset, PLAYERS, rngs(4))
    for k, m in enumerate(singles):
        m.move_player(1, -10.0, 0.0, 0.3)
        assert m.dash(1, 80.0, float(directions[k]))
    batch.move_player(1, -10.0, 0.0, 0.3)
    assert batch.dash(1, 80.0, directions).all()
    for m in singles:
        m.step()
    batch.step()
    assert_same(singles, batch)
    moved = np.hypot(batch.x[:, 1] + 10.0, batch.y[:, 1])
    if name == "rcssserver_19_async":  # side and back dashes are slower than straight ones
        assert moved.min() < 0.7 * moved.max()
    else:  # no dash direction in 1996: every dash runs straight ahead
        np.testing.assert_allclose(moved, 0.8, atol=1e-12)
