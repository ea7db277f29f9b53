"""The batch's referee: goals, the after-goal wait, kick-offs, play modes (§6), per trial.

:class:`BatchReferee` is the part of
:class:`~field_models.soccer_server.batch.BatchSoccerServer` that keeps the play modes: the
one-trial model's :class:`~field_models.soccer_server.referee.ModelReferee` over K trials, the
trials that need the scalar rules (a ball that crossed an end line, a kick-off) picked by
vector tests first.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from field_models.protocol import Pitch, end_line_crossing
from field_models.soccer_server.cycle_rules import (
    AFTER_GOAL_MODES,
    PLAY_MODE_CODE,
    PLAY_MODES,
)
from field_models.soccer_server.params import DynamicsParams

_GOAL_L, _GOAL_R = PLAY_MODE_CODE["goal_l"], PLAY_MODE_CODE["goal_r"]
_KICK_OFF_L, _KICK_OFF_R = PLAY_MODE_CODE["kick_off_l"], PLAY_MODE_CODE["kick_off_r"]


class BatchReferee:
    """The play modes and scores of K trials, and the referee's rules that change them (§6).

    A mixin of :class:`~field_models.soccer_server.batch.BatchSoccerServer`, which owns the
    state named below; see the batch for what each attribute holds.
    """

    params: DynamicsParams
    k: int
    x: np.ndarray
    y: np.ndarray
    vx: np.ndarray
    vy: np.ndarray
    mode: np.ndarray
    score_left: np.ndarray
    score_right: np.ndarray
    _ax: np.ndarray
    _ay: np.ndarray
    _after_goal: np.ndarray
    _announce: dict[int, list[str]]
    _side: np.ndarray
    _has_left: bool
    _has_right: bool
    _pitch: Pitch
    _mask: Callable[[np.ndarray | None], np.ndarray]

    def change_mode(self, mode: str, mask: np.ndarray | None = None) -> None:
        """Set the play mode in the trials of `mask`; announced at the next step."""
        if mode not in PLAY_MODES:
            raise ValueError(f"unknown play mode {mode!r}; known: {', '.join(PLAY_MODES)}")
        m = self._mask(mask)
        self.mode[m] = PLAY_MODE_CODE[mode]
        self._after_goal[m] = 0
        if mode not in AFTER_GOAL_MODES:
            for trial in np.flatnonzero(m).tolist():
                self._announce.setdefault(trial, []).append(mode)

    def _judge(
        self, bx0: np.ndarray, by0: np.ndarray, moving: np.ndarray, messages: dict[int, list[str]]
    ) -> None:
        mode = self.mode.copy()
        after = moving & ((mode == _GOAL_L) | (mode == _GOAL_R))
        self._after_goal[after] += 1
        ready = after & (self._after_goal >= self.params.after_goal_wait_cycles)
        if ready.any():
            self._kick_off(np.flatnonzero(ready), messages)
        side = self._goal_side(bx0, by0, moving & ~after)
        if side.any():
            self._score(side, messages)
        kick_off = moving & ~after & (side == 0) & ((mode == _KICK_OFF_L) | (mode == _KICK_OFF_R))
        if kick_off.any():
            self._keep_halves(kick_off, np.where(mode == _KICK_OFF_L, 1, -1))

    def _goal_side(self, x0: np.ndarray, y0: np.ndarray, judged: np.ndarray) -> np.ndarray:
        """Per trial +1 (goal at +x, for the left team), -1 (at -x) or 0, among `judged`.

        A vector test picks the trials whose ball crossed an end line this cycle; only those
        go through the scalar rule, ``field_models.protocol.end_line_crossing``.
        """
        x1, y1 = self.x[:, 0], self.y[:, 0]
        line = 0.5 * self._pitch.length_m + self._pitch.ball_radius_m
        crossed = judged & (np.abs(x1) > line) & ~(np.abs(x0) > line)
        side = np.zeros(self.k, dtype=int)
        for trial in np.flatnonzero(crossed).tolist():
            crossing = end_line_crossing(
                self._pitch, float(x0[trial]), float(y0[trial]), float(x1[trial]), float(y1[trial])
            )
            if crossing.is_goal:
                side[trial] = int(crossing)
        return side

    def _score(self, side: np.ndarray, messages: dict[int, list[str]]) -> None:
        """The goals of this cycle: side[k] +1 (the left team scored), -1 (the right), 0."""
        scored = np.flatnonzero(side)
        left = side[scored] > 0
        self.score_left[scored[left]] += 1 if self._has_left else 0
        self.score_right[scored[~left]] += 1 if self._has_right else 0
        for trial, by_left in zip(scored.tolist(), left.tolist(), strict=True):
            count = self.score_left[trial] if by_left else self.score_right[trial]
            messages.setdefault(trial, []).append(f"goal_{'l' if by_left else 'r'}_{count}")
        self.mode[scored] = np.where(left, _GOAL_L, _GOAL_R)
        for arr in (self.vx, self.vy, self._ax, self._ay):
            arr[scored, 0] = 0.0
        self._after_goal[scored] = 0
        if self.params.after_goal_wait_cycles == 0:
            self._kick_off(scored, messages)

    def _kick_off(self, trials: np.ndarray, messages: dict[int, list[str]]) -> None:
        """Kick-offs after goals in `trials` (indices): ball to the centre, players placed."""
        kicker = np.where(self.mode[trials] == _GOAL_L, -1, 1)
        self.mode[trials] = np.where(kicker < 0, _KICK_OFF_R, _KICK_OFF_L)
        for trial in trials.tolist():
            messages.setdefault(trial, []).append(PLAY_MODES[int(self.mode[trial])])
        for arr in (self.x, self.y, self.vx, self.vy, self._ax, self._ay):
            arr[trials, 0] = 0.0
        chosen = np.zeros(self.k, dtype=bool)
        chosen[trials] = True
        kickers = np.zeros(self.k, dtype=int)
        kickers[trials] = kicker
        self._keep_halves(chosen, kickers)

    def _keep_halves(self, trials: np.ndarray, kicker: np.ndarray) -> None:
        """Players into their own half; the team not kicking off out of the centre circle."""
        p = self.params
        rows = np.flatnonzero(trials)  # a few trials: work on their rows only
        side = self._side[1:]
        x, y = self.x[rows, 1:], self.y[rows, 1:]
        x = np.where(side * x > 0.0, -side * p.player_size_m, x)
        radius = p.center_circle_radius_m + p.player_size_m
        r = np.sqrt(x * x + y * y)
        inside = (side != 0) & (side != kicker[rows, None]) & ~(r > radius)
        with np.errstate(divide="ignore", invalid="ignore"):
            nx = np.where(r == 0.0, radius, x * (radius / r))
            ny = np.where(r == 0.0, 0.0, y * (radius / r))
        self.x[rows, 1:] = np.where(inside, nx, x)
        self.y[rows, 1:] = np.where(inside, ny, y)
