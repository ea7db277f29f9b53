"""One trial, start to finish: coach places, field steps, minds act on percepts, coach labels.

A trial is a pure function of its :class:`TrialSpec` and index: the trial's seed sequence is
derived from the experiment seed and the index alone (DESIGN.md §4), so results do not depend on
how many workers ran or in which order.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

from field_models.arena import Arena, ArenaEvent
from field_models.protocol import Action, Dash, Kick, Mind, Percept, PlayerRef, Say, Turn
from field_models.registry import make_arena
from field_models.seeding import TrialRngs
from robotsoccer.drills import Drill, Verdict, make_drill

Observer = Callable[[Arena, list[Percept]], None]
"""Called after every tick with the arena and the percepts of that tick (recordings, traces)."""

DrillOption = str | float | int | bool
"""A drill option's value (kept to plain types so a TrialSpec pickles and prints)."""

DecisionLog = Callable[[Percept, tuple[Action, ...]], None]
"""Called with every percept a mind acted on and the actions it chose."""


@dataclass(frozen=True, slots=True)
class TrialSpec:
    """Everything that defines the trials of one run, except the trial index.

    Attributes:
        drill: Registered drill name.
        field_model: ``"robot_physics"`` or ``"soccer_server"``.
        preset: Preset name or path for that field model.
        seed: Experiment seed; trial i uses the seed sequence (seed, i).
        perfect_perception: Robots: camera without noise, misses or latency.
        record_dir: Folder for rerun recordings, or None.
        record_trials: Record the trials whose index is below this.
        drill_options: Keyword arguments for the drill, as (name, value) pairs.
        ball_noise: Override of the ball-motion noise (Soccer Server ``ball_rand``; robots
            ``ball.motion_noise``), or None for the preset's.
        camera_latency_s: Robots: override of the camera latency [s], or None.
        ball_noise_period_s: Robots: override of how often ball noise acts [s], or None
            (then the drill's setting, else the preset's).
    """

    drill: str = "shootout"
    field_model: str = "robot_physics"
    preset: str = "small_size_1997"
    seed: int = 0
    perfect_perception: bool = False
    record_dir: str | None = None
    record_trials: int = 0
    drill_options: tuple[tuple[str, DrillOption], ...] = ()
    ball_noise: float | None = None
    camera_latency_s: float | None = None
    ball_noise_period_s: float | None = None

    def with_options(self, **options: DrillOption) -> TrialSpec:
        """A copy with these drill options added (replacing any of the same name)."""
        merged = dict(self.drill_options) | options
        return dataclasses.replace(self, drill_options=tuple(sorted(merged.items())))


@dataclass(frozen=True, slots=True)
class TrialResult:
    """The outcome of one trial.

    Attributes:
        index: Trial index (its seed is the experiment seed and this index).
        label: The coach's label.
        reason: Why, in words.
        ticks: Ticks the trial lasted.
        time_s: Simulated seconds it lasted.
        data: What the drill recorded (e.g. the interception example BD, BA, previous BD, TA).
    """

    index: int
    label: str
    reason: str
    ticks: int
    time_s: float
    data: tuple[float, ...] = ()

    CSV_HEADER = "index,label,ticks,time_s,data,reason"

    def csv_row(self) -> str:
        """This result as a CSV line: floats exactly (repr); the reason last, free text."""
        data = " ".join(repr(v) for v in self.data)
        return f"{self.index},{self.label},{self.ticks},{self.time_s!r},{data},{self.reason}"

    @classmethod
    def from_csv_row(cls, row: str) -> TrialResult:
        """Parse a line written by :meth:`csv_row`."""
        index, label, ticks, time_s, data, reason = row.rstrip("\n").split(",", 5)
        values = tuple(float(v) for v in data.split())
        return cls(int(index), label, reason, int(ticks), float(time_s), values)


def play(
    arena: Arena,
    drill: Drill,
    minds: dict[PlayerRef, Mind],
    observer: Observer | None = None,
    decisions: DecisionLog | None = None,
) -> Verdict:
    """Step `arena` until `drill` gives a verdict or its time runs out."""
    max_ticks = round(drill.max_time_s / arena.dt_s)
    thinking = dict(minds)
    arena.listen(frozenset(thinking))
    while arena.tick < max_ticks:
        percepts = arena.step()
        for percept in percepts:
            mind = thinking.get(percept.player)
            if mind is None:
                continue
            actions = mind.act(percept)
            if decisions is not None:
                decisions(percept, actions)
            arena.submit(percept.player, actions)
            if getattr(mind, "done", False):
                del thinking[percept.player]
                arena.listen(frozenset(thinking))
        if observer is not None:
            observer(arena, percepts)
        verdict = drill.judge(arena)
        if verdict is not None:
            return verdict
    return drill.timeout(arena)


def build_trial(
    spec: TrialSpec, index: int, *, keep_events: bool = False, trace: bool = False
) -> tuple[TrialRngs, Drill, Arena]:
    """The generators, drill and arena of trial `index` of `spec`, before the coach places.

    The one place a trial is put together, so that a run, a recording and a trace of the same
    spec and index are the same trial.
    """
    rngs = TrialRngs.for_trial(spec.seed, index)
    drill = make_drill(spec.drill, dict(spec.drill_options))
    settings = drill.arena_settings(spec.field_model, spec.preset)
    noise_period = spec.ball_noise_period_s or settings.get("ball_noise_period_s")
    arena = make_arena(
        spec.field_model,
        spec.preset,
        drill.players(),
        rngs,
        perfect=spec.perfect_perception,
        keep_events=keep_events,
        trace=trace,
        ball_noise=spec.ball_noise,
        camera_latency_s=spec.camera_latency_s,
        ball_noise_period_s=noise_period,
    )
    return rngs, drill, arena


def run_trial(spec: TrialSpec, index: int) -> TrialResult:
    """Run trial `index` of `spec` and return its result."""
    recording = spec.record_dir is not None and index < spec.record_trials
    rngs, drill, arena = build_trial(spec, index, keep_events=recording)
    drill.setup(arena, rngs)
    minds = drill.minds(arena, rngs)
    if recording:
        verdict = _play_recorded(arena, drill, minds, spec, index)
    else:
        verdict = play(arena, drill, minds)
    return TrialResult(
        index, verdict.label, verdict.reason, arena.tick, arena.tick * arena.dt_s, drill.data()
    )


def _play_recorded(
    arena: Arena, drill: Drill, minds: dict[PlayerRef, Mind], spec: TrialSpec, index: int
) -> Verdict:
    from robotsoccer.replay.recording import TrialRecorder  # rerun loads only when recording

    assert spec.record_dir is not None
    path = Path(spec.record_dir) / f"trial_{index:04d}.rrd"
    path.parent.mkdir(parents=True, exist_ok=True)
    every = max(1, round(1.0 / 60.0 / arena.dt_s))  # draw at ≤ 60 Hz: enough to watch
    recorder = TrialRecorder(
        path,
        pitch=arena.pitch,
        players=arena.players,
        dt_s=arena.dt_s,
        recording_id=f"{spec.drill}-{spec.field_model}-seed{spec.seed}-trial{index}",
        player_shape="square" if arena.model_name == "robot_physics" else "circle",
        every_ticks=every,
    )

    def observe(a: Arena, percepts: list[Percept]) -> None:
        if a.tick % every == 0:
            recorder.log_truth(a.truth())
        for percept in percepts:
            recorder.log_percept(percept, a.player_state(percept.player))
        recorder.log_events(a.drain_events())

    def decide(percept: Percept, actions: tuple[Action, ...]) -> None:
        text = ", ".join(map(describe_action, actions)) or "nothing"
        event = ArenaEvent(percept.tick, "decision", f"{percept.player}: {text}", percept.player)
        recorder.log_events([event])

    with recorder:
        recorder.log_truth(arena.truth())
        verdict = play(arena, drill, minds, observe, decide)
        recorder.log_label(arena.tick, verdict.label, verdict.reason)
    return verdict


def describe_action(action: Action) -> str:
    """An action in the Soccer Server's words, degrees for angles (for logs and traces)."""
    if isinstance(action, Turn):
        return f"turn {math.degrees(action.angle_rad):.1f}"
    if isinstance(action, Dash):
        return f"dash {action.power:.0f}"
    if isinstance(action, Kick):
        return f"kick {action.power:.0f} {math.degrees(action.direction_rad):.1f}"
    if isinstance(action, Say):
        return f"say {action.text}"
    raise TypeError(f"not an action: {action!r}")
