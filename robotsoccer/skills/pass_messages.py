"""Layer 2's messages: the passer's intention and announcement, the receivers' reports (§6).

The texts said and heard in one pass drill trial (Figures 9–12; the conversation is described
in :mod:`robotsoccer.skills.passing`): the intention :data:`INTENT`, a receiver's report
``r<NN>`` + its encoded view (:func:`learning.pass_codec.encode_view`) or ``r<NN>d<distance>``
(:func:`report_text`, read back by :func:`parse_report`), and the announcement ``k<NN>``
(:func:`announce_text`, :func:`announced_number`). Distances in units (Soccer Server metres,
the field's ``unit_m``).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from learning.pass_codec import decode_view
from learning.pass_features import receiver_attributes, unknown_half

INTENT = "pass"
"""What the passer says first (Figure 9)."""


def report_text(number: int, view: str | None, distance_units: float) -> str:
    """A receiver's report: ``r<NN>`` + its encoded view, or ``r<NN>d<distance>`` without one."""
    if view is None:
        return f"r{number:02d}d{distance_units:.1f}"
    return f"r{number:02d}{view}"


def announce_text(number: int) -> str:
    """The passer's announcement of its receiver (Figure 12)."""
    return f"k{number:02d}"


def announced_number(text: str) -> int | None:
    """The receiver number an announcement names, or None if `text` is not one."""
    if len(text) == 3 and text[0] == "k" and text[1:].isdigit():
        return int(text[1:])
    return None


@dataclass(frozen=True, slots=True)
class Report:
    """A receiver's report as the passer decoded it.

    Attributes:
        number: The receiver's uniform number.
        passer_distance_units: The receiver's distance to the passer [units].
        half: The receiver's 87 attributes, all unknown when it sent only its distance.
    """

    number: int
    passer_distance_units: float
    half: np.ndarray


def parse_report(text: str) -> Report | None:
    """A report from its text; None if `text` is not a well-formed report."""
    if len(text) < 4 or text[0] != "r" or not text[1:3].isdigit():
        return None
    number, body = int(text[1:3]), text[3:]
    if body.startswith("d"):
        try:
            distance = float(body[1:])
        except ValueError:
            return None
        return Report(number, distance, unknown_half())
    try:
        passer_distance, passer_angle, dist, angle, team = decode_view(body)
    except ValueError:
        return None
    half = receiver_attributes(passer_distance, passer_angle, dist, angle, team)
    return Report(number, passer_distance, half)
