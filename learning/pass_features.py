"""The pass attributes of layer 2: 174 continuous numbers per candidate pass.

Layer 2 of the paper (§6, "Learning a Higher-level Decision") has the passer record 174
attributes for each trial, "half each from the passer's and the receiver's perspective", and
learns with C4.5 whether a pass to that receiver will succeed (Figure 14 shows the tree). This
module builds those attributes from two *views*; it takes arrays and returns arrays.

Units and conventions:

* Distances are in *units*: Soccer Server metres. On a smaller field the caller divides its
  distances by its unit length first, so a tree threshold (``passer receiver distance <= 22``)
  means the same on both fields.
* Angles are in degrees, because Figure 14's thresholds are ("ang6", "angle > 13").
* A view is what one player sees. For each seen player: its distance, its direction (degrees,
  counter-clockwise positive, relative to the viewer's heading; any fixed reference works since
  only differences are used) and its team relative to the viewer: +1 teammate, -1 opponent,
  0 unknown (the Soccer Server hides the team of far players, ``team_far_length``). They are
  passed as three arrays ``distance (k,)``, ``angle_deg (k,)``, ``team (k,)``.
* The *target* of a half is the player the attributes are centred on: the receiver in the
  passer's half, the passer in the receiver's half. Every angle attribute except
  ``passer receiver angle`` is the absolute offset, in [0, 180], of a player's direction from
  the target's direction; ``passer receiver angle`` is the receiver's direction as seen,
  wrapped to [-180, 180).
* Unknown or unseen is ``nan``: the paper's "Whenever fewer than the maximum number of players
  were visible, the remaining attributes were marked as *unknown*." Counts are never nan
  (0 when nothing is seen), except in :func:`unknown_half`. A seen player whose distance is
  nan is listed with a nan distance and counted only in the ``ang{a}`` regions; one whose
  angle is nan has a nan angle (and sorts last in the passer's lists) and is counted nowhere.

The passer's half (87), from the passer's view, target = the receiver:

* ``passer receiver distance``, ``passer receiver angle`` (2);
* the other teammates, up to 9, sorted by angular offset from the receiver (18);
* the opponents, up to 11, sorted the same way (22);
* counts (45): 3 kinds x 15 regions (:data:`COUNT_REGIONS`).

The receiver's half (87), from the receiver's reported view, target = the passer:

* teammates, up to 10, the passer included, sorted by distance from the receiver (20);
* opponents, up to 11, sorted by distance (22);
* counts (45) around the passer, the passer itself not counted.

Choices that are ours (the paper gives only the list and the names in Figure 14):

* The regions: ``dist{d} ang{a}`` for d, a in (4, 8, 12) are the players within distance d of
  the *target* (by the law of cosines from the two polar positions) and within angular offset
  a of the target's direction; ``ang{a}`` for a in 1..6 is offset <= a at any distance. Both
  bounds are inclusive. The paper's gloss "the number of players that the receiver sees within
  a distance of 8 and angle of 12 from the passer" fixes the meaning for the receiver's half;
  we read the passer's half the same way around the receiver.
* The kinds: ``teammates`` and ``opponents`` count players of known team; ``players`` counts
  every seen player other than the target, unknown-team ones included. Unknown-team players
  appear only in the ``players`` counts, never in the sorted lists.
* The receiver's list angles are offsets from the passer's direction, so the passer's own entry
  has angle 0; ties in the sort keep the input order (the passer first in the receiver's list).
* Player lists interleave: ``teammate1 distance``, ``teammate1 angle``, ``teammate2 distance``...

Attribute names are versioned as :data:`PASS_SCHEMA`; every dataset and tree stores it.

The receiver's half reaches the passer as a ``say`` message (paper Figure 10): its view goes
through the compact fixed-width codec of :mod:`learning.pass_codec`. Where no message comes (a
match's open play) the half is unknown, or :func:`estimated_receiver_half` estimates it from
the passer's own view.
"""

from __future__ import annotations

import math
from typing import TypeVar

import numpy as np
import numpy.typing as npt

PASS_SCHEMA = "pass-attributes/1"
"""Versioned id of the pass attribute schema; stored with every dataset and tree."""

HALF = 87
"""Attributes per half: 2 + 18 + 22 + 45 (passer's) and 20 + 22 + 45 (receiver's) (paper §6)."""

PASSER_TEAMMATES = 9
"""Teammates in the passer's list: "other teammates (up to 9)" (paper §6)."""

RECEIVER_TEAMMATES = 10
"""Teammates in the receiver's list, the passer included: "teammates (up to 10)" (paper §6)."""

OPPONENTS = 11
"""Opponents in either list: "opponents (up to 11)" (paper §6)."""

COUNT_REGIONS: tuple[tuple[float | None, float], ...] = (
    *((d, a) for d in (4.0, 8.0, 12.0) for a in (4.0, 8.0, 12.0)),
    *((None, a) for a in (1.0, 2.0, 3.0, 4.0, 5.0, 6.0)),
)
"""The 15 count regions as (max distance from the target [units] or None for any, max angular
offset from the target's direction [deg]); names ``dist{d} ang{a}`` and ``ang{a}`` (Figure 14)."""

COUNT_KINDS = ("teammates", "opponents", "players")
"""The counted kinds, in attribute order (kind-major)."""


def _region_name(region: tuple[float | None, float]) -> str:
    distance, angle = region
    if distance is None:
        return f"ang{angle:g}"
    return f"dist{distance:g} ang{angle:g}"


def _player_names(prefix: str, n: int) -> tuple[str, ...]:
    return tuple(f"{prefix}{i} {q}" for i in range(1, n + 1) for q in ("distance", "angle"))


def _count_names(side: str) -> tuple[str, ...]:
    return tuple(f"{side} {kind} {_region_name(r)}" for kind in COUNT_KINDS for r in COUNT_REGIONS)


PASSER_NAMES: tuple[str, ...] = (
    "passer receiver distance",
    "passer receiver angle",
    *_player_names("passer teammate", PASSER_TEAMMATES),
    *_player_names("passer opponent", OPPONENTS),
    *_count_names("passer"),
)
"""The passer's 87 attribute names, in order."""

RECEIVER_NAMES: tuple[str, ...] = (
    *_player_names("receiver teammate", RECEIVER_TEAMMATES),
    *_player_names("receiver opponent", OPPONENTS),
    *_count_names("receiver"),
)
"""The receiver's 87 attribute names, in order."""

ATTRIBUTE_NAMES: tuple[str, ...] = PASSER_NAMES + RECEIVER_NAMES
"""All 174 attribute names: the passer's half, then the receiver's (paper §6)."""

_N_COUNTS = len(COUNT_KINDS) * len(COUNT_REGIONS)
_PASSER_LISTS = 2
"""Index of the passer's first list attribute (after the receiver's distance and angle)."""

# Region bounds as rows, so one broadcast comparison tests every player against all 15 regions.
# Distances are compared squared, saving a square root; "any distance" is +inf.
_REGION_DISTANCE_SQ = np.array([np.inf if d is None else d * d for d, _ in COUNT_REGIONS])
_REGION_ANGLE = np.array([a for _, a in COUNT_REGIONS])

# Tables indexed by a team value's byte (int8 seen as uint8: +1 -> 1, 0 -> 0, -1 -> 255), so
# one fancy index replaces three comparisons. _KIND: the count kinds a player adds to; a byte
# that is no team is a row of nan, which the column sums reveal. _GROUP: the primary key that
# sorts teammates before opponents before unknown-team players in one lexsort.
_KIND = np.full((256, 3), np.nan)
_KIND[1], _KIND[255], _KIND[0] = (1.0, 0.0, 1.0), (0.0, 1.0, 1.0), (0.0, 0.0, 1.0)
_GROUP = np.full(256, 2, dtype=np.int8)
_GROUP[1], _GROUP[255] = 0, 1

assert len(PASSER_NAMES) == HALF and len(RECEIVER_NAMES) == HALF
assert len(set(ATTRIBUTE_NAMES)) == 2 * HALF


_Array = TypeVar("_Array", npt.NDArray[np.float64], npt.NDArray[np.int8])


def wrap_deg(angle: npt.NDArray[np.float64]) -> npt.NDArray[np.float64]:
    """Angles wrapped to [-180, 180) [deg]."""
    return np.asarray((angle + 180.0) % 360.0 - 180.0, dtype=np.float64)


def view_arrays(
    distance: npt.ArrayLike, angle_deg: npt.ArrayLike, team: npt.ArrayLike
) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64], npt.NDArray[np.int8]]:
    """The three view arrays as float, float, int8, checked for shape (team values: by _KIND)."""
    d = np.asarray(distance, dtype=np.float64)
    a = np.asarray(angle_deg, dtype=np.float64)
    t = np.asarray(team)
    if d.ndim != 1 or a.shape != d.shape or t.shape != d.shape:
        raise ValueError(
            f"distance, angle_deg and team must be 1-D of one length, got shapes "
            f"{d.shape}, {a.shape}, {t.shape}"
        )
    if t.dtype != np.int8:
        # The slow path, for callers that pass lists or wider integers.
        if not np.all((t == 1) | (t == -1) | (t == 0)):
            raise ValueError(f"team values must be +1, -1 or 0, got {t!r}")
        t = t.astype(np.int8)
    return d, a, t


def prepend(x: _Array, value: float) -> _Array:
    """``x`` with ``value`` in front (faster than ``np.concatenate`` for a dozen elements)."""
    y = np.empty(x.size + 1, dtype=x.dtype)
    y[0] = value
    y[1:] = x
    return y


def _check_target(distance: float, angle_deg: float, who: str) -> None:
    if not (math.isfinite(distance) and distance >= 0.0 and math.isfinite(angle_deg)):
        raise ValueError(
            f"the {who} must be seen (finite distance >= 0 and angle), got distance "
            f"{distance!r}, angle {angle_deg!r}; use unknown_half() when it is not"
        )


def _fill_half(
    out: npt.NDArray[np.float64],
    lists: tuple[int, int],
    target: tuple[float, float],
    view: tuple[npt.NDArray[np.float64], npt.NDArray[np.float64], npt.NDArray[np.int8]],
    sort_by_distance: bool,
    first_is_target: bool,
) -> None:
    """Write a half's sorted lists and counts into ``out`` (pre-filled with nan).

    The lists start at ``lists[0]``: ``lists[1]`` teammates then :data:`OPPONENTS` (distance,
    offset) pairs, sorted by distance or by offset; the 45 counts fill the last 45 places.
    ``target`` is the target's (distance, angle [deg]) and ``view`` the seen players' distance,
    angle and team arrays. With ``first_is_target`` the first player is the target itself
    (listed, never counted).
    """
    lists_start, n_teammates = lists
    target_distance, target_angle_deg = target
    d, a, t = view
    # |wrap(direction - target direction)| in [0, 180].
    w = (a - target_angle_deg) % 360.0
    offset = np.minimum(w, 360.0 - w)
    # Squared distance to the target, by the law of cosines between the two polar positions.
    # fmin turns nan (distance unknown) into inf: such a player counts only in the ang-only
    # regions, whose bound is inf.
    squared = np.fmin(
        d * (d - 2.0 * target_distance * np.cos(np.radians(offset))) + target_distance**2,
        np.inf,
    )
    u = t.view(np.uint8)
    kinds = _KIND[u]
    totals = kinds.sum(axis=0)
    if math.isnan(totals[0]):
        raise ValueError(f"team values must be +1, -1 or 0, got {t!r}")
    if first_is_target:
        kinds[0] = 0.0
    within = (offset[:, None] <= _REGION_ANGLE) & (squared[:, None] <= _REGION_DISTANCE_SQ)
    np.matmul(kinds.T, within, out=out[HALF - _N_COUNTS :].reshape(len(COUNT_KINDS), -1))

    key = d if sort_by_distance else offset
    # lexsort is stable and puts a nan key last within its group.
    order = np.lexsort((key, _GROUP[u]))
    sorted_d, sorted_offset = d[order], offset[order]
    n_mates, n_opps = int(totals[0]), int(totals[1])
    # "the remaining attributes were marked as unknown" (paper §6): the nan fill stays beyond.
    m = min(n_mates, n_teammates)
    out[lists_start : lists_start + 2 * m : 2] = sorted_d[:m]
    out[lists_start + 1 : lists_start + 2 * m : 2] = sorted_offset[:m]
    start = lists_start + 2 * n_teammates
    m = min(n_opps, OPPONENTS)
    out[start : start + 2 * m : 2] = sorted_d[n_mates : n_mates + m]
    out[start + 1 : start + 2 * m : 2] = sorted_offset[n_mates : n_mates + m]


def passer_attributes(
    receiver_distance: float,
    receiver_angle_deg: float,
    distance: npt.ArrayLike,
    angle_deg: npt.ArrayLike,
    team: npt.ArrayLike,
) -> npt.NDArray[np.float64]:
    """The passer's half: 87 attributes centred on the receiver as the passer sees it.

    Teammates and opponents are sorted by angular offset from the receiver (paper §6), so
    ``passer opponent1 angle`` is the opponent nearest the line of the pass (Figure 14's second
    test: "If there is no opponent within 13 degrees of the receiver, the tree predicts success").

    Args:
        receiver_distance: The receiver's distance from the passer [units].
        receiver_angle_deg: The receiver's direction from the passer's heading [deg, CCW +].
        distance: Distances of the OTHER players the passer sees (receiver excluded) [units].
        angle_deg: Their directions, same reference as ``receiver_angle_deg`` [deg].
        team: Their teams relative to the passer: +1 teammate, -1 opponent, 0 unknown.

    Returns:
        ``(87,)`` float64 in :data:`PASSER_NAMES` order; nan where no player fills a slot.

    Raises:
        ValueError: The receiver is not seen (non-finite), the arrays' shapes differ, or a team
            value is not +1, -1 or 0.
    """
    _check_target(receiver_distance, receiver_angle_deg, "receiver")
    d, a, t = view_arrays(distance, angle_deg, team)
    out = np.full(HALF, np.nan)
    out[0] = receiver_distance
    out[1] = (receiver_angle_deg + 180.0) % 360.0 - 180.0
    _fill_half(
        out,
        (_PASSER_LISTS, PASSER_TEAMMATES),
        (receiver_distance, receiver_angle_deg),
        (d, a, t),
        sort_by_distance=False,
        first_is_target=False,
    )
    return out


def receiver_attributes(
    passer_distance: float,
    passer_angle_deg: float,
    distance: npt.ArrayLike,
    angle_deg: npt.ArrayLike,
    team: npt.ArrayLike,
) -> npt.NDArray[np.float64]:
    """The receiver's half: 87 attributes centred on the passer as the receiver sees it.

    Teammates (the passer among them, at angle 0) and opponents are sorted by distance from the
    receiver (paper §6); the counts are around the passer, e.g. ``receiver players dist8 ang12``
    is "the number of players that the receiver sees within a distance of 8 and angle of 12
    from the passer" (Figure 14's caption).

    Args:
        passer_distance: The passer's distance from the receiver [units].
        passer_angle_deg: The passer's direction from the receiver's heading [deg, CCW +].
        distance: Distances of the players the receiver sees other than the passer [units].
        angle_deg: Their directions, same reference as ``passer_angle_deg`` [deg].
        team: Their teams relative to the receiver: +1 teammate, -1 opponent, 0 unknown.

    Returns:
        ``(87,)`` float64 in :data:`RECEIVER_NAMES` order; nan where no player fills a slot.

    Raises:
        ValueError: The passer is not seen (non-finite), the arrays' shapes differ, or a team
            value is not +1, -1 or 0.
    """
    _check_target(passer_distance, passer_angle_deg, "passer")
    d, a, t = view_arrays(distance, angle_deg, team)
    # The passer is one of the receiver's "teammates (up to 10)"; first, so a tie in distance
    # keeps it ahead. Its offset from itself comes out exactly 0.
    d, a, t = prepend(d, passer_distance), prepend(a, passer_angle_deg), prepend(t, 1)
    out = np.full(HALF, np.nan)
    _fill_half(
        out,
        (0, RECEIVER_TEAMMATES),
        (passer_distance, passer_angle_deg),
        (d, a, t),
        sort_by_distance=True,
        first_is_target=True,
    )
    return out


def unknown_half() -> npt.NDArray[np.float64]:
    """A half with every attribute unknown: ``(87,)`` nan.

    The receiver's half when no report was heard, e.g. because the server's ``say_msg_size``
    (10 characters in rcssserver 19) is too short for the view; C4.5 treats nan as unknown.
    """
    return np.full(HALF, np.nan)


def pass_attributes(
    passer_half: npt.ArrayLike, receiver_half: npt.ArrayLike
) -> npt.NDArray[np.float64]:
    """The 174 attributes of one candidate pass, in :data:`ATTRIBUTE_NAMES` order.

    Args:
        passer_half: ``(87,)`` from :func:`passer_attributes`.
        receiver_half: ``(87,)`` from :func:`receiver_attributes` or :func:`unknown_half`.

    Raises:
        ValueError: A half is not ``(87,)``.
    """
    p = np.asarray(passer_half, dtype=np.float64)
    r = np.asarray(receiver_half, dtype=np.float64)
    if p.shape != (HALF,) or r.shape != (HALF,):
        raise ValueError(f"each half must have shape ({HALF},), got {p.shape} and {r.shape}")
    return np.concatenate((p, r))


RECEIVER_VIEW_HALF_ANGLE_DEG = 45.0
"""The receiver's view half-angle in :func:`estimated_receiver_half` [deg]: the Soccer
Server's normal view width (``visible_angle`` 90°, both presets)."""

RECEIVER_FEEL_M = 3.0
"""Players this close to the receiver count as seen in :func:`estimated_receiver_half`
whatever their direction [m]: the Soccer Server's ``visible_distance`` (both presets)."""


def estimated_receiver_view(
    receiver_distance: float,
    receiver_angle_deg: float,
    distance: npt.ArrayLike,
    angle_deg: npt.ArrayLike,
    team: npt.ArrayLike,
    half_angle_deg: float = RECEIVER_VIEW_HALF_ANGLE_DEG,
    feel_distance: float = RECEIVER_FEEL_M,
) -> tuple[npt.NDArray[np.float64], npt.NDArray[np.float64], npt.NDArray[np.int8]]:
    """The players a receiver facing the passer would see, placed from the passer's view.

    The passer stands at the origin of its own frame; the receiver and every other player it
    sees are placed there from their polar positions. The receiver faces the passer (receivers
    face the ball in the pass drill, paper §6), so each other player's direction is measured
    from the receiver's line to the passer, and a player is kept when it lies within
    ``half_angle_deg`` of that line or within ``feel_distance`` of the receiver. Teams stay as
    the passer sees them (relative to the receiver, the passer's teammate, they are the same).

    Args:
        receiver_distance: The receiver's distance from the passer [units].
        receiver_angle_deg: The receiver's direction from the passer's heading [deg, CCW +].
        distance: Distances of the other players the passer sees (receiver excluded) [units].
        angle_deg: Their directions, same reference as ``receiver_angle_deg`` [deg].
        team: Their teams relative to the passer: +1 teammate, -1 opponent, 0 unknown.
        half_angle_deg: The receiver's view half-angle [deg].
        feel_distance: Players this close to the receiver are kept in any direction [units].

    Returns:
        ``(distance [units], angle [deg], team)`` of the kept players from the receiver, angles
        relative to its heading (the passer at 0), in the input order; a player whose distance
        or angle the passer does not know is left out (it cannot be placed).

    Raises:
        ValueError: The receiver is not seen (non-finite), or the arrays' shapes differ.
    """
    _check_target(receiver_distance, receiver_angle_deg, "receiver")
    d, a, t = view_arrays(distance, angle_deg, team)
    placed = np.isfinite(d) & np.isfinite(a)
    d, a, t = d[placed], a[placed], t[placed]
    r = math.radians(receiver_angle_deg)
    rx, ry = receiver_distance * math.cos(r), receiver_distance * math.sin(r)
    radians = np.radians(a)
    vx, vy = d * np.cos(radians) - rx, d * np.sin(radians) - ry
    from_receiver = np.hypot(vx, vy)
    # The receiver's heading points at the passer (the origin): direction of -R.
    heading_deg = math.degrees(math.atan2(-ry, -rx))
    direction = wrap_deg(np.degrees(np.arctan2(vy, vx)) - heading_deg)
    kept = (np.abs(direction) <= half_angle_deg) | (from_receiver <= feel_distance)
    return from_receiver[kept], direction[kept], t[kept]


def estimated_receiver_half(
    receiver_distance: float,
    receiver_angle_deg: float,
    distance: npt.ArrayLike,
    angle_deg: npt.ArrayLike,
    team: npt.ArrayLike,
    half_angle_deg: float = RECEIVER_VIEW_HALF_ANGLE_DEG,
    feel_distance: float = RECEIVER_FEEL_M,
) -> npt.NDArray[np.float64]:
    """An *estimate* of the receiver's half (87), from the passer's own view.

    What the receiver would report (:func:`receiver_attributes`) if it faced the passer and saw
    what the passer sees of its surroundings (:func:`estimated_receiver_view`): players the
    passer cannot see are missing, and distances carry the passer's noise, not the receiver's.
    The match uses it where no ``say`` report reaches the passer (open play). The arguments
    are :func:`estimated_receiver_view`'s, in units (``feel_distance`` too).
    """
    d, a, t = estimated_receiver_view(
        receiver_distance,
        receiver_angle_deg,
        distance,
        angle_deg,
        team,
        half_angle_deg,
        feel_distance,
    )
    return receiver_attributes(receiver_distance, 0.0, d, a, t)
