"""A Soccer Server over UDP behind the Arena interface: a trainer places, players are clients.

One :class:`WireArena` per trial (shared `specs/soccer_server.md` §5):

* **the server**: ``served`` starts our model (:class:`~field_models.soccer_server.serving.
  ServedGame` on :class:`~field_models.soccer_server.udp.UdpServer`, free ports, synch mode,
  seeded from the trial's streams) in a thread of this process; ``binary`` starts a real
  rcssserver with the preset's parameters (:func:`~field_models.rcssserver.config.server_options`);
  ``address`` connects to one already running. The arena's server stops when the arena is
  closed or collected.
* **the trainer** (offline coach, port 6001) does the coach's work: ``move`` places the ball and
  players (server frame: y down, degrees, velocities per cycle), ``look`` reads the truth
  (``(ok look ...)``, six significant digits, body angles in whole degrees), ``ear on`` hears
  the referee's goals. A placement reads back exactly as it was made while the server's look
  agrees with it (to its printed precision), as the trainer knows what it just placed.
* **each player** is one client in synch mode, team names ``left`` and ``right`` (the left
  team connects first, so it gets the left side). Uniform numbers come from the server in
  order, so the arena connects 1..N of each team and says ``bye`` for numbers not in the trial.
* **a tick** is one cycle: every player sends the commands of its plan (body actions one per
  cycle; says, neck turns and view changes at once, as the Soccer Server arena queues them)
  and ``(done)``; the server steps and sends each player its sense_body, hears and see, then
  ``(think)``; a see becomes a percept through the same parser as the Soccer Server arena's
  trace path, with the neck angle of the cycle's sense_body (``head_angle``: the see's
  directions are relative to the head).

Starting, connecting and shutting down the server and the clients are
:mod:`~field_models.rcssserver.launch`'s; writing and reading the trainer's and the clients'
texts (frames and units on the wire) :mod:`~field_models.rcssserver.wire_text`'s.
"""

from __future__ import annotations

import math
import time
import weakref
from collections import deque

from field_models.arena import ArenaEvent, EventChannel, FieldFacts
from field_models.commands import render_command
from field_models.protocol import (
    Action,
    BodyState,
    ChangeView,
    Heard,
    Percept,
    PlayerRef,
    Say,
    Truth,
    TurnNeck,
)
from field_models.rcssserver.client import WireClient, WireError
from field_models.rcssserver.config import WirePreset
from field_models.rcssserver.launch import connect_players, shut, start_server
from field_models.rcssserver.wire_text import (
    TEAM_NAMES,
    head_angle,
    move_text,
    parse_look,
    sense_time,
)
from field_models.seeding import TrialRngs
from field_models.soccer_server.messages import (
    MessageParseError,
    parse_hear,
    parse_see,
)
from field_models.soccer_server.percepts import heard_from_hear, percept_from_see


class WireArena:
    """A Soccer Server reached over UDP, behind :class:`~field_models.arena.Arena`.

    Args:
        preset: Which server and its Soccer Server preset (:mod:`~field_models.rcssserver.config`).
        facts: Its facts.
        players: The trial's players (teams ``left`` and ``right``, numbers 1..11).
        rngs: The trial's streams: a served server draws its noise from them.
        keep_events: Keep commands and referee calls for :meth:`drain_events`.
        trace: Also keep every see and hear, as the clients got them.

    Raises:
        field_models.rcssserver.client.WireError: The server did not answer.
    """

    def __init__(
        self,
        preset: WirePreset,
        facts: FieldFacts,
        players: tuple[PlayerRef, ...],
        rngs: TrialRngs,
        *,
        keep_events: bool = False,
        trace: bool = False,
    ) -> None:
        for ref in players:
            if ref.team not in TEAM_NAMES or not 1 <= ref.number <= 11:
                raise ValueError(f"player {ref}: the server has teams left and right, 1..11")
        self.preset = preset
        self.facts = facts
        self.players = players
        self.keep_events = keep_events or trace
        self.trace = trace
        self._dt = facts.dt_s
        self._tick = 0
        self._events: list[ArenaEvent] = []
        self._listening = set(players)
        self._plans: dict[PlayerRef, deque[Action]] = {ref: deque() for ref in players}
        self._says: dict[PlayerRef, list[str]] = {ref: [] for ref in players}
        self._side: dict[PlayerRef, list[str]] = {ref: [] for ref in players}  # neck, view
        self._heard: dict[PlayerRef, list[Heard]] = {ref: [] for ref in players}
        self._placed: dict[PlayerRef | None, BodyState] = {}
        self._look: tuple[int, BodyState, dict[PlayerRef, BodyState]] | None = None
        self._score = [0, 0]
        self._server_time: int | None = None  # the server's clock at the last step's sense_body
        resources: list[object] = []  # what the arena opened, for shut
        self._resources = resources
        self._finalizer = weakref.finalize(self, shut, resources)
        host, port, trainer_port = start_server(preset, rngs, resources)
        self._trainer = WireClient(host, trainer_port, preset.timeout_s)
        resources.append(self._trainer)
        self._connect_trainer()
        self._clients = connect_players(preset, players, (host, port), resources)
        self._command("(change_mode play_on)", "(ok change_mode)")

    # ------------------------------------------------------------------ set-up

    def _connect_trainer(self) -> None:
        version = self.preset.client_version
        deadline = time.monotonic() + self.preset.timeout_s
        while True:  # a binary just started may not listen yet: ask again
            self._trainer.send(f"(init (version {version}))")
            try:
                self._trainer.timeout_s = 0.2
                self._trainer.until("(init ok)")
                break
            except WireError:
                if time.monotonic() > deadline:
                    raise
        self._trainer.timeout_s = self.preset.timeout_s
        self._command("(change_mode before_kick_off)", "(ok change_mode)")
        self._command("(ear on)", "(ok ear")

    # ------------------------------------------------------------------ the trainer

    def _command(self, text: str, expect: str) -> str:
        self._trainer.send(text)
        for reply in self._trainer.until(expect):
            self._trainer_message(reply)
        return reply

    def _trainer_message(self, text: str) -> None:
        """Referee calls the trainer hears: goals count, everything is an event."""
        if not text.startswith("(hear referee "):
            return
        message = text[len("(hear referee ") : -1].split(" ", 1)[-1]
        for side, prefix in ((0, "goal_l_"), (1, "goal_r_")):
            if message.startswith(prefix) and message[len(prefix) :].isdigit():
                self._score[side] = int(message[len(prefix) :])
        self._log(self._tick, "referee", message)

    # ------------------------------------------------------------------ coach side

    @property
    def tick(self) -> int:
        """Cycles stepped since the trial began."""
        return self._tick

    def place_player(self, ref: PlayerRef, x: float, y: float, heading: float) -> None:
        """The trainer's ``(move (player Team Unum) X Y Dir 0 0)``."""
        if ref not in self._clients:
            raise KeyError(f"{ref} is not a player of this arena")
        text = move_text(x, y, heading, 0.0, 0.0, self._dt)
        self._command(f"(move (player {TEAM_NAMES[ref.team]} {ref.number}) {text})", "(ok move)")
        self._placed[ref] = BodyState(float(x), float(y), float(heading))
        self._look = None

    def place_ball(self, x: float, y: float, vx: float = 0.0, vy: float = 0.0) -> None:
        """The trainer's ``(move (ball) X Y 0 VX VY)``."""
        self._command(f"(move (ball) {move_text(x, y, 0.0, vx, vy, self._dt)})", "(ok move)")
        self._placed[None] = BodyState(float(x), float(y), 0.0, float(vx), float(vy))
        self._look = None

    def ball_state(self) -> BodyState:
        """The ball as the trainer's look shows it."""
        return self._looked()[1]

    def player_state(self, ref: PlayerRef) -> BodyState:
        """A player as the trainer's look shows it."""
        return self._looked()[2][ref]

    def truth(self) -> Truth:
        """Everything, from one look."""
        _, ball, players = self._looked()
        ordered = {ref: players[ref] for ref in self.players if ref in players}
        return Truth(self._tick, self._tick * self._dt, ball, ordered)

    def score(self) -> tuple[int, int]:
        """Goals as the server's referee announced them to the trainer."""
        for text in self._trainer.poll():
            self._trainer_message(text)
        return self._score[0], self._score[1]

    def _looked(self) -> tuple[int, BodyState, dict[PlayerRef, BodyState]]:
        if self._look is None or self._look[0] != self._tick:
            reply = self._command("(look)", "(ok look ")
            ball, players = parse_look(reply, self._dt)
            ball = self._as_placed(None, ball)
            players = {ref: self._as_placed(ref, st) for ref, st in players.items()}
            self._look = (self._tick, ball, players)
        return self._look

    def _as_placed(self, key: PlayerRef | None, seen: BodyState) -> BodyState:
        """The exact placement while the look agrees with it to its printed precision."""
        placed = self._placed.get(key)
        if placed is None:
            return seen
        close = (
            abs(seen.x - placed.x) <= 1e-4 * max(1.0, abs(placed.x))
            and abs(seen.y - placed.y) <= 1e-4 * max(1.0, abs(placed.y))
            and abs(math.remainder(seen.heading - placed.heading, math.tau)) <= math.radians(0.51)
            and abs(seen.vx - placed.vx) <= 1e-3 * max(1.0, abs(placed.vx))
            and abs(seen.vy - placed.vy) <= 1e-3 * max(1.0, abs(placed.vy))
        )
        return placed if close else seen

    # ------------------------------------------------------------------ client side

    def step(self) -> list[Percept]:
        """One cycle in synch mode (module docstring); the percepts of the sees it brought.

        Every client's messages are read up to a ``(think)`` whose cycle's ``sense_body`` shows
        the server's new time: a real rcssserver sends ``(think)`` to the players it waits for
        while the arena is still setting up, so a client may hold one cycle's stale messages
        (its ``(think)`` with no ``(done)`` sent yet). Those are read past at the first step,
        where the new time is the trainer's look time + 1, and at any later step where a client
        is behind the others; their hears still count, the newest see makes the percept.
        """
        target = self._trainer_time() + 1 if self._server_time is None else None
        for ref, client in self._clients.items():
            commands = [f'(say "{text}")' for text in self._says[ref]] + self._side[ref]
            self._says[ref].clear()
            self._side[ref] = []
            plan = self._plans[ref]
            if plan:
                commands.append(render_command(plan.popleft()))
            client.send("".join(commands) + "(done)")
        self._tick += 1
        self._placed.clear()
        self._look = None
        batches = {ref: client.until("(think)") for ref, client in self._clients.items()}
        times = {ref: sense_time(batch) for ref, batch in batches.items()}
        known = [t for t in (*times.values(), target) if t is not None]
        now = max(known) if known else None
        if now is not None:
            for ref, client in self._clients.items():
                while (behind := times[ref]) is None or behind < now:  # stale: read on
                    more = client.until("(think)")
                    batches[ref] += more
                    times[ref] = sense_time(more)
            self._server_time = now
        percepts = []
        for ref, batch in batches.items():
            seen = None
            for text in batch:
                if text.startswith("(see "):
                    seen = text
                elif text.startswith("(hear "):
                    self._hear(ref, text)
            if seen is not None and ref in self._listening:
                percepts.append(self._percept(ref, seen, now, head_angle(batch)))
        return percepts

    def _trainer_time(self) -> int:
        """The server's clock now, from the trainer's look (the server waits for our done)."""
        reply = self._command("(look)", "(ok look ")
        try:
            return int(reply.split()[2])
        except (IndexError, ValueError):
            raise WireError(f"unreadable look: {reply[:80]}") from None

    def _hear(self, ref: PlayerRef, text: str) -> None:
        if self.trace:
            self._log(self._tick, "hear", text, ref)
        try:
            heard = heard_from_hear(parse_hear(text), ref)
        except MessageParseError:
            return
        if heard is not None:
            self._heard[ref].append(heard)

    def _percept(self, ref: PlayerRef, text: str, now: int | None, neck: float = 0.0) -> Percept:
        """The see's percept at this tick; a see older than the server's time is dated back.

        `neck` is the player's neck angle [rad, CCW] from the cycle's sense_body.
        """
        if self.trace:
            self._log(self._tick, "see", text, ref)
        heard = tuple(self._heard[ref])
        self._heard[ref].clear()
        tick = self._tick
        info = parse_see(text)
        late = max(0, now - info.time) if now is not None else 0
        observed = max(0, tick - late)
        return percept_from_see(info, ref, tick, observed, heard, cycle_s=self._dt, neck_rad=neck)

    def listen(self, refs: frozenset[PlayerRef]) -> None:
        """Build percepts only for these players (the others' sees still come, unread)."""
        self._listening = set(refs)

    def submit(self, ref: PlayerRef, actions: tuple[Action, ...]) -> None:
        """Says go with the next cycle's datagram; body actions one per cycle from then on."""
        body = []
        for action in actions:
            if isinstance(action, Say):
                self._says[ref].append(action.text)
            elif isinstance(action, TurnNeck | ChangeView):  # not body commands (spec §1.1)
                self._side[ref].append(render_command(action))
            else:
                body.append(action)
            if self.keep_events:
                self._log(self._tick, "command", render_command(action), ref)
        plan = self._plans[ref]
        plan.clear()
        plan.extend(body)

    def drain_events(self) -> list[ArenaEvent]:
        """Commands, sees, hears and referee calls since the last call, oldest first."""
        events, self._events = self._events, []
        return events

    def close(self) -> None:
        """Say goodbye, stop the arena's own server, close every socket; again: no-op."""
        self._finalizer()

    def _log(
        self, tick: int, channel: EventChannel, text: str, ref: PlayerRef | None = None
    ) -> None:
        if self.keep_events:
            self._events.append(ArenaEvent(tick, channel, text, ref))
