"""Swept ball–player collisions (a diagnostic preset switch) and preset inheritance."""

from __future__ import annotations

import numpy as np
import pytest

from field_models.presets import PresetError
from field_models.protocol import LEFT, PlayerRef
from field_models.soccer_server.batch import BatchSoccerServer
from field_models.soccer_server.dynamics import SoccerServerModel
from field_models.soccer_server.params import load_server_preset

ONE = (PlayerRef(LEFT, 1),)


def head_on(swept: bool) -> SoccerServerModel:
    """A fast ball and a player running at each other: 1.6 + 1.6 m/cycle ≫ 1.77 m diameter."""
    preset = load_server_preset("soccer_server_1996").replace_dynamics(
        ball_rand=0.0, player_rand=0.0, swept_ball_collisions=swept
    )
    model = SoccerServerModel(preset, ONE, np.random.default_rng(0))
    model.move_player(1, 0.0, 0.0, 0.0)  # facing +x, toward the ball
    model.move_ball(3.5, 0.0, vx_mps=-16.0)
    return model


def test_end_of_cycle_check_lets_a_fast_ball_pass_through_a_dashing_player() -> None:
    model = head_on(swept=False)
    for _ in range(3):
        model.dash(1, 100.0)
        model.step()
    assert model.ball_state().x < model.player_state(1).x  # the ball is behind the player
    assert model.ball_state().vx < 0  # and still going


def test_swept_check_stops_it() -> None:
    model = head_on(swept=True)
    for _ in range(3):
        model.dash(1, 100.0)
        model.step()
    assert model.ball_state().x > model.player_state(1).x  # still in front
    assert model.ball_state().speed < 1.0  # stopped: velocity × −0.1 at each contact


def test_batch_mode_refuses_swept_collisions() -> None:
    preset = load_server_preset("soccer_server_1996_swept")
    with pytest.raises(ValueError, match="swept"):
        BatchSoccerServer(preset, ONE, [np.random.default_rng(0)])


def test_a_variant_preset_inherits_its_base_and_overrides_one_key() -> None:
    base = load_server_preset("soccer_server_1996")
    swept = load_server_preset("soccer_server_1996_swept")
    assert swept.name == "soccer_server_1996_swept" and swept.era == base.era
    assert swept.dynamics.swept_ball_collisions and not base.dynamics.swept_ball_collisions
    assert swept.dynamics.replace(swept_ball_collisions=False) == base.dynamics
    assert swept.sensing == base.sensing


def test_base_errors_name_the_file(tmp_path) -> None:
    cyclic = tmp_path / "a.toml"
    cyclic.write_text(f'base = "{cyclic}"\n')
    with pytest.raises(PresetError, match="cycle"):
        load_server_preset(str(cyclic))
    wrong = tmp_path / "b.toml"
    wrong.write_text("base = 3\n")
    with pytest.raises(PresetError, match=r"b\.toml: key 'base'"):
        load_server_preset(str(wrong))
    typo = tmp_path / "c.toml"
    typo.write_text('base = "soccer_server_1996"\n[dynamics]\nball_rnd = 0.1\n')
    with pytest.raises(PresetError, match=r"c\.toml: key 'dynamics\.ball_rnd'"):
        load_server_preset(str(typo))
