"""The robot engine's fast paths (issue 21) give exactly what the plain paths give.

* positional makers build the same frozen dataclass objects as their ``__init__``;
* a robot at steady wheel speeds that cruises moves bit for bit as it would under full steering;
* the host's identity row look-up agrees with the hash look-up, equal copies included;
* robot and ball states built as tuples are the BodyState their fields make;
* the ball noise computed a chunk at a time, the camera's list draws and the walls built without
  pymunk's wrappers give the numbers and shapes the plain paths give.
"""

from __future__ import annotations

import gc
import math
from dataclasses import dataclass

import numpy as np
import pymunk
import pytest
from pymunk._chipmunk import lib as _cp

from field_models.protocol import (
    LEFT,
    RIGHT,
    BodyState,
    Percept,
    PlayerRef,
    SeenBall,
    SeenLandmark,
    SeenPlayer,
    wrap_angle,
)
from field_models.records import positional_maker
from field_models.robot_physics.camera import Frame, RobotDetection
from field_models.robot_physics.config import load_preset
from field_models.robot_physics.link import Command, Primitive
from field_models.robot_physics.world import RobotWorld, _BallNoise
from field_models.seeding import Stream, stream_key

PRESET = load_preset()
REFS = (PlayerRef(LEFT, 1), PlayerRef(RIGHT, 1), PlayerRef(LEFT, 2))


@pytest.mark.parametrize(
    ("cls", "args"),
    [
        (SeenPlayer, (1.25, -0.5, "left", 3)),
        (SeenBall, (0.75, 2.0, None, None)),
        (SeenLandmark, ("g r", 4.5, 0.125)),
        (Percept, (REFS[0], 12, 4, SeenBall(1.0, 0.5), (SeenPlayer(2.0, 0.1),), (), (), 0.0)),
        (Command, (7, REFS[1], Primitive.TURN, 1.5, 24, 3, 0.0)),
        (RobotDetection, (REFS[2], 0.1, -0.2, 3.0)),
        (Frame, (8, 12, None, ())),
    ],
)
def test_a_positional_maker_builds_the_object_init_builds(cls: type, args: tuple) -> None:
    made = positional_maker(cls)(*args)
    plain = cls(*args)
    assert type(made) is cls
    assert made == plain and hash(made) == hash(plain) and repr(made) == repr(plain)
    with pytest.raises(AttributeError):  # still frozen
        made.__setattr__(next(iter(cls.__slots__)), None)


def test_a_positional_maker_refuses_what_it_cannot_build_faithfully() -> None:
    @dataclass
    class Mutable:
        x: float

    @dataclass(frozen=True)
    class NoSlots:
        x: float

    @dataclass(frozen=True, slots=True)
    class Checked:
        x: float

        def __post_init__(self) -> None:
            if self.x < 0:
                raise ValueError("negative")

    for cls in (Mutable, NoSlots, Checked, int):
        with pytest.raises(TypeError, match=cls.__name__):
            positional_maker(cls)


def _run(world: RobotWorld, plan: list[tuple[int, int, float, float]], ticks: int) -> list:
    """Step `world`, setting (robot, left, right) targets at the planned ticks; every truth."""
    out = []
    for tick in range(ticks):
        for at, i, left, right in plan:
            if at == tick:
                world.set_wheel_targets(i, left, right)
        world.step()
        out.append(world.truth())
    return out


def _world() -> RobotWorld:
    world = RobotWorld(PRESET, REFS)
    world.place_robot(0, -1.0, 0.0, 0.3)
    world.place_robot(1, 0.5, 0.4, -2.0)
    world.place_robot(2, 0.0, -0.5, 1.0)
    world.place_ball(0.0, 0.0, 0.8, 0.3)
    return world


PLAN = [
    (0, 0, 1.0, 1.0),  # straight: ramps, then cruises
    (0, 1, -0.4, 0.4),  # spin in place: ramps, then needs nothing
    (5, 2, 0.9, 0.6),  # an arc: cruises with a spin already set
    (150, 0, 1.0, 1.0),  # the same targets again: back to steering for a tick
    (200, 0, 0.2, 0.8),  # a new target while cruising
    (260, 2, 0.0, 0.0),  # stop: settles at rest
    (300, 1, 0.5, 0.5),
]


def test_cruising_robots_move_exactly_as_fully_steered_ones(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    fast = _run(_world(), PLAN, 420)

    def steer_all(self: RobotWorld) -> None:  # the old rule: leave steering only at rest
        for d in self._moving:
            d.moving = not d.at_rest()
        self._moving = [d for d in self._moving if d.moving]

    monkeypatch.setattr(RobotWorld, "_settle", steer_all)
    plain = _run(_world(), PLAN, 420)
    assert fast == plain
    assert fast[-1].players[REFS[0]].speed > 0.1  # it did drive


def test_cruising_is_used_and_left_on_a_new_target() -> None:
    world = _world()
    world.set_wheel_targets(0, 1.0, 1.0)
    for _ in range(200):
        world.step()
    assert [d for d in world._cruising] == [world._drives[0]]
    world.set_wheel_targets(0, 0.5, 1.0)
    assert world._cruising == [] and world._moving == [world._drives[0]]
    world.place_robot(0, 0.0, 0.0, 0.0)
    assert world._cruising == [] and world._moving == []


def test_states_built_as_tuples_are_the_body_states_of_their_fields() -> None:
    world = _world()
    world.set_wheel_targets(1, -1.0, 1.0)  # spins past ±π
    for _ in range(400):
        world.step()
        state = world.robot_state(1)
        body = world._drives[1].body
        expected = BodyState(
            body.position.x,
            body.position.y,
            wrap_angle(body.angle),
            body.velocity.x,
            body.velocity.y,
        )
        assert type(state) is BodyState and state == expected
    assert abs(world._drives[1].body.angle) > math.pi  # the wrap was exercised
    ball = world.ball_state()
    assert type(ball) is BodyState
    assert ball == BodyState(
        world.ball.position.x, world.ball.position.y, 0.0, *world.ball.velocity
    )


def test_the_host_finds_rows_by_identity_and_by_equality() -> None:
    from field_models.robot_physics.host import CentralHost
    from field_models.robot_physics.link import Link
    from field_models.seeding import TrialRngs

    link = Link(
        PRESET.link, packet_period_ticks=1, latency_ticks=0, rng=TrialRngs.for_trial(0, 0)["link"]
    )
    host = CentralHost(REFS, PRESET, link, frame_period_ticks=8)
    for i, ref in enumerate(REFS):
        assert host._row(ref) == i
        copy = PlayerRef(ref.team, ref.number)
        assert copy is not ref and host._row(copy) == i and host._row_of(copy) == i
    stranger = PlayerRef(RIGHT, 9)
    assert host._row(stranger) == -1
    with pytest.raises(KeyError):
        host._row_of(stranger)


def _old_ball_noise(rng: Stream, pairs: int) -> list[tuple[float, float]]:
    """The ball noise as the world drew it before: whole blocks of 512, used last first."""
    out, block = [], []
    for _ in range(pairs):
        if len(block) < 2:
            block = rng.uniform(-1.0, 1.0, 512).tolist()
        out.append((block.pop(), block.pop()))
    return out


@pytest.mark.parametrize("pairs", [1, 31, 32, 33, 256, 257, 700])
def test_the_ball_noise_gives_the_old_block_numbers_in_the_old_order(pairs: int) -> None:
    # Chunk (64 draws) and block (512) edges are crossed: the numbers and the stream's
    # position afterwards are the old ones.
    old_rng, new_rng = Stream(stream_key(5, 3, "movement")), Stream(stream_key(5, 3, "movement"))
    noise = _BallNoise(new_rng)
    assert [noise.pair() for _ in range(pairs)] == _old_ball_noise(old_rng, pairs)
    assert new_rng.position == old_rng.position
    assert new_rng.random() == old_rng.random()  # a later reader of the stream sees the same


def test_the_ball_noise_takes_a_numpy_generator_as_before() -> None:
    draws = _BallNoise(np.random.default_rng(3))
    old = np.random.default_rng(3).uniform(-1.0, 1.0, 512).tolist()
    assert draws.pair() == (old[-1], old[-2])


def test_list_draws_are_the_array_draws() -> None:
    a, b = Stream(stream_key(1, 2, "camera")), Stream(stream_key(1, 2, "camera"))
    for n in (1, 2, 5, 8, 11, 200):
        assert a.standard_normal_list(n) == b.standard_normal(n).tolist()
        assert a.random_list(n) == b.random(n).tolist()
    assert a.position == b.position
    assert a.draws_list(3, 4) == b.draws_list(3, 4) == Stream(a.key).random(7).tolist()[3:]


def test_raw_walls_are_the_shapes_pymunk_polys_would_be() -> None:
    """The walls built without pymunk's wrappers: same vertices, surface and order in the space."""
    world = RobotWorld(PRESET, REFS)
    raw = world._walls
    expected = pymunk.Space()
    static = expected.static_body
    f = PRESET.field
    count = 0
    for shape in raw:
        assert _cp.cpShapeGetSpace(shape) == world.space._space
        assert _cp.cpShapeGetElasticity(shape) == PRESET.ball.wall_restitution
        assert _cp.cpShapeGetFriction(shape) == 0.2
        corners = [_cp.cpPolyShapeGetVert(shape, i) for i in range(_cp.cpPolyShapeGetCount(shape))]
        poly = pymunk.Poly(static, [(v.x, v.y) for v in corners])
        assert [tuple(v) for v in poly.get_vertices()] == [(v.x, v.y) for v in corners]
        count += 1
    assert count == 12 + (4 if f.corner_fillet_m > 0 else 0)
    # The space frees cleanly whichever goes first: the world (space and walls together), or
    # a wall handle dropped while the space lives.
    del world
    gc.collect()
    other = RobotWorld(PRESET, REFS)
    other._walls.pop()
    gc.collect()
    other.step()
