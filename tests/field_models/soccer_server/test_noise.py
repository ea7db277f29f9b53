"""Noise statistics of the Soccer Server model (specs/soccer_server.md §1.3, §2.2, §2.3, §8.7)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from field_models.protocol import LEFT, PlayerRef
from field_models.soccer_server.dynamics import SoccerServerModel
from field_models.soccer_server.params import load_server_preset

ME = PlayerRef(LEFT, 1)
SPEED = 1.0  # m/cycle
DRAWS = 100_000


def movement_noise(noise_model: str, draws: int = DRAWS) -> np.ndarray:
    """Per-cycle perturbation of a ball moving at SPEED along x (no acceleration, no decay)."""
    preset = load_server_preset("rcssserver_19_async").replace_dynamics(
        noise_model=noise_model, ball_rand=0.05, ball_decay=1.0, referee=False
    )
    m = SoccerServerModel(preset, (ME,), np.random.default_rng(2024))
    out = np.empty((draws, 2))
    for k in range(draws):
        m.move_ball(0.0, 0.0, vx_mps=SPEED / m.dt_s)
        u = m.vx[0]
        m.step()
        out[k] = (m.x[0] - u, m.y[0])
    return out


def test_box_noise_per_axis_variance_is_r2_over_3() -> None:
    n = movement_noise("box")
    r = 0.05 * SPEED
    assert np.abs(n).max() <= r
    for axis in (0, 1):
        assert n[:, axis].var() == pytest.approx(r * r / 3.0, rel=0.05)
        assert abs(n[:, axis].mean()) < 0.01 * r


def test_polar_noise_per_axis_variance_is_r2_over_6() -> None:
    n = movement_noise("polar")
    r = 0.05 * SPEED
    radius = np.hypot(n[:, 0], n[:, 1])
    assert radius.max() <= r * (1.0 + 1e-12)
    assert radius.mean() == pytest.approx(r / 2.0, rel=0.05)  # radius uniform on [0, R]
    for axis in (0, 1):
        assert n[:, axis].var() == pytest.approx(r * r / 6.0, rel=0.05)


def test_noise_scales_with_speed_after_the_kick() -> None:
    # §1.3: a ball kicked from rest already gets noise in the kick cycle, sized 0.05 * 2.7.
    preset = load_server_preset("rcssserver_19_async").replace_dynamics(
        kick_rand=0.0, referee=False
    )
    deviations = []
    for seed in range(300):
        m = SoccerServerModel(preset, (ME,), np.random.default_rng(seed))
        m.move_ball(0.385, 0.0)
        m.move_player(1, 0.0, 0.0, 0.0)
        m.kick(1, 100.0, 0.0)
        m.step()
        deviations.append(math.hypot(m.x[0] - 0.385 - 2.7, m.y[0]))
    assert max(deviations) <= 0.05 * 2.7
    assert max(deviations) > 0.8 * 0.05 * 2.7


def test_a_ball_at_rest_stays_at_rest() -> None:
    n = movement_noise("polar", draws=10)
    assert n.shape == (10, 2)
    m = SoccerServerModel(
        load_server_preset("rcssserver_19_async"), (ME,), np.random.default_rng(1)
    )
    m.move_ball(3.0, 4.0)
    for _ in range(50):
        m.step()
    assert (m.x[0], m.y[0]) == (3.0, 4.0)


def test_turn_noise_is_uniform_within_player_rand() -> None:
    preset = load_server_preset("soccer_server_1996").replace_dynamics(referee=False)
    m = SoccerServerModel(preset, (ME,), np.random.default_rng(7))
    turns = []
    for _ in range(20_000):
        m.move_player(1, 0.0, 10.0, 0.0)
        m.turn(1, 1.0)
        m.step()
        turns.append(m.heading[1])
    t = np.array(turns)
    assert t.min() >= 0.9 and t.max() < 1.1  # (1 + ξ)·1 rad, ξ uniform in ±0.1
    assert t.min() < 0.901 and t.max() > 1.099
    assert t.var() == pytest.approx(0.1**2 / 3.0, rel=0.05)


def kick_noise(name: str, **changes: object) -> np.ndarray:
    """Deviation of a power-50 kick's acceleration (1.35, below every cap) from its mean."""
    preset = load_server_preset(name).replace_dynamics(
        ball_rand=0.0,
        referee=False,
        kick_reduction=True,
        kick_power_rate_m_per_cycle2=0.027,
        **changes,
    )
    m = SoccerServerModel(preset, (ME,), np.random.default_rng(99))
    touch = m.params.player_size_m + m.params.ball_size_m
    out = np.empty((20_000, 2))
    for k in range(len(out)):
        m.move_ball(touch, 0.0)
        m.move_player(1, 0.0, 0.0, 0.0)
        m.kick(1, 50.0, 0.0)
        m.step()
        out[k] = (m.x[0] - touch - 1.35, m.y[0])
    return out


def test_todays_kick_noise_is_polar_with_the_spec_radius() -> None:
    # §2.3: pos_rate 0.5 (touching, straight ahead), speed_rate 0.5 (ball at rest):
    # R = kick_rand · (50/100) · 1.0 = 0.05.
    n = kick_noise("rcssserver_19_async")
    r = 0.05
    assert np.hypot(n[:, 0], n[:, 1]).max() <= r * (1.0 + 1e-9)
    for axis in (0, 1):
        assert n[:, axis].var() == pytest.approx(r * r / 6.0, rel=0.05)


def test_box_kick_noise_when_switched_on_in_the_old_model() -> None:
    # 6.07-11.x form: each axis uniform on ±kick_rand · P/maxpower = ±0.05.
    n = kick_noise("soccer_server_1996", kick_rand=0.1, ball_accel_max_m_per_cycle2=10.0)
    assert np.abs(n).max() <= 0.05 * (1.0 + 1e-9)
    for axis in (0, 1):
        assert n[:, axis].var() == pytest.approx(0.05**2 / 3.0, rel=0.05)


def test_1996_preset_has_no_kick_noise() -> None:
    n = kick_noise("soccer_server_1996")
    assert np.abs(n).max() < 1e-12
