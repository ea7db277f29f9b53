"""Replaying runs: rerun recordings, Soccer Server game logs and paper-style text traces.

The drawing toolkit: :mod:`~robotsoccer.replay.geometry` (pitch markings, outlines, sizes),
:mod:`~robotsoccer.replay.palette` (colours, draw orders, names),
:mod:`~robotsoccer.replay.lettering` (stroke letters), :mod:`~robotsoccer.replay.toolkit` (the
stream, the static field and team styles, the layout pieces) and :mod:`~robotsoccer.replay.rows`
(rows buffered for ``send_columns``). On it, :mod:`~robotsoccer.replay.field_recorder` is every
recording's core, and two thin layers use it: :mod:`~robotsoccer.replay.recording` (a drill's trial)
and :mod:`~robotsoccer.replay.match_recording` (a whole match, with
:mod:`~robotsoccer.replay.match_drawing`). :mod:`~robotsoccer.replay.rrd_files` verifies, reads back
and replays ``.rrd`` files; :mod:`~robotsoccer.replay.raster` draws the same picture into arrays.
Beside them, the Soccer Server's ``.rcg`` game log (:mod:`~robotsoccer.replay.rcg`),
:mod:`~robotsoccer.replay.game_log` (a recording from a game log) and
:mod:`~robotsoccer.replay.trace` (a trial printed as the paper's Figure 4).
"""
