r"""Issue 23: what the team minds' turn hold costs against the set play's reckoning.

The motion skill (:mod:`robotsoccer.skills.motion`) has two settings for a percept that does
not show a player's last turn yet: the team minds' *hold* (decide nothing until it shows) and
the set play's *reckoning* (decide on the percept turned into the frame of the turns sent).
This script plays baseline against baseline with one team reckoning and the other holding
(match option ``turn_latency=left|right``), the reckoning team on the left in the first half
of the games and on the right in the rest, and reports per preset the reckoning team's goal
difference, both teams' goals and turn reversals per player-minute
(:class:`~robotsoccer.skills.cycle.TurnReversals`, true headings sampled every 100 ms, the
Soccer Server's cycle, so the rates compare across fields):

    python scripts/turn_latency_series.py --games 10 --half-time 30 \
        soccer_server:soccer_server_1996 robot_physics:small_size_1997 \
        robot_physics:small_size_1997_arc
"""

from __future__ import annotations

import argparse
import json
from pathlib import Path

from field_models.protocol import Percept
from robotsoccer.experiments.match import mean_interval
from robotsoccer.runs.runner import DrillOption, TrialLoop, TrialSpec, build_trial
from robotsoccer.skills.cycle import TurnReversals

SAMPLE_S = 0.1
"""Heading sample period for the reversal count [s]: the Soccer Server's cycle."""


def game(model: str, preset: str, index: int, side: str, half_time_s: float) -> dict[str, float]:
    """Game `index`, team `side` reckoning: goals and reversals per player-minute, by setting."""
    options: tuple[tuple[str, DrillOption], ...] = (
        ("left", "baseline"),
        ("right", "baseline"),
        ("half_time_s", half_time_s),
        ("turn_latency", side),
    )
    spec = TrialSpec("match", model, preset, drill_options=options)
    rngs, drill, arena = build_trial(spec, index)
    drill.setup(arena, rngs)
    minds = drill.minds(arena, rngs)
    left_team = arena.players[0].team
    teams = {ref: ("left" if ref.team == left_team else "right") for ref in arena.players}
    counters = {"left": TurnReversals(), "right": TurnReversals()}
    every = max(1, round(SAMPLE_S / arena.facts.dt_s))
    for ref in arena.players:
        counters[teams[ref]].sample(ref, arena.player_state(ref).heading)

    def observe(a: object, percepts: list[Percept]) -> None:
        if arena.tick % every == 0:
            for ref in arena.players:
                counters[teams[ref]].sample(ref, arena.player_state(ref).heading)

    TrialLoop(arena, drill, minds, observe).run()
    measures = drill.measures()
    minutes = arena.tick * arena.facts.dt_s / 60.0
    players = {s: sum(t == s for t in teams.values()) for s in counters}
    other = "right" if side == "left" else "left"
    mine, theirs = side[0], other[0]
    return {
        "goals_reckon": measures[f"goals_{mine}"],
        "goals_hold": measures[f"goals_{theirs}"],
        "reversals_reckon": counters[side].count / (players[side] * minutes),
        "reversals_hold": counters[other].count / (players[other] * minutes),
    }


def cell(values: list[float], sign: str = "") -> str:
    """Mean [95% interval] of `values`."""
    m = mean_interval(values)
    return f"{m.value:{sign}.2f} [{m.low:{sign}.2f}, {m.high:{sign}.2f}]"


def main() -> None:
    """Play the series of each preset named and print a markdown table (module docstring)."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("fields", nargs="+", help="model:preset, e.g. robot_physics:vss")
    parser.add_argument("--games", type=int, default=10)
    parser.add_argument("--half-time", type=float, default=30.0, help="one half [s]")
    parser.add_argument("--out", type=Path, help="a JSON file for every game's numbers")
    args = parser.parse_args()
    print(
        "| field | games | reckon − hold goals/game [95%] | reckon goals | hold goals | "
        "reversals /player-min reckon | hold |\n|" + "---|" * 7
    )
    data = {}
    for field in args.fields:
        model, _, preset = field.partition(":")
        games = [
            game(model, preset, i, "left" if i < (args.games + 1) // 2 else "right", args.half_time)
            for i in range(args.games)
        ]
        data[field] = games
        reckon = [g["goals_reckon"] for g in games]
        hold = [g["goals_hold"] for g in games]
        difference = [r - h for r, h in zip(reckon, hold, strict=True)]
        print(
            f"| `{preset}` | {len(games)} | {cell(difference, '+')} | "
            f"{cell(reckon)} | {cell(hold)} | {cell([g['reversals_reckon'] for g in games])} | "
            f"{cell([g['reversals_hold'] for g in games])} |",
            flush=True,
        )
    if args.out is not None:
        args.out.write_text(json.dumps(data, indent=1) + "\n")


if __name__ == "__main__":
    main()
