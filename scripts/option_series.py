r"""What one setting of the team minds is worth: one team with it against the same team without.

Match options that take a team's side as their value (``turn_latency``, issue 23: the motion
skill's *reckoning* against the team minds' *hold*; ``client``, issue 28: the per-cycle client
against the see-triggered one; ``dead_band``, issue 28 item 5) give one team the setting and
leave the other as it is. This script plays such matches, baseline against baseline (or
layered against layered with ``--net``/``--tree``), the team with the setting on the left in
the first half of the games and on the right in the rest, and reports per preset that team's
goal difference, both teams' goals and turn reversals per player-minute
(:class:`~robotsoccer.skills.reversals.TurnReversals`, true headings sampled every 100 ms, the
Soccer Server's cycle, so the rates compare across fields):

    python scripts/option_series.py --option turn_latency --games 10 --half-time 30 \
        soccer_server:soccer_server_1996 robot_physics:small_size_1997 \
        robot_physics:small_size_1997_arc
    python scripts/option_series.py --option client --games 34 --half-time 300 \
        soccer_server:soccer_server_1996 soccer_server:rcssserver_19

``--with NAME=VALUE`` sets further options for both teams (``look=neck``).
"""

from __future__ import annotations

import argparse
import json
from pathlib import Path

from field_models.protocol import Percept
from robotsoccer.experiments.match import mean_interval
from robotsoccer.runs.runner import DrillOption, TrialLoop, TrialSpec, build_trial
from robotsoccer.skills.reversals import TurnReversals

SAMPLE_S = 0.1
"""Heading sample period for the reversal count [s]: the Soccer Server's cycle."""


def game(
    model: str, preset: str, index: int, side: str, options: tuple[tuple[str, DrillOption], ...]
) -> dict[str, float]:
    """Game `index`, team `side` with the setting: goals and reversals per player-minute.

    `options` are the match's, the setting's own (its name with `side`) among them.
    """
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
        "goals_on": measures[f"goals_{mine}"],
        "goals_off": measures[f"goals_{theirs}"],
        "reversals_on": counters[side].count / (players[side] * minutes),
        "reversals_off": counters[other].count / (players[other] * minutes),
    }


def cell(values: list[float], sign: str = "") -> str:
    """Mean [95% interval] of `values`."""
    m = mean_interval(values)
    return f"{m.value:{sign}.2f} [{m.low:{sign}.2f}, {m.high:{sign}.2f}]"


SIDED_OPTIONS = ("turn_latency", "client", "dead_band")
"""Match options whose value may name one team."""


def match_options(args: argparse.Namespace, side: str) -> tuple[tuple[str, DrillOption], ...]:
    """The options of a game whose team `side` has the setting (:func:`main`'s arguments)."""
    kind = "layered" if args.net else "baseline"
    options: list[tuple[str, DrillOption]] = [
        ("left", kind),
        ("right", kind),
        ("half_time_s", args.half_time),
        (args.option, side),
    ]
    if args.net:
        options += [("net", str(args.net)), ("tree", str(args.tree))]
    for item in args.with_:
        name, _, value = item.partition("=")
        options.append((name, value))
    return tuple(options)


def main() -> None:
    """Play the series of each preset named and print a markdown table (module docstring)."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("fields", nargs="+", help="model:preset, e.g. robot_physics:vss")
    parser.add_argument("--option", choices=SIDED_OPTIONS, default="turn_latency")
    parser.add_argument("--games", type=int, default=10)
    parser.add_argument("--half-time", type=float, default=30.0, help="one half [s]")
    parser.add_argument("--net", type=Path, help="layer 1's net: layered against layered")
    parser.add_argument("--tree", type=Path, help="layer 2's tree (with --net)")
    parser.add_argument(
        "--with", dest="with_", action="append", default=[], metavar="NAME=VALUE",
        help="a match option for both teams (repeatable)",
    )  # fmt: skip
    parser.add_argument("--out", type=Path, help="a JSON file for every game's numbers")
    args = parser.parse_args()
    if bool(args.net) != bool(args.tree):
        parser.error("--net and --tree go together")
    print(
        f"| field | games | with − without {args.option} goals/game [95%] | with goals | "
        "without goals | reversals /player-min with | without |\n|" + "---|" * 7
    )
    data = {}
    for field in args.fields:
        model, _, preset = field.partition(":")
        games = []
        for i in range(args.games):
            side = "left" if i < (args.games + 1) // 2 else "right"
            games.append(game(model, preset, i, side, match_options(args, side)))
        data[field] = games
        on = [g["goals_on"] for g in games]
        off = [g["goals_off"] for g in games]
        difference = [a - b for a, b in zip(on, off, strict=True)]
        print(
            f"| `{preset}` | {len(games)} | {cell(difference, '+')} | "
            f"{cell(on)} | {cell(off)} | {cell([g['reversals_on'] for g in games])} | "
            f"{cell([g['reversals_off'] for g in games])} |",
            flush=True,
        )
    if args.out is not None:
        args.out.write_text(json.dumps(data, indent=1) + "\n")


if __name__ == "__main__":
    main()
