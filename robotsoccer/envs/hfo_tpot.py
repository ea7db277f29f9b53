"""TPOT-RL as the half-field offense ball holder: its row in the HFO goal-rate table.

The match's layer 3 (:mod:`robotsoccer.skills.layer3`) chooses among 8 ball destinations. In
half-field offense the holder's choices are HFO's macros (:mod:`robotsoccer.envs.macros`), and
the learners already in the table (the random kick, the cross-entropy holder of
``examples/train_hfo_holder_cem.py``) choose among SHOOT, DRIBBLE and a pass. So that the
comparison is on equal terms, TPOT-RL here chooses among the same three (:data:`HOLDER_ACTIONS`),
with TPOT-RL's own machinery (:mod:`learning.tpot`): one partition (both attackers share a row,
as the policy is not told which attacker asks), an action-dependent feature per action with
``|U| = 3``, Q(e(a), a) values averaged from rewards, only SUCCESS actions competing (the
paper's W), epsilon-greedy while training. The destinations are *not* mapped onto the macros:
HFO's DRIBBLE goes toward the goal only, so six of the eight destinations would have collapsed
into one macro.

**Features e(s, a)** from the observation vector (the attacker's percept,
:func:`~robotsoccer.envs.control_spaces.observation_names`), with the match team's own
distances (:data:`~robotsoccer.drills.match_setup.SHOOT_RANGE_UNITS`,
:data:`~robotsoccer.drills.match_setup.BLOCKED_UNITS`,
:data:`~robotsoccer.skills.setplay.PATH_HALF_ANGLE_RAD`):

* SHOOT: MISS when the goal is unknown or beyond the shooting range (the shot reaches no one);
  FAILURE when an opponent is seen within the blocked distance inside the path's half-angle of
  the goal's direction; SUCCESS otherwise;
* DRIBBLE (toward the goal): FAILURE when so blocked, SUCCESS otherwise;
* PASS (to the teammate the mask opens; with several, the lowest number): MISS when none is
  open; FAILURE when an opponent is seen nearer than the teammate within :data:`LANE_RAD` of
  its direction; SUCCESS otherwise.

**Rewards** (:func:`learning.tpot.reward`, TPOT-RL's window of t_lim after the action): every
choice is fixed when the episode ends. Within :data:`~learning.tpot.HORIZON_S` of the choice,
GOAL counts as a goal for, CAPTURED_BY_DEFENSE and OUT_OF_BOUNDS as a goal against (HFO's lost
episodes), both discounted by the time since the choice; OUT_OF_TIME, and any end past the
horizon, from the ball's x over the choosing attacker's own observations since (the share of
the way it advanced toward the goal or fell back). A first version fixed a choice already at
the same attacker's next choice, as the match's layer 3 does: then the last kick of an episode
(mostly a shot or a pass) bore the loss of nearly every captured episode while the dribbles
before it were paid their short advance, and the greedy table dribbled (README, "Layer 3").

**Training** (:func:`train_holder`): episodes of experiment seed :data:`TRAIN_SEED` (apart from
the table's seed-0 episodes), the table updated after every episode, epsilon linear from
``epsilon_start`` to ``epsilon_end``; everything is seeded.
``python -m robotsoccer.envs.hfo_tpot --field F`` trains and prints the table's rows for the
hand-written, random and TPOT-RL holders (CEM's row: ``examples/train_hfo_holder_cem.py``).
"""

from __future__ import annotations

import argparse
import math
import time
from dataclasses import dataclass
from typing import Any

import numpy as np
import numpy.typing as npt

from field_models.registry import FIELD_MODELS
from learning.tpot import (
    FAILURE,
    HORIZON_S,
    MISS,
    SUCCESS,
    Experience,
    TpotTable,
    choose,
    epsilon_at,
    reward,
    update,
)
from robotsoccer.drills.match_setup import BLOCKED_UNITS, SHOOT_RANGE_UNITS
from robotsoccer.envs.control_spaces import observation_names
from robotsoccer.envs.hfo import GOAL, OUT_OF_TIME, HalfFieldOffenseEnv
from robotsoccer.envs.hfo_eval import TABLE_HEAD, RandomHolder, goal_rate, handwritten, table_row
from robotsoccer.envs.macros import PASS_BASE, Macro
from robotsoccer.skills.setplay import PATH_HALF_ANGLE_RAD

HOLDER_ACTIONS = ("SHOOT", "DRIBBLE", "PASS")
"""TPOT-RL's actions in half-field offense: the random and CEM holders' three choices."""
SHOOT_A, DRIBBLE_A, PASS_A = 0, 1, 2
LANE_RAD = math.radians(15.0)
"""An opponent nearer than the receiver within this of its direction blocks a pass."""
TRAIN_SEED = 2_000
"""Training episodes come from this experiment seed (the table's are seed 0's)."""
POSITION = 1
"""The one partition both attackers share."""

FloatArray = npt.NDArray[np.float32]
MaskArray = npt.NDArray[np.int8]


@dataclass(frozen=True, slots=True)
class Layout:
    """Where the observation vector holds what the features read, and the field's scales.

    Attributes:
        index: Entry name -> position in the vector.
        teammates: Teammate slots.
        opponents: Opponent slots.
        length_m: The pitch length L the distances are scaled by [m].
        shoot_range_m: The shooting range [m].
        blocked_m: An opponent this near in the path blocks it [m].
        half_length_m: Half the pitch's length [m] (the ball's x for the rewards).
        dt_s: One tick [s].
    """

    index: dict[str, int]
    teammates: int
    opponents: int
    length_m: float
    shoot_range_m: float
    blocked_m: float
    half_length_m: float
    dt_s: float

    @classmethod
    def of(cls, env: HalfFieldOffenseEnv) -> Layout:
        """The layout of an attacker's observation in `env`."""
        offense, defense, goalie = env.counts
        teammates, opponents = offense - 1, defense + int(goalie)
        names = observation_names(teammates, opponents)
        facts = env.facts
        length = facts.pitch.length_m
        return cls(
            {name: i for i, name in enumerate(names)},
            teammates,
            opponents,
            length,
            SHOOT_RANGE_UNITS * facts.unit_m,
            BLOCKED_UNITS * facts.unit_m,
            length / 2.0,
            facts.dt_s,
        )

    def seen(self, obs: FloatArray, group: str, i: int) -> tuple[float, float] | None:
        """(distance [m], angle [rad]) of slot `i` of `group`, or None: not seen."""
        get = self.index
        if obs[get[f"{group}{i}_seen"]] < 0.5:
            return None
        d = float(obs[get[f"{group}{i}_distance"]]) * self.length_m
        a = math.atan2(float(obs[get[f"{group}{i}_sin"]]), float(obs[get[f"{group}{i}_cos"]]))
        return d, a

    def opponents_seen(self, obs: FloatArray) -> list[tuple[float, float]]:
        """Every opponent seen, (distance [m], angle [rad])."""
        out = []
        for i in range(self.opponents):
            seen = self.seen(obs, "opponent", i)
            if seen is not None:
                out.append(seen)
        return out

    def ball_x(self, obs: FloatArray) -> float | None:
        """The ball's x in the field frame [m] from a localised pose and a sighting, or None."""
        get = self.index
        if obs[get["ball_seen"]] < 0.5 or obs[get["self_known"]] < 0.5:
            return None
        x = float(obs[get["self_x"]]) * self.half_length_m
        heading = math.atan2(float(obs[get["self_sin"]]), float(obs[get["self_cos"]]))
        bearing = math.atan2(float(obs[get["ball_sin"]]), float(obs[get["ball_cos"]]))
        d = float(obs[get["ball_distance"]]) * self.length_m
        return x + d * math.cos(heading + bearing)


def features(layout: Layout, obs: FloatArray, mask: MaskArray) -> tuple[int, int, int]:
    """e(s, a) of SHOOT, DRIBBLE and PASS (module docstring)."""
    get = layout.index
    opponents = layout.opponents_seen(obs)
    known = obs[get["target_known"]] >= 0.5
    goal_d = float(obs[get["target_distance"]]) * layout.length_m
    goal_a = math.atan2(float(obs[get["target_sin"]]), float(obs[get["target_cos"]]))
    blocked = known and any(
        d <= layout.blocked_m and abs(_wrap(a - goal_a)) <= PATH_HALF_ANGLE_RAD
        for d, a in opponents
    )
    in_range = known and goal_d <= layout.shoot_range_m
    shoot = (FAILURE if blocked else SUCCESS) if in_range else MISS
    dribble = FAILURE if blocked else SUCCESS
    receiver = _receiver(layout, obs) if _pass_macro(mask) is not None else None
    if receiver is None:
        passing = MISS
    else:
        rd, ra = receiver
        lane = any(d < rd and abs(_wrap(a - ra)) <= LANE_RAD for d, a in opponents)
        passing = FAILURE if lane else SUCCESS
    return (shoot, dribble, passing)


def _receiver(layout: Layout, obs: FloatArray) -> tuple[float, float] | None:
    """The nearest teammate seen (the observation's first teammate slot)."""
    return layout.seen(obs, "teammate", 0) if layout.teammates else None


def _pass_macro(mask: MaskArray) -> int | None:
    """The open pass with the lowest teammate number, or None."""
    passes = [int(i) for i in np.flatnonzero(mask) if i >= PASS_BASE]
    return passes[0] if passes else None


def _wrap(angle: float) -> float:
    return (angle + math.pi) % (2.0 * math.pi) - math.pi


class TpotHolder:
    """The HFO ball holder's choice by a TPOT-RL table (module docstring).

    Args:
        table: One position, :data:`HOLDER_ACTIONS` actions.
        layout: The observation's layout (:meth:`Layout.of`).
        seed: The tie-breaking and exploration generator's seed.
        epsilon: Exploration rate (0: greedy).

    Raises:
        ValueError: A table of another shape.
    """

    def __init__(
        self, table: TpotTable, layout: Layout, seed: int = 0, epsilon: float = 0.0
    ) -> None:
        if table.actions != len(HOLDER_ACTIONS) or table.positions != 1:
            raise ValueError(
                f"an HFO holder's table is 1 position x {len(HOLDER_ACTIONS)} actions, got "
                f"{table.positions} x {table.actions}"
            )
        self.table = table
        self.layout = layout
        self.rng = np.random.default_rng(seed)
        self.epsilon = epsilon
        self.last: tuple[int, int] = (0, 0)  # (feature, action) of the last choice

    def __call__(self, observation: FloatArray, mask: MaskArray) -> int:
        """The macro of the chosen action (SHOOT, DRIBBLE or the open pass)."""
        e = features(self.layout, observation, mask)
        action = choose(self.table, POSITION, e, self.rng, self.epsilon)
        macro = _pass_macro(mask) if action == PASS_A else None
        if action == PASS_A and macro is None:  # a MISS pass chosen: nobody to pass to
            action = DRIBBLE_A
        self.last = (e[action], action)
        if macro is not None:
            return macro
        return int(Macro.SHOOT if action == SHOOT_A else Macro.DRIBBLE)


@dataclass(frozen=True, slots=True)
class HolderTraining:
    """What :func:`train_holder` returns.

    Attributes:
        table: The learned table.
        episodes: Training episodes played.
        goals: Of them, ending in a goal.
        rewards: Rewards fixed.
        wall_s: Wall time [s].
    """

    table: TpotTable
    episodes: int
    goals: int
    rewards: int
    wall_s: float


@dataclass(slots=True)
class _OpenChoice:
    feature: int
    action: int
    tick: int
    x0: float
    samples: list[float]


def train_holder(
    field_model: str = FIELD_MODELS[0],
    episodes: int = 3000,
    seed: int = TRAIN_SEED,
    epsilon_start: float = 0.3,
    epsilon_end: float = 0.05,
    **env_options: Any,
) -> HolderTraining:
    """Learn the holder's table in `episodes` HFO episodes of experiment seed `seed`.

    Raises:
        ValueError: Fewer than 1 episode, or an option the environment refuses.
    """
    if episodes < 1:
        raise ValueError(f"episodes must be at least 1, got {episodes!r}")
    env = HalfFieldOffenseEnv(field_model, action="macro", controlled="offense", **env_options)
    layout = Layout.of(env)
    provenance = {"method": "TPOT-RL, HFO holder", "field": field_model, "seed": seed,
                  "episodes": episodes, "actions": list(HOLDER_ACTIONS)}  # fmt: skip
    table = TpotTable.empty(1, provenance, actions=len(HOLDER_ACTIONS))
    holder = TpotHolder(table, layout, seed)
    goals = fixed = 0
    start = time.perf_counter()
    for k in range(episodes):
        holder.epsilon = epsilon_at(k, episodes, epsilon_start, epsilon_end)
        observations, infos = env.reset(seed=seed if k == 0 else None)
        pending: list[tuple[str, _OpenChoice]] = []  # every choice still open, in order
        experiences: list[Experience] = []
        status = OUT_OF_TIME
        while env.agents:
            actions: dict[str, int] = {}
            for agent in env.agents:
                view = observations[agent]
                assert isinstance(view, dict)
                obs, mask = view["observation"], view["action_mask"]
                tick = int(infos[agent]["tick"])
                x = layout.ball_x(obs)
                for who, open_ in pending:
                    if who == agent and x is not None:
                        open_.samples.append(x)
                if infos[agent]["deciding"] and bool(mask[Macro.SHOOT]):
                    actions[agent] = holder(obs, mask)
                    if x is not None:
                        feature, action = holder.last
                        pending.append((agent, _OpenChoice(feature, action, tick, x, [])))
                else:
                    actions[agent] = int(Macro.AUTO)
            observations, _, _, _, infos = env.step(actions)
        info = next(iter(infos.values()))
        status, tick = str(info["status"]), int(info["tick"])
        sign = 1 if status == GOAL else 0 if status == OUT_OF_TIME else -1
        for _, open_ in pending:  # past the horizon a goal no longer counts (reward())
            late = (tick - open_.tick) * layout.dt_s > HORIZON_S
            experiences.append(_fixed(open_, 0 if late else sign, tick, layout))
        for experience in experiences:
            update(table, experience)
        goals += status == GOAL
        fixed += len(experiences)
    wall = time.perf_counter() - start
    table.provenance |= {"goals": goals, "rewards": fixed, "wall_s": round(wall, 1)}
    return HolderTraining(table, episodes, goals, fixed, wall)


def _fixed(pending: _OpenChoice, goal: int, tick: int, layout: Layout) -> Experience:
    after = (tick - pending.tick) * layout.dt_s
    r = reward(
        pending.x0,
        pending.samples,
        goal=goal,
        goal_after_s=after,
        own_goal_x=-layout.half_length_m,
        opponent_goal_x=layout.half_length_m,
    )
    return Experience(POSITION, pending.feature, pending.action, r)


def main(argv: list[str] | None = None) -> None:
    """Train TPOT-RL's holder, then print the table's rows on the same episodes."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--field", required=True, choices=FIELD_MODELS)
    parser.add_argument("--train-episodes", type=int, default=3000)
    parser.add_argument("--episodes", type=int, default=500)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--save", default=None, help="write the learned table (.npz)")
    args = parser.parse_args(argv)
    training = train_holder(args.field, args.train_episodes)
    print(f"trained: {training.episodes} episodes, {training.goals} goals, "
          f"{training.rewards} rewards, {training.wall_s:.0f} s wall")  # fmt: skip
    per = training.table.n.sum(axis=2)[0]
    print("rewards by e:", dict(zip(("SUCCESS", "FAILURE", "MISS"), per.tolist(), strict=True)))
    for e, name in enumerate(("SUCCESS", "FAILURE", "MISS")):
        cells = ", ".join(
            f"{a} {training.table.q[0, e, i]:+.3f} ({training.table.n[0, e, i]})"
            for i, a in enumerate(HOLDER_ACTIONS)
        )
        print(f"Q(e={name}): {cells}")
    if args.save:
        from learning.tpot import save_table

        save_table(training.table, args.save)
    env = HalfFieldOffenseEnv(args.field, action="macro", controlled="offense")
    rows = (
        ("hand-written (AUTO)", handwritten),
        ("uniform random kick", RandomHolder(args.seed)),
        ("TPOT-RL (greedy)", TpotHolder(training.table, Layout.of(env), args.seed)),
    )
    print(TABLE_HEAD)
    for name, policy in rows:
        result = goal_rate(policy, args.field, args.episodes, args.seed)
        print(table_row(name, args.field, result), flush=True)


if __name__ == "__main__":
    main()
