"""Issue 28: what the match coach's "passes" are, per team kind, with the minds' options or not.

The match drill counts a pass each time the ball's last touch (the referee's nearest player within
control reach) goes from one player to a teammate (``robotsoccer.drills.match``). That counts a
kicked pass that arrives, but also two teammates at the ball together taking turns at being the
nearest, and a teammate picking up a ball the last toucher lost. This script replays the games of
a layered-v-baseline series (the same trials as ``scripts/server_series.py`` plays: its base spec,
both sides, game indices 0..N-1) through the runner's loop and splits each team's passes by

* what the last toucher's last kick was (``pass``, ``dribble``, ``shoot``; ``none``: it touched
  the ball without kicking it);
* whether the two players stood within :data:`CROWDED_M` of each other at the change (a crowd at
  the ball) or farther apart;

and counts the pass kicks, with the share of them whose ball a teammate touched next.

    python scripts/pass_breakdown.py --net NET --tree TREE --games 8 [--look neck] [--steady-turns]
"""

from __future__ import annotations

import argparse
import math
from collections import Counter
from pathlib import Path
from typing import Any

from field_models.protocol import Action, Kick, Percept, PlayerRef
from robotsoccer.drills.match import MatchDrill
from robotsoccer.experiments.match import mean_interval, series_specs
from robotsoccer.experiments.team_study import match_base
from robotsoccer.runs.runner import TrialLoop, TrialSpec, build_trial
from robotsoccer.stats import wilson_interval

CROWDED_M = 3.0
"""Two teammates nearer than this [m] when the touch changes: a crowd at the ball."""


def breakdown(spec: TrialSpec, index: int) -> dict[str, Counter[str]]:
    """Game `index` of `spec`: each team kind's passes by kind, and its pass kicks' outcomes."""
    if spec.drill != "match":
        raise ValueError(f"{spec.drill}: not a match drill (pass_breakdown replays matches)")
    rngs, drill, arena = build_trial(spec, index)
    drill.setup(arena, rngs)
    minds = drill.minds(arena, rngs)
    options = dict(spec.drill_options)
    left_team = arena.players[0].team
    kind_of = {
        ref: str(options["left" if ref.team == left_team else "right"]) for ref in arena.players
    }
    counts: dict[str, Counter[str]] = {kind: Counter() for kind in kind_of.values()}
    last_kick: dict[PlayerRef, str] = {}
    waiting: dict[PlayerRef, bool] = {}  # pass kickers whose ball no one else touched yet
    last: list[PlayerRef | None] = [None]
    assert isinstance(drill, MatchDrill) and drill.referee is not None
    referee = drill.referee

    def decided(percept: Percept, actions: tuple[Action, ...]) -> None:
        if any(isinstance(a, Kick) for a in actions):
            kick = str(getattr(minds[percept.player], "intent", "none")).split()[0]
            last_kick[percept.player] = kick
            if kick == "pass":
                if not waiting.get(percept.player):
                    counts[kind_of[percept.player]]["pass kicks"] += 1
                waiting[percept.player] = True

    def observe(a: object, percepts: list[Percept]) -> None:
        toucher, before = referee.last_touch, last[0]
        last[0] = toucher
        if toucher is None or before is None or toucher == before:
            return
        if waiting.pop(before, False) and toucher.team == before.team:
            counts[kind_of[before]]["pass kicks arrived"] += 1
        if toucher.team != before.team:
            return
        p, q = arena.player_state(before), arena.player_state(toucher)
        where = "crowded" if math.hypot(p.x - q.x, p.y - q.y) < CROWDED_M else "apart"
        counts[kind_of[before]][f"after {last_kick.get(before, 'none')}, {where}"] += 1
        counts[kind_of[before]]["passes"] += 1

    TrialLoop(arena, drill, minds, observe, decided).run()
    # The loop calls the observer before the coach's judge of each tick, so it sees each touch
    # one tick late (the players' places a tick later too); once more for the last tick's.
    observe(arena, [])
    measures = drill.measures()
    for side, team in (("l", left_team), ("r", None)):
        kind = str(options["left" if team is not None else "right"])
        counts[kind]["coach passes"] += int(measures[f"passes_{side}"])
    return counts


def main() -> None:
    """Replay the games and print each kind's figures per game with 95% intervals."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--preset", default="soccer_server_1996")
    parser.add_argument("--games", type=int, default=8, help="per side")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--half-time", type=float, default=None, help="one half [s] (300)")
    parser.add_argument("--net", type=Path, required=True)
    parser.add_argument("--tree", type=Path, required=True)
    parser.add_argument("--steady-turns", action="store_true")
    parser.add_argument("--look", choices=("body", "neck"), default="body")
    args = parser.parse_args()
    if args.games < 1:
        parser.error("--games must be >= 1")
    options: dict[str, Any] = {"players": 0, "net": str(args.net), "tree": str(args.tree)}
    if args.half_time is not None:
        options["half_time_s"] = args.half_time
    if args.steady_turns:
        options["steady_turns"] = True
    if args.look != "body":
        options["look"] = args.look
    base = match_base("soccer_server", args.preset, args.seed, args.net, args.tree)
    base = base.with_options(**options)
    games = [breakdown(spec, i) for spec in series_specs(base) for i in range(args.games)]
    print(f"{args.preset} {options}: {len(games)} games (n per kind)")
    for kind in ("layered", "baseline"):
        names = sorted({name for game in games for name in game[kind]})
        for name in names:
            value = mean_interval([float(game[kind][name]) for game in games])
            print(f"  {kind} {name} per game: {value.text()}")
        kicks = sum(game[kind]["pass kicks"] for game in games)
        arrived = sum(game[kind]["pass kicks arrived"] for game in games)
        if kicks:
            low, high = wilson_interval(arrived, kicks)
            share = f"{100 * arrived / kicks:.1f} [{100 * low:.1f}, {100 * high:.1f}] %"
            print(f"  {kind} pass kicks a teammate touched next: {share} ({arrived}/{kicks})")


if __name__ == "__main__":
    main()
