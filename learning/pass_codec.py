"""The say codec of layer 2: a player's view as a short message in the Soccer Server's alphabet.

The receiver's half of the pass attributes (:mod:`learning.pass_features`) reaches the passer as
a ``say`` message (paper Figure 10). The Soccer Server limits its length (``say_msg_size``: 512
characters in the 1998 server, 10 today) and its characters; :func:`encode_view` /
:func:`decode_view` are a compact fixed-width codec for it. Distances are in units and angles in
degrees, as the attributes take them.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from learning.pass_features import prepend, view_arrays, wrap_deg

# The layout: 'v', the passer (distance, angle: 2 + 2 characters), then 5 characters per seen player
# (distance 2, angle 2, team 1). Every character is in the Soccer Server's say alphabet
# `[-0-9a-zA-Z ().+*/?<>_]` and none is a space, parenthesis or quote.

VIEW_TAG = "v"
"""First character of an encoded view."""

ALPHABET = "0123456789ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz-_"
"""The 64 digits of the fixed-width number code (two digits: 4096 codes)."""

DISTANCE_STEP = 0.05
"""Quantisation step of an encoded distance [units]; the top code stands for nan."""

ANGLE_STEP_DEG = 360.0 / 4095
"""Quantisation step of an encoded angle [deg] (about 0.088°); the top code stands for nan."""

_NAN_CODE = 64 * 64 - 1
MAX_DISTANCE = (_NAN_CODE - 1) * DISTANCE_STEP
"""Largest encodable distance [units] (204.7; the Soccer Server pitch diagonal is about 125)."""

TEAM_CHARACTERS = {1: "t", -1: "o", 0: "u"}
"""The team character of an encoded player: teammate, opponent, unknown."""

_HEAD = len(VIEW_TAG) + 4
_PER_PLAYER = 5
_ALPHABET_BYTES = np.frombuffer(ALPHABET.encode("ascii"), dtype=np.uint8)
# Byte tables, in the manner of pass_features' team tables: 0 / -1 / 2 mark a value or
# character that is invalid.
_TEAM_BYTE = np.zeros(256, dtype=np.uint8)  # team value's byte -> character
_DIGIT_VALUE = np.full(256, -1, dtype=np.int64)  # character -> digit
_DIGIT_VALUE[_ALPHABET_BYTES] = np.arange(64)
_TEAM_VALUE = np.full(256, 2, dtype=np.int8)  # character -> team value
for _team, _char in TEAM_CHARACTERS.items():
    _TEAM_BYTE[np.uint8(np.int8(_team).view(np.uint8))] = ord(_char)
    _TEAM_VALUE[ord(_char)] = _team


def view_message_length(n_players: int) -> int:
    """Characters in the encoding of a view with ``n_players`` seen players besides the passer.

    ``1 + 4 + 5 * n_players``: a 512-character say (1998 server) holds 101 players, a
    10-character one (rcssserver 19) only 1.

    >>> view_message_length(8)
    45
    """
    if n_players < 0:
        raise ValueError(f"n_players must be >= 0, got {n_players}")
    return _HEAD + _PER_PLAYER * n_players


def encode_view(
    passer_distance: float,
    passer_angle_deg: float,
    distance: npt.ArrayLike,
    angle_deg: npt.ArrayLike,
    team: npt.ArrayLike,
) -> str:
    """Encode the receiver's view as a say message (paper Figure 10: "what the world looks like").

    Distances are rounded to :data:`DISTANCE_STEP`, angles to :data:`ANGLE_STEP_DEG` (0° is on
    the grid; decoded angles lie in [-180, 180)); nan stays nan. The message has
    :func:`view_message_length` characters.

    Args:
        passer_distance: The passer's distance from the receiver [units].
        passer_angle_deg: The passer's direction [deg].
        distance: Distances of the other seen players [units].
        angle_deg: Their directions [deg].
        team: Their teams: +1 teammate, -1 opponent, 0 unknown.

    Returns:
        The message: the tag, then letters, digits, ``-`` and ``_`` only.

    Raises:
        ValueError: A distance is negative or above :data:`MAX_DISTANCE`, an angle is infinite,
            a team value is not +1, -1 or 0, or the arrays' shapes differ.
    """
    d, a, t = view_arrays(distance, angle_deg, team)
    d, a = prepend(d, passer_distance), prepend(a, passer_angle_deg)
    if np.any(d < 0.0) or np.any(d > MAX_DISTANCE) or np.any(np.isinf(a)):
        raise ValueError(
            f"distances must be nan or in [0, {MAX_DISTANCE}] and angles finite or nan, got "
            f"{d!r}, {a!r}"
        )
    codes = np.empty((d.size, 2), dtype=np.int64)
    # fmin maps nan to the nan code; every other value is below it.
    codes[:, 0] = np.fmin(np.rint(d / DISTANCE_STEP), _NAN_CODE)
    # Code c is c steps counter-clockwise from 0°, so 0° (straight at the passer) is exact.
    codes[:, 1] = np.fmin(np.rint(a % 360.0 / ANGLE_STEP_DEG) % _NAN_CODE, _NAN_CODE)
    chars = np.empty((d.size, _PER_PLAYER), dtype=np.uint8)
    chars[:, 0:4:2] = _ALPHABET_BYTES[codes >> 6]
    chars[:, 1:4:2] = _ALPHABET_BYTES[codes & 63]
    chars[0, 4] = ord(VIEW_TAG)  # placeholder; the passer has no team character
    chars[1:, 4] = team_bytes = _TEAM_BYTE[t.view(np.uint8)]
    if not np.all(team_bytes):
        raise ValueError(f"team values must be +1, -1 or 0, got {t!r}")
    raw = chars.tobytes()
    return VIEW_TAG + (raw[:4] + raw[5:]).decode("ascii")


def decode_view(
    text: str,
) -> tuple[float, float, npt.NDArray[np.float64], npt.NDArray[np.float64], npt.NDArray[np.int8]]:
    """Decode a message from :func:`encode_view`.

    Returns:
        ``(passer_distance, passer_angle_deg, distance, angle_deg, team)``, ready for
        :func:`receiver_attributes` (which refuses a nan passer).

    Raises:
        ValueError: ``text`` is not a str, lacks the tag, has a length that is not
            :func:`view_message_length` of some count, or holds a character out of place.
    """
    if not isinstance(text, str):
        raise ValueError(f"a view message is a str, got {type(text).__name__}")
    n, rest = divmod(len(text) - _HEAD, _PER_PLAYER)
    if not text.startswith(VIEW_TAG) or not text.isascii() or n < 0 or rest:
        raise ValueError(f"not a view message (tag {VIEW_TAG!r}, ASCII, length 5 + 5n): {text!r}")
    # The passer's four digits padded with its tag as a team character, so all rows are alike.
    raw = np.frombuffer((text[1:_HEAD] + VIEW_TAG + text[_HEAD:]).encode("ascii"), np.uint8)
    rows = raw.reshape(n + 1, _PER_PLAYER)
    digits = _DIGIT_VALUE[rows[:, :4]]
    team = _TEAM_VALUE[rows[1:, 4]]
    if np.any(digits < 0) or np.any(team == 2):
        raise ValueError(f"view message has a character out of place: {text!r}")
    codes = digits[:, 0::2] * 64 + digits[:, 1::2]
    values = codes * np.array((DISTANCE_STEP, ANGLE_STEP_DEG))
    values[:, 1] = wrap_deg(values[:, 1])
    values[codes == _NAN_CODE] = np.nan
    d, a = values[:, 0], values[:, 1]
    return float(d[0]), float(a[0]), d[1:], a[1:], team
