"""The Soccer Server model as an arena: the server's dynamics, see/hear sensing and command queue.

One tick is one 100 ms server cycle (shared `specs/soccer_server.md` §1):

1. the body command queued for this cycle (see below) and any says are handed to the model,
   which steps: commands, per-object update in shuffled order, collisions, goal check;
2. says and referee messages of the cycle are delivered to the players in hearing range
   (`hearing.deliver_says`, §2.6); they reach the client with its next percept;
3. each player whose see timer fires this cycle (§3.1, the preset's `send_step_ms`; the paper's
   250 ms by default) gets a percept built from its see by the structured fast path
   (:func:`~field_models.soccer_server.percepts.percept_from_state`, which a test proves equal
   to rendering the see message as text and parsing it back), all of the cycle's at once
   (:func:`~field_models.soccer_server.percepts_many.percepts_of`, equal to that bit for bit).

**Several body actions per decision.** The paper's clients send more than one command per see
(Figure 4: ``(turn 1)`` then ``(dash 60)``), and the server runs one body command per cycle. So a
mind may return several body actions: they run in order, one per cycle, and a new decision
replaces whatever is left of the previous one. Says, neck turns and view changes are not body
commands (§1.1): they go out at once, beside the decision's first body action.

**Neck and view.** A ``TurnNeck`` turns the player's neck at the next step (the model's
:meth:`~field_models.soccer_server.dynamics.SoccerServerModel.turn_neck`); its sees then look
along body + neck and its percepts carry the neck angle (``Percept.neck_rad``). A
``ChangeView`` changes that player's view width and quality at once (§3.1): its cone and its
see interval. Until some player changes its view, every player's sees come on one shared
schedule (phase 0); from then on each player counts the server's visual-timer ticks (every
``send_step / 4`` ms) and gets a see when its count reaches its view's interval (4 ticks at
normal width and high quality, ×½ narrow, ×2 wide, ×½ low quality), keeping the remainder:
with a view that never changes this gives exactly the shared schedule. At most one percept a
cycle, as before (the fast views of a 150 ms ``send_step`` can fire twice in one cycle).

**Counts.** Like rcssserver, the arena counts each player's commands as the server carries them
out (:meth:`SoccerServerArena.command_tally`): a body action when its cycle comes (one left in
a replaced decision was never sent, so it is not counted), a say when the server accepts it
(not one longer than ``say_msg_size``), and whether the cycle's kick reached the ball.

**Text.** With ``trace=True`` every see and hear is also rendered in the server's text format
(Figure 4) into the event log, and the percept is taken from the *parsed text*, so a trace shows
exactly what the client acted on. Commands are logged (``keep_events``) in the client's command
text (:mod:`field_models.commands`) as they are handed to the server.
"""

from __future__ import annotations

from collections import deque
from functools import lru_cache

from field_models.arena import (
    COMMAND_COUNTERS,
    ArenaEvent,
    CommandTally,
    EventChannel,
    FieldFacts,
)
from field_models.commands import render_command
from field_models.protocol import (
    Action,
    BodyState,
    ChangeView,
    Dash,
    Heard,
    Kick,
    Percept,
    PlayerRef,
    Say,
    Truth,
    Turn,
    TurnNeck,
)
from field_models.seeding import TrialRngs
from field_models.soccer_server.dynamics import SoccerServerModel
from field_models.soccer_server.hearing import HearInfo, deliver_says, referee_hear
from field_models.soccer_server.messages import parse_see, render_hear, render_see
from field_models.soccer_server.params import ServerPreset
from field_models.soccer_server.percepts import (
    heard_from_hear,
    percept_from_see,
    percept_from_state,
)
from field_models.soccer_server.percepts_many import percepts_of
from field_models.soccer_server.see_timing import SeeTimer, visual_send_interval
from field_models.soccer_server.sensing import Bodies, LandmarkMode, observe
from field_models.soccer_server.sensing_params import SensingParams


class SoccerServerArena:
    """The Soccer Server field model behind the :class:`~field_models.arena.Arena` interface.

    Args:
        preset: The server preset, options already applied (:mod:`field_models.registry`).
        facts: Its facts.
        players: The players, rows 1..N of the model.
        rngs: The trial's generators ("movement", "sensing").
        keep_events: Keep commands, says and referee calls for :meth:`drain_events`.
        trace: Also keep every see and hear as text, and take percepts from that text.
    """

    def __init__(
        self,
        preset: ServerPreset,
        facts: FieldFacts,
        players: tuple[PlayerRef, ...],
        rngs: TrialRngs,
        *,
        keep_events: bool = False,
        trace: bool = False,
    ) -> None:
        self.preset = preset
        self.facts = facts
        self.players = players
        self.model = SoccerServerModel(preset, players, rngs["movement"])
        self.sensing = preset.sensing
        self.keep_events = keep_events or trace
        self.trace = trace
        self._see_rng = rngs["sensing"]
        self._landmarks: LandmarkMode = "all" if self.sensing.percept_flags else "goals"
        self._see_schedule = see_schedule(self.sensing)
        self._timer = SeeTimer(self.sensing)  # every player's sees share one phase (0)
        self._observers = tuple(range(1, len(players) + 1))  # rows whose sees are built
        self._rows = {ref: i + 1 for i, ref in enumerate(players)}
        self._plans: list[deque[Action]] = [deque() for _ in players]
        self._heard: list[list[Heard]] = [[] for _ in players]
        self._events: list[ArenaEvent] = []
        self._counts = [[0] * len(COMMAND_COUNTERS) for _ in players]
        self._kick_tick = [-1] * len(players)  # the tick whose cycle carried out a kick
        self._views: list[SensingParams] = [self.sensing] * len(players)
        self._view_params: dict[tuple[str, str], SensingParams] = {}  # one object per view
        self._view_ticks: list[int] | None = None  # timer ticks per player, once views differ

    @property
    def tick(self) -> int:
        """Server cycles stepped since the trial began."""
        return self.model.cycle

    # ------------------------------------------------------------------ coach side

    def place_player(self, ref: PlayerRef, x: float, y: float, heading: float) -> None:
        """The trainer's move: put a player at rest at (x, y) [m] facing `heading` [rad]."""
        self.model.move_player(self._rows[ref], x, y, heading)

    def place_ball(self, x: float, y: float, vx: float = 0.0, vy: float = 0.0) -> None:
        """The trainer's move of the ball, with velocity (vx, vy) [m/s]."""
        self.model.move_ball(x, y, vx, vy)

    def ball_state(self) -> BodyState:
        """The ball's exact state (velocity in m/s)."""
        return self.model.ball_state()

    def player_state(self, ref: PlayerRef) -> BodyState:
        """A player's exact state (velocity in m/s)."""
        return self.model.player_state(self._rows[ref])

    def truth(self) -> Truth:
        """Exact state of everything."""
        players = {ref: self.model.player_state(row) for ref, row in self._rows.items()}
        return Truth(self.tick, self.tick * self.facts.dt_s, self.model.ball_state(), players)

    def score(self) -> tuple[int, int]:
        """Goals of the left and right team, as the server's referee counted them (§6)."""
        return (self.model.score_left, self.model.score_right)

    # ------------------------------------------------------------------ client side

    def step(self) -> list[Percept]:
        """Run one server cycle; return the percepts of the players whose see fires now."""
        model = self.model
        for i, plan in enumerate(self._plans):
            if plan:
                action = plan.popleft()
                if model.command(i + 1, action):
                    kind = _COUNTER[type(action)]
                    self._counts[i][kind] += 1
                    if kind == _KICK:
                        self._kick_tick[i] = model.cycle + 1
        referee = model.step()
        cycle = model.cycle
        says = model.said()
        for row, _ in says:
            self._counts[row - 1][_SAY] += 1
        if says or referee:
            self._hear(says, referee, cycle)
        if self._view_ticks is not None:
            return self._own_sees(cycle)
        schedule = self._see_schedule
        due = schedule[cycle] if cycle < len(schedule) else self._timer.due(cycle)
        if not due:
            return []
        return self._sees(self._observers, cycle)

    def _sees(self, rows: tuple[int, ...], cycle: int) -> list[Percept]:
        """The percepts of the sees of players `rows` (in order) at this cycle.

        All at once (:func:`~field_models.soccer_server.percepts_many.percepts_of`, equal bit for
        bit to one see at a time) while every head looks along its body and every player has
        the preset's view; one at a time once a neck is turned or a view changed.
        """
        if self.trace:
            return [self._see_text(row - 1, cycle) for row in rows]
        m = self.model
        if self._view_ticks is not None or any(m.neck):
            return [self._see_state(row - 1, cycle) for row in rows]
        bodies = Bodies(m.x, m.y, m.vx, m.vy, m.heading)
        heard = [self._take_heard(row - 1) for row in rows]
        return percepts_of(
            rows, bodies, self.players, self.sensing, self._see_rng, cycle, heard, self._landmarks
        )

    def _own_sees(self, cycle: int) -> list[Percept]:
        """The sees of this cycle once views differ: each player's own timer count (docstring)."""
        assert self._view_ticks is not None
        new = self._ticks_in(cycle)
        listening = set(self._observers)
        due = []
        for i, view in enumerate(self._views):
            interval = visual_send_interval(view)
            count = self._view_ticks[i] + new
            self._view_ticks[i] = count % interval
            if count >= interval and i + 1 in listening:
                due.append(i + 1)
        return self._sees(tuple(due), cycle)

    def _ticks_in(self, cycle: int) -> int:
        """Visual-timer ticks fired in `cycle`'s window (as :meth:`SeeTimer.sees_in_cycle`)."""
        step = self.sensing.simulator_step_ms
        return self._timer.ticks_by(step * (cycle + 1) - 1) - self._timer.ticks_by(step * cycle - 1)

    def _change_view(self, row: int, view: ChangeView) -> None:
        """Player `row`'s view width and quality change now (§3.1); counted as the server does."""
        if self._view_ticks is None:  # the shared schedule's phase, as each player's own count
            step = self.sensing.simulator_step_ms
            done = self._timer.ticks_by(step * (self.model.cycle + 1) - 1)
            interval = visual_send_interval(self.sensing)
            self._view_ticks = [done % interval] * len(self.players)
        key = (view.width, view.quality)
        params = self._view_params.get(key)
        if params is None:  # one object per view: the see's constants are cached by identity
            params = self.sensing.replace(view_width=view.width, view_quality=view.quality)
            self._view_params[key] = params
        self._views[row - 1] = params
        self._counts[row - 1][_VIEW] += 1

    def listen(self, refs: frozenset[PlayerRef]) -> None:
        """See only for these players (the others' see messages would go unread)."""
        self._observers = tuple(row for row, ref in enumerate(self.players, 1) if ref in refs)

    def _take_heard(self, i: int) -> tuple[Heard, ...]:
        """What player `i` heard since its last percept (handed over once)."""
        heard = tuple(self._heard[i])
        self._heard[i].clear()
        return heard

    def _see_state(self, i: int, cycle: int) -> Percept:
        """Player `i`'s percept of its see of this cycle, through its own view and neck."""
        m = self.model
        return percept_from_state(
            i + 1,
            Bodies(m.x, m.y, m.vx, m.vy, m.heading, neck=m.neck),
            self.players,
            cycle,
            self._views[i],
            self._see_rng,
            heard=self._take_heard(i),
            landmarks=self._landmarks,
        )

    def _see_text(self, i: int, cycle: int) -> Percept:
        """Player `i`'s percept from the text of its see of this cycle (the trace route)."""
        m = self.model
        heard = self._take_heard(i)
        view = self._views[i]
        info = observe(
            i + 1,
            Bodies(m.x, m.y, m.vx, m.vy, m.heading, neck=m.neck),
            self.players,
            cycle,
            view,
            self._see_rng,
            landmarks="all",
        )
        ref = self.players[i]
        text = render_see(info, view.protocol_version)
        self._log(cycle, "see", text, ref)
        return percept_from_see(
            parse_see(text), ref, cycle, cycle, heard, cycle_s=m.dt_s, neck_rad=m.neck[i + 1]
        )

    def _hear(self, says: list[tuple[int, str]], referee: list[str], cycle: int) -> None:
        m = self.model
        delivered = deliver_says(says, m.x, m.y, m.heading, self.players, cycle, self.sensing)
        for message in referee:
            self._log(cycle, "referee", message)
            for row in range(1, len(self.players) + 1):
                delivered.setdefault(row, []).append(referee_hear(cycle, message))
        for row, infos in delivered.items():
            ref = self.players[row - 1]
            for info in infos:
                self._deliver(row, ref, info, cycle)

    def _deliver(self, row: int, ref: PlayerRef, info: HearInfo, cycle: int) -> None:
        if self.trace:
            self._log(cycle, "hear", render_hear(info, self.sensing.protocol_version), ref)
        heard = heard_from_hear(info, ref)
        if heard is not None:
            self._heard[row - 1].append(heard)

    def submit(self, ref: PlayerRef, actions: tuple[Action, ...]) -> None:
        """Queue a decision: says, neck turns and view changes now, body actions one per cycle.

        The body actions start with the next cycle; a neck turn goes with that cycle's step
        (the first of a cycle wins, §2.2), a view change applies at once (§3.1).
        """
        row = self._rows[ref]
        body = []
        for action in actions:
            if isinstance(action, Say):
                self.model.say(row, action.text)
            elif isinstance(action, TurnNeck):
                if self.model.turn_neck(row, action.angle_rad):
                    self._counts[row - 1][_NECK] += 1
            elif isinstance(action, ChangeView):
                self._change_view(row, action)
            else:
                body.append(action)
            if self.keep_events:
                self._log(self.tick, "command", render_command(action), ref)
        plan = self._plans[row - 1]
        plan.clear()
        plan.extend(body)

    def drain_events(self) -> list[ArenaEvent]:
        """Commands, messages and referee calls since the last call, oldest first."""
        events, self._events = self._events, []
        return events

    def command_tally(self) -> dict[PlayerRef, CommandTally]:
        """Every player's commands as the server counted them, and the last cycle's kicks.

        Counts are of commands carried out (module docstring, "Counts"); `kicked` marks a kick
        in the cycle just stepped that reached the ball, `kick_missed` one that did not.
        """
        tick, took = self.tick, self.model.kicked_at
        return {
            ref: CommandTally(
                tuple(self._counts[i]),
                kicked=took[i + 1] == tick,
                kick_missed=self._kick_tick[i] == tick and took[i + 1] != tick,
            )
            for i, ref in enumerate(self.players)
        }

    def _log(
        self, tick: int, channel: EventChannel, text: str, ref: PlayerRef | None = None
    ) -> None:
        if self.keep_events:
            self._events.append(ArenaEvent(tick, channel, text, ref))


_COUNTER = {
    Kick: COMMAND_COUNTERS.index("kick"),
    Dash: COMMAND_COUNTERS.index("dash"),
    Turn: COMMAND_COUNTERS.index("turn"),
    Say: COMMAND_COUNTERS.index("say"),
}
_KICK = _COUNTER[Kick]
_SAY = _COUNTER[Say]
_NECK = COMMAND_COUNTERS.index("turn_neck")
_VIEW = COMMAND_COUNTERS.index("change_view")

SCHEDULE_CYCLES = 6000
"""Cycles (10 simulated minutes) whose see timing is computed once per preset."""


@lru_cache(maxsize=16)
def see_schedule(params: SensingParams) -> tuple[bool, ...]:
    """For each cycle, whether a see is sent in it (`SeeTimer`, phase 0), computed once."""
    timer = SeeTimer(params)
    return tuple(timer.due(cycle) for cycle in range(SCHEDULE_CYCLES))
