"""Domain randomisation's variants (issue 10): parameter ranges, drawn values, variant presets.

A :class:`Randomisation` names the reference preset and the :class:`ParameterRange` s drawn per
variant; :func:`draw_variants` draws them from the run's seed, and :func:`write_variants` writes
each variant as a preset file naming the reference preset as its ``base``. The method that uses
them is :func:`robotsoccer.experiments.gap_closing.domain_randomised_net`.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from pathlib import Path

import numpy as np

PresetValue = float | int


@dataclass(frozen=True)
class ParameterRange:
    """One preset parameter drawn per variant, uniformly (or log-uniformly) in [low, high].

    Attributes:
        key: Dotted preset key, ``"<table>.<name>"`` (e.g. ``"dynamics.player_decay"``).
        low: Smallest value, in the key's unit.
        high: Largest value.
        log: Draw uniformly in log space (for rates spanning a factor of several).
        step: Round to a multiple of this (an integer step gives an integer); None: no rounding.
        why: What on the target the range is meant to cover, for the report.
    """

    key: str
    low: float
    high: float
    log: bool = False
    step: float | None = None
    why: str = ""

    def __post_init__(self) -> None:
        table, _, name = self.key.partition(".")
        if not table or not name or "." in name:
            raise ValueError(f"range key {self.key!r} is not '<table>.<name>'")
        if not (math.isfinite(self.low) and math.isfinite(self.high) and self.low <= self.high):
            raise ValueError(
                f"range {self.key}: need finite low <= high, got {self.low}, {self.high}"
            )
        if self.log and self.low <= 0.0:
            raise ValueError(f"range {self.key}: a log range needs low > 0, got {self.low}")
        if self.step is not None and not self.step > 0.0:
            raise ValueError(f"range {self.key}: step must be > 0, got {self.step}")

    def draw(self, rng: np.random.Generator) -> PresetValue:
        """One value from `rng`."""
        if self.log:
            value = math.exp(rng.uniform(math.log(self.low), math.log(self.high)))
        else:
            value = rng.uniform(self.low, self.high)
        if self.step is None:
            return float(value)
        rounded = self.step * round(value / self.step)
        return int(rounded) if float(self.step).is_integer() else float(rounded)


@dataclass(frozen=True)
class Randomisation:
    """Domain randomisation of the reference field: its preset and the ranges drawn.

    Attributes:
        base_preset: The reference preset every variant starts from.
        ranges: The parameters drawn per variant.
        variants: Variant presets (each collects an equal share of the saves).
    """

    base_preset: str
    ranges: tuple[ParameterRange, ...]
    variants: int = 10

    def __post_init__(self) -> None:
        if self.variants < 1:
            raise ValueError(f"variants must be >= 1, got {self.variants}")
        keys = [r.key for r in self.ranges]
        if len(set(keys)) != len(keys):
            raise ValueError(f"a key is drawn twice: {keys}")


RANDOMISATION_STREAM = 0xD0A1
"""Names the generator of the variants' draws among those spawned from a run's seed."""


def draw_variants(randomisation: Randomisation, seed: int) -> list[dict[str, PresetValue]]:
    """Each variant's drawn values, by key; a function of `seed` only."""
    rng = np.random.default_rng(np.random.SeedSequence([seed, RANDOMISATION_STREAM]))
    return [
        {r.key: r.draw(rng) for r in randomisation.ranges} for _ in range(randomisation.variants)
    ]


def variant_text(base_preset: str, values: Mapping[str, PresetValue], note: str) -> str:
    """A preset file naming `base_preset` as its base and setting `values` (TOML)."""
    tables: dict[str, list[str]] = {}
    for key, value in values.items():
        table, name = key.split(".")
        tables.setdefault(table, []).append(f"{name} = {value!r}")
    lines = [f"# {note}", f'base = "{base_preset}"']
    for table, entries in tables.items():
        lines += ["", f"[{table}]", *entries]
    return "\n".join(lines) + "\n"


def write_variants(randomisation: Randomisation, folder: Path, seed: int) -> list[Path]:
    """Write the variant presets into `folder` (``variant_<k>.toml``); their paths."""
    folder.mkdir(parents=True, exist_ok=True)
    paths = []
    for k, values in enumerate(draw_variants(randomisation, seed)):
        note = f"domain randomisation variant {k} of {randomisation.base_preset} (seed {seed})"
        path = folder / f"variant_{k}.toml"
        path.write_text(variant_text(randomisation.base_preset, values, note))
        paths.append(path.resolve())
    return paths
