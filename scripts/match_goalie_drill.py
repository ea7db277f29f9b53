"""Layer 1's goal-mouth drill with the match's goalie mind as the defender.

The robots' lead study (``robotsoccer learn lead``) measures layer 1 with its own defender mind
(:class:`~robotsoccer.skills.lead.LeadDefenderMind`). A match's goalie is a
:class:`~robotsoccer.skills.team.TeamMind` that also keeps a formation spot, holds its turns and
decides when to go for the ball. This runs the study's robot drill (``small_size_1997_arc``,
shots across the goal mouth at 0.6-1.2 m/s, ball noise .05, the study's evaluation seed) with
that goalie in the defender's place, with and without the lead net, beside the drill's own
defender, so the README can say how much of layer 1's gain the match's goalie keeps.

Usage::

    python scripts/match_goalie_drill.py LEAD_NET.npz [--trials N]
"""

from __future__ import annotations

import argparse
from collections import Counter

from field_models.protocol import RIGHT
from robotsoccer.drills.intercept_plan import DEFENDER
from robotsoccer.drills.match import MatchDrill
from robotsoccer.runs.runner import TrialSpec, build_trial, play
from robotsoccer.skills.intercept import load_net_function
from robotsoccer.skills.team import TeamMind
from robotsoccer.stats import wilson_interval

DRILL = (
    ("shot", "goal_mouth"),
    ("scaling", "task"),
    ("launch", "coach"),
    ("launch_speed_mps", 0.6),
    ("launch_speed_max_mps", 1.2),
    ("decision", "lead"),
)
"""The lead study's robot drill (``robotsoccer.cli.options.LEAD_DRILLS``)."""


def saves(net: str, trials: int, defender: str, lead: bool) -> Counter[str]:
    """Labels of `trials` drill trials with the ``drill`` or ``match`` defender."""
    behaviour = (("behaviour", "net"), ("model", net)) if lead else (("behaviour", "straight"),)
    spec = TrialSpec(
        "intercept", "robot_physics", "small_size_1997_arc", 0, drill_options=DRILL + behaviour
    ).with_field(ball_noise=0.05)
    labels: Counter[str] = Counter()
    for index in range(trials):
        rngs, drill, arena = build_trial(spec, index)
        drill.setup(arena, rngs)
        minds = drill.minds(arena, rngs)
        if defender == "match":
            setup = MatchDrill(left="baseline", right="baseline").team_setup(arena.facts, 2, RIGHT)
            policy = load_net_function(net, 1.0) if lead else None
            minds[DEFENDER] = TeamMind(1, setup, lead=policy)
        labels[play(arena, drill, minds).label] += 1
    return labels


def main() -> None:
    """Print the save share of each defender, with and without the lead net."""
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("net", help="the robots' lead net (.npz)")
    parser.add_argument("--trials", type=int, default=300)
    args = parser.parse_args()
    print("| defender | τ | saves | goals | misses | save share (95%) |")
    print("|---|---|---|---|---|---|")
    for defender in ("drill", "match"):
        for lead in (True, False):
            c = saves(args.net, args.trials, defender, lead)
            low, high = wilson_interval(c["SAVE"], args.trials)
            share = f"{100 * c['SAVE'] / args.trials:.1f} [{100 * low:.1f}, {100 * high:.1f}]"
            row = (defender, "net" if lead else "0", c["SAVE"], c["GOAL"], c["MISS"], share)
            print("| " + " | ".join(str(x) for x in row) + " |", flush=True)


if __name__ == "__main__":
    main()
