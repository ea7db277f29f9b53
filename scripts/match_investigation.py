"""Instrumented robot matches: where the goals come from, and what each team's layers did.

Plays matches of the ``match`` drill (layered against baseline, each trial index once with the
layered team on each side) and counts, per team, from the coach's truth:

* each goal by who touched the ball last (the scorers, or the conceding team: an own goal; the
  goalie or a field player) and what that player's mind was doing (its ``intent``), how far
  from the goal that touch was and how long before the goal;
* shots on target faced: the ball rolling into the team's goal mouth (its straight path
  crosses the goal line between the posts) from within 0.8 m, faster than 0.2 m/s; whether
  the goalie touched it, whether the goalie met it (``intercept``/``meet``), and the goals;
* decisions: spells of each intent (``intercept`` is layer 1's lead or net, ``meet`` the
  baseline's straight meeting), pass kicks and whether a teammate or an opponent touched the
  ball next, shot kicks and their outcome.

It prints one JSON line per game and then a summary with 95% Wilson intervals. Used for the
README's "Matches (measured)", "On the robots" (8 games: trial indices 0-3)::

    python scripts/match_investigation.py LEAD_NET.npz PASS_TREE.json --games 0,1,2,3
"""

from __future__ import annotations

import argparse
import json
import math
from collections import Counter, defaultdict
from typing import Any

from field_models.protocol import LEFT, RIGHT, Action, Percept, PlayerRef
from robotsoccer.drills.match import MatchDrill
from robotsoccer.runs.runner import TrialLoop, TrialSpec, build_trial
from robotsoccer.skills.team import TeamMind
from robotsoccer.stats import wilson_interval

WATCH_M = 0.8
"""A ball rolling into the goal mouth from within this of the goal line is a shot faced [m]."""
ROLLING_MPS = 0.2
"""... when faster than this [m/s]."""
NEAR_GOAL_M = 0.3
"""A goal's last touch this near the goal counts as near."""


def game(spec: TrialSpec, index: int, layered_left: bool) -> dict[str, Any]:
    """One instrumented game: the counts per team (``layered``, ``baseline``)."""
    sides = ("layered", "baseline") if layered_left else ("baseline", "layered")
    spec = spec.with_options(left=sides[0], right=sides[1])
    rngs, drill, arena = build_trial(spec, index)
    assert isinstance(drill, MatchDrill)
    drill.setup(arena, rngs)
    minds: dict[PlayerRef, TeamMind] = dict(drill.minds(arena, rngs))  # type: ignore[arg-type]
    kind = {LEFT: sides[0], RIGHT: sides[1]}
    goalie = {t: next(r for r in minds if r.team == t and minds[r].is_goalie) for t in kind}
    st: dict[str, Counter[str]] = defaultdict(Counter)
    ref = drill.referee
    assert ref is not None
    half_l = arena.facts.pitch.half_length_m
    half_goal = 0.5 * arena.facts.pitch.goal_width_m
    last: dict[str, Any] = {"touch": None, "intent": None, "xy": None, "tick": 0}
    faced: dict[str, dict[str, bool]] = {
        t: {"open": False, "touch": False, "met": False} for t in kind
    }
    pending: list[tuple[str, PlayerRef]] = []  # shots and passes awaiting the next toucher
    previous: dict[PlayerRef, str] = {}
    judge = drill.judge

    def decisions(percept: Percept, actions: tuple[Action, ...]) -> None:
        intent = minds[percept.player].intent.split()[0]
        if intent != previous.get(percept.player):
            st[kind[percept.player.team]]["spell_" + intent] += 1
            if intent in ("shoot", "pass"):
                pending.append((intent, percept.player))
        previous[percept.player] = intent

    def judged(a: Any) -> Any:
        before = ref.last_touch
        score0 = list(ref.score)
        bx, by, _, vx, vy = a.ball_state()
        verdict = judge(a)
        now = ref.last_touch
        if now is not None and now != before:
            mind = minds[now]
            last.update(touch=now, intent=mind.intent.split()[0], xy=(bx, by), tick=a.tick)
            keep = []
            for what, who in pending:
                if who == now:
                    keep.append((what, who))
                    continue
                team = kind[who.team]
                if what == "pass":
                    st[team]["pass_ok" if now.team == who.team else "pass_lost"] += 1
                else:
                    by_whom = "mate" if now.team == who.team else "opp"
                    st[team]["shot_touched_by_" + ("goalie" if mind.is_goalie else by_whom)] += 1
            pending[:] = keep
        scored = ref.score != score0
        for team in (LEFT, RIGHT):
            gx = -half_l if team == LEFT else half_l  # the team's own goal line
            at_goal = False
            if vx * gx > 0 and math.hypot(vx, vy) > ROLLING_MPS and abs(bx - gx) < WATCH_M:
                at_goal = abs(by + vy * (gx - bx) / vx) < half_goal
            f = faced[team]
            if at_goal and not f["open"]:
                f.update(open=True, touch=False, met=False)
                st[kind[team]]["shots_faced"] += 1
            if f["open"] and minds[goalie[team]].intent in ("meet", "intercept"):
                f["met"] = True
            if f["open"] and now is not None and now == goalie[team]:
                f["touch"] = True
            if f["open"] and not at_goal and not scored:
                f["open"] = False
                st[kind[team]]["faced_not_in"] += 1
                st[kind[team]]["met_not_in"] += f["met"]
                st[kind[team]]["faced_goalie_saved"] += f["touch"]
        if scored:
            conceded = RIGHT if ref.score[0] > score0[0] else LEFT
            scorer = LEFT if conceded == RIGHT else RIGHT
            f = faced[conceded]
            if f["open"]:
                st[kind[conceded]]["faced_conceded"] += 1
                st[kind[conceded]]["met_conceded"] += f["met"]
            else:
                st[kind[conceded]]["conceded_unfaced"] += 1
            f["open"] = False
            team = kind[scorer]
            toucher = last["touch"]
            if toucher is None:
                source = "none"
            elif toucher.team != scorer:
                role = "goalie" if minds[toucher].is_goalie else "field"
                source = f"own_{role}_{last['intent']}"
            else:
                source = f"by_{last['intent']}"
            st[team]["goal_" + source] += 1
            if last["xy"] is not None:
                gx = half_l if scorer == LEFT else -half_l
                distance = math.hypot(last["xy"][0] - gx, last["xy"][1])
                st[team]["goal_near"] += distance < NEAR_GOAL_M
                st[team]["goal_after_ds"] += round(10 * (a.tick - last["tick"]) * a.facts.dt_s)
            st[team]["shot_goal"] += sum(w == "shoot" and p.team == scorer for w, p in pending)
            pending.clear()
            last.update(touch=None, intent=None, xy=None)
        return verdict

    drill.judge = judged  # type: ignore[method-assign, assignment]
    verdict = TrialLoop(arena, drill, minds, None, decisions).run()  # type: ignore[arg-type]
    assert verdict is not None
    measures = drill.measures()
    for team, side in ((LEFT, "l"), (RIGHT, "r")):
        for figure in ("goals", "shots"):
            st[kind[team]][figure] += int(measures[f"{figure}_{side}"])
    return {"index": index, "layered_left": layered_left, "result": verdict.reason} | {
        k: dict(v) for k, v in st.items()
    }


def share(k: float, n: float) -> str:
    """``k/n`` in percent with its Wilson interval and n."""
    if n <= 0:
        return "n=0"
    low, high = wilson_interval(int(k), int(n))
    return f"{100 * k / n:.1f}% [{100 * low:.1f}, {100 * high:.1f}] (n={int(n)})"


def summary(games: list[dict[str, Any]]) -> list[str]:
    """Per-game means and shares for each team (module docstring)."""
    n = len(games)
    lines = [f"{n} games"]
    for team in ("layered", "baseline"):
        c: Counter[str] = Counter()
        for g in games:
            c.update(g.get(team, {}))
        own = sum(v for k, v in c.items() if k.startswith("goal_own"))
        passes = c["pass_ok"] + c["pass_lost"]
        lines += [
            f"{team}: goals/game {c['goals'] / n:.2f}; "
            f"own goals among them {share(own, c['goals'])}; last touch >= {NEAR_GOAL_M} m "
            f"from goal {share(c['goals'] - c['goal_near'], c['goals'])}; "
            f"shots on target faced/game {c['shots_faced'] / n:.1f}, conceded "
            f"{share(c['faced_conceded'], c['shots_faced'])}; met by the goalie and conceded "
            f"{share(c['met_conceded'], c['met_conceded'] + c['met_not_in'])}; "
            f"intercept spells/game {c['spell_intercept'] / n:.1f}, meet spells/game "
            f"{c['spell_meet'] / n:.1f}; pass kicks/game {passes / n:.2f}, completed "
            f"{share(c['pass_ok'], passes)}; shots/game {c['shots'] / n:.2f}"
        ]
    return lines


def main() -> None:
    """Play the games asked for and print their counts and the summary."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("net", help="the layered team's layer-1 net (.npz)")
    parser.add_argument("tree", help="its pass tree (.json)")
    parser.add_argument("--games", default="0,1,2,3", help="trial indices, comma-separated")
    parser.add_argument("--seed", type=int, default=0)
    parser.add_argument("--preset", default="small_size_1997_arc")
    args = parser.parse_args()
    spec = TrialSpec("match", "robot_physics", args.preset, args.seed).with_options(
        net=args.net, tree=args.tree
    )
    games = []
    for index in (int(i) for i in args.games.split(",")):
        for layered_left in (True, False):
            games.append(game(spec, index, layered_left))
            print(json.dumps(games[-1]), flush=True)
    print("\n".join(summary(games)))


if __name__ == "__main__":
    main()
