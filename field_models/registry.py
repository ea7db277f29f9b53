"""The registry of field models: build an arena, or read a field's facts, by model name.

The one place (with the CLI's choices) that knows which field models exist. Each model has an
entry module (``field_models.<model>.model``) with the same small interface,
:class:`FieldModelEntry`; the registry imports it only when the model is first used, so naming
the models costs nothing (the robot entry's arena loads pymunk).
"""

from __future__ import annotations

import importlib
from functools import lru_cache
from typing import Any, Protocol, cast

from field_models.arena import Arena, FieldFacts, FieldOptions
from field_models.batch_arena import BatchArena
from field_models.presets import PRESET_DIR
from field_models.protocol import PlayerRef
from field_models.seeding import StreamBatch, TrialRngs

_ENTRIES = {
    "robot_physics": "field_models.robot_physics.model",
    "soccer_server": "field_models.soccer_server.model",
    "rcssserver": "field_models.rcssserver.model",
}
FIELD_MODELS: tuple[str, ...] = tuple(_ENTRIES)
"""Registered field models, by name."""

DEFAULT_OPTIONS = FieldOptions()
"""Every preset value as it is."""

PAPER_FIELD = ("soccer_server", "soccer_server_1996")
"""The paper's own field (model, preset): the reference a drill carried to another field is
matched to."""


class FieldModelEntry(Protocol):
    """What a field model's entry module provides (module-level names)."""

    NAME: str
    """The model's registered name."""
    DEFAULT_PRESET: str
    """The preset used when none is named."""

    def load(self, preset: str, options: FieldOptions) -> Any:
        """The named (or file) preset with `options` applied (cached; frozen, hashable).

        Raises:
            field_models.presets.PresetError: A missing or wrong preset file.
            ValueError: An option the model cannot apply.
        """
        ...

    def facts(self, preset: Any) -> FieldFacts:
        """The facts of a loaded preset."""
        ...

    def build(
        self,
        preset: Any,
        facts: FieldFacts,
        players: tuple[PlayerRef, ...],
        rngs: TrialRngs,
        *,
        keep_events: bool,
        trace: bool,
    ) -> Arena:
        """A fresh arena of a loaded preset (and its facts) with these players."""
        ...

    def benchmarks(self, quick: bool = False) -> dict[str, Any]:
        """The model's own speed figures (nested dict of numbers; medians of repeats)."""
        ...


def entry(model: str) -> FieldModelEntry:
    """The entry module of `model`.

    Raises:
        ValueError: An unknown field model (the message lists the known ones).
    """
    loaded = _LOADED.get(model)
    if loaded is not None:
        return loaded
    try:
        module = _ENTRIES[model]
    except KeyError:
        raise ValueError(
            f"unknown field model {model!r} (known: {', '.join(FIELD_MODELS)})"
        ) from None
    loaded = _LOADED[model] = cast(FieldModelEntry, importlib.import_module(module))
    return loaded


_LOADED: dict[str, FieldModelEntry] = {}


def preload_modules() -> tuple[str, ...]:
    """Every field model's entry and arena modules: what a worker process imports up front."""
    entries = tuple(_ENTRIES.values())
    return entries + tuple(name.rsplit(".", 1)[0] + ".arena" for name in entries)


def default_preset(model: str) -> str:
    """The preset `model` uses when none is named."""
    return entry(model).DEFAULT_PRESET


def shipped_presets(model: str) -> tuple[str, ...]:
    """Names of the presets shipped for `model` (its folder under ``field_models/presets``)."""
    entry(model)
    return tuple(sorted(path.stem for path in (PRESET_DIR / model).glob("*.toml")))


def has_preset(model: str, name: str) -> bool:
    """Whether `model` ships a preset called `name`."""
    return name in shipped_presets(model)


@lru_cache(maxsize=64)
def field_facts(
    model: str, preset: str | None = None, options: FieldOptions = DEFAULT_OPTIONS
) -> FieldFacts:
    """The facts of `model` with `preset` (default: the model's) and `options` applied.

    Raises:
        ValueError: An unknown model or an option the model cannot apply.
        field_models.presets.PresetError: A missing or wrong preset.
    """
    module = entry(model)
    return module.facts(module.load(preset or module.DEFAULT_PRESET, options))


def make_arena(
    model: str,
    preset: str | None,
    players: tuple[PlayerRef, ...],
    rngs: TrialRngs,
    options: FieldOptions = DEFAULT_OPTIONS,
    *,
    keep_events: bool = False,
    trace: bool = False,
) -> Arena:
    """A fresh arena of `model` loaded with `preset` (default: the model's) and the players.

    `keep_events` keeps commands and messages for :meth:`Arena.drain_events` (recordings);
    `trace` also records every see and hear the clients get, as text.

    Raises:
        ValueError: An unknown model or an option the model cannot apply.
        field_models.presets.PresetError: A missing or wrong preset.
    """
    module = entry(model)
    name = preset or module.DEFAULT_PRESET
    loaded = module.load(name, options)
    facts = field_facts(model, name, options)  # cached by name: no hashing of whole presets
    return module.build(loaded, facts, players, rngs, keep_events=keep_events, trace=trace)


def batch_reason(
    model: str, preset: str | None, options: FieldOptions = DEFAULT_OPTIONS
) -> str | None:
    """Why `model` with `preset` and `options` has no batch arena (None: it has one).

    Raises:
        ValueError: An unknown model or an option the model cannot apply.
        field_models.presets.PresetError: A missing or wrong preset.
    """
    module = entry(model)
    reason = getattr(module, "batch_reason", None)
    if reason is None:
        return f"the {model} model has no batch form"
    found: str | None = reason(module.load(preset or module.DEFAULT_PRESET, options))
    return found


def conformance_limits(model: str, preset: str | None) -> dict[str, str]:
    """Promises of the conformance suite that `model` with `preset` cannot keep, with why.

    A model names them through an optional module function ``conformance_limits(preset)``
    (e.g. a real rcssserver takes no seed); keys are a check's name (skipped) or an aspect a
    check relaxes (``"identity"``: a far player may be seen without its number). Most models
    have none.
    """
    module = entry(model)
    limits = getattr(module, "conformance_limits", None)
    if limits is None:
        return {}
    found: dict[str, str] = limits(module.load(preset or module.DEFAULT_PRESET, DEFAULT_OPTIONS))
    return found


def make_batch_arena(
    model: str,
    preset: str | None,
    players: tuple[PlayerRef, ...],
    movement: StreamBatch,
    options: FieldOptions = DEFAULT_OPTIONS,
) -> BatchArena:
    """K trials of `model` stepped together, one per row of the trials' "movement" streams.

    Raises:
        ValueError: The model or preset has no batch form (:func:`batch_reason`).
    """
    why = batch_reason(model, preset, options)
    if why is not None:
        raise ValueError(why)
    module = entry(model)
    loaded = module.load(preset or module.DEFAULT_PRESET, options)
    built: BatchArena = cast(Any, module).build_batch(loaded, players, movement)  # optional
    return built


def paper_field_facts() -> FieldFacts:
    """The facts of :data:`PAPER_FIELD`, with its presets' values as they are."""
    return field_facts(*PAPER_FIELD)
