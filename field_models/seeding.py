"""One seed per trial, many named streams of random numbers (DESIGN.md §4).

Every trial of an experiment owns independent, *named* streams (:data:`STREAMS`), so adding a
new consumer never shifts the numbers an existing one draws. Nothing in the project uses
module-level `random` or `np.random.*`.

**Counter-based streams.** A stream is a 64-bit key and a position; its draw number ``n`` is
``mix(key + (n + 1)·γ)``, the SplitMix64 generator (Steele, Lea & Flood, OOPSLA 2014; the one
behind Java's ``SplittableRandom``), whose output passes BigCrush. Because draw ``n`` is a
function of the key and ``n`` alone, the streams of thousands of trials can be drawn as one
array operation (:class:`StreamBatch`) and give exactly the numbers each trial's own
:class:`Stream` gives: the batched Soccer Server drill (:mod:`robotsoccer.drills.intercept_batch`)
relies on it. The key hashes (experiment seed, trial index, CRC of the stream name) with the
same mixer, so it is stable across processes, machines and runs; two streams could only
overlap if their keys differed by a multiple of γ below 2^64 / (draws per stream), which for
random 64-bit keys and streams far shorter than 2^40 draws is negligible.

Setting up a trial's streams costs a few microseconds (a numpy ``SeedSequence`` and
``Generator`` per stream cost about 45 µs each), which matters when a drill trial lasts 200 µs.

A misspelt stream name is an error, not a fresh unrelated stream.
"""

from __future__ import annotations

import math
import zlib
from collections.abc import Sequence
from typing import TypeAlias, overload

import numpy as np
import numpy.typing as npt

STREAMS = ("placement", "movement", "camera", "link", "sensing", "policy")
"""The named random streams every trial owns: the coach's placement, the field's movement noise,
the robots' camera and link, the Soccer Server's sensing, the minds' own choices."""

_GAMMA = np.uint64(0x9E3779B97F4A7C15)
_M1 = np.uint64(0xBF58476D1CE4E5B9)
_M2 = np.uint64(0x94D049BB133111EB)
_S30, _S27, _S31, _S11 = np.uint64(30), np.uint64(27), np.uint64(31), np.uint64(11)
_TO_UNIT = 1.0 / 9007199254740992.0  # 2**-53: the top 53 bits as a double in [0, 1)
_MASK64 = (1 << 64) - 1
STREAM_BLOCK = 64
STREAM_BLOCK_MAX = 4096
"""Draws a :class:`Stream` computes at once: its first block, and the most a block grows to
(any value gives the same numbers)."""


def _mix(z: npt.NDArray[np.uint64]) -> npt.NDArray[np.uint64]:
    """SplitMix64's output function (Stafford's variant 13), wrapping uint64 arithmetic."""
    z = (z ^ (z >> _S30)) * _M1
    z = (z ^ (z >> _S27)) * _M2
    return z ^ (z >> _S31)


def _mix_in_place(z: npt.NDArray[np.uint64]) -> None:
    """:func:`_mix` overwriting `z` (one temporary instead of six)."""
    tmp = z >> _S30
    z ^= tmp
    z *= _M1
    np.right_shift(z, _S27, out=tmp)
    z ^= tmp
    z *= _M2
    np.right_shift(z, _S31, out=tmp)
    z ^= tmp


def _mix_int(value: int) -> int:
    """:func:`_mix` of one Python int (mod 2**64), in plain integers (no array overhead)."""
    z = value & _MASK64
    z = ((z ^ (z >> 30)) * 0xBF58476D1CE4E5B9) & _MASK64
    z = ((z ^ (z >> 27)) * 0x94D049BB133111EB) & _MASK64
    return z ^ (z >> 31)


def _combine(h: int, value: int) -> int:
    """Hash `value` into the running key `h`."""
    return _mix_int(h ^ _mix_int(value + 0x9E3779B97F4A7C15))


def stream_key(experiment_seed: int, trial_index: int, name: str) -> int:
    """The 64-bit key of stream `name` of trial `trial_index` of an experiment.

    Raises:
        KeyError: `name` is not a declared stream.
    """
    if name not in STREAMS:
        raise KeyError(f"unknown random stream {name!r} (declared: {', '.join(STREAMS)})")
    h = _combine(_mix_int(0x5EED), experiment_seed)
    h = _combine(h, trial_index)
    return _combine(h, zlib.crc32(name.encode()))


def stream_keys(
    experiment_seed: int | npt.NDArray[np.int64],
    trial_indices: Sequence[int] | npt.NDArray[np.int64],
    name: str,
) -> npt.NDArray[np.uint64]:
    """The keys of stream `name` of many trials (as :func:`stream_key`, one array pass).

    `experiment_seed` is one seed for all, or one per trial.
    """
    if name not in STREAMS:
        raise KeyError(f"unknown random stream {name!r} (declared: {', '.join(STREAMS)})")
    trials = np.asarray(trial_indices, dtype=np.int64).astype(np.uint64)
    seeds = np.asarray(experiment_seed, dtype=np.int64).astype(np.uint64)
    with np.errstate(over="ignore"):
        seed_h = _mix(np.uint64(_mix_int(0x5EED)) ^ _mix(seeds + _GAMMA))
        h = _mix(seed_h ^ _mix(trials + _GAMMA))
        tag = np.uint64(_mix_int(zlib.crc32(name.encode()) + 0x9E3779B97F4A7C15))
        return _mix(h ^ tag)


def uniforms(
    keys: npt.NDArray[np.uint64], positions: npt.NDArray[np.int64] | int, count: int
) -> npt.NDArray[np.float64]:
    """Draws ``positions .. positions + count - 1`` of the streams `keys`: shape (K, count).

    Doubles in [0, 1) with 53 random bits, the draws a :class:`Stream` gives.
    """
    pos = np.asarray(positions, dtype=np.int64).reshape(-1, 1)
    return draws_at(keys, pos + np.arange(count, dtype=np.int64))


def draws_at(
    keys: npt.NDArray[np.uint64], positions: npt.NDArray[np.int64]
) -> npt.NDArray[np.float64]:
    """Draw number ``positions[k, j]`` (0-based) of stream ``keys[k]``, shape of `positions`.

    The one place draws are computed: ``mix(key + (n + 1)·γ)``, top 53 bits as a double.
    """
    z = positions.astype(np.uint64)  # the draw numbers, then mixed in place (no temporaries)
    with np.errstate(over="ignore"):
        z += np.uint64(1)
        z *= _GAMMA
        z += keys.reshape(-1, 1)
        _mix_in_place(z)
        z >>= _S11
    out = z.astype(np.float64)
    out *= _TO_UNIT
    return out


class Stream:
    """One named random stream of one trial: a key and a position (module docstring).

    It has the part of numpy's ``Generator`` interface the project uses: :meth:`random`,
    :meth:`uniform`, :meth:`standard_normal`, :meth:`normal`, :meth:`integers`.
    """

    __slots__ = ("_buffer", "_key", "_list", "_start", "key", "position")

    def __init__(self, key: int) -> None:
        self.key = key & _MASK64
        self._key = np.array([self.key], dtype=np.uint64)
        self.position = 0
        self._start = 0  # the buffer holds draws _start .. _start + len - 1
        self._buffer = np.empty(0)
        self._list: list[float] = []

    def _cover(self, count: int) -> int:
        """Make the buffer hold the next `count` draws; their index in it.

        Draws are computed a block ahead (a draw depends only on its position, so the numbers
        are the same): small draws then cost a slice, not a dozen numpy calls.
        """
        i = self.position - self._start
        if i < 0 or i + count > len(self._list):
            # Blocks grow (64, 128, ... 4096): a short stream computes little, a long one
            # pays numpy's per-call cost rarely.
            block = min(STREAM_BLOCK_MAX, 2 * len(self._list)) if self._list else STREAM_BLOCK
            self._buffer = uniforms(self._key, self.position, max(block, count))[0]
            self._buffer.flags.writeable = False  # views of it are handed out (random(n))
            self._list = self._buffer.tolist()
            self._start, i = self.position, 0
        return i

    def _take(self, count: int) -> npt.NDArray[np.float64]:
        i = self._cover(count)
        self.position += count
        return self._buffer[i : i + count].copy()

    def _take_list(self, count: int) -> list[float]:
        i = self._cover(count)
        self.position += count
        return self._list[i : i + count]

    def _one(self) -> float:
        """The next draw (the first few in plain integers: a coach's two draws need no block)."""
        i = self.position - self._start
        if 0 <= i < len(self._list):
            self.position += 1
            return self._list[i]
        if self.position < STREAM_BLOCK // 4:
            self.position += 1
            return (_mix_int(self.key + self.position * 0x9E3779B97F4A7C15) >> 11) * _TO_UNIT
        i = self._cover(1)
        self.position += 1
        return self._list[i]

    @overload
    def random(self, size: None = None, *, out: None = None) -> float: ...

    @overload
    def random(
        self, size: int | tuple[int, ...], *, out: None = None
    ) -> npt.NDArray[np.float64]: ...

    @overload
    def random(
        self, size: None = None, *, out: npt.NDArray[np.float64]
    ) -> npt.NDArray[np.float64]: ...

    def random(
        self,
        size: int | tuple[int, ...] | None = None,
        *,
        out: npt.NDArray[np.float64] | None = None,
    ) -> float | npt.NDArray[np.float64]:
        """Uniform doubles in [0, 1): one float, an array of `size`, or filling `out`.

        An array of an int `size` is read-only (a view of the stream's block); copy it to write.
        """
        if type(size) is int:  # the hot call (a see's draws): a read-only view, no copy
            i = self.position - self._start
            if i < 0 or i + size > len(self._list):
                i = self._cover(size)
            self.position += size
            return self._buffer[i : i + size]
        if out is not None:
            out[...] = self._take(out.size).reshape(out.shape)
            return out
        if size is None:
            return self._one()
        shape = (size,) if isinstance(size, int) else tuple(size)
        return self._take(math.prod(shape)).reshape(shape)

    @overload
    def uniform(self, low: float = 0.0, high: float = 1.0, size: None = None) -> float: ...

    @overload
    def uniform(
        self, low: float, high: float, size: int | tuple[int, ...]
    ) -> npt.NDArray[np.float64]: ...

    def uniform(
        self, low: float = 0.0, high: float = 1.0, size: int | tuple[int, ...] | None = None
    ) -> float | npt.NDArray[np.float64]:
        """Uniform in [low, high): ``low + (high - low)·u`` (numpy's formula)."""
        if size is None:
            return low + (high - low) * self._one()
        return low + (high - low) * self.random(size)

    @overload
    def standard_normal(self, size: None = None) -> float: ...

    @overload
    def standard_normal(self, size: int) -> npt.NDArray[np.float64]: ...

    def standard_normal(self, size: int | None = None) -> float | npt.NDArray[np.float64]:
        """Standard normal draws by the Box–Muller transform (two uniforms per pair)."""
        z = self.standard_normal_list(1 if size is None else int(size))
        return z[0] if size is None else np.array(z)

    def standard_normal_list(self, n: int) -> list[float]:
        """`n` standard normal draws as a list: :meth:`standard_normal`'s numbers, no array.

        For a caller that reads them one by one (the camera's frames): building and unpacking
        an array would cost more than the draws.
        """
        pairs = (n + 1) // 2
        u = self._take_list(2 * pairs)
        z: list[float] = []
        log1p, sqrt, cos, sin, tau = math.log1p, math.sqrt, math.cos, math.sin, math.tau
        for j in range(pairs):
            radius = sqrt(-2.0 * log1p(-u[2 * j]))  # 1 - u in (0, 1]: the log is finite
            angle = tau * u[2 * j + 1]
            z += (radius * cos(angle), radius * sin(angle))
        return z[:n] if len(z) > n else z

    def draws_list(self, position: int, count: int) -> list[float]:
        """Draws ``position .. position + count - 1`` of this stream, without moving it.

        For a reader that consumes a reserved range in its own order (the robot world's ball
        noise, :mod:`field_models.robot_physics.world`); the numbers :meth:`random` gives there.
        """
        return uniforms(self._key, position, count)[0].tolist()

    def random_list(self, n: int) -> list[float]:
        """The next `n` uniform draws in [0, 1) as a list (:meth:`random`'s numbers)."""
        return self._take_list(n)

    def normal(
        self, loc: float = 0.0, scale: float = 1.0, size: int | None = None
    ) -> float | npt.NDArray[np.float64]:
        """Normal draws: ``loc + scale·z``."""
        return loc + scale * self.standard_normal(size)

    def integers(self, low: int, high: int | None = None) -> int:
        """One integer in [low, high) (or [0, low) with one argument)."""
        if high is None:
            low, high = 0, low
        if high <= low:
            raise ValueError(f"integers: empty range [{low}, {high})")
        return low + min(high - low - 1, int(self._one() * (high - low)))


class StreamBatch:
    """The same named stream of many trials, drawn as arrays (:func:`uniforms`).

    Row k gives exactly the numbers trial k's :class:`Stream` of that name gives, as long as
    both are asked for the same counts in the same order.

    Attributes:
        keys: One key per trial (K,).
        positions: Draws taken so far per trial (K,).
    """

    def __init__(self, keys: npt.NDArray[np.uint64]) -> None:
        self.keys = np.asarray(keys, dtype=np.uint64)
        self.positions = np.zeros(len(self.keys), dtype=np.int64)

    @classmethod
    def for_trials(
        cls,
        experiment_seed: int | npt.NDArray[np.int64],
        trial_indices: Sequence[int] | npt.NDArray[np.int64],
        name: str,
    ) -> StreamBatch:
        """Stream `name` of the given trials of an experiment (or one seed per trial)."""
        return cls(stream_keys(experiment_seed, trial_indices, name))

    def take(self, count: int, rows: npt.NDArray[np.intp] | None = None) -> npt.NDArray[np.float64]:
        """The next `count` draws of every trial (or of `rows` only): (K or len(rows), count)."""
        if rows is None:
            drawn = uniforms(self.keys, self.positions, count)
            self.positions += count
            return drawn
        drawn = uniforms(self.keys[rows], self.positions[rows], count)
        self.positions[rows] += count
        return drawn

    def peek(
        self, offsets: npt.NDArray[np.int64], rows: npt.NDArray[np.intp] | None = None
    ) -> npt.NDArray[np.float64]:
        """Draws at ``positions + offsets`` of every trial (or of `rows`), without advancing.

        `offsets` has shape (m,) (the same for every trial) or (len(rows), m). Counter-based
        streams allow it: a caller can compute only the draws it will use, then
        :meth:`advance` past the block.
        """
        keys = self.keys if rows is None else self.keys[rows]
        base = self.positions if rows is None else self.positions[rows]
        return draws_at(keys, base.reshape(-1, 1) + np.asarray(offsets, dtype=np.int64))

    def advance(self, count: int) -> None:
        """Move every trial's stream `count` draws on (past a block :meth:`peek` read)."""
        self.positions += count

    def subset(self, rows: npt.NDArray[np.intp]) -> StreamBatch:
        """The streams of `rows`, at their present positions (for compacting a batch)."""
        kept = StreamBatch(self.keys[rows])
        kept.positions = self.positions[rows].copy()
        return kept


class TrialRngs:
    """The named streams of one trial, created on first use."""

    __slots__ = ("_cache", "experiment_seed", "trial_index")

    def __init__(self, experiment_seed: int, trial_index: int) -> None:
        self.experiment_seed = experiment_seed
        self.trial_index = trial_index
        self._cache: dict[str, Stream] = {}

    @classmethod
    def for_trial(cls, experiment_seed: int, trial_index: int) -> TrialRngs:
        """The streams of trial `trial_index` of the experiment seeded `experiment_seed`."""
        return cls(experiment_seed, trial_index)

    def __getitem__(self, name: str) -> Stream:
        """The stream `name` (one of :data:`STREAMS`).

        Raises:
            KeyError: `name` is not a declared stream.
        """
        stream = self._cache.get(name)
        if stream is None:
            key = stream_key(self.experiment_seed, self.trial_index, name)
            stream = self._cache[name] = Stream(key)
        return stream


Rng: TypeAlias = Stream | np.random.Generator
"""A random stream: a trial's :class:`Stream`, or a numpy ``Generator`` (tests, benchmarks)."""
