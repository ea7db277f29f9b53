"""Layer 3: team-partitioned, opaque-transition reinforcement learning (TPOT-RL).

Stone & Veloso's next layer above the pass evaluator ("Team-partitioned, opaque-transition
reinforcement learning", 1999; issue 24). Each player with the ball chooses one of
:data:`N_ACTIONS` ball destinations. Its state is reduced to three things:

* **the partition** ``p``: its formation position (the team is partitioned by position, each
  position learns its own values);
* **the action-dependent features** ``e(s, a)``: for every destination ``a``, the layer-2
  tree's verdict on sending the ball there, discretised to :data:`FEATURE_VALUES` (``|U| = 3``:
  SUCCESS, FAILURE, MISS; the field side computes it, :mod:`robotsoccer.skills.layer3`);
* **the values** ``Q(p, e, a)``: under TPOT-RL's assumption that an action's long-term reward
  depends only on its own feature, the table holds ``|positions| x |U| x |A|`` numbers.

Transitions are *opaque*: a player cannot see what its teammates do next, so there is no
bootstrapping. After an action the player watches where the ball goes and fixes one reward
(:func:`reward`); the update is a running average toward it (:func:`update`):
``Q <- Q + alpha (r - Q)``, ``alpha = max(1 / n, alpha_min)`` (``n``: updates of that entry,
so early values are sample means and later ones track the teammates' changing policies).

**Action choice** (:func:`choose`): like the paper, only actions whose feature is in the
considered set ``W`` (default: SUCCESS only, the paper's ``|W| = 1``) compete, all of them when
none is; among those the highest ``Q(p, e(a), a)`` wins, ties broken at random. **Exploration**
is epsilon-greedy: with probability epsilon the action is drawn uniformly from the competing
ones; :func:`epsilon_at` gives the linear schedule of a training series.

This module is pure numpy: no field model, no robotsoccer import (DESIGN.md: ``learning`` sits
below ``robotsoccer``). A table is saved as an ``.npz`` without pickles, its provenance as JSON
inside, and a digest of its arrays: :func:`load_table` refuses a file whose arrays or digest do
not match.
"""

from __future__ import annotations

import hashlib
import json
import math
import os
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Protocol

import numpy as np
import numpy.typing as npt

N_ACTIONS = 8
"""Ball destinations a player chooses among (the TPOT-RL paper's 8; a table may hold another
number of actions, e.g. the half-field offense holder's macros)."""
FEATURE_VALUES: tuple[str, ...] = ("SUCCESS", "FAILURE", "MISS")
"""The values of e(s, a), in table order: the layer-2 labels (|U| = 3)."""
SUCCESS, FAILURE, MISS = 0, 1, 2
"""Indices into :data:`FEATURE_VALUES`."""
CONSIDERED: tuple[int, ...] = (SUCCESS,)
"""The feature values whose actions compete (the paper's W, |W| = 1)."""
ALPHA_MIN = 0.1
"""The update's least step size (later updates track a shifting reward)."""
HORIZON_S = 30.0
"""t_lim: a reward is fixed at the latest this long after the action [s]."""
Q_MAX = 1.0
"""Rewards lie in [-Q_MAX, +Q_MAX]: a goal at once is +-Q_MAX."""
WINDOW_CHOICE = "choice"
"""A reward closes at the horizon, a goal, game end, or the same player's next choice (the
first studies' rule: it rewards an action by the ball's advance until its player next has the
ball, so a kick that loses the ball for good looks as good as one that lands with a teammate)."""
WINDOW_HORIZON = "horizon"
"""A reward closes only at the horizon, a goal, play stopping or game end: the fixed window
after the action of Stone & Veloso 1999's R (§4: the ball's average position over t_lim after
the action, or a goal within it); the player's later choices do not cut it short."""
REWARD_WINDOWS: tuple[str, ...] = (WINDOW_CHOICE, WINDOW_HORIZON)
"""The reward windows a field side may close by (:mod:`robotsoccer.skills.layer3`)."""
TABLE_FORMAT = "robotsoccer/tpot-table"
TABLE_FORMAT_VERSION = 1


class UniformSource(Protocol):
    """What :func:`choose` draws from (a seeded stream: numpy's Generator or a trial Stream)."""

    def random(self) -> float:
        """A float in [0, 1)."""
        ...


@dataclass(slots=True)
class TpotTable:
    """Per-position Q-values with their update counts and provenance.

    Attributes:
        q: float64 (n_positions, |U|, n_actions): Q(p, e, a); position p is uniform number p+1
            (n_actions: :data:`N_ACTIONS` for the field's destinations, or another count).
        n: int64, same shape: how many rewards each entry has averaged.
        provenance: JSON scalars and strings: seed, games, code version, tree digest, ...
    """

    q: npt.NDArray[np.float64]
    n: npt.NDArray[np.int64]
    provenance: dict[str, Any] = field(default_factory=dict)

    def __post_init__(self) -> None:
        self.q = np.asarray(self.q, dtype=np.float64)
        self.n = np.asarray(self.n, dtype=np.int64)
        u = len(FEATURE_VALUES)
        if self.q.ndim != 3 or self.q.shape[1] != u or min(self.q.shape) < 1:
            raise ValueError(f"a Q table is (positions, {u}, actions), got {self.q.shape}")
        if self.n.shape != self.q.shape:
            raise ValueError(f"counts {self.n.shape} do not match values {self.q.shape}")
        if not np.all(np.isfinite(self.q)) or np.any(np.abs(self.q) > Q_MAX):
            raise ValueError(f"Q values must be finite and within +-{Q_MAX:g}")
        if np.any(self.n < 0):
            raise ValueError("update counts must be >= 0")

    @classmethod
    def empty(
        cls,
        positions: int,
        provenance: Mapping[str, Any] | None = None,
        actions: int = N_ACTIONS,
    ) -> TpotTable:
        """A table of zeros for `positions` positions (uniform numbers 1..positions)."""
        if positions < 1 or actions < 1:
            raise ValueError(f"positions and actions must be >= 1, got {positions}, {actions}")
        shape = (positions, len(FEATURE_VALUES), actions)
        return cls(np.zeros(shape), np.zeros(shape, dtype=np.int64), dict(provenance or {}))

    @property
    def positions(self) -> int:
        """How many positions the table holds."""
        return int(self.q.shape[0])

    @property
    def actions(self) -> int:
        """How many actions each position chooses among."""
        return int(self.q.shape[2])

    def values(
        self, number: int, features: Sequence[int] | npt.NDArray[np.intp]
    ) -> npt.NDArray[np.float64]:
        """Q(p, e(a), a) for every action a of the player with uniform `number`."""
        p = self._row(number)
        e = _features(features, self.actions)
        return self.q[p, e, np.arange(self.actions)]

    def digest(self) -> str:
        """SHA-256 (short) of the values and counts as stored (little-endian)."""
        h = hashlib.sha256()
        h.update(self.q.astype("<f8").tobytes())
        h.update(self.n.astype("<i8").tobytes())
        return h.hexdigest()[:16]

    def _row(self, number: int) -> int:
        if not 1 <= number <= self.positions:
            raise ValueError(f"uniform number {number} outside the table's 1..{self.positions}")
        return number - 1


@dataclass(frozen=True, slots=True)
class Experience:
    """One action and the reward it earned.

    Attributes:
        number: The acting player's uniform number (its position).
        feature: e(s, a) of the action taken (index into :data:`FEATURE_VALUES`).
        action: The action chosen (0..the table's actions - 1).
        reward: The reward fixed for it (:func:`reward`).
    """

    number: int
    feature: int
    action: int
    reward: float


def _features(features: Sequence[int] | npt.NDArray[np.intp], actions: int) -> npt.NDArray[np.intp]:
    e = np.asarray(features, dtype=np.intp)
    if e.shape != (actions,):
        raise ValueError(f"one feature per action ({actions}), got shape {e.shape}")
    if np.any((e < 0) | (e >= len(FEATURE_VALUES))):
        raise ValueError(f"feature values must be in 0..{len(FEATURE_VALUES) - 1}, got {e}")
    return e


def choose(
    table: TpotTable,
    number: int,
    features: Sequence[int],
    rng: UniformSource,
    epsilon: float = 0.0,
    considered: Sequence[int] = CONSIDERED,
) -> int:
    """The destination a player takes (module docstring: W, greedy, epsilon-greedy).

    One draw decides exploring (only when ``epsilon > 0``); one more breaks a tie or picks the
    explored action, so a seeded `rng` gives the same choice every time.
    """
    if not 0.0 <= epsilon <= 1.0:
        raise ValueError(f"epsilon must be in [0, 1], got {epsilon}")
    e = _features(features, table.actions)
    allowed = np.flatnonzero(np.isin(e, list(considered)))
    if allowed.size == 0:
        allowed = np.arange(table.actions)
    if epsilon > 0.0 and rng.random() < epsilon:
        return int(allowed[_index(rng, allowed.size)])
    q = table.values(number, e)[allowed]
    best = allowed[q >= q.max()]
    return int(best[_index(rng, best.size)]) if best.size > 1 else int(best[0])


def _index(rng: UniformSource, size: int) -> int:
    return min(int(rng.random() * size), size - 1)


def update(table: TpotTable, experience: Experience, alpha_min: float = ALPHA_MIN) -> None:
    """Q(p, e, a) <- Q + alpha (r - Q), alpha = max(1/n, alpha_min) (module docstring)."""
    if not 0.0 < alpha_min <= 1.0:
        raise ValueError(f"alpha_min must be in (0, 1], got {alpha_min}")
    r = float(experience.reward)
    if not (math.isfinite(r) and abs(r) <= Q_MAX):
        raise ValueError(f"a reward must be finite and within +-{Q_MAX:g}, got {r}")
    if not 0 <= experience.action < table.actions:
        raise ValueError(f"action {experience.action} outside 0..{table.actions - 1}")
    if not 0 <= experience.feature < len(FEATURE_VALUES):
        raise ValueError(f"feature {experience.feature} outside 0..{len(FEATURE_VALUES) - 1}")
    key = (table._row(experience.number), experience.feature, experience.action)
    table.n[key] += 1
    alpha = max(1.0 / float(table.n[key]), alpha_min)
    table.q[key] += alpha * (r - table.q[key])


def reward(
    x0: float,
    samples: Sequence[float],
    *,
    goal: int = 0,
    goal_after_s: float = 0.0,
    own_goal_x: float,
    opponent_goal_x: float,
    horizon_s: float = HORIZON_S,
) -> float:
    """TPOT-RL's internal reinforcement for one action (Stone & Veloso 1999, §4's R).

    Coordinates are along the team's attack: `opponent_goal_x` > `own_goal_x`.

    * **A goal** within the horizon (`goal` = +1 for, -1 against, `goal_after_s` after the
      action): ``+-Q_MAX * horizon / (horizon + t)``: the later the goal, the less it says about
      the action (a discount, as the paper scales by time); half at the horizon.
    * **Otherwise** (the horizon passed, or the window closed earlier: play stopped, the game
      ended, or with :data:`WINDOW_CHOICE` the player acted again): from the
      ball's mean x over the player's own sightings `samples` since the action, x̄: the share
      of the way to the opponents' goal it advanced, ``Q_MAX (x̄ - x0) / (x_og - x0)``, or the
      share of the way back to its own goal, ``-Q_MAX (x0 - x̄) / (x0 - x_lg)``. No sighting:
      0.
    """
    if not own_goal_x < opponent_goal_x:
        raise ValueError("the opponents' goal must lie ahead of the own goal (x_lg < x_og)")
    if horizon_s <= 0.0:
        raise ValueError(f"horizon_s must be > 0, got {horizon_s}")
    if goal not in (-1, 0, 1):
        raise ValueError(f"goal must be -1, 0 or +1, got {goal}")
    if goal:
        t = max(goal_after_s, 0.0)
        return goal * Q_MAX * horizon_s / (horizon_s + t)
    if not samples:
        return 0.0
    x0 = min(max(x0, own_goal_x), opponent_goal_x)
    mean = min(max(float(np.mean(samples)), own_goal_x), opponent_goal_x)
    if mean >= x0:
        span = opponent_goal_x - x0
        return Q_MAX * (mean - x0) / span if span > 0.0 else 0.0
    span = x0 - own_goal_x
    return -Q_MAX * (x0 - mean) / span if span > 0.0 else 0.0


def loss_penalty(penalty: float, lost_after_s: float, horizon_s: float = HORIZON_S) -> float:
    """What the opponents' gaining the ball `lost_after_s` after an action costs it.

    ``penalty * (1 - t / horizon)``: a ball lost at once costs the whole `penalty`, one lost
    at the window's end nothing (a loss long after the action says little about it).
    """
    if penalty < 0.0 or horizon_s <= 0.0:
        raise ValueError(f"penalty must be >= 0 and horizon_s > 0, got {penalty}, {horizon_s}")
    return penalty * max(0.0, 1.0 - max(lost_after_s, 0.0) / horizon_s)


def epsilon_at(game: int, games: int, start: float, end: float) -> float:
    """The exploration rate of training game `game` of `games`: linear from start to end."""
    if games < 1 or not 0 <= game < games:
        raise ValueError(f"game {game} outside 0..{games - 1}")
    for name, value in (("start", start), ("end", end)):
        if not 0.0 <= value <= 1.0:
            raise ValueError(f"epsilon {name} must be in [0, 1], got {value}")
    if games == 1:
        return start
    return start + (end - start) * game / (games - 1)


# ----------------------------------------------------------------------------- the file


def save_table(table: TpotTable, path: str | os.PathLike[str]) -> Path:
    """Write `table` as ``.npz`` (no pickles); returns the path written.

    The file holds the values, the counts, and a JSON header with the format, the provenance
    and the arrays' digest.
    """
    header = {
        "format": TABLE_FORMAT,
        "version": TABLE_FORMAT_VERSION,
        "feature_values": list(FEATURE_VALUES),
        "actions": table.actions,
        "digest": table.digest(),
        "provenance": table.provenance,
    }
    text = json.dumps(header, sort_keys=True)
    out = Path(path)
    with out.open("wb") as f:
        np.savez(f, q=table.q, n=table.n, header=np.array(text))
    return out


def load_table(path: str | os.PathLike[str]) -> TpotTable:
    """A table saved by :func:`save_table`.

    Raises:
        ValueError: Not such a file, another format or version, arrays of the wrong shape or
            values, or arrays that do not match the digest written with them (a corrupt file).
    """
    name = os.fspath(path)
    try:
        with np.load(name, allow_pickle=False) as data:
            q, n, raw = data["q"], data["n"], str(data["header"])
    except (OSError, ValueError, KeyError, EOFError) as exc:
        raise ValueError(f"{name}: not a TPOT-RL table ({exc})") from None
    except Exception as exc:  # zipfile.BadZipFile and kin: a damaged archive
        raise ValueError(f"{name}: not a TPOT-RL table ({type(exc).__name__}: {exc})") from None
    try:
        header = json.loads(raw)
    except json.JSONDecodeError:
        raise ValueError(f"{name}: its header is not JSON") from None
    if not isinstance(header, dict) or header.get("format") != TABLE_FORMAT:
        raise ValueError(f"{name}: not a {TABLE_FORMAT} file")
    if header.get("version") != TABLE_FORMAT_VERSION:
        raise ValueError(f"{name}: format version {header.get('version')!r}, "
                         f"this code reads {TABLE_FORMAT_VERSION}")  # fmt: skip
    actions = q.shape[2] if q.ndim == 3 else None
    if header.get("feature_values") != list(FEATURE_VALUES) or header.get("actions") != actions:
        raise ValueError(f"{name}: features or actions differ from this code's or its values "
                         f"(header: {header.get('actions')!r} actions)")  # fmt: skip
    if q.dtype.kind != "f" or n.dtype.kind not in "iu":
        raise ValueError(f"{name}: arrays of the wrong types ({q.dtype}, {n.dtype})")
    provenance = header.get("provenance", {})
    if not isinstance(provenance, dict):
        raise ValueError(f"{name}: provenance is not an object")
    try:
        table = TpotTable(q, n, provenance)
    except ValueError as exc:
        raise ValueError(f"{name}: {exc}") from None
    if table.digest() != header.get("digest"):
        raise ValueError(f"{name}: its arrays do not match their digest (a corrupt file)")
    return table
