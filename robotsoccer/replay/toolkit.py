"""The rerun drawing toolkit: the field, the teams, the ball, percept rings, text and layout.

Both kinds of recording are thin layers on this module and
:mod:`~robotsoccer.replay.field_recorder`: a drill's trial (:mod:`robotsoccer.replay.recording`) and
a whole match (:mod:`robotsoccer.replay.match_recording`). Here are the pieces they share: the
static pitch (:func:`log_pitch`), the per-team styles (:func:`log_team_styles`), percept rings
(:func:`log_ring_style`), both timelines (:func:`time_indexes`) and the pieces of a layout
(:func:`field_view`, :func:`text_log_view`, :func:`side_by_side`); the rows buffered for
``send_columns`` (truth, percepts, text, stroke text) are :mod:`robotsoccer.replay.rows`'. The
geometry comes from :mod:`~robotsoccer.replay.geometry`, the style from
:mod:`~robotsoccer.replay.palette`.

Rerun draws 2-D views with y pointing down, and ignores view coordinates in 2-D views (upstream
issue rerun-io/rerun#1387). The data therefore stay in the field frame (y up), so what is read
back is what was logged, and a static ``Transform3D(scale=[1, -1, 1])`` on the ``field``
entity turns them the right way up in the view, which shows the root frame (:func:`log_pitch`).

Rerun is imported inside functions only, so importing this module does not load the SDK.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np

from field_models.protocol import LEFT, RIGHT, Pitch
from robotsoccer.replay.geometry import (
    DrawSizes,
    goal_box,
    goal_posts,
    pitch_lines,
    pitch_markings,
)
from robotsoccer.replay.palette import (
    ARROW_COLOUR,
    BALL_COLOUR,
    LINE_COLOUR,
    ORDER_BALL,
    ORDER_HEADING,
    ORDER_MARKINGS,
    ORDER_OUTLINE,
    ORDER_PERCEPT,
    ORDER_PLAYERS,
    PITCH_COLOUR,
    SIM_TIME,
    TICK,
    Colour,
    entity_name,
    lighter,
    team_colour,
)
from robotsoccer.replay.rrd_files import has_display, rerun_executable

if TYPE_CHECKING:
    import rerun as rr
    import rerun.blueprint as rrb


# ----------------------------------------------------------------------------- timelines


def time_indexes(ticks: Sequence[int], dt_s: float) -> list[Any]:
    """The ``sim_time`` (ns from integer ticks, never accumulated) and ``tick`` index columns."""
    import rerun as rr

    tick_arr = np.asarray(ticks, dtype=np.int64)
    # Rounded to whole ns per tick, so 1/240 s ticks do not truncate to ...666 ns.
    ns = np.rint(tick_arr * (dt_s * 1e9)).astype(np.int64).astype("timedelta64[ns]")
    return [rr.TimeColumn(SIM_TIME, duration=ns), rr.TimeColumn(TICK, sequence=tick_arr)]


def set_tick(rec: rr.RecordingStream, tick: int, dt_s: float) -> None:
    """Set both timelines of `rec` to `tick`, for plain ``log`` calls (undo: ``reset_time``)."""
    rec.set_time(SIM_TIME, duration=np.timedelta64(round(tick * (dt_s * 1e9)), "ns"))
    rec.set_time(TICK, sequence=tick)


# ----------------------------------------------------------------------------- the stream


def open_stream(
    path: Path, ids: tuple[str, str], viewer: bool, blueprint: rrb.Blueprint
) -> rr.RecordingStream:
    """A recording stream to the file `path`, or to a viewer, with `blueprint` as its layout.

    Args:
        path: The ``.rrd`` file (its folder is created) when not to a viewer.
        ids: The rerun application id and recording id.
        viewer: Stream to a viewer: with a display, the viewer beside this interpreter is
            spawned (or reused, when one listens); without one, the stream goes to rerun's
            default address, where a viewer started later (``rerun``) picks it up.
        blueprint: The default layout.
    """
    import rerun as rr

    application_id, recording_id = ids
    rec = rr.RecordingStream(application_id, recording_id=recording_id)
    if viewer and has_display():
        rr.spawn(
            executable_path=str(rerun_executable()), recording=rec, default_blueprint=blueprint
        )
    elif viewer:
        rec.connect_grpc(default_blueprint=blueprint)
    else:
        path.parent.mkdir(parents=True, exist_ok=True)
        rec.save(path, default_blueprint=blueprint)
    return rec


# ----------------------------------------------------------------------------- layout


def field_view(
    name: str, contents: str | list[str], bounds: tuple[list[float], list[float]]
) -> rrb.Spatial2DView:
    """The field's 2-D view: origin at the root (so the ``field`` flip applies), on the grass.

    Args:
        name: The view's title.
        contents: Its entity-path query.
        bounds: The x and y ranges shown, in the view's (flipped, y down) frame.
    """
    import rerun.blueprint as rrb

    x_range, y_range = bounds
    return rrb.Spatial2DView(
        name=name,
        origin="/",
        contents=contents,
        background=rrb.Background(kind="SolidColor", color=PITCH_COLOUR),
        visual_bounds=rrb.VisualBounds2D(x_range=x_range, y_range=y_range),
    )


def side_by_side(
    field: rrb.Spatial2DView,
    column: Sequence[rrb.View],
    *,
    row_shares: Sequence[int],
    column_shares: Sequence[int],
) -> rrb.Blueprint:
    """The field on the left, `column` stacked on the right, side panels collapsed.

    The time panel stays collapsed to its scrubber and play controls on ``sim_time``.
    """
    import rerun.blueprint as rrb

    return rrb.Blueprint(
        rrb.Horizontal(
            field,
            rrb.Vertical(*column, row_shares=list(row_shares)),
            column_shares=list(column_shares),
        ),
        rrb.BlueprintPanel(state="collapsed"),
        rrb.SelectionPanel(state="collapsed"),
        rrb.TimePanel(timeline=SIM_TIME, state="collapsed"),
    )


def text_log_view(
    name: str, origin: str, *, entity_column: bool = True, hidden: Sequence[str] = ()
) -> rrb.TextLogView:
    """A text-log view of `origin` that shows each line's body first, then its entity.

    By default rerun 0.41 puts the entity path and level first, and in a narrow view the body
    is cut off (``rrb.TextLogColumns``, blueprint/archetypes/text_log_columns). Without
    `entity_column` the entity path is hidden too (where the body names its channel).
    Entities in `hidden` (paths without the leading ``/``) are left out of the view's
    contents: recorded, and shown again by adding them in the blueprint panel.
    """
    import rerun.blueprint as rrb

    return rrb.TextLogView(
        name=name,
        origin=origin,
        contents=["+ $origin/**", *(f"- /{path}/**" for path in hidden)],
        columns=rrb.TextLogColumns(
            timeline_columns=[rrb.encodings.TimelineColumn(SIM_TIME)],
            text_log_columns=[
                rrb.encodings.TextLogColumn("body"),
                rrb.encodings.TextLogColumn("entitypath", visible=entity_column),
                rrb.encodings.TextLogColumn("loglevel", visible=False),
            ],
        ),
        format_options=rrb.TextLogFormat(monospace_body=False),
    )


# ----------------------------------------------------------------------------- static styles


def log_pitch(rec: rr.RecordingStream, pitch: Pitch, teams: Sequence[str]) -> None:
    """The display flip and the pitch's geometry (lines, markings, goals, posts), static."""
    import rerun as rr

    # The display flip: field frame (y up) to rerun's 2-D frame (y down).
    rec.log("field", rr.Transform3D(scale=[1.0, -1.0, 1.0]), static=True)
    line_radius = rr.Radius.ui_points(1.0)
    for entity, strips in (
        ("field/lines", pitch_lines(pitch)),
        ("field/markings", pitch_markings(pitch)),
    ):
        rec.log(
            entity,
            rr.LineStrips2D(
                strips, radii=line_radius, colors=LINE_COLOUR, draw_order=ORDER_MARKINGS
            ),
            static=True,
        )
    for team, side in ((LEFT, -1.0), (RIGHT, 1.0)):
        rec.log(
            f"field/goals/{team}",
            rr.LineStrips2D(
                [goal_box(pitch, side)],
                radii=rr.Radius.ui_points(2.5),
                colors=team_colour(team, teams),
                draw_order=ORDER_MARKINGS,
            ),
            static=True,
        )
    rec.log(
        "field/posts",
        rr.Points2D(
            goal_posts(pitch),
            radii=rr.Radius.ui_points(4.0),
            colors=LINE_COLOUR,
            draw_order=ORDER_MARKINGS,
        ),
        static=True,
    )


def log_team_styles(rec: rr.RecordingStream, sizes: DrawSizes, teams: Sequence[str]) -> None:
    """Static styles of the ball and of each team's discs, names, outlines and arrows."""
    import rerun as rr

    rec.log(
        "field/ball",
        rr.Points2D.from_fields(radii=sizes.ball_m, colors=BALL_COLOUR, draw_order=ORDER_BALL),
        static=True,
    )
    for team in teams:
        colour = team_colour(team, teams)
        base = f"field/players/{entity_name(team)}"
        # The discs keep the ids as labels (hover, read-back) but do not show them: rerun
        # draws a point's label over the point. The ids show on anchors above the players.
        rec.log(
            base,
            rr.Points2D.from_fields(
                radii=sizes.player_m, colors=colour, show_labels=False, draw_order=ORDER_PLAYERS
            ),
            static=True,
        )
        rec.log(
            f"{base}/name",
            rr.Points2D.from_fields(
                radii=0.0,
                colors=ARROW_COLOUR,  # label text takes this colour: white reads best
                show_labels=True,
                draw_order=ORDER_PLAYERS,
            ),
            static=True,
        )
        rec.log(
            f"{base}/outline",
            rr.LineStrips2D.from_fields(
                radii=rr.Radius.ui_points(1.5), colors=lighter(colour), draw_order=ORDER_OUTLINE
            ),
            static=True,
        )
        rec.log(
            f"{base}/heading",
            rr.Arrows2D.from_fields(
                radii=sizes.arrow_radius_m, colors=ARROW_COLOUR, draw_order=ORDER_HEADING
            ),
            static=True,
        )


def log_ring_style(rec: rr.RecordingStream, base: str, colour: Colour) -> None:
    """Static style of one observer's percept rings under `base`: its colour, thin lines."""
    import rerun as rr

    for entity in (f"{base}/ball", f"{base}/players"):
        rec.log(
            entity,
            rr.Ellipses2D.from_fields(
                line_radii=rr.Radius.ui_points(1.5),
                colors=colour,
                show_labels=False,  # the seen identities clutter; hover shows them
                draw_order=ORDER_PERCEPT,
            ),
            static=True,
        )
