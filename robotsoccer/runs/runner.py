"""One trial, start to finish: coach places, field steps, minds act on percepts, coach labels.

A trial is a pure function of its :class:`TrialSpec` and index: the trial's seed sequence is
derived from the experiment seed and the index alone (DESIGN.md §4), so results do not depend on
how many workers ran or in which order.
"""

from __future__ import annotations

import csv
import io
import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Protocol, runtime_checkable

from field_models.arena import Arena, ArenaEvent
from field_models.commands import render_command
from field_models.protocol import Action, Mind, Percept, PlayerRef
from field_models.registry import make_arena
from field_models.seeding import TrialRngs
from robotsoccer.drills import Drill, Verdict
from robotsoccer.replay.frames import GameFrame

# TrialSpec and its resolution live in robotsoccer.runs.spec; re-exported here, where every
# caller has always found them.
from robotsoccer.runs.spec import DrillOption as DrillOption
from robotsoccer.runs.spec import ResolvedSpec as ResolvedSpec
from robotsoccer.runs.spec import TrialSpec as TrialSpec
from robotsoccer.runs.spec import field_options as field_options
from robotsoccer.runs.spec import resolve as resolve

Observer = Callable[[Arena, list[Percept]], None]
"""Called after every tick with the arena and the percepts of that tick (recordings, traces)."""

DecisionLog = Callable[[Percept, tuple[Action, ...]], None]
"""Called with every percept a mind acted on and the actions it chose."""


def csv_record(fields: Sequence[str]) -> str:
    r"""One CSV record of `fields`, with its ``\n`` line end, quoted by the ``csv`` module.

    A field that holds a comma, a quote or a line end is quoted, so it stays one field and can
    never swallow the next row; a row without such a field reads as it always did. Python 3.11's
    writer does not quote a lone ``\r`` when lines end in ``\n``, though its reader ends a
    record there, so a row with one has every field quoted.
    """
    text = io.StringIO()
    if any("\r" in field for field in fields):
        csv.writer(text, lineterminator="\n", quoting=csv.QUOTE_ALL).writerow(fields)
    else:
        csv.writer(text, lineterminator="\n", quoting=csv.QUOTE_MINIMAL).writerow(fields)
    return text.getvalue()


@dataclass(frozen=True, slots=True)
class TrialResult:
    """The outcome of one trial.

    Attributes:
        index: Trial index (its seed is the experiment seed and this index).
        label: The coach's label.
        reason: Why, in words.
        ticks: Ticks the trial lasted.
        time_s: Simulated seconds it lasted.
        data: What the drill recorded for learning (e.g. the example BD, BA, previous BD, TA).
        measures: What the coach measured, by name (e.g. the defender's travel), for reports.
    """

    index: int
    label: str
    reason: str
    ticks: int
    time_s: float
    data: tuple[float, ...] = ()
    measures: tuple[tuple[str, float], ...] = ()

    CSV_COLUMNS = ("index", "label", "ticks", "time_s", "data", "measures", "reason")
    """The results table's columns (:mod:`robotsoccer.runs.table`)."""
    CSV_HEADER = ",".join(CSV_COLUMNS)
    """The table's header line."""

    def csv_fields(self) -> list[str]:
        """This result as the table's fields: floats exactly (repr), the reason as it is."""
        data = " ".join(repr(v) for v in self.data)
        measures = " ".join(f"{name}={value!r}" for name, value in self.measures)
        return [str(self.index), self.label, str(self.ticks), repr(self.time_s), data, measures,
                self.reason]  # fmt: skip

    @classmethod
    def from_csv_fields(cls, fields: Sequence[str]) -> TrialResult:
        """Parse the fields :meth:`csv_fields` made.

        Raises:
            ValueError: Not the table's 7 fields, or one of them does not parse.
        """
        if len(fields) != len(cls.CSV_COLUMNS):
            raise ValueError(f"{len(fields)} fields, not {len(cls.CSV_COLUMNS)}")
        index, label, ticks, time_s, data, measures, reason = fields
        if not (index.isascii() and index.isdigit()):
            raise ValueError(f"index {index!r} is not a whole number >= 0")
        values = tuple(float(v) for v in data.split())
        named = tuple(_measure(item) for item in measures.split())
        return cls(int(index), label, reason, int(ticks), float(time_s), values, named)

    def csv_row(self) -> str:
        """This result as one CSV record (:func:`csv_record`), without its line end."""
        return csv_record(self.csv_fields())[: -len("\n")]

    @classmethod
    def from_csv_row(cls, row: str) -> TrialResult:
        """Parse one record written by :meth:`csv_row`.

        Raises:
            ValueError: The text is not exactly one complete result record.
        """
        try:
            records = list(csv.reader(io.StringIO(row, newline=""), strict=True))
        except csv.Error as exc:
            raise ValueError(str(exc)) from None
        if len(records) != 1:
            raise ValueError(f"{len(records)} records, not 1")
        return cls.from_csv_fields(records[0])

    def measure(self, name: str) -> float:
        """The measure called `name`, or nan when the trial did not record it."""
        return dict(self.measures).get(name, math.nan)


def _measure(item: str) -> tuple[str, float]:
    name, sep, value = item.partition("=")
    if not sep or not name:
        raise ValueError(f"not a name=value measure: {item!r}")
    return name, float(value)


def play(
    arena: Arena,
    drill: Drill,
    minds: dict[PlayerRef, Mind],
    observer: Observer | None = None,
    decisions: DecisionLog | None = None,
) -> Verdict:
    """Step `arena` until `drill` gives a verdict or its time runs out."""
    verdict = TrialLoop(arena, drill, minds, observer, decisions).run()
    assert verdict is not None
    return verdict


class TrialLoop:
    """One trial's loop: step the arena, let each mind act on its percept, ask the coach.

    :func:`play` runs it to the end. :meth:`run` can also stop just before a percept, so an
    environment (:mod:`robotsoccer.envs`) can take a decision from outside and then go on.
    """

    def __init__(
        self,
        arena: Arena,
        drill: Drill,
        minds: dict[PlayerRef, Mind],
        observer: Observer | None = None,
        decisions: DecisionLog | None = None,
    ) -> None:
        self.arena, self.drill = arena, drill
        self.observer, self.decisions = observer, decisions
        self.max_ticks = round(drill.max_time_s / arena.facts.dt_s)
        self.thinking = dict(minds)
        arena.listen(frozenset(self.thinking))
        self.verdict: Verdict | None = None
        self._percepts: list[Percept] = []
        self._next = 0  # the next percept of this tick to hand to its mind
        self._tick_open = False

    def pending(self) -> list[Percept]:
        """The open tick's percepts not yet handed to their minds; empty between ticks.

        After a pause the percept paused on comes first.
        """
        return self._percepts[self._next :] if self._tick_open else []

    def run(self, pause: Callable[[Percept], bool] | None = None) -> Verdict | None:
        """Run to the verdict; with `pause`, return None before the first percept it accepts.

        That percept is handed to its mind by the next call.
        """
        arena, drill, thinking = self.arena, self.drill, self.thinking
        while self.verdict is None:
            if not self._tick_open:
                if arena.tick >= self.max_ticks:
                    self.verdict = drill.timeout(arena)
                    break
                self._percepts, self._next, self._tick_open = arena.step(), 0, True
            percepts = self._percepts
            while self._next < len(percepts):
                percept = percepts[self._next]
                if pause is not None and pause(percept):
                    return None
                self._next += 1
                mind = thinking.get(percept.player)
                if mind is None:
                    continue
                actions = mind.act(percept)
                if self.decisions is not None:
                    self.decisions(percept, actions)
                arena.submit(percept.player, actions)
                if getattr(mind, "done", False):
                    del thinking[percept.player]
                    arena.listen(frozenset(thinking))
            self._tick_open = False
            if self.observer is not None:
                self.observer(arena, percepts)
            self.verdict = drill.judge(arena)
        return self.verdict


def build_trial(
    spec: TrialSpec, index: int, *, keep_events: bool = False, trace: bool = False
) -> tuple[TrialRngs, Drill, Arena]:
    """The generators, drill and arena of trial `index` of `spec`, before the coach places.

    The one place a trial is put together, so that a run, a recording and a trace of the same
    spec and index are the same trial.
    """
    resolved = resolve(spec)
    rngs = TrialRngs.for_trial(spec.seed, index)
    arena = make_arena(
        spec.field_model,
        spec.preset,
        resolved.players,
        rngs,
        resolved.options,
        keep_events=keep_events,
        trace=trace,
    )
    return rngs, resolved.new_drill(), arena


def check_spec(spec: TrialSpec) -> None:
    """Set trial 0 up front, so a bad preset, option or model fails here in one line.

    Commands check their spec before they touch a run folder or start workers.
    """
    rngs, drill, arena = build_trial(spec, 0)
    drill.setup(arena, rngs)
    drill.minds(arena, rngs)


def run_trial(spec: TrialSpec, index: int) -> TrialResult:
    """Run trial `index` of `spec` and return its result."""
    recording = spec.records(index)
    rngs, drill, arena = build_trial(spec, index, keep_events=recording)
    drill.setup(arena, rngs)
    minds = drill.minds(arena, rngs)
    if recording and isinstance(drill, MatchLike):
        verdict = _play_match_recorded(arena, drill, drill, minds, spec, index)
    elif recording:
        verdict = _play_recorded(arena, drill, minds, spec, index)
    else:
        verdict = play(arena, drill, minds)
    return TrialResult(
        index,
        verdict.label,
        verdict.reason,
        arena.tick,
        arena.tick * arena.facts.dt_s,
        drill.data(),
        tuple(drill.measures().items()),
    )


def describe_decision(actions: tuple[Action, ...]) -> str:
    """A decision as the commands a client sends (``(turn -30) (dash 100)``), or "nothing"."""
    return " ".join(render_command(a) for a in actions) or "nothing"


def _play_recorded(
    arena: Arena, drill: Drill, minds: dict[PlayerRef, Mind], spec: TrialSpec, index: int
) -> Verdict:
    """Play trial `index` with a rerun recording of it, named with its outcome.

    The file is written under a temporary name (``trial_<index>.rrd.part``) and renamed to
    :func:`~robotsoccer.replay.recording.recording_name` (``trial_<index>_<LABEL>.rrd``) once
    the verdict is known and the file is closed; an interrupted trial leaves only the part file.
    """
    from robotsoccer.replay.field_recorder import Scene
    from robotsoccer.replay.recording import TrialRecorder, recording_name  # rerun loads late

    assert spec.record_dir is not None
    facts = arena.facts
    folder = Path(spec.record_dir)
    partial = folder / f"trial_{index:04d}.rrd.part"
    folder.mkdir(parents=True, exist_ok=True)
    every = max(1, round(1.0 / 60.0 / facts.dt_s))  # draw at ≤ 60 Hz: enough to watch
    title = f"{spec.drill} drill on {spec.field_model} ({spec.preset_name}), seed {spec.seed}"
    recorder = TrialRecorder(
        partial,
        Scene.of(facts, arena.players, f"{title}, trial {index}"),
        recording_id=f"{spec.drill}-{spec.field_model}-seed{spec.seed}-trial{index}",
        every_ticks=every,
    )

    def observe(a: Arena, percepts: list[Percept]) -> None:
        if a.tick % every == 0:
            recorder.log_truth(a.truth())
        for percept in percepts:
            recorder.log_percept(percept, a.player_state(percept.player))
        recorder.log_events(a.drain_events())

    def decide(percept: Percept, actions: tuple[Action, ...]) -> None:
        event = ArenaEvent(percept.tick, "decision", describe_decision(actions), percept.player)
        recorder.log_decision(event, actions)  # routine ones go where the layout hides them

    with recorder:
        recorder.log_truth(arena.truth())
        verdict = play(arena, drill, minds, observe, decide)
        recorder.log_label(arena.tick, verdict.label, verdict.reason)
    partial.replace(folder / recording_name(index, verdict.label))
    return verdict


@runtime_checkable
class MatchLike(Protocol):
    """A drill that plays a match: its frames and referee calls make a match recording."""

    def game_frame(self, arena: Arena) -> GameFrame:
        """This tick as a match recording keeps it."""
        ...

    def drain_events(self) -> list[ArenaEvent]:
        """Referee calls and the coach's events since the last call."""
        ...

    def team_names(self) -> tuple[str, str]:
        """The teams' names."""
        ...

    def goalies(self) -> tuple[PlayerRef, ...]:
        """The goalkeepers (game logs flag them)."""
        ...


def _play_match_recorded(
    arena: Arena,
    drill: Drill,
    match: MatchLike,
    minds: dict[PlayerRef, Mind],
    spec: TrialSpec,
    index: int,
) -> Verdict:
    """Play match `index` with a rerun recording (and an ``.rcg`` game log on a server pitch).

    The game log (:mod:`robotsoccer.replay.rcg_write`) is written only on a field drawn in Soccer
    Server metres (``unit_m`` 1): the format's tools draw the server's pitch. It starts at
    cycle 1, as a server's does, and ends with ``time_over``. Both files are written under
    part names and renamed once the match is over (``match_<index>_<LABEL>.rrd`` / ``.rcg``).
    The left team's last player's percepts are drawn beside the truth.
    """
    from robotsoccer.replay.field_recorder import Scene
    from robotsoccer.replay.match_recording import MatchRecorder  # rerun loads late
    from robotsoccer.replay.rcg_write import RcgWriter, log_team_name

    assert spec.record_dir is not None
    facts = arena.facts
    folder = Path(spec.record_dir)
    folder.mkdir(parents=True, exist_ok=True)
    stem = f"match_{index:04d}"
    teams = match.team_names()
    selected = arena.players[len(arena.players) // 2 - 1]  # the left team's last: a forward
    every = max(1, round(1.0 / 30.0 / facts.dt_s))  # draw at <= 30 Hz: enough to watch
    title = (
        f"{teams[0]} v {teams[1]} on {spec.field_model} ({spec.preset_name}), "
        f"seed {spec.seed}, game {index}"
    )
    recorder = MatchRecorder(
        folder / f"{stem}.rrd.part",
        Scene.of(facts, arena.players, title),
        teams=teams,
        selected=selected,
        recording_id=f"match-{spec.field_model}-seed{spec.seed}-game{index}",
        every_ticks=every,
    )
    server_pitch = math.isclose(facts.unit_m, 1.0)
    rcg = folder / f"{stem}.rcg"
    writer = None
    if server_pitch:
        pitch = facts.pitch
        params: dict[str, float | int | str] = {
            "goal_width": pitch.goal_width_m,
            "ball_size": pitch.ball_radius_m,
            "player_size": pitch.player_radius_m,
            "ball_decay": facts.ball.decay_per_tick,
        }
        if facts.kick is not None:
            params["kickable_margin"] = facts.kick.reach_m - facts.touch_distance_m
        writer = RcgWriter(
            rcg,
            players=arena.players,
            teams=(log_team_name(teams[0]), log_team_name(teams[1])),
            dt_s=facts.dt_s,
            server_params=params,
            goalies=match.goalies(),
        )

    def observe(a: Arena, percepts: list[Percept]) -> None:
        frame = match.game_frame(a)
        recorder.log_frame(frame)
        if writer is not None:
            writer.write(frame)
        for percept in percepts:
            if percept.player == selected:
                recorder.log_percept(percept, a.player_state(selected))
        recorder.log_events(match.drain_events())

    def decide(percept: Percept, actions: tuple[Action, ...]) -> None:
        if percept.player == selected:
            text = describe_decision(actions)
            event = ArenaEvent(percept.tick, "decision", text, percept.player)
            recorder.log_decision(event, actions)  # routine ones go where the layout hides them

    with recorder:
        # The kick-off placement before the first cycle: the recording shows it, a server's
        # log starts at the first cycle stepped.
        recorder.log_frame(match.game_frame(arena))
        verdict = play(arena, drill, minds, observe, decide)
        recorder.log_events(match.drain_events())
        recorder.log_events([ArenaEvent(arena.tick, "referee", f"time_over: {verdict.reason}")])
    if writer is not None:
        writer.finish(match.game_frame(arena).score)  # a goal in the last cycle counts too
        rcg.replace(folder / f"{stem}_{verdict.label}.rcg")
    (folder / f"{stem}.rrd.part").replace(folder / f"{stem}_{verdict.label}.rrd")
    return verdict
