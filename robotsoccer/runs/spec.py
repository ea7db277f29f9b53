"""What a run is: a :class:`TrialSpec`, and everything that follows from it, resolved once.

A spec names a drill, a field model and preset, an experiment seed, field settings and drill
options. Several things follow from it that every trial needs: the field settings with the
drill's own added (:func:`field_options`), the field's facts under those settings, and the
players the drill puts on that field. :func:`resolve` works them out once per spec and process
(the result is cached and immutable), and the runner, the pool and the batched engine all take
the :class:`ResolvedSpec`; only the drill itself is made fresh for each trial, since a drill
holds the state of the trial it coaches.
"""

from __future__ import annotations

import dataclasses
import functools
from dataclasses import dataclass
from typing import Any

from field_models.arena import FieldFacts, FieldOptions
from field_models.protocol import PlayerRef
from field_models.registry import DEFAULT_OPTIONS, default_preset, field_facts
from robotsoccer.drills import Drill, make_drill

DrillOption = str | float | int | bool
"""A drill option's value (kept to plain types so a TrialSpec pickles and prints)."""


@dataclass(frozen=True, slots=True)
class TrialSpec:
    """Everything that defines the trials of one run, except the trial index.

    Attributes:
        drill: Registered drill name.
        field_model: Registered field model name (:data:`field_models.registry.FIELD_MODELS`).
        preset: Preset name or path for that field model; None: the model's default.
        seed: Experiment seed; trial i uses the seed sequence (seed, i).
        field: Settings changed on the field model (perfect perception, ball noise, sensor
            latency, ball-noise period); the drill may add its own where these leave None.
        drill_options: Keyword arguments for the drill, as (name, value) pairs.
        record_dir: Folder for rerun recordings, or None.
        record_trials: Record the trials whose index is below this.
    """

    drill: str
    field_model: str
    preset: str | None = None
    seed: int = 0
    field: FieldOptions = DEFAULT_OPTIONS
    drill_options: tuple[tuple[str, DrillOption], ...] = ()
    record_dir: str | None = None
    record_trials: int = 0

    def __post_init__(self) -> None:
        if self.preset is None:
            object.__setattr__(self, "preset", default_preset(self.field_model))

    @property
    def preset_name(self) -> str:
        """The preset (resolved: never None)."""
        assert self.preset is not None
        return self.preset

    def records(self, index: int) -> bool:
        """Whether trial `index` is recorded (a record folder, and among the first trials)."""
        return self.record_dir is not None and index < self.record_trials

    def with_options(self, **options: DrillOption) -> TrialSpec:
        """A copy with these drill options added (replacing any of the same name)."""
        merged = dict(self.drill_options) | options
        return dataclasses.replace(self, drill_options=tuple(sorted(merged.items())))

    def with_field(self, **settings: Any) -> TrialSpec:
        """A copy with these field settings changed (names of :class:`FieldOptions`)."""
        return dataclasses.replace(self, field=dataclasses.replace(self.field, **settings))


def field_options(spec: TrialSpec, drill: Drill) -> FieldOptions:
    """The spec's field settings, plus the drill's own where the spec leaves one unset."""
    facts = field_facts(spec.field_model, spec.preset, spec.field)
    wanted = drill.field_settings(facts)
    unset: dict[str, Any] = {k: v for k, v in wanted.items() if getattr(spec.field, k) is None}
    return dataclasses.replace(spec.field, **unset) if unset else spec.field


@dataclass(frozen=True)
class ResolvedSpec:
    """A spec with what follows from it worked out: settings, facts and players.

    Attributes:
        spec: The spec.
        options: The spec's field settings plus the drill's own where the spec left them unset.
        facts: The field's facts under `options`.
        players: The players the drill puts on this field.
    """

    spec: TrialSpec
    options: FieldOptions
    facts: FieldFacts
    players: tuple[PlayerRef, ...]

    def new_drill(self) -> Drill:
        """A fresh drill for one trial (a drill holds the state of the trial it coaches)."""
        return make_drill(self.spec.drill, dict(self.spec.drill_options))


@functools.lru_cache(maxsize=128)
def resolve(spec: TrialSpec) -> ResolvedSpec:
    """`spec` resolved (cached: once per spec and process).

    Raises:
        ValueError: An unknown drill or field model, a bad option or preset.
    """
    return resolve_with(spec, make_drill(spec.drill, dict(spec.drill_options)))


def resolve_with(spec: TrialSpec, drill: Drill) -> ResolvedSpec:
    """`spec` resolved with `drill` in place of the one its name and options make (not cached).

    For a drill the registry does not make (an environment's own, such as half-field offense):
    its field settings and players count as a registered drill's do, and the caller makes
    each trial's drill itself (:meth:`ResolvedSpec.new_drill` makes only registered ones).

    Raises:
        ValueError: An unknown field model or a bad preset.
    """
    options = field_options(spec, drill)
    facts = field_facts(spec.field_model, spec.preset, options)
    sized = getattr(drill, "players_for", None)  # a drill whose team size follows the field
    players = drill.players() if sized is None else sized(facts)
    return ResolvedSpec(spec, options, facts, tuple(players))
