"""The one-trial model's referee: goals, the after-goal wait, kick-offs, play modes (§6).

:class:`ModelReferee` is the part of
:class:`~field_models.soccer_server.dynamics.SoccerServerModel` that keeps the play mode:
the trainer's ``change_mode`` (§5), and, with ``DynamicsParams.referee`` on, the goal
judged at the end of each cycle, the stopped ball and the wait after a goal, the kick-off
that follows, and the kick-off modes' halves (the server's ``forbid_kick_off_offside``).
What the referee does and does not model is listed in the model's docstring
(:mod:`~field_models.soccer_server.dynamics`). An accepted kick in a restart mode turns it
into ``play_on``; that rule runs with the commands
(:meth:`~field_models.soccer_server.commands.PlayerCommands._run_commands`).
"""

from __future__ import annotations

from field_models.protocol import Pitch, end_line_crossing
from field_models.soccer_server.cycle_rules import AFTER_GOAL_MODES, PLAY_MODES, out_of_circle
from field_models.soccer_server.params import DynamicsParams


class ModelReferee:
    """The play mode and score of one trial, and the referee's rules that change them (§6).

    A mixin of :class:`~field_models.soccer_server.dynamics.SoccerServerModel`, which owns
    the state named below; see the model for what each attribute holds.
    """

    params: DynamicsParams
    play_mode: str
    score_left: int
    score_right: int
    x: list[float]
    y: list[float]
    vx: list[float]
    vy: list[float]
    _n: int
    _ax: list[float]
    _ay: list[float]
    _side: list[int]
    _pitch: Pitch
    _goal_line: float
    _announce: list[str]
    _after_goal_cycles: int

    def change_mode(self, mode: str) -> None:
        """Set the play mode (trainer ``change_mode``); announced at the next step (§5, §6)."""
        if mode not in PLAY_MODES:
            raise ValueError(f"unknown play mode {mode!r}; known: {', '.join(PLAY_MODES)}")
        self.play_mode = mode
        self._after_goal_cycles = 0
        if mode not in AFTER_GOAL_MODES:
            self._announce.append(mode)

    def _judge(self, bx0: float, by0: float, messages: list[str]) -> None:
        mode = self.play_mode
        if mode in AFTER_GOAL_MODES:
            self._after_goal_cycles += 1
            if self._after_goal_cycles >= self.params.after_goal_wait_cycles:
                self._kick_off(mode, messages)
            return
        bx1, line = self.x[0], self._goal_line
        crossing = (
            end_line_crossing(self._pitch, bx0, by0, bx1, self.y[0])
            if abs(bx1) > line and not abs(bx0) > line  # a cheap test first: crossed at all
            else None
        )
        if crossing is not None and crossing.is_goal:
            self._score(int(crossing), messages)
        elif mode in ("kick_off_l", "kick_off_r"):
            self._keep_halves(1 if mode == "kick_off_l" else -1)

    def _score(self, side: int, messages: list[str]) -> None:
        """Count the goal (`side` +1: at +x, for the left team), stop the ball (§6)."""
        if side > 0:
            self.score_left += 1 if 1 in self._side else 0
            messages.append(f"goal_l_{self.score_left}")
            self.play_mode = "goal_l"
        else:
            self.score_right += 1 if -1 in self._side else 0
            messages.append(f"goal_r_{self.score_right}")
            self.play_mode = "goal_r"
        self.vx[0] = self.vy[0] = self._ax[0] = self._ay[0] = 0.0
        self._after_goal_cycles = 0
        if self.params.after_goal_wait_cycles == 0:
            self._kick_off(self.play_mode, messages)

    def _kick_off(self, after_goal_mode: str, messages: list[str]) -> None:
        """Ball to the centre; the team that conceded kicks off (§6)."""
        kicker = -1 if after_goal_mode == "goal_l" else 1
        self.play_mode = "kick_off_r" if kicker < 0 else "kick_off_l"
        messages.append(self.play_mode)
        # The trainer's move_ball(0, 0), written out: the ball at rest on the centre mark.
        self.x[0] = self.y[0] = self.vx[0] = self.vy[0] = self._ax[0] = self._ay[0] = 0.0
        self._keep_halves(kicker)

    def _keep_halves(self, kicker: int) -> None:
        """Players into their own half; the other team out of the centre circle."""
        p = self.params
        keep_out = p.center_circle_radius_m + p.player_size_m
        for i in range(1, self._n):
            side = self._side[i]
            if side * self.x[i] > 0.0:
                self.x[i] = -side * p.player_size_m
            if side and side != kicker:
                self.x[i], self.y[i] = out_of_circle(self.x[i], self.y[i], keep_out)
