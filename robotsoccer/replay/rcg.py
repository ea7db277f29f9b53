"""The Soccer Server's text game log (``.rcg``, format ``ULG5``): the format, shared by both sides.

Writing ours is :mod:`robotsoccer.replay.rcg_write`
(:class:`~robotsoccer.replay.rcg_write.RcgWriter`), reading any is
:mod:`robotsoccer.replay.rcg_read` (:func:`~robotsoccer.replay.rcg_read.read_rcg`); this module
holds what both need: the header, the player slots, the state bits, the cycle.

rcssserver writes one such log per match when started with ``game_log_version 5``; rcssmonitor,
rcsslogplayer and the usual analysis tools replay and read it. The syntax here is rcssserver
19.0.0's, read from its source:

* ``src/initsenderlogger.cpp`` (``InitSenderLoggerV5``): the header line ``ULG5``, then the
  ``(server_param ...)``, ``(player_param ...)`` and ``(player_type ...)`` lines
  (``src/initsender.cpp``, ``InitSenderCommonV8``; each parameter ``(name value)`` with no
  space between parameters, doubles as a C++ stream prints them, booleans ``0``/``1``,
  strings in double quotes). A log gets every parameter (its sender asks as protocol 999),
  sorted by name (the server's ``std::map``), and one line per player type: the writer writes
  all of them (:mod:`field_models.rcss_params`), rcssserver 19's defaults where it was given
  no value, and 18 types that are each the default type;
* ``src/logger.cpp`` (``Logger::writeGameLogImpl``): every cycle a ``(playmode T mode)`` line
  when the play mode changed, a ``(team T LEFT RIGHT SL SR)`` line when a name or the score
  changed (both first written at the first cycle), then the ``(show T ...)`` line;
* ``src/dispsender.cpp`` (``DispSenderLoggerV4::sendShow``) and ``src/serializermonitor.cpp``
  (``SerializerMonitorStdv3``/``v4``; log version 5 uses monitor serializer 4): the show line
  ``(show T ((b) x y vx vy) ((l 1) TYPE STATE x y vx vy body neck (v h 90)
  (s stamina effort recovery capacity) (c kick dash turn catch move turn_neck change_view say
  tackle pointto attentionto)) ...)``. Every show carries all 22 player slots in the
  server's order (left 1..11, right 1..11): the server creates its 22 players at the start
  (``Stadium``'s constructor, ``src/stadium.cpp``), and rcssmonitor's reader
  (``rcss/rcg/parser_v4.cpp``) refuses a show with fewer. STATE is hexadecimal with a ``0x``
  prefix (``std::showbase``, which prints zero as ``0``); bit 0x1 (``STAND``) marks an
  enabled player. A player not connected is written disabled (state 0) at x = -3·unum·side,
  y = -(68/2 + 3) (``Player::disable`` in ``src/player.cpp``; side +1 left, -1 right), which
  is how this writer writes a slot without a player in the frame.

**What the writer writes as the server does** (``src/types.h`` ``PlayerState``,
``src/referee.cpp``, ``src/stadium.cpp``):

* **cycles**: the frame's tick, which on a 100 ms field is the server's cycle count. The server
  logs a cycle after stepping it, so its first show is cycle 1: a frame at tick 0 (the placement
  before the first step) is refused;
* **play modes**: each frame's mode, where it changed. A goal is written as the referee calls
  it: the cycle the score rose in (the frame before the first frame with the new score) reads
  ``goal_l`` or ``goal_r`` with the new score and the ball still, and is shown
  :data:`AFTER_GOAL_WAIT` times in all with the clock held (``AFTER_GOAL_WAIT``: the server's
  pause before the kick-off), the players frozen where they stood, as our models do not play
  out that pause. (The 1996 preset puts the ball back on the centre spot in the goal's own
  cycle, as that server did, so its goal scene shows the ball there.) :meth:`RcgWriter.finish`
  ends the log with ``time_over`` at the last cycle;
* **state**: ``STAND`` (0x1) for every player on the field, ``GOALIE`` (0x8) for the goalies
  given, ``KICK`` (0x2) in a cycle whose kick reached the ball and ``KICK_FAULT`` (0x4) in one
  whose kick did not (from the frame's :class:`~field_models.arena.CommandTally`); our players
  cannot catch or tackle, so those flags never appear;
* **counters** ``(c kick dash turn catch move turn_neck change_view say tackle pointto
  attentionto)``: the frame's counts of the commands the server carried out; zeros where the
  field model does not count them. Our clients send only kick, dash, turn and say (the
  coach's kick-off placement is a trainer's move, not the player's), so the others stay 0;
* **stamina, effort, recovery, capacity** ``(s ...)``: our models do not simulate stamina (the
  dash uses effort 1), so every show carries the real server's initial values: the given
  ``stamina_max``, ``effort_init``, ``recover_init`` and ``stamina_capacity``, otherwise
  rcssserver 19's defaults 8000, 1, 1 and 130600. The neck angle is 0 (our players have no
  neck) and the view ``(v h visible_angle)``, the server's default view.

Coordinates are the server's: metres, x toward the right goal, **y down**, angles in degrees
clockwise positive, velocities per cycle. Our field frame has y up, counter-clockwise radians
and m/s, so the writer writes y, vy and the body angle negated and velocities times the cycle
(``dt_s``), and the reader undoes it. Positions and velocities are written with four decimals
and angles with three (the server's ``PREC`` 0.0001 and ``DPREC`` 0.001); with ``%.4f``
instead of the server's ``%g`` of the quantised value the file is a little larger and every
log reader parses it the same. Velocities are therefore kept to 0.0001 m per cycle (0.001 m/s
at the server's 100 ms cycle).

The cycle written is the frame's tick. ``simulator_step`` (ms) is always written, from
``dt_s``; the reader takes the cycle from it (0.1 s when a log has none). A step that is not a
whole number of milliseconds (a robot table's 1/240 s) is written as a decimal: the log players
then warn that the value is not an integer and keep their default, and our reader keeps the
exact step.
"""

from __future__ import annotations

from field_models.protocol import LEFT, RIGHT, PlayerRef

HEADER = "ULG5"
"""First line of the log: text format, version 5."""
FIRST_CYCLE = 1
"""The first cycle a server's log shows: it logs each cycle after stepping it."""
AFTER_GOAL_WAIT = 50
"""Shows of a goal's cycle, the clock held: rcssserver's pause before the kick-off
(``AFTER_GOAL_WAIT``, ``src/referee.h``)."""
TIME_OVER = "time_over"
"""The play mode of a log's last cycle (:meth:`RcgWriter.finish`)."""
READABLE_HEADERS = ("ULG4", "ULG5", "ULG6")
"""Headers :func:`read_rcg` accepts: the text versions, whose show lines read alike."""
MAX_PLAYERS_PER_TEAM = 11
"""Highest uniform number the log players accept (rcssmonitor's ``MAX_PLAYER``)."""
DEFAULT_CYCLE_S = 0.1
"""Cycle assumed when a log's ``server_param`` line has no ``simulator_step``."""
NO_PLAY_MODE = "before_kick_off"
"""Play mode of shows read before any ``playmode`` line (real logs always have one first)."""

SLOTS = tuple(
    PlayerRef(team, number)
    for team in (LEFT, RIGHT)
    for number in range(1, MAX_PLAYERS_PER_TEAM + 1)
)
"""Every show line's player slots, in rcssserver's order: left 1..11, then right 1..11."""

STAND = 0x1
"""rcssserver's ``PlayerState`` bit of an enabled player (``src/types.h``)."""
