"""Issue 28: the 34-game Soccer Server series, layered against baseline, steady turns or not.

``robotsoccer match --games N`` has no switch for the match drill's ``steady_turns`` option, so
this script builds the same series (the CLI's base spec, :func:`robotsoccer.experiments.match.
run_series` and its report) with the option set or not, and then counts turn reversals
(:class:`~robotsoccer.skills.reversals.TurnReversals`: a turn of more than 10° the other way from
the player's last such turn, every cycle, true headings) in the first `--reversal-games` games of
each side through the trial runner's own loop, per team kind, per player-minute.

    python scripts/server_series.py --preset soccer_server_1996 --games 34 --workers 2 \
        --net NET --tree TREE [--steady-turns] [--look neck] [--client cycle] \
        [--receiver-half estimated] --out runs/series-ss-default

``--dither SEEDS`` counts the reversals of baseline-v-baseline matches instead (game 0 of each
seed, both teams together; no net or tree), the issue's measure of dithering:

    python scripts/server_series.py --dither 0,1 --half-time 30 [--steady-turns] [--look neck]
"""

from __future__ import annotations

import argparse
import csv
import json
import time
from pathlib import Path
from typing import Any

from field_models.arena import FieldOptions
from field_models.protocol import Percept
from robotsoccer.experiments.match import mean_interval, run_series, series_specs, write_report
from robotsoccer.experiments.team_study import match_base
from robotsoccer.runs.runner import TrialLoop, TrialSpec, build_trial
from robotsoccer.skills.reversals import TurnReversals
from robotsoccer.skills.team_setup import RECEIVER_HALVES


def reversals(spec: TrialSpec, index: int) -> dict[str, Any]:
    """Turn reversals by team kind in game `index` of `spec`, with the players' minutes."""
    rngs, drill, arena = build_trial(spec, index)
    drill.setup(arena, rngs)
    minds = drill.minds(arena, rngs)
    options = dict(spec.drill_options)
    kind = {"left": str(options["left"]), "right": str(options["right"])}
    counters = {side: TurnReversals() for side in kind}
    side_of = {}
    for ref in arena.players:
        side_of[ref] = "left" if ref.team == arena.players[0].team else "right"
        counters[side_of[ref]].sample(ref, arena.player_state(ref).heading)

    def observe(a: object, percepts: list[Percept]) -> None:
        for ref in arena.players:
            counters[side_of[ref]].sample(ref, arena.player_state(ref).heading)

    verdict = TrialLoop(arena, drill, minds, observe).run()
    minutes = arena.tick * arena.facts.dt_s / 60.0
    players = {side: sum(s == side for s in side_of.values()) for side in kind}
    by_kind: dict[str, dict[str, float]] = {}
    for side in kind:  # both sides of one kind (baseline v baseline) add up
        counts = by_kind.setdefault(kind[side], {"reversals": 0, "player_minutes": 0.0})
        counts["reversals"] += counters[side].count
        counts["player_minutes"] += players[side] * minutes
    return {"label": None if verdict is None else verdict.label, "by_kind": by_kind}


def dither(preset: str, seeds: list[int], options: dict[str, Any]) -> list[dict[str, Any]]:
    """Reversals per player-minute of baseline v baseline, game 0 of each seed (both teams)."""
    out = []
    for seed in seeds:
        spec = TrialSpec(
            drill="match",
            field_model="soccer_server",
            preset=preset,
            seed=seed,
            field=FieldOptions(),
        ).with_options(left="baseline", right="baseline", players=0, **options)
        game = reversals(spec, 0)
        counts = game["by_kind"]["baseline"]
        rate = counts["reversals"] / counts["player_minutes"]
        out.append({"seed": seed, "label": game["label"], **counts, "per_player_minute": rate})
    return out


def goal_differences(folder: Path) -> dict[tuple[str, int], float]:
    """Each game's goal difference (layered - baseline) of a series folder, by side and index."""
    out = {}
    for side, sign in (("layered_left", 1.0), ("layered_right", -1.0)):
        with (folder / side / "results.csv").open() as f:
            for game in csv.DictReader(f):
                goals = dict(kv.split("=") for kv in game["measures"].split())
                difference = float(goals["goals_l"]) - float(goals["goals_r"])
                out[(side, int(game["index"]))] = sign * difference
    return out


def paired_change(before: Path, after: Path) -> str:
    """The mean change of the layered team's goal difference, game by game on the same seeds."""
    old, new = goal_differences(before), goal_differences(after)
    if old.keys() != new.keys():
        raise ValueError(f"{before} and {after} did not play the same games")
    change = mean_interval([new[k] - old[k] for k in sorted(old)])
    return f"{change.value:+.2f} [{change.low:+.2f}, {change.high:+.2f}] (n={len(old)} games)"


def main() -> None:
    """Run the series and the reversal count; write the report, the counts and the wall times."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--preset", default="soccer_server_1996")
    parser.add_argument("--games", type=int, default=34)
    parser.add_argument("--workers", type=int, default=2)
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--half-time", type=float, default=None, help="one half [s] (300)")
    parser.add_argument("--net", type=Path)
    parser.add_argument("--tree", type=Path)
    parser.add_argument(
        "--dither", help="seeds (e.g. 0,1): count baseline-v-baseline reversals only and stop"
    )
    parser.add_argument("--steady-turns", action="store_true")
    parser.add_argument(
        "--look", choices=("body", "neck"), default="body", help="the minds' look (issue 28)"
    )
    parser.add_argument(
        "--client",
        choices=("see", "cycle"),
        default="see",
        help="the minds' client: see-triggered or per-cycle (issue 28 item 3)",
    )
    parser.add_argument(
        "--net-domain",
        choices=("any", "trained"),
        default="any",
        help="where the layered team asks its net: any ball met, or inside its training domain",
    )
    parser.add_argument(
        "--receiver-half",
        choices=RECEIVER_HALVES,
        default="unknown",
        help="what the passer tells layer 2's tree of the receiver's half (issue 28 goal 4)",
    )
    parser.add_argument(
        "--transfer", action="store_true", help="net and tree trained on another preset"
    )
    parser.add_argument("--reversal-games", type=int, default=2, help="per side")
    parser.add_argument("--out", type=Path)
    parser.add_argument(
        "--before", type=Path, help="a finished series folder: print the paired change and stop"
    )
    args = parser.parse_args()
    minds: dict[str, Any] = {}
    if args.steady_turns:
        minds["steady_turns"] = True
    if args.look != "body":
        minds["look"] = args.look
    if args.client != "see":
        minds["client"] = args.client
    if args.net_domain != "any":
        minds["net_domain"] = args.net_domain
    if args.receiver_half != "unknown":
        minds["receiver_half"] = args.receiver_half
    if args.dither is not None:
        if args.half_time is not None:
            minds["half_time_s"] = args.half_time
        seeds = [int(seed) for seed in args.dither.split(",")]
        rows = dither(args.preset, seeds, minds)
        for g in rows:
            count = f"{g['reversals']:.0f} in {g['player_minutes']:.0f} player-minutes"
            rate = f"{g['per_player_minute']:.1f} reversals per player-minute ({count})"
            print(f"{args.preset} {minds or 'default'} seed {g['seed']}: {rate}")
        total = sum(g["reversals"] for g in rows) / sum(g["player_minutes"] for g in rows)
        print(f"all seeds: {total:.1f} reversals per player-minute")
        return
    if args.net is None or args.tree is None or args.out is None:
        parser.error("a series needs --net, --tree and --out")
    if args.before is not None:
        print(
            f"goal difference, {args.out} - {args.before}: {paired_change(args.before, args.out)}"
        )
        return
    if args.games < 2 or args.reversal_games < 0 or args.workers < 1:
        parser.error("--games must be >= 2, --reversal-games >= 0, --workers >= 1")
    for path in (args.net, args.tree):
        if not path.is_file():
            parser.error(f"no such file: {path}")
    options: dict[str, Any] = {"players": 0, "net": str(args.net), "tree": str(args.tree)}
    if args.half_time is not None:
        options["half_time_s"] = args.half_time
    options.update(minds)
    if args.transfer:
        options["transfer"] = True
    base = match_base("soccer_server", args.preset, args.seed, args.net, args.tree)
    base = base.with_options(**options)
    args.out.mkdir(parents=True, exist_ok=True)
    start = time.perf_counter()
    games = run_series(base, args.games, args.out, workers=args.workers, progress=False)
    series_s = time.perf_counter() - start
    which = "steady turns" if args.steady_turns else "default minds"
    if args.look == "neck":
        which = "looking with the neck (and steady turns)"
    if args.client == "cycle":
        which += ", per-cycle client"
    if args.net_domain == "trained":
        which += ", net asked inside its training domain only"
    if args.receiver_half != "unknown":
        which += f", receiver's half {args.receiver_half}"
    title = f"Layered vs baseline on soccer_server ({args.preset}), seed {args.seed}, {which}"
    write_report(games, args.out, title, print)
    start = time.perf_counter()
    counted = [
        reversals(spec, index)
        for spec in series_specs(base)
        for index in range(args.reversal_games)
    ]
    totals: dict[str, dict[str, float]] = {}
    for game in counted:
        for name, c in game["by_kind"].items():
            t = totals.setdefault(name, {"reversals": 0, "player_minutes": 0.0})
            t["reversals"] += c["reversals"]
            t["player_minutes"] += c["player_minutes"]
    for name, t in totals.items():
        t["per_player_minute"] = t["reversals"] / t["player_minutes"]
        print(f"{name}: {t['per_player_minute']:.1f} reversals per player-minute "
              f"({t['reversals']:.0f} in {t['player_minutes']:.0f} player-minutes)")  # fmt: skip
    summary = {
        "options": options,
        "preset": args.preset,
        "games": args.games,
        "series_wall_s": series_s,
        "reversal_games_per_side": args.reversal_games,
        "reversal_wall_s": time.perf_counter() - start,
        "reversals": totals,
        "reversal_games": counted,
    }
    (args.out / "reversals.json").write_text(json.dumps(summary, indent=2) + "\n")
    print(f"series {series_s:.0f} s; report: {args.out}")


if __name__ == "__main__":
    main()
