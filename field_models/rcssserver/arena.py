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
"""

from __future__ import annotations

import contextlib
import math
import os
import socket
import subprocess
import tempfile
import threading
import time
import weakref
from collections import deque

from field_models.arena import ArenaEvent, EventChannel, FieldFacts
from field_models.commands import render_command
from field_models.protocol import (
    LEFT,
    RIGHT,
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
from field_models.rcssserver.config import WirePreset, server_options
from field_models.seeding import TrialRngs
from field_models.soccer_server.messages import (
    MessageParseError,
    Quoted,
    parse_hear,
    parse_see,
    parse_sexpr,
)
from field_models.soccer_server.percepts import heard_from_hear, percept_from_see

_RAD2DEG = 180.0 / math.pi
TEAM_NAMES = {LEFT: "left", RIGHT: "right"}
"""Team names on the wire: the model's own, so a see names players as our refs do."""


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
        self._clients: dict[PlayerRef, WireClient] = {}
        resources: list[object] = []
        self._resources = resources
        self._finalizer = weakref.finalize(self, _shut, resources)
        host, port, trainer_port = self._start_server(rngs)
        timeout = preset.timeout_s
        self._trainer = WireClient(host, trainer_port, timeout)
        resources.append(self._trainer)
        self._connect_trainer()
        self._connect_players(host, port, timeout)
        self._command("(change_mode play_on)", "(ok change_mode)")

    # ------------------------------------------------------------------ set-up

    def _start_server(self, rngs: TrialRngs) -> tuple[str, int, int]:
        p = self.preset
        if p.start == "address":
            return p.host, p.port, p.trainer_port
        if p.start == "binary":
            port = _free_port_triple()
            # rcssserver writes its ~/.rcssserver/*.conf on start (a literal "~" folder in the
            # working directory where it does not expand it) and reads them back: a folder of
            # its own keeps a user's configuration out, and nothing is left behind.
            home = tempfile.TemporaryDirectory(prefix="rcssserver-")
            self._resources.append(home)
            process = subprocess.Popen(
                [p.binary, *server_options(p, port)],
                stdout=subprocess.DEVNULL,
                stderr=subprocess.DEVNULL,
                cwd=home.name,
                env={**os.environ, "HOME": home.name},
            )
            self._resources.append(process)
            return "127.0.0.1", port, port + 1
        # Imported here: the served model is needed only by this kind of preset.
        from field_models.soccer_server.serving import ServedGame
        from field_models.soccer_server.udp import UdpServer

        game = ServedGame(p.server, rngs=rngs, synch=True)
        # The arena is the only client: the server never needs to step without it.
        server = UdpServer(
            game, port=0, trainer_port=0, olcoach_port=0, synch_timeout_s=3600.0,
            idle_timeout_s=3600.0,
        )  # fmt: skip
        stop = threading.Event()
        thread = threading.Thread(
            target=server.serve, kwargs={"stop": stop.is_set}, daemon=True, name="served"
        )
        thread.start()
        self._resources.append((stop, thread, server))
        player, trainer, _ = server.ports
        return "127.0.0.1", player, trainer

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

    def _connect_players(self, host: str, port: int, timeout: float) -> None:
        version = self.preset.client_version
        for team in (LEFT, RIGHT):
            wanted = sorted(ref.number for ref in self.players if ref.team == team)
            if not wanted:
                continue
            fillers = []
            for number in range(1, wanted[-1] + 1):
                client = WireClient(host, port, timeout)
                self._resources.append(client)
                client.send(f"(init {TEAM_NAMES[team]} (version {version}))")
                reply = client.until("(init ")[-1]
                if reply.split()[2] != str(number):
                    raise WireError(f"expected uniform number {number}, the server gave {reply}")
                ref = PlayerRef(team, number)
                if ref in self._plans:
                    self._clients[ref] = client
                else:
                    fillers.append(client)
            for client in fillers:
                client.send("(bye)")  # a number the trial does not use: its slot stays empty

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

    def _state_text(self, x: float, y: float, heading: float, vx: float, vy: float) -> str:
        dt = self._dt
        deg = -heading * _RAD2DEG
        return f"{x!r} {-y!r} {deg!r} {vx * dt!r} {-vy * dt!r}"

    # ------------------------------------------------------------------ coach side

    @property
    def tick(self) -> int:
        """Cycles stepped since the trial began."""
        return self._tick

    def place_player(self, ref: PlayerRef, x: float, y: float, heading: float) -> None:
        """The trainer's ``(move (player Team Unum) X Y Dir 0 0)``."""
        if ref not in self._clients:
            raise KeyError(f"{ref} is not a player of this arena")
        text = self._state_text(x, y, heading, 0.0, 0.0)
        self._command(f"(move (player {TEAM_NAMES[ref.team]} {ref.number}) {text})", "(ok move)")
        self._placed[ref] = BodyState(float(x), float(y), float(heading))
        self._look = None

    def place_ball(self, x: float, y: float, vx: float = 0.0, vy: float = 0.0) -> None:
        """The trainer's ``(move (ball) X Y 0 VX VY)``."""
        self._command(f"(move (ball) {self._state_text(x, y, 0.0, vx, vy)})", "(ok move)")
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
            ball, players = self._parse_look(reply)
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

    def _parse_look(self, text: str) -> tuple[BodyState, dict[PlayerRef, BodyState]]:
        try:
            tree = parse_sexpr(text)
        except MessageParseError as exc:
            raise WireError(f"unreadable look: {exc}") from None
        dt = self._dt
        ball = BodyState(0.0, 0.0, 0.0)
        players: dict[PlayerRef, BodyState] = {}
        teams = {name: team for team, name in TEAM_NAMES.items()}
        for item in tree[3:]:
            if not isinstance(item, list) or not isinstance(item[0], list):
                continue
            name, values = item[0], [float(v) for v in item[1:] if isinstance(v, str)]
            if name == ["b"]:
                x, y, vx, vy = values[:4]
                ball = BodyState(x, -y + 0.0, 0.0, vx / dt, -vy / dt + 0.0)
            elif name and name[0] == "p" and len(name) >= 3 and isinstance(name[1], Quoted):
                team = teams.get(str(name[1]))
                if team is None:
                    continue
                x, y, vx, vy, body = values[:5]
                ref = PlayerRef(team, int(str(name[2])))
                heading = math.remainder(-body / _RAD2DEG, math.tau)
                players[ref] = BodyState(x, -y + 0.0, heading, vx / dt, -vy / dt + 0.0)
        return ball, players

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
        times = {ref: _sense_time(batch) for ref, batch in batches.items()}
        known = [t for t in (*times.values(), target) if t is not None]
        now = max(known) if known else None
        if now is not None:
            for ref, client in self._clients.items():
                while (behind := times[ref]) is None or behind < now:  # stale: read on
                    more = client.until("(think)")
                    batches[ref] += more
                    times[ref] = _sense_time(more)
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
                percepts.append(self._percept(ref, seen, now, _head_angle(batch)))
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


def _shut(resources: list[object]) -> None:
    """Close what an arena opened, newest first (kept apart from the arena: a finalizer)."""
    for item in reversed(resources):
        if isinstance(item, WireClient):
            with contextlib.suppress(OSError):
                item.send("(bye)")
            item.close()
        elif isinstance(item, subprocess.Popen):
            item.terminate()
            try:
                item.wait(timeout=5.0)
            except subprocess.TimeoutExpired:
                item.kill()
        elif isinstance(item, tempfile.TemporaryDirectory):
            item.cleanup()
        elif isinstance(item, tuple):
            stop, thread, server = item
            stop.set()
            thread.join(timeout=5.0)
            server.close()
    resources.clear()


def _head_angle(batch: list[str]) -> float:
    """The neck angle [rad, CCW] of the last ``sense_body``'s ``(head_angle H)`` (0: none).

    H is in the server's degrees, clockwise on our field, so its sign flips.
    """
    angle = 0.0
    for text in batch:
        if text.startswith("(sense_body "):
            start = text.find("(head_angle ")
            if start >= 0:
                token = text[start + len("(head_angle ") :].split(")", 1)[0]
                with contextlib.suppress(ValueError):
                    angle = -math.radians(float(token)) + 0.0
    return angle


def _sense_time(batch: list[str]) -> int | None:
    """The time of the last ``sense_body`` in a client's messages (None: there was none)."""
    time_ = None
    for text in batch:
        if text.startswith("(sense_body "):
            with contextlib.suppress(IndexError, ValueError):
                time_ = int(text.split(maxsplit=2)[1])
    return time_


def _free_port_triple() -> int:
    """A port p with p, p+1 and p+2 free now (a real server's player, trainer, coach ports)."""
    for _ in range(100):
        probe = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
        probe.bind(("127.0.0.1", 0))
        base = int(probe.getsockname()[1])
        probe.close()
        if base + 2 > 65535:
            continue
        held = []
        try:
            for p in (base, base + 1, base + 2):
                s = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
                held.append(s)
                s.bind(("127.0.0.1", p))
            return base
        except OSError:
            continue
        finally:
            for s in held:
                s.close()
    raise WireError("no three free consecutive UDP ports")
