"""``robotsoccer learn intercept|pass|lead|team``: one layer's experiment.

The pipelines are in :mod:`robotsoccer.experiments.learn_run` (``intercept``, through
:func:`robotsoccer.experiments.reproduce.run_reproduce`; ``pass``; ``lead``) and
:mod:`robotsoccer.experiments.team_run` (``team``); each command reads its options into the
pipeline's request and prints the outcome.
"""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import TYPE_CHECKING

from field_models.registry import FIELD_MODELS
from robotsoccer.cli.options import DEFAULT_FIELD, LEAD_DRILLS, TEAM_FIELD, _positive_int
from robotsoccer.cli.running import clock_log, run_settings, show
from robotsoccer.cli.shared import Commands, Parser, experiment_options

if TYPE_CHECKING:
    from robotsoccer.experiments.learn_run import InterceptRun, LeadRun, PassRun
    from robotsoccer.experiments.team_run import TeamRun


def cmd_learn(args: argparse.Namespace) -> int:
    """``learn intercept``: layer 1 on one field model (and the other targets' dispatch)."""
    if args.target == "pass":
        return cmd_learn_pass(args)
    if args.target == "lead":
        return cmd_learn_lead(args)
    if args.target == "team":
        return cmd_learn_team(args)
    from robotsoccer.experiments.reproduce import run_reproduce

    return show(lambda: run_reproduce(intercept_request(args), clock_log()))


def intercept_request(args: argparse.Namespace) -> InterceptRun:
    """The run ``robotsoccer learn intercept``'s options ask for."""
    from robotsoccer.experiments.learn_run import InterceptRun

    return InterceptRun(
        field=args.field,
        preset=args.field_preset,
        client=args.client,
        **run_settings(args),
    )


def cmd_learn_pass(args: argparse.Namespace) -> int:
    """``learn pass``: layer 2 on one field model (collect → train → evaluate → report)."""
    from robotsoccer.experiments.learn_run import run_learn_pass

    return show(lambda: run_learn_pass(pass_request(args), clock_log()))


def pass_request(args: argparse.Namespace) -> PassRun:
    """The run ``robotsoccer learn pass``'s options ask for."""
    from robotsoccer.experiments.learn_run import PassRun

    return PassRun(
        field=args.field,
        preset=args.field_preset,
        net=args.net,
        client=args.client,
        **run_settings(args),
    )


def cmd_learn_lead(args: argparse.Namespace) -> int:
    """``learn lead``: layer 1's two decisions on one or both field models, with a report."""
    from robotsoccer.experiments.learn_run import run_learn_lead

    return show(lambda: run_learn_lead(lead_request(args), clock_log()))


def lead_request(args: argparse.Namespace) -> LeadRun:
    """The study ``robotsoccer learn lead``'s options ask for: one field's drill, or both."""
    from robotsoccer.experiments.lead_study import StudyDrill
    from robotsoccer.experiments.learn_run import LeadRun

    fields = [args.field] if args.field else list(LEAD_DRILLS)
    drills = tuple(StudyDrill(f, *LEAD_DRILLS[f]) for f in fields)
    return LeadRun(
        drills=drills,
        **run_settings(args),
    )


def cmd_learn_team(args: argparse.Namespace) -> int:
    """``learn team``: layer 3 (TPOT-RL) trained against the baseline, then the two series."""
    from robotsoccer.experiments.team_run import run_learn_team

    return show(lambda: run_learn_team(team_request(args), clock_log()))


def team_request(args: argparse.Namespace) -> TeamRun:
    """The study ``robotsoccer learn team``'s options ask for."""
    from robotsoccer.cli.commands.match import layer_files
    from robotsoccer.experiments.team_run import TeamRun

    return TeamRun(
        field=args.field,
        preset=args.field_preset,
        layers=layer_files(args),
        table=args.table,
        every=args.every,
        window=args.window,
        shot_guard=args.shot_guard,
        loss_penalty=args.loss_penalty,
        features_tree=args.features_tree,
        success=args.success_cut,
        games_per_round=args.games_per_round,
        training_games=args.training_games,
        **run_settings(args),
    )


def add_parser(commands: Commands) -> None:
    """``learn``'s targets and their options."""
    learn = commands.add("learn", "learn a layer: collect, train, evaluate, report")
    targets = learn.add_subparsers(dest="target", required=True, parser_class=Parser)
    common = [commands.common]
    intercept = targets.add_parser(
        "intercept", help="layer 1: the interception net (paper §5)", parents=common
    )
    intercept.add_argument(
        "--field", default=DEFAULT_FIELD, choices=FIELD_MODELS, help="field model"
    )
    intercept.add_argument(
        "--field-preset", default=None, help="preset name, .toml or server.conf (model's default)"
    )
    intercept.add_argument(
        "--client",
        default="see",
        choices=("see", "cycle"),
        help="the defender's client: see (the paper's: turn, then dash, at each see) or cycle "
        "(a command every cycle, issue 28)",
    )
    experiment_options(intercept)
    passing = targets.add_parser(
        "pass", help="layer 2: the pass-evaluation tree (paper §6)", parents=common
    )
    passing.add_argument("--field", default=DEFAULT_FIELD, choices=FIELD_MODELS, help="field model")
    passing.add_argument(
        "--field-preset", default=None, help="preset name, .toml or server.conf (model's default)"
    )
    passing.add_argument(
        "--net",
        type=Path,
        default=None,
        help="layer 1's interception net (.npz) for receivers and defenders (default: train it)",
    )
    passing.add_argument(
        "--client",
        default="see",
        choices=("see", "cycle"),
        help="the receivers' and defenders' client: see (the paper's: turn, then dash, at each "
        "see) or cycle (a command every cycle, issue 28)",
    )
    experiment_options(passing)
    lead = targets.add_parser(
        "lead",
        help="layer 1 with the lead decision beside the paper's turn angle, both field models",
        parents=common,
    )
    lead.add_argument(
        "--field",
        default=None,
        choices=FIELD_MODELS,
        help="one field model (default: both)",
    )
    experiment_options(lead)
    _team_parser(targets.add_parser(
        "team",
        help="layer 3: TPOT-RL's ball destinations learned in games against the baseline, "
        "then series against the layered team and the baseline",
        parents=common,
    ))  # fmt: skip


def _team_parser(team: argparse.ArgumentParser) -> None:
    """``learn team``'s options."""
    team.add_argument("--field", default=TEAM_FIELD, choices=FIELD_MODELS, help="field model")
    team.add_argument(
        "--field-preset", default=None, help="preset name, .toml or server.conf (model's default)"
    )
    team.add_argument("--net", type=Path, default=None, help="layer 1's net (.npz)")
    team.add_argument("--tree", type=Path, default=None, help="layer 2's pass tree (.json)")
    team.add_argument(
        "--models",
        type=Path,
        default=None,
        help="run folder with models/<field>/ holding the net and pass tree (as `match`)",
    )
    team.add_argument(
        "--table",
        type=Path,
        default=None,
        help="a learned layer-3 table (.npz): skip training, play the series only",
    )
    team.add_argument(
        "--every",
        action="store_true",
        help="TPOT-RL's own rule: the holder chooses a destination on every spell on the ball "
        "(shoot and keep included), not only where the layered team would ask the tree",
    )
    team.add_argument(
        "--window",
        choices=("choice", "horizon"),
        default="choice",
        help="when a reward closes: choice (also at the player's next choice, the first "
        "studies') or horizon (only at 30 s, a goal or play stopping: TPOT-RL's fixed window)",
    )
    team.add_argument(
        "--shot-guard",
        action="store_true",
        help="with --every: the goal is a shot only within the teams' shooting range, beyond "
        "it an advance toward the goal (a pass toward it, else a dribble)",
    )
    team.add_argument(
        "--loss-penalty",
        type=float,
        default=0.0,
        help="reward possession: an opponent's touch closes a choice's reward, which loses up "
        "to this much (0..1; default 0: the ball's advance alone)",
    )
    team.add_argument(
        "--features-tree",
        type=Path,
        default=None,
        help="layer 3's own pass tree for its features e(s, a) (default: --tree's; the team's "
        "other play keeps --tree), e.g. `learn pass`'s pass_tree_passer_only.json",
    )
    team.add_argument(
        "--success-cut",
        type=float,
        default=None,
        help="layer 3's SUCCESS cut on that tree's confidence, 0..1 (default: the plan's, "
        "0.95 with --every, else 0.5)",
    )
    team.add_argument(
        "--games-per-round",
        type=_positive_int,
        default=None,
        help="training games that share one table before it learns from them (default 4); "
        "up to this many play at once, so a many-core machine needs it at least its workers",
    )
    team.add_argument(
        "--training-games",
        type=_positive_int,
        default=None,
        help="training games instead of the plan's (400 with --every, 240 without)",
    )
    experiment_options(team)
