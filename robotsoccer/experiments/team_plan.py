"""Layer 3's study plans: how many training games, rounds, halves and series games it plays.

:func:`plan_for` picks the full or quick plan, for the layered team's asking points or TPOT-RL's
own rule on every spell on the ball, with its reward window (:mod:`robotsoccer.experiments.
team_study` runs them).
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass, replace
from typing import Any

from learning.tpot import REWARD_WINDOWS, WINDOW_CHOICE


@dataclass(frozen=True, slots=True)
class TeamPlan:
    """How much layer 3's study plays.

    Attributes:
        name: ``full`` or ``quick``.
        training_games: Training games against the baseline.
        games_per_round: Games that share one table (then it learns from them).
        half_time_s: One half of a training game [s].
        epsilon_start: Exploration rate of the first round.
        epsilon_end: ... of the last.
        series_games: Games of each closing series.
        series_half_time_s: One half of a series game [s].
        curve_block: Training games per point of the learning curve.
        every: Layer 3 decides on every spell on the ball, shot and keep included (drill
            option ``tpot_every``; :mod:`robotsoccer.skills.layer3`); False: only where the
            layered team would ask the tree.
        success: The tree's least confidence for e = SUCCESS (drill option ``tpot_success``).
        window: When a reward closes (drill option ``tpot_window``,
            :data:`learning.tpot.REWARD_WINDOWS`): ``choice`` (the first studies') or
            ``horizon`` (Stone & Veloso 1999's fixed window after the action).
        guard: The shot-range guard (drill option ``tpot_guard``; needs ``every``): the goal
            destination is a shot only within the teams' shooting range, else an advance
            toward the goal (:mod:`robotsoccer.skills.layer3`).
        loss: The loss penalty of the possession reward (drill option ``tpot_loss``; 0: the
            ball's advance alone, the first studies').
        features_tree: Layer 3's own pass tree for its features (drill option ``tpot_tree``;
            empty: the layered team's tree, the first studies').
    """

    name: str
    training_games: int
    games_per_round: int
    half_time_s: float
    epsilon_start: float
    epsilon_end: float
    series_games: int
    series_half_time_s: float
    curve_block: int
    every: bool = False
    success: float = 0.5
    window: str = WINDOW_CHOICE
    guard: bool = False
    loss: float = 0.0
    features_tree: str = ""

    def __post_init__(self) -> None:
        if self.training_games < 1 or self.games_per_round < 1 or self.series_games < 0:
            raise ValueError("training games and games per round must be >= 1, series >= 0")
        if self.curve_block < 1:
            raise ValueError("curve_block must be >= 1")
        if not 0.0 <= self.success <= 1.0:
            raise ValueError(f"success must be in [0, 1], got {self.success}")
        if self.guard and not self.every:
            raise ValueError("the shot-range guard needs every (the goal is a shot only then)")
        if not 0.0 <= self.loss <= 1.0:
            raise ValueError(f"loss must be in [0, 1], got {self.loss}")
        if self.window not in REWARD_WINDOWS:
            raise ValueError(
                f"window must be one of {', '.join(REWARD_WINDOWS)}, got {self.window!r}"
            )

    def drill_options(self) -> dict[str, Any]:
        """The match drill's layer-3 options this plan plays with.

        The guard, the loss penalty and layer 3's own tree are named only when set, so the
        earlier studies' specs stay as they were.
        """
        options: dict[str, Any] = {
            "tpot_every": self.every,
            "tpot_success": self.success,
            "tpot_window": self.window,
        }
        if self.guard:
            options["tpot_guard"] = True
        if self.loss:
            options["tpot_loss"] = self.loss
        if self.features_tree:
            options["tpot_tree"] = self.features_tree
        return options

    @property
    def rounds(self) -> int:
        """Training rounds (the last may be short)."""
        return math.ceil(self.training_games / self.games_per_round)

    def to_dict(self) -> dict[str, Any]:
        """The plan as JSON scalars."""
        return asdict(self)


FULL_PLAN = TeamPlan("full", 240, 4, 150.0, 0.3, 0.05, 34, 300.0, 24)
"""240 training games of 2 x 150 s (half rcssserver's half), tables updated every 4 games; the
series are 34 full games (2 x 300 s) each."""
QUICK_PLAN = TeamPlan("quick", 8, 2, 60.0, 0.3, 0.05, 4, 60.0, 2)
"""A smoke test of every step."""
EVERY_SUCCESS = 0.95
"""The SUCCESS cut of the ``every`` plans. Asked with the passer's half of the attributes only,
the quick soccer-server tree of the first study answered 0.923 or 0.968 and nothing else (two
probe games of 2 x 300 s, 158 passes judged): at the layered team's 0.5 every pass was
SUCCESS and FAILURE never occurred; a cut between the two makes the lower leaf FAILURE, so
|U| = 3 occurs."""
EVERY_PLAN = TeamPlan("every", 400, 4, 150.0, 0.3, 0.05, 34, 300.0, 40, True, EVERY_SUCCESS)
"""Stone & Veloso's rule: the holder decides on every spell on the ball (shoot and keep among
the destinations), 400 training games of 2 x 150 s, the series as the full plan's."""
EVERY_QUICK_PLAN = TeamPlan("every-quick", 8, 2, 60.0, 0.3, 0.05, 4, 60.0, 2, True, EVERY_SUCCESS)
"""A smoke test of the ``every`` plan."""


def plan_for(quick: bool, every: bool = False, window: str = WINDOW_CHOICE) -> TeamPlan:
    """The quick or the full plan.

    `every`: layer 3 on every spell on the ball; `window`: when its rewards close
    (:data:`learning.tpot.REWARD_WINDOWS`).
    """
    if every:
        plan = EVERY_QUICK_PLAN if quick else EVERY_PLAN
    else:
        plan = QUICK_PLAN if quick else FULL_PLAN
    return plan if window == plan.window else replace(plan, window=window)
