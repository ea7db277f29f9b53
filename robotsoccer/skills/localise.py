"""A player's pose from the landmarks it sees: where it stands and which way it faces.

A percept names landmarks with their distance and direction (the Soccer Server's flags and
goals; the robots' host gives the two goals), and the field's facts say where they stand
(:attr:`~field_models.arena.FieldFacts.landmarks`). Two landmarks fix the heading; with one, the
last heading is kept; with none, the last pose. Team minds (:mod:`robotsoccer.skills.team`) and
the lead defender (:mod:`robotsoccer.skills.lead`) localise so.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

from field_models.protocol import Percept, wrap_angle


@dataclass(frozen=True, slots=True)
class Pose:
    """Where a player believes it is: field frame [m], heading [rad]."""

    x: float
    y: float
    heading: float


class Localiser:
    """A player's pose from the landmarks it sees (module docstring, step 1).

    Args:
        landmarks: (name, x [m], y [m]) of the field's landmarks (:attr:`FieldFacts.landmarks`).
    """

    def __init__(self, landmarks: Sequence[tuple[str, float, float]]) -> None:
        self.known = {name: (x, y) for name, x, y in landmarks}
        self.pose: Pose | None = None
        self._turned = 0.0  # turns told since the last heading fix (:meth:`turned`)

    def turned(self, angle_rad: float) -> None:
        """A turn the player commanded: added to the kept heading until two landmarks fix it.

        Only callers that want dead reckoning call it (team minds with steady turns); the
        others keep the last heading as it was.
        """
        self._turned += angle_rad

    def update(self, percept: Percept) -> Pose | None:
        """The pose this percept gives (or the last one, when it gives none)."""
        marks = []
        for mark in percept.landmarks:
            where = self.known.get(mark.name)
            if where is not None:
                ex = mark.distance_m * math.cos(mark.angle_rad)
                ey = mark.distance_m * math.sin(mark.angle_rad)
                marks.append((where[0], where[1], ex, ey, mark.distance_m))
        if len(marks) >= 2:
            heading = _heading_from_pair(marks)
            self._turned = 0.0
        elif marks and self.pose is not None:
            heading = wrap_angle(self.pose.heading + self._turned)
            self._turned = 0.0
        else:
            if self.pose is not None and self._turned:
                pose = self.pose
                self.pose = Pose(pose.x, pose.y, wrap_angle(pose.heading + self._turned))
                self._turned = 0.0
            return self.pose
        c, s = math.cos(heading), math.sin(heading)
        # Near landmarks weigh more: the server quantises log-distance, so far ones err more.
        x = y = total = 0.0
        for wx, wy, ex, ey, distance in marks:
            w = 1.0 / (1.0 + distance)
            x += w * (wx - (c * ex - s * ey))
            y += w * (wy - (s * ex + c * ey))
            total += w
        x, y = x / total, y / total
        self.pose = Pose(x, y, heading)
        return self.pose


def _heading_from_pair(marks: Sequence[tuple[float, float, float, float, float]]) -> float:
    """Heading from the two landmarks farthest apart in view (the best-conditioned pair)."""
    best, pair = -1.0, (marks[0], marks[1])
    for i in range(len(marks)):
        for j in range(i + 1, len(marks)):
            a, b = marks[i], marks[j]
            gap = (a[2] - b[2]) ** 2 + (a[3] - b[3]) ** 2
            if gap > best:
                best, pair = gap, (a, b)
    a, b = pair
    world = math.atan2(b[1] - a[1], b[0] - a[0])
    seen = math.atan2(b[3] - a[3], b[2] - a[2])
    return wrap_angle(world - seen)
