"""Layer 3's study: train TPOT-RL against the baseline, then series against both fixed teams.

**Training** (:func:`train`). The layer-3 team (:mod:`robotsoccer.skills.layer3`) plays
:attr:`TeamPlan.training_games` matches against the baseline in *rounds* of
:attr:`TeamPlan.games_per_round` games, half with it on each side. Within a round every game
uses the same table (the one saved after the last round) and the round's exploration rate; the
games record each reward they fix, and after the round the table averages them in, game by
game in index order, left-side games first. So the tables depend on the seed and the plan, not
on how many workers played the games (the determinism test). A round's exploration rate is
:func:`learning.tpot.epsilon_at` of its first game, linear from
:attr:`TeamPlan.epsilon_start` to :attr:`TeamPlan.epsilon_end`.

Each round's games are the match drill's trials (seed ``seed * ROUND_SEED_STRIDE + round``,
trial index = the game's place in its side's share of the round), played by one pool of worker
processes kept for the whole training, so the workers keep what they loaded (the layers, the
field's launch plan) from round to round. Every game goes to ``train/games.json`` with its
goals and how many rewards it fixed; the table each round played is
``train/tables/round_<r>_in.npz``, and the last one is ``models/<field>/tpot_table.npz`` with
its provenance (seed, games, plan, code version, the tree's and net's digests).

**Learning curves**: goals for and against per training game, in blocks of games with 95%
intervals (table and plot).

**Series**: :func:`robotsoccer.experiments.match.run_series` of the layer-3 team (greedy: no
exploration) against the fixed layered team and against the baseline, half the games on each
side, with the series report of :mod:`robotsoccer.experiments.match`.
"""

from __future__ import annotations

import json
import signal
import time
from collections.abc import Callable, Sequence
from concurrent.futures import ProcessPoolExecutor
from dataclasses import asdict, dataclass
from pathlib import Path
from typing import Any

from field_models.protocol import LEFT, RIGHT
from learning.tpot import (
    ALPHA_MIN,
    FEATURE_VALUES,
    HORIZON_S,
    TpotTable,
    epsilon_at,
    load_table,
    save_table,
    update,
)
from robotsoccer.drills.match import layer3_experiences
from robotsoccer.drills.match_setup import FORMATIONS
from robotsoccer.experiments.match import (
    Game,
    game_from,
    mean_interval,
    run_series,
    series_specs,
    summary_lines,
)

# The plans live in team_plan; re-exported here, where the CLI and the tests find them.
from robotsoccer.experiments.team_plan import EVERY_PLAN as EVERY_PLAN
from robotsoccer.experiments.team_plan import FULL_PLAN as FULL_PLAN
from robotsoccer.experiments.team_plan import QUICK_PLAN as QUICK_PLAN
from robotsoccer.experiments.team_plan import TeamPlan as TeamPlan
from robotsoccer.experiments.team_plan import plan_for as plan_for
from robotsoccer.runs.pool import worker_context
from robotsoccer.runs.provenance import code_version, file_digest
from robotsoccer.runs.runner import TrialResult, TrialSpec, run_trial
from robotsoccer.skills.layer3 import DESTINATIONS

ROUND_SEED_STRIDE = 1_000_003
"""Round r of a study with seed s plays trial seeds s * stride + r (distinct per round)."""
OPPONENTS = ("layered", "baseline")
"""The fixed teams the trained layer-3 team meets in the closing series."""


@dataclass(frozen=True, slots=True)
class TrainingGame:
    """One training game from the layer-3 team's side.

    Attributes:
        index: Its place in the training series (0 first).
        epsilon: Its exploration rate.
        goals_for: Goals the layer-3 team scored.
        goals_against: Goals it conceded.
        experiences: Rewards it fixed.
    """

    index: int
    epsilon: float
    goals_for: float
    goals_against: float
    experiences: int


@dataclass(frozen=True, slots=True)
class Training:
    """What :func:`train` returns.

    Attributes:
        table: The learned table.
        path: Where it was saved.
        games: The training games in order.
        wall_s: Training's wall time [s].
    """

    table: TpotTable
    path: Path
    games: list[TrainingGame]
    wall_s: float


def match_base(
    field: str,
    preset: str | None,
    seed: int,
    net: Path,
    tree: Path,
    players: int = 0,
) -> TrialSpec:
    """A ``match`` spec with the layered team's files (sides, table and halves set later)."""
    return TrialSpec(drill="match", field_model=field, preset=preset, seed=seed).with_options(
        net=str(net), tree=str(tree), players=players
    )


def _features_tree(plan: TeamPlan) -> dict[str, str]:
    """Layer 3's own tree and its digest, for the table's provenance (none: the team's)."""
    if not plan.features_tree:
        return {}
    return {"features_tree_digest": file_digest(plan.features_tree)}


def train(
    base: TrialSpec,
    plan: TeamPlan,
    out: Path,
    *,
    workers: int,
    log: Callable[[str], None],
) -> Training:
    """Learn a layer-3 table against the baseline (module docstring) into `out`."""
    options = dict(base.drill_options) | plan.drill_options()
    net, tree = str(options["net"]), str(options["tree"])
    players = int(options.get("players", 0) or 0) or 11
    if players not in FORMATIONS:
        raise ValueError(f"no formation for {players} players a side")
    provenance = {
        "method": "TPOT-RL (Stone & Veloso 1999)",
        "field": base.field_model,
        "preset": base.preset_name,
        "seed": base.seed,
        "plan": plan.to_dict(),
        "opponent": "baseline",
        "code_version": code_version(),
        "tree": tree,
        "tree_digest": file_digest(tree),
        "net": net,
        "net_digest": file_digest(net),
        **_features_tree(plan),
        "alpha_min": ALPHA_MIN,
        "horizon_s": HORIZON_S,
        "reward_window": plan.window,
        "feature_values": list(FEATURE_VALUES),
        "destinations": [d[0] for d in DESTINATIONS],
    }
    table = TpotTable.empty(players, provenance | {"games": 0})
    tables = out / "train" / "tables"
    tables.mkdir(parents=True, exist_ok=True)
    played: list[TrainingGame] = []
    start = time.perf_counter()
    with _Games(workers) as pool:
        for r in range(plan.rounds):
            _train_round(base, plan, r, table, tables, pool, played, options)
            log(
                f"  round {r + 1}/{plan.rounds}: {len(played)} games, "
                f"epsilon {played[-1].epsilon:.3f}, {int(table.n.sum())} updates"
            )
    wall = time.perf_counter() - start
    field_dir = out / "models" / base.field_model
    field_dir.mkdir(parents=True, exist_ok=True)
    table.provenance["training_wall_s"] = round(wall, 1)
    table.provenance["workers"] = workers
    path = save_table(table, field_dir / "tpot_table.npz")
    return Training(table, path, played, wall)


class _Games:
    """Plays games (``run_trial``) in this process or in one pool kept across rounds."""

    def __init__(self, workers: int) -> None:
        self.workers = workers
        self.pool: ProcessPoolExecutor | None = None

    def __enter__(self) -> _Games:
        if self.workers > 1:
            self.pool = ProcessPoolExecutor(
                max_workers=self.workers, mp_context=worker_context(), initializer=_quiet
            )
        return self

    def __exit__(self, *exc: object) -> None:
        if self.pool is not None:
            self.pool.shutdown(cancel_futures=True)

    def play(self, games: list[tuple[TrialSpec, int]]) -> list[TrialResult]:
        """The results of `games` (spec, trial index), in their order."""
        if self.pool is None:
            return [run_trial(spec, i) for spec, i in games]
        futures = [self.pool.submit(run_trial, spec, i) for spec, i in games]
        return [f.result() for f in futures]


def _quiet() -> None:
    """Workers leave Ctrl-C to the parent."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)


def _train_round(
    base: TrialSpec,
    plan: TeamPlan,
    r: int,
    table: TpotTable,
    tables: Path,
    pool: _Games,
    played: list[TrainingGame],
    options: dict[str, Any],
) -> None:
    """Round `r`: its games with the current table, then their rewards into it (in order)."""
    first = r * plan.games_per_round
    n = min(plan.games_per_round, plan.training_games - first)
    epsilon = epsilon_at(first, plan.training_games, plan.epsilon_start, plan.epsilon_end)
    current = save_table(table, tables / f"round_{r:04d}_in.npz")
    spec = TrialSpec(
        drill=base.drill,
        field_model=base.field_model,
        preset=base.preset,
        seed=base.seed * ROUND_SEED_STRIDE + r,
        field=base.field,
    ).with_options(
        **(
            options
            | {"tpot": str(current), "explore": epsilon, "learn": True,
               "half_time_s": plan.half_time_s}
        )
    )  # fmt: skip
    left, right = series_specs(spec, ("layer3", "baseline"))
    games = [(left, i) for i in range((n + 1) // 2)] + [(right, i) for i in range(n // 2)]
    for (side_spec, _), result in zip(games, pool.play(games), strict=True):
        on_left = side_spec is left
        game = game_from(result, on_left)
        team = LEFT if on_left else RIGHT
        mine = [e for t, e in layer3_experiences(result.data) if t == team]
        for experience in mine:
            update(table, experience)
        played.append(
            TrainingGame(
                len(played), epsilon, game.layered["goals"], game.baseline["goals"], len(mine)
            )
        )
    table.provenance["games"] = len(played)


# ----------------------------------------------------------------------------- reports


def curve_rows(games: Sequence[TrainingGame], block: int) -> list[tuple[str, str, str, str]]:
    """Per block of training games: (games, epsilon, goals for, goals against), with intervals."""
    rows = []
    for i in range(0, len(games), block):
        chunk = games[i : i + block]
        gf = mean_interval([g.goals_for for g in chunk]).text()
        ga = mean_interval([g.goals_against for g in chunk]).text()
        eps = f"{chunk[0].epsilon:.3f}–{chunk[-1].epsilon:.3f}"
        rows.append((f"{chunk[0].index + 1}–{chunk[-1].index + 1}", eps, gf, ga))
    return rows


def plot_curve(games: Sequence[TrainingGame], block: int, path: Path) -> Path | None:
    """Goals for and against per block of training games, with 95% intervals."""
    try:
        from robotsoccer.experiments.plots import _pyplot, _save, error_bars
    except ImportError:  # pragma: no cover - matplotlib is a dependency
        return None
    plt = _pyplot()
    fig, ax = plt.subplots(figsize=(6.4, 4.0))
    for name, key, colour in (
        ("goals for (layer 3)", "goals_for", "tab:blue"),
        ("goals against (baseline)", "goals_against", "tab:red"),
    ):
        xs, ys, lo, hi = [], [], [], []
        for i in range(0, len(games), block):
            chunk = games[i : i + block]
            m = mean_interval([getattr(g, key) for g in chunk])
            xs.append(chunk[-1].index + 1)
            ys.append(m.value)
            lo.append(m.low)
            hi.append(m.high)
        ax.errorbar(xs, ys, yerr=error_bars(ys, lo, hi), marker="o", capsize=3, label=name,
                    color=colour)  # fmt: skip
    ax.set_xlabel("training games played")
    ax.set_ylabel("goals per game (block mean, 95% interval)")
    ax.set_title("Layer 3 (TPOT-RL) against the baseline while learning")
    ax.legend()
    return _save(plt, fig, path)


def table_lines(table: TpotTable) -> list[str]:
    """The learned Q(p, SUCCESS, a) per position and destination, and the counts behind them."""
    names = [d[0] for d in DESTINATIONS]
    lines = [
        "| position | " + " | ".join(names) + " |",
        "|---" * (len(names) + 1) + "|",
    ]
    for p in range(table.positions):
        cells = [f"{table.q[p, 0, a]:+.2f} ({int(table.n[p, 0, a])})" for a in range(len(names))]
        lines.append(f"| {p + 1} | " + " | ".join(cells) + " |")
    return lines


def feature_line(table: TpotTable) -> str:
    """How many rewards each value of e(s, a) got (|U| = 3 in use, or not)."""
    per = table.n.sum(axis=(0, 2))
    total = int(per.sum())
    parts = ", ".join(
        f"{name} {int(k)} ({100 * k / total:.1f} %)" if total else f"{name} 0"
        for name, k in zip(FEATURE_VALUES, per, strict=True)
    )
    return f"Rewards by the chosen action's feature e(s, a) ({total} in all): {parts}."


def series_section(
    games: Sequence[Game], opponent: str, plan: TeamPlan, wall_s: float
) -> list[str]:
    """One closing series' report lines (the match report's own, renamed)."""
    half = plan.series_half_time_s
    title = f"Layer 3 against the {opponent} team ({len(games)} games, 2 × {half:g} s)"
    lines = summary_lines(games, title, ("layer3", opponent))
    lines[0] = "### " + lines[0].removeprefix("# ")
    return [*lines, "", f"Series wall time: {wall_s:.0f} s.", ""]


def run_team_study(
    base: TrialSpec,
    plan: TeamPlan,
    out: Path,
    *,
    workers: int,
    log: Callable[[str], None],
    resume: bool = False,
    progress: bool = False,
    table: Path | None = None,
) -> Path:
    """Train (or take `table`), plot, play the series; write ``<out>/report.md``."""
    base = base.with_options(**plan.drill_options())
    lines = [f"## Layer 3: TPOT-RL on {base.field_model} ({plan.name} plan), seed {base.seed}", ""]
    if plan.guard or plan.loss or plan.features_tree:
        features = f"`{Path(plan.features_tree).name}`" if plan.features_tree else "the team's"
        lines += [
            f"Rule: every spell on the ball, SUCCESS cut {plan.success:g}, reward window "
            f"`{plan.window}`, shot-range guard {'on' if plan.guard else 'off'}, loss penalty "
            f"{plan.loss:g}, features from {features} tree (`robotsoccer/skills/layer3.py`).",
            "",
        ]
    if table is None:
        log(f"training: {plan.training_games} games against the baseline")
        training = train(base, plan, out, workers=workers, log=log)
        table_path, learned = training.path, training.table
        games = training.games
        total = sum(g.experiences for g in games)
        lines += [
            f"Trained over {len(games)} games (2 × {plan.half_time_s:g} s) against the baseline "
            f"in {plan.rounds} rounds of {plan.games_per_round}, epsilon-greedy from "
            f"{plan.epsilon_start:g} to {plan.epsilon_end:g}: {total} rewards "
            f"({total / max(len(games), 1):.1f} a game), {training.wall_s:.0f} s wall time with "
            f"{workers} worker(s). Table: `{table_path}`.",
            "",
            "| training games | epsilon | goals for (layer 3) | goals against (baseline) |",
            "|---|---|---|---|",
        ]
        lines += [
            f"| {a} | {b} | {c} | {d} |" for a, b, c, d in curve_rows(games, plan.curve_block)
        ]
        plot = plot_curve(games, plan.curve_block, out / "plots" / "layer3_curve.png")
        if plot is not None:
            lines += ["", f"![learning curve]({plot.relative_to(out)})"]
        (out / "train" / "games.json").write_text(
            json.dumps([asdict(g) for g in games], indent=1) + "\n"
        )
    else:
        table_path, learned = table, load_table(table)
        lines += [f"Table given: `{table}` (provenance: {json.dumps(learned.provenance)})."]
    lines += ["", feature_line(learned)]
    lines += ["", "Learned Q(position, SUCCESS, destination) (updates in brackets):", ""]
    lines += table_lines(learned)
    lines.append("")
    series_base = base.with_options(tpot=str(table_path), half_time_s=plan.series_half_time_s)
    if plan.series_games:
        for opponent in OPPONENTS:
            log(f"series: layer 3 against the {opponent} team, {plan.series_games} games")
            t0 = time.perf_counter()
            games_played = run_series(
                series_base,
                plan.series_games,
                out / f"series-vs-{opponent}",
                workers=workers,
                resume=resume,
                progress=progress,
                teams=("layer3", opponent),
            )
            lines += series_section(games_played, opponent, plan, time.perf_counter() - t0)
    report = out / "report.md"
    report.write_text("\n".join(lines) + "\n")
    return report
