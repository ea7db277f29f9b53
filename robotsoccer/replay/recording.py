"""Rerun recordings of a drill's trials (DESIGN.md §5): a thin layer on the drawing toolkit.

A :class:`TrialRecorder` writes one ``.rrd`` file per trial with a default layout (blueprint):
the field on the left, a legend and the events on the right, the time panel below.

The field shows the pitch's markings (boundary, centre line and circle, penalty areas, goals
and posts) once as static geometry; every recorded tick the true ball and players (filled
discs labelled with the player ids, rotated outlines, heading arrows); what each player
*perceived*, converted to the field frame, as hollow rings in a colour of its own, cleared once
that player's latest percept is older than :data:`PERCEPT_LIFETIME_PERIODS` sensor periods; and,
from the verdict on, the outcome above the field with the field's boundary in the outcome's
colour. Small things are drawn no smaller than a fraction of the pitch length
(:func:`draw_sizes`), so the Soccer Server's ball shows on its large pitch; the legend says
which sizes are enlarged. Everything sits on a ``sim_time`` duration timeline derived from
integer ticks × ``dt_s`` (plus a ``tick`` sequence timeline with the raw tick), never on
wall-clock time.

What a trial adds to every recording's core
(:class:`~robotsoccer.replay.field_recorder.FieldRecorder`: the stream, the statics, the buffered
rows) is its layout, its legend and its outcome
(:meth:`TrialRecorder.log_label`). The drawing is :mod:`robotsoccer.replay.toolkit`'s (with
:mod:`~robotsoccer.replay.geometry`, :mod:`~robotsoccer.replay.lettering` and
:mod:`~robotsoccer.replay.palette`); reading, verifying and replaying files is
:mod:`robotsoccer.replay.rrd_files`'.

The replay modules that write or read rerun files (this one, ``match_recording``,
``field_recorder``, ``toolkit``, ``rrd_files``) are the only modules of the project that import
``rerun``, and they do so inside functions, so ``import robotsoccer`` (and importing them) never
loads the 800 MB SDK.

Entity layout (paths are what :func:`~robotsoccer.replay.rrd_files.read_entity_positions`
takes)::

    field                                            Transform3D: the display flip
    field/lines, field/markings, field/goals/<team>, field/posts    static pitch geometry
    field/ball                                       Points2D, one point per recorded tick
    field/players/<team>                             Points2D centres, labels = player ids
    field/players/<team>/outline                     LineStrips2D rotated outlines
    field/players/<team>/heading                     Arrows2D headings
    field/perceived/<player>/ball                    Ellipses2D ring (empty row: none current)
    field/perceived/<player>/players                 Ellipses2D rings, labels = team+number seen
    field/outcome, field/outcome/frame               the label above the field, the boundary
    legend                                           TextDocument (markdown), outcome on top
    events/<channel>, events/label                   TextLog, "[channel] player: text"
    events/routine                                   TextLog, routine decisions (turns,
                                                     dashes, nothing); hidden by default

A mind's decision goes to ``events/decision`` when it kicks or says something (a kick, a
pass, a set play's call) and to ``events/routine`` when it only steers (turns and dashes) or
does nothing (:meth:`~robotsoccer.replay.field_recorder.FieldRecorder.log_decision`): a player
decides at every percept, and those lines would bury the few events a viewer looks for. The
default layout leaves ``events/routine`` out of the events view; the blueprint panel can add it
back.

Positions are stored as float32 (rerun's ``Vec2D``).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from robotsoccer.replay.field_recorder import PERCEPT_LIFETIME_PERIODS, FieldRecorder
from robotsoccer.replay.geometry import pitch_lines
from robotsoccer.replay.lettering import text_strokes
from robotsoccer.replay.palette import (
    ARROW_COLOUR,
    ORDER_OUTCOME,
    PERCEPT_COLOUR_NAMES,
    ROUTINE_DECISIONS,
    colour_name,
    entity_name,
    length_text,
    outcome_colour,
    outcome_text,
    team_colour,
)
from robotsoccer.replay.toolkit import field_view, set_tick, side_by_side, text_log_view

if TYPE_CHECKING:
    import rerun.blueprint as rrb


def recording_name(index: int, label: str) -> str:
    """File name of trial `index`'s recording once its outcome `label` is known.

    ``trial_0007_GOAL.rrd``: the label is made safe for a file name.
    """
    return f"trial_{index:04d}_{entity_name(label)}.rrd"


class TrialRecorder(FieldRecorder):
    """Writes one trial to a rerun ``.rrd`` file: the field, a legend, the events, the outcome.

    Use it as a context manager, or call :meth:`close` at the end: the file's footer is only
    written when the stream disconnects, and ``rerun rrd verify`` fails without it. The
    arguments are :class:`~robotsoccer.replay.field_recorder.FieldRecorder`'s: the path, the
    :class:`~robotsoccer.replay.field_recorder.Scene` drawn, the ids and the cadence.
    """

    _outcome: tuple[int, str, str] | None = None
    """The outcome once logged (tick, label, text); a class default, so the base class's
    ``__init__``, which builds the legend, finds none."""

    def _blueprint(self) -> rrb.Blueprint:
        """The field beside the legend and the events, side panels collapsed, on ``sim_time``.

        The field view's origin is the root, so the ``field`` entity's flip applies to what it
        shows (a view's own origin transform would not). The events view shows the message
        body first (:func:`~robotsoccer.replay.toolkit.text_log_view`).
        """
        import rerun.blueprint as rrb

        field = field_view(
            "field (y up; truth filled, percepts as rings)", "/field/**", self._view_bounds()
        )
        legend = rrb.TextDocumentView(name="legend", origin="/legend")
        events = text_log_view("events", "/events", hidden=(ROUTINE_DECISIONS,))
        return side_by_side(field, (legend, events), row_shares=[3, 5], column_shares=[5, 2])

    def legend(self, outcome: str = "") -> str:
        """The legend shown beside the field (markdown), with `outcome` on top once known."""
        sizes, pitch = self.sizes, self.pitch
        teams = "; ".join(
            f"{colour_name(team_colour(team, self._teams))}: "
            + ", ".join(str(p) for p in self.players if p.team == team)
            for team in self._teams
        )
        body = "square robots" if self._player_shape == "square" else "round players"
        ball = f"radius {length_text(pitch.ball_radius_m)}"
        if sizes.ball_enlarged:
            ball += f", **drawn enlarged** to {length_text(sizes.ball_m)}"
        players = f"{body} ({teams})"
        if sizes.players_enlarged:
            players += (
                f", half-size {length_text(pitch.player_radius_m)} "
                f"**drawn enlarged** to {length_text(sizes.player_m)}"
            )
        rings = ", ".join(
            f"{PERCEPT_COLOUR_NAMES[i % len(PERCEPT_COLOUR_NAMES)]}: what {p} perceives"
            for i, p in enumerate(self.players)
        )
        gone = (
            f" They vanish {PERCEPT_LIFETIME_PERIODS:g} sensor periods after that player's "
            "latest percept; the ball's ring also when a percept has no ball."
            if self._percept_life is not None
            else ""
        )
        lines = [
            f"### {outcome}" if outcome else "### outcome: not yet decided",
            "",
            self.title,
            "",
            f"- **Truth** (filled): orange disc = the ball ({ball}); discs = {players}; "
            "white arrow = heading.",
            f"- **Percepts** (hollow rings, small = ball, large = player): {rings}.{gone}",
            "- The field is shown y up (left turns counter-clockwise); markings in FIFA "
            "proportions. **Events** below: commands, sees, hears, referee, link, decisions, "
            "the outcome.",
        ]
        return "\n".join(lines)

    # --- the outcome ------------------------------------------------------------------------

    def log_label(self, tick: int, label: str, detail: str = "") -> None:
        """Record the trial's outcome (e.g. ``"GOAL"``, ``"SUCCESS"``) and why, at `tick`.

        A text line under ``events/label``; from `tick` on, the outcome above the field (in
        the label's colour, with the boundary in that colour too) and on top of the legend.
        A later call replaces an earlier one from its own tick on.
        """
        self._check_open()
        text = outcome_text(label, detail)
        self._add_text("events/label", tick, f"{label}: {detail}" if detail else label, "INFO")
        if tick > self._last_tick:
            self._last_tick = tick
        self._log_outcome(tick, label, text)

    def _log_outcome(self, tick: int, label: str, text: str) -> None:
        """Show the outcome from `tick` on: on the field and on top of the legend.

        Large letters and the reason above the field, and the boundary in the outcome's colour.
        Logged once per trial, so plain ``log`` calls at `tick` serve.
        """
        import rerun as rr

        pitch, rec = self.pitch, self._rec
        length, top = pitch.length_m, pitch.half_width_m
        colour = outcome_colour(label)
        set_tick(rec, tick, self.dt_s)
        try:
            # Above the top side line, in the room :meth:`_view_bounds` leaves: the reason (a
            # label, drawn below its anchor point) just above the line, the label above that.
            strokes = text_strokes(
                label, height_m=0.05 * length, centre_x_m=0.0, base_y_m=top + 0.045 * length
            )
            rec.log(
                "field/outcome",
                rr.LineStrips2D(
                    strokes,
                    colors=colour,
                    radii=rr.Radius.ui_points(3.0),
                    draw_order=ORDER_OUTCOME,
                ),
            )
            rec.log(
                "field/outcome/reason",
                rr.Points2D(
                    [[0.0, top + 0.035 * length]],
                    labels=text,
                    colors=ARROW_COLOUR,  # label text takes this colour: white reads best
                    radii=0.0,
                    show_labels=True,
                    draw_order=ORDER_OUTCOME,
                ),
            )
            rec.log(
                "field/outcome/frame",
                rr.LineStrips2D(
                    [pitch_lines(pitch)[0]],
                    colors=colour,
                    radii=rr.Radius.ui_points(4.0),
                    draw_order=ORDER_OUTCOME,
                ),
            )
        finally:
            rec.reset_time()
        self._log_legend(tick, text)
        self._outcome = (tick, label, text)

    @property
    def outcome(self) -> tuple[int, str, str] | None:
        """The latest :meth:`log_label`: (tick, label, text as shown), or None."""
        return self._outcome
