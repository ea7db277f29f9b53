"""Frames for every environment: ``render_mode="rgb_array"`` (numpy) and ``"human"`` (rerun).

An environment holds one :class:`ArenaView` and asks it for the frame of the arena it is
running. ``"rgb_array"`` draws the arena's truth headless (:mod:`robotsoccer.replay.raster`):
no display and no window library. ``"human"`` streams the same truth to the rerun viewer
(spawned when none listens) with the recordings' layout, one recording per episode
(:class:`~robotsoccer.replay.recording.TrialRecorder`, which is where rerun is imported).
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from field_models.arena import Arena
from robotsoccer.replay.raster import DEFAULT_WIDTH_PX, FieldPainter, Frame

RENDER_MODES = ["rgb_array", "human"]
"""The render modes every environment of the project offers."""


def check_render_mode(mode: str | None) -> str | None:
    """`mode`, if it is None or one of :data:`RENDER_MODES`.

    Raises:
        ValueError: Any other mode (one line naming the choices).
    """
    if mode is not None and mode not in RENDER_MODES:
        raise ValueError(f"render_mode must be None, 'rgb_array' or 'human', got {mode!r}")
    return mode


class ArenaView:
    """Draws an environment's arena (module docstring).

    Args:
        mode: The render mode (None: nothing is drawn).
        width_px: Frame width [px].
        title: Names the environment in the viewer.
        recording_path: ``"human"`` writes this ``.rrd`` file instead of streaming to a viewer
            (tests, machines without one).
    """

    def __init__(
        self,
        mode: str | None,
        width_px: int = DEFAULT_WIDTH_PX,
        title: str = "robotsoccer",
        recording_path: Path | None = None,
    ) -> None:
        self.mode = check_render_mode(mode)
        self.width_px = width_px
        self.title = title
        self.recording_path = recording_path
        self._painter: FieldPainter | None = None
        self._painted_for: tuple[Any, ...] = ()
        self._recorder: Any = None
        self._recorded_arena: Arena | None = None
        self._episodes = 0

    def frame(self, arena: Arena) -> Frame:
        """The RGB frame of `arena`'s present truth, (height, width, 3) uint8."""
        facts = arena.facts
        key = (facts.pitch, arena.players, facts.player_shape)
        if self._painter is None or key != self._painted_for:
            self._painter = FieldPainter(facts.pitch, arena.players, facts.player_shape,
                                         self.width_px)  # fmt: skip
            self._painted_for = key
        return self._painter.paint(arena.truth())

    def show(self, arena: Arena) -> None:
        """``"human"``: log `arena`'s truth to the viewer (a new recording for a new arena)."""
        from robotsoccer.replay.field_recorder import Scene
        from robotsoccer.replay.recording import TrialRecorder  # rerun loads late

        facts = arena.facts
        if arena is not self._recorded_arena:
            self.close()
            self._episodes += 1
            # No sensor period: the live view keeps each percept until the next one.
            scene = Scene(
                facts.pitch,
                arena.players,
                facts.dt_s,
                facts.player_shape,
                title=f"{self.title}, episode {self._episodes}",
            )
            self._recorder = TrialRecorder(
                self.recording_path or Path("live.rrd"),
                scene,
                recording_id=f"{self.title}-episode{self._episodes}",
                chunk_frames=1,
                viewer=self.recording_path is None,
            )
            self._recorded_arena = arena
        self._recorder.log_truth(arena.truth())

    def render(self, arena: Arena | None) -> Frame | None:
        """What ``env.render()`` returns: a frame (``"rgb_array"``), else None."""
        if arena is None or self.mode is None:
            return None
        if self.mode == "human":
            self.show(arena)
            return None
        return self.frame(arena)

    def close(self) -> None:
        """Close the viewer's recording, if one is open."""
        if self._recorder is not None:
            self._recorder.close()
            self._recorder = None
            self._recorded_arena = None
