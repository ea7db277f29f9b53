"""One seed per trial, many named generators (DESIGN.md §4).

An experiment seed spawns one :class:`numpy.random.SeedSequence` per trial. Each trial splits its
sequence into independent, *named* generators, so adding a new consumer never shifts the numbers
an existing one draws. Nothing in the project uses module-level `random` or `np.random.*`.

The names are declared in :data:`STREAMS`; asking for any other name is an error, so a misspelt
stream fails loudly instead of silently drawing from a fresh, unrelated generator.
"""

from __future__ import annotations

import zlib

import numpy as np

STREAMS = ("placement", "movement", "camera", "link", "sensing", "policy")
"""The named random streams every trial owns: the coach's placement, the field's movement noise,
the robots' camera and link, the Soccer Server's sensing, the minds' own choices."""


def trial_sequence(experiment_seed: int, trial_index: int) -> np.random.SeedSequence:
    """The seed sequence of trial `trial_index` of an experiment: independent of worker count."""
    return np.random.SeedSequence(entropy=experiment_seed, spawn_key=(trial_index,))


def named_generator(seq: np.random.SeedSequence, name: str) -> np.random.Generator:
    """A generator for stream `name` of a trial; the same name always gives the same stream.

    The stream is keyed by a CRC of its name (not Python's salted `hash`), so it is stable
    across processes and runs.
    """
    key = (*seq.spawn_key, zlib.crc32(name.encode()))
    return np.random.default_rng(np.random.SeedSequence(entropy=seq.entropy, spawn_key=key))


class TrialRngs:
    """The named generators of one trial, created on first use."""

    def __init__(self, seq: np.random.SeedSequence) -> None:
        self._seq = seq
        self._cache: dict[str, np.random.Generator] = {}

    @classmethod
    def for_trial(cls, experiment_seed: int, trial_index: int) -> TrialRngs:
        """The generators of trial `trial_index` of the experiment seeded `experiment_seed`."""
        return cls(trial_sequence(experiment_seed, trial_index))

    def __getitem__(self, name: str) -> np.random.Generator:
        """The generator of stream `name` (one of :data:`STREAMS`).

        Raises:
            KeyError: `name` is not a declared stream.
        """
        generator = self._cache.get(name)
        if generator is None:
            if name not in STREAMS:
                raise KeyError(f"unknown random stream {name!r} (declared: {', '.join(STREAMS)})")
            generator = self._cache[name] = named_generator(self._seq, name)
        return generator
