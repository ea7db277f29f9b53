"""The conformance suite every field model passes, in the manner of Gymnasium's env checker.

Each check builds arenas of one registered field model through :mod:`field_models.registry`
and drives them only through the :class:`~field_models.arena.Arena` interface, so a field model
added later runs the same checks unchanged (``tests/field_models/test_conformance.py`` runs them
on every registered model). A failed check raises :class:`ConformanceError` saying what the
interface promised and what the model did.

What is checked (distances in the field's own units, pitch length / 105, so one tolerance fits
a 2.74 m table and a 105 m pitch):

* :func:`check_facts` — the facts are consistent: positive tick, sensor period at least a tick,
  a ball law whose closed forms invert each other, a kick that reaches beyond the body;
* :func:`check_placement_and_stepping` — placed objects are where they were put, at rest; the
  tick counts steps; truth agrees with the coach's accessors; a rolling ball follows the
  field's ball law;
* :func:`check_percepts` — percepts come once per sensor period, for the listening players
  only, never before their sample; they are egocentric (left positive) and carry the ball,
  the other player with its identity, and the goal in view where they should be;
* :func:`check_actions` — a turn turns the body toward its sign, a dash runs along the heading,
  a kick (or a push where there is no kicker) sends the ball forward;
* :func:`check_head` — a neck turn and a view change go beside a body command without taking
  its place, and percepts measure from the head (``Percept.neck_rad`` from the body), so
  :meth:`~field_models.protocol.Percept.body_relative` shows the ball where the body has it
  (a model without a head accepts both and keeps ``neck_rad`` 0);
* :func:`check_hearing` — a say reaches another player's percept;
* :func:`check_events` — kept events carry every command in the client's command text;
* :func:`check_determinism` — the same seed gives the same percepts and truth, another seed
  does not.
"""

from __future__ import annotations

import math
from collections.abc import Callable

from field_models.arena import Arena, FieldOptions
from field_models.benchmarks import ChaseLoad
from field_models.commands import render_command
from field_models.protocol import (
    LEFT,
    RIGHT,
    Action,
    ChangeView,
    Dash,
    Kick,
    Percept,
    PlayerRef,
    Say,
    Turn,
    TurnNeck,
    wrap_angle,
)
from field_models.registry import conformance_limits, field_facts, make_arena
from field_models.seeding import TrialRngs

A = PlayerRef(LEFT, 1)
"""The player the checks mostly drive."""
B = PlayerRef(RIGHT, 1)
"""The other player: seen, heard, or out of the way."""
PLAYERS = (A, B)

QUIET = FieldOptions(perfect_perception=True, ball_noise=0.0)
"""Exact sensing, no ball noise: what the geometric checks run with."""


class ConformanceError(AssertionError):
    """A field model broke a promise of the Arena interface."""


def _require(ok: bool, model: str, what: str) -> None:
    if not ok:
        raise ConformanceError(f"{model}: {what}")


def _arena(
    model: str,
    preset: str | None,
    options: FieldOptions = QUIET,
    seed: int = 0,
    keep_events: bool = False,
) -> Arena:
    return make_arena(
        model, preset, PLAYERS, TrialRngs.for_trial(seed, 0), options, keep_events=keep_events
    )


def _ticks(arena: Arena, seconds: float) -> int:
    return max(1, round(seconds / arena.facts.dt_s))


def _run(
    arena: Arena, seconds: float, mind: Callable[[Percept], tuple[Action, ...]] | None = None
) -> list[Percept]:
    """Step for `seconds`; every percept goes to `mind` (if any), its actions to the arena."""
    seen: list[Percept] = []
    for _ in range(_ticks(arena, seconds)):
        for percept in arena.step():
            seen.append(percept)
            if mind is not None:
                arena.submit(percept.player, mind(percept))
    return seen


def _park(arena: Arena, ref: PlayerRef = B) -> None:
    """Put a player in a corner of the field, out of the way, facing the centre."""
    pitch = arena.facts.pitch
    x, y = -0.8 * pitch.half_length_m, -0.8 * pitch.half_width_m
    arena.place_player(ref, x, y, math.atan2(-y, -x))


# ----------------------------------------------------------------------------- facts


def check_facts(model: str, preset: str | None = None) -> None:
    """The facts hang together (module docstring)."""
    facts = field_facts(model, preset)
    pitch = facts.pitch
    _require(facts.dt_s > 0.0, model, "a tick must last a positive time")
    _require(facts.sensor_period_s >= facts.dt_s, model, "percepts cannot come faster than ticks")
    _require(
        pitch.length_m > 0 and pitch.width_m > 0 and 0 < pitch.goal_width_m < pitch.width_m,
        model,
        "the pitch needs a positive size and a goal narrower than the field",
    )
    speed, time = 0.1 * pitch.length_m, 1.0
    covered = facts.ball.distance_in(speed, time)
    _require(0.0 < covered <= speed * time, model, "a free ball must slow down, not speed up")
    back = facts.ball.time_to_cover(covered, speed)
    _require(back is not None and math.isclose(back, time, rel_tol=1e-6), model, "time_to_cover")
    again = facts.ball.speed_to_cover(covered, time)
    _require(
        again is not None and math.isclose(again, speed, rel_tol=1e-6), model, "speed_to_cover"
    )
    if facts.kick is not None:
        _require(facts.kick.reach_m > facts.touch_distance_m, model, "a kick must reach the ball")
        _require(facts.kick.speed(100.0) > 0.0, model, "a kick must move the ball")
    _require(facts.player_top_speed_mps > 0.0, model, "players must be able to move")


# ----------------------------------------------------------------------------- placement


def check_placement_and_stepping(model: str, preset: str | None = None) -> None:
    """Placed objects stay where they were put; ticks count; a ball rolls by the ball law."""
    arena = _arena(model, preset)
    facts = arena.facts
    pitch, unit = facts.pitch, facts.unit_m
    _require(arena.tick == 0, model, "a fresh arena starts at tick 0")
    _require(arena.players == PLAYERS, model, "players come in the order given")
    _require(arena.score() == (0, 0), model, "a fresh arena's score is (0, 0)")
    arena.place_player(A, -10 * unit, 5 * unit, 0.5)
    _park(arena)
    start = -0.2 * pitch.length_m
    speed = 0.1 * pitch.length_m
    arena.place_ball(start, 0.0, speed, 0.0)
    a, ball = arena.player_state(A), arena.ball_state()
    _require(math.isclose(a.x, -10 * unit) and math.isclose(a.y, 5 * unit), model, "player placed")
    _require(math.isclose(a.heading, 0.5) and a.speed == 0.0, model, "placed player at rest")
    _require(
        math.isclose(ball.x, start) and math.isclose(ball.vx, speed), model, "ball placed moving"
    )
    truth = arena.truth()
    _require(truth.ball == ball and truth.players[A] == a, model, "truth agrees with the coach")
    ticks = _ticks(arena, 1.0)
    for _ in range(ticks):
        arena.step()
    _require(arena.tick == ticks, model, f"{ticks} steps must make tick {ticks}")
    truth = arena.truth()
    _require(
        truth.tick == arena.tick and math.isclose(truth.time_s, ticks * facts.dt_s),
        model,
        "truth carries the tick and its time",
    )
    moved = arena.ball_state()
    expected = facts.ball.distance_in(speed, ticks * facts.dt_s)
    _require(
        math.isclose(moved.x - start, expected, rel_tol=0.03),
        model,
        f"a free ball covered {moved.x - start:.4g} m in 1 s; its ball law says {expected:.4g}",
    )
    _require(abs(moved.y) < 0.01 * expected, model, "a free ball keeps its direction")
    still = arena.player_state(A)
    _require(math.hypot(still.x - a.x, still.y - a.y) < 0.1 * unit, model, "an idle player stays")


# ----------------------------------------------------------------------------- percepts


def check_percepts(model: str, preset: str | None = None) -> None:
    """Percepts: their timing, listeners, frame, and what they carry (module docstring)."""
    arena = _arena(model, preset)
    facts = arena.facts
    unit = facts.unit_m
    heading = 0.4
    arena.place_player(A, 0.0, 0.0, heading)
    ball_angle, ball_distance = math.radians(20.0), 15 * unit
    other_angle, other_distance = math.radians(-25.0), 20 * unit
    arena.place_ball(*_polar(ball_distance, heading + ball_angle))
    arena.place_player(B, *_polar(other_distance, heading + other_angle), 0.0)
    arena.listen(frozenset({A}))
    seconds = 2.0
    seen = _run(arena, seconds)
    _require(all(p.player == A for p in seen), model, "percepts only for listening players")
    expected = seconds / facts.sensor_period_s
    _require(
        abs(len(seen) - expected) <= 1.0 + 0.1 * expected,
        model,
        f"{len(seen)} percepts in {seconds} s; the sensor period says about {expected:.1f}",
    )
    # A model may fade a far player's number (a real rcssserver at 20 m): the team must agree.
    fades = "identity" in conformance_limits(model, preset)
    for p in seen:
        _require(p.observed_tick <= p.tick, model, "a percept cannot show the future")
        _check_seen(model, p, ball_angle, ball_distance, other_angle, other_distance, fades)
    ticks = [p.tick for p in seen]
    _require(ticks == sorted(ticks) and ticks[-1] <= arena.tick, model, "percepts come in order")


def _check_seen(
    model: str,
    p: Percept,
    ball_angle: float,
    ball_distance: float,
    other_angle: float,
    other_distance: float,
    fades: bool = False,
) -> None:
    tolerance = math.radians(2.0)
    _require(p.ball is not None, model, "a ball in front of a player is seen")
    assert p.ball is not None
    _require(
        abs(wrap_angle(p.ball.angle_rad - ball_angle)) < tolerance,
        model,
        f"the ball 20° to the left is seen at {math.degrees(p.ball.angle_rad):.1f}°",
    )
    _require(
        math.isclose(p.ball.distance_m, ball_distance, rel_tol=0.05),
        model,
        "the ball is seen at its distance",
    )
    others = [s for s in p.players if abs(wrap_angle(s.angle_rad - other_angle)) < tolerance]
    _require(len(others) == 1, model, "the other player 25° to the right is seen there")
    other = others[0]
    _require(math.isclose(other.distance_m, other_distance, rel_tol=0.05), model, "at its distance")
    number_ok = other.number == B.number or (fades and other.number is None)
    _require(other.team == B.team and number_ok, model, "and who it is")


def _polar(distance: float, angle: float) -> tuple[float, float]:
    return distance * math.cos(angle), distance * math.sin(angle)


# ----------------------------------------------------------------------------- actions


def check_actions(model: str, preset: str | None = None) -> None:
    """A turn turns toward its sign, a dash runs along the heading, a kick moves the ball."""
    for sign in (1.0, -1.0):
        _check_turn(model, preset, sign)
    _check_dash(model, preset)
    _check_kick(model, preset)


def _once(actions: tuple[Action, ...]) -> Callable[[Percept], tuple[Action, ...]]:
    """A mind that sends `actions` at its first percept and nothing after."""
    sent: list[bool] = []

    def act(percept: Percept) -> tuple[Action, ...]:
        if sent or percept.player != A:
            return ()
        sent.append(True)
        return actions

    return act


def _check_turn(model: str, preset: str | None, sign: float) -> None:
    arena = _arena(model, preset)
    _park(arena)
    arena.place_player(A, 0.0, 0.0, 0.0)
    angle = sign * math.radians(60.0)
    _run(arena, 1.0, _once((Turn(angle),)))
    turned = wrap_angle(arena.player_state(A).heading)
    _require(
        math.isclose(turned, angle, rel_tol=0.15),
        model,
        f"Turn({math.degrees(angle):+.0f}°) turned the body {math.degrees(turned):+.1f}°",
    )


def _check_dash(model: str, preset: str | None) -> None:
    arena = _arena(model, preset)
    _park(arena)
    heading = 0.3
    arena.place_player(A, 0.0, 0.0, heading)
    arena.place_ball(0.0, -0.4 * arena.facts.pitch.width_m)

    def dash(percept: Percept) -> tuple[Action, ...]:
        return (Dash(100.0),) if percept.player == A else ()

    _run(arena, 1.0, dash)
    a = arena.player_state(A)
    along = a.x * math.cos(heading) + a.y * math.sin(heading)
    across = -a.x * math.sin(heading) + a.y * math.cos(heading)
    least = 0.2 * arena.facts.player_top_speed_mps * 0.5
    _require(along > least, model, f"a second of Dash(100) ran {along:.3g} m along the heading")
    _require(abs(across) < 0.1 * along, model, "a dash runs along the heading, not sideways")


def _check_kick(model: str, preset: str | None) -> None:
    arena = _arena(model, preset)
    facts = arena.facts
    _park(arena)
    arena.place_player(A, 0.0, 0.0, 0.0)
    reach = facts.kick.reach_m if facts.kick is not None else facts.touch_distance_m
    gap = facts.touch_distance_m + 0.25 * (reach - facts.touch_distance_m) + 0.01 * facts.unit_m
    arena.place_ball(gap, 0.0)

    def kick(percept: Percept) -> tuple[Action, ...]:
        ball = percept.ball
        near = ball is not None and ball.distance_m < 2.0 * gap
        return (Kick(100.0, 0.0),) if percept.player == A and near else ()

    _run(arena, 1.0, kick)
    ball = arena.ball_state()
    _require(
        ball.x - gap > 2.0 * facts.unit_m and abs(ball.y) < 0.5 * (ball.x - gap),
        model,
        f"Kick(100, 0) should send the ball forward; it is at ({ball.x:.3g}, {ball.y:.3g})",
    )


# ----------------------------------------------------------------------------- hearing


def check_hearing(model: str, preset: str | None = None) -> None:
    """A say reaches the other player with one of its next percepts."""
    arena = _arena(model, preset)
    unit = arena.facts.unit_m
    arena.place_player(A, -5 * unit, 0.0, 0.0)
    arena.place_player(B, 5 * unit, 0.0, math.pi)
    arena.place_ball(0.0, 0.0)
    seen = _run(arena, 1.0, _once((Say("hello"),)))
    heard = [h.text for p in seen if p.player == B for h in p.heard]
    _require("hello" in heard, model, "a say must reach the other player's percepts")


# ----------------------------------------------------------------------------- the head


def check_head(model: str, preset: str | None = None) -> None:
    """A neck turn and a view change leave the body command alone; percepts say the neck."""
    arena = _arena(model, preset)
    _park(arena)
    heading, turn, neck = 0.4, 0.3, 0.5
    arena.place_player(A, 0.0, 0.0, heading)
    arena.place_ball(*_polar(15 * arena.facts.unit_m, heading + math.radians(20.0)))
    arena.listen(frozenset({A}))
    seen = _run(arena, 1.0, _once((TurnNeck(neck), ChangeView("normal", "high"), Turn(turn))))
    a, ball = arena.player_state(A), arena.ball_state()
    _require(
        math.isclose(wrap_angle(a.heading - heading), turn, rel_tol=0.15),
        model,
        "a Turn sent with a TurnNeck and a ChangeView still turns the body",
    )
    last = seen[-1]
    _require(
        last.neck_rad == 0.0 or math.isclose(last.neck_rad, neck, rel_tol=0.05),
        model,
        f"the neck turned by {neck} rad (or, without a head, stays 0): {last.neck_rad}",
    )
    body = last.body_relative()
    _require(body.ball is not None, model, "the ball in view of the head is seen")
    assert body.ball is not None
    truth = wrap_angle(math.atan2(ball.y - a.y, ball.x - a.x) - a.heading)
    _require(
        abs(wrap_angle(body.ball.angle_rad - truth)) < math.radians(2.0),
        model,
        f"the ball from the body at {math.degrees(body.ball.angle_rad):.1f}°, "
        f"truly {math.degrees(truth):.1f}°",
    )


# ----------------------------------------------------------------------------- events


def check_events(model: str, preset: str | None = None) -> None:
    """Kept events carry every command in the client's command text, once."""
    arena = _arena(model, preset, keep_events=True)
    _park(arena)
    arena.place_player(A, 0.0, 0.0, 0.0)
    actions = (Turn(0.5), Dash(80.0), Say("go"))
    _run(arena, 0.5, _once(actions))
    events = arena.drain_events()
    commands = [e.text for e in events if e.channel == "command" and e.player == A]
    _require(
        commands == [render_command(a) for a in actions],
        model,
        f"command events {commands} should be the commands sent, in order",
    )
    _require(all(e.tick <= arena.tick for e in events), model, "no event from the future")
    _require(arena.drain_events() == [], model, "draining empties the events")


# ----------------------------------------------------------------------------- determinism


def _history(model: str, preset: str | None, seed: int) -> tuple[list[Percept], list[object]]:
    arena = _arena(model, preset, FieldOptions(), seed=seed)
    unit, pitch = arena.facts.unit_m, arena.facts.pitch
    arena.place_player(A, -20 * unit, 3 * unit, 0.0)
    arena.place_player(B, 20 * unit, -3 * unit, math.pi)
    arena.place_ball(0.0, 0.0, 0.05 * pitch.length_m, 0.02 * pitch.length_m)
    minds = {ref: ChaseLoad() for ref in PLAYERS}
    truths: list[object] = []
    seen: list[Percept] = []
    for _ in range(_ticks(arena, 2.0)):
        for percept in arena.step():
            seen.append(percept)
            arena.submit(percept.player, minds[percept.player].act(percept))
        truths.append(arena.truth())
    return seen, truths


def check_determinism(model: str, preset: str | None = None) -> None:
    """The same seed gives the same percepts and truth; another seed does not (noise on)."""
    first = _history(model, preset, 11)
    _require(first == _history(model, preset, 11), model, "the same seed must replay exactly")
    _require(first != _history(model, preset, 12), model, "another seed must change the noise")


CHECKS: tuple[Callable[[str, str | None], None], ...] = (
    check_facts,
    check_placement_and_stepping,
    check_percepts,
    check_actions,
    check_head,
    check_hearing,
    check_events,
    check_determinism,
)
"""Every conformance check, in the order :func:`check_field_model` runs them."""


def check_field_model(model: str, preset: str | None = None) -> None:
    """Run every check on a registered field model (and preset).

    Checks the model names in :func:`~field_models.registry.conformance_limits` are left out.

    Raises:
        ConformanceError: The first promise the model broke.
    """
    limits = conformance_limits(model, preset)
    for check in CHECKS:
        if check.__name__ not in limits:
            check(model, preset)
