"""Open a Soccer Server game log (``.rcg``) in the rerun viewer: convert it to a recording.

The game log holds what the monitor shows (positions, headings, play modes, score), so the
recording made from it has the match layout of :mod:`robotsoccer.replay.match_recording`
without percepts or decisions. The pitch is the Soccer Server's, sized from the log's
``server_param`` line where it gives the sizes.
"""

from __future__ import annotations

from pathlib import Path

from field_models.protocol import Pitch, PlayerRef
from robotsoccer.replay.rcg_read import read_rcg

SERVER_PITCH = Pitch(
    length_m=105.0,
    width_m=68.0,
    goal_width_m=14.02,
    goal_depth_m=2.0,
    ball_radius_m=0.085,
    player_radius_m=0.3,
)
"""The Soccer Server's pitch (its spec, §6); a log's parameters override the sizes."""


def pitch_of(params: dict[str, str]) -> Pitch:
    """The pitch a game log's server parameters describe (the server's defaults otherwise)."""

    def number(name: str, default: float) -> float:
        try:
            return float(params[name])
        except (KeyError, ValueError):
            return default

    p = SERVER_PITCH
    return Pitch(
        length_m=p.length_m,
        width_m=p.width_m,
        goal_width_m=number("goal_width", p.goal_width_m),
        goal_depth_m=p.goal_depth_m,
        ball_radius_m=number("ball_size", p.ball_radius_m),
        player_radius_m=number("player_size", p.player_radius_m),
    )


def rrd_from_rcg(path: Path, out: Path | None = None) -> Path:
    """Write the recording of game log `path` (default: beside it, ``<name>.rcg.rrd``).

    The default name keeps a match's own ``.rrd`` (written beside its ``.rcg``) untouched.

    Raises:
        ValueError: The game log is malformed (the message names the file and line).
    """
    from robotsoccer.replay.field_recorder import Scene
    from robotsoccer.replay.match_recording import MatchRecorder  # rerun loads late

    game = read_rcg(path)
    frames = game.frames
    if not frames:
        raise ValueError(f"{path}: the game log has no show line")
    players: list[PlayerRef] = sorted({ref for f in frames for ref in f.truth.players})
    dt_s = float(game.server_params.get("simulator_step", "100")) / 1000.0
    target = out or path.with_name(path.name + ".rrd")
    title = f"{game.teams[0]} v {game.teams[1]}: game log {path.name}"
    scene = Scene(pitch_of(game.server_params), tuple(players), dt_s, "circle", dt_s, title)
    with MatchRecorder(
        target, scene, teams=game.teams, selected=None, recording_id=f"rcg-{path.stem}"
    ) as recorder:
        for frame in frames:
            recorder.log_frame(frame)
    return target
