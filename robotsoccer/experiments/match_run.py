"""``robotsoccer match`` as a pipeline: one match, or a series with its report.

The CLI (:mod:`robotsoccer.cli.commands.match`) only reads its options into a
:class:`MatchRun` and prints what :func:`run_match` returns; which layers play, the drill's
options, the run folder, ``config.json``, the games and the recordings are decided here.

A *series* (more than one game) is the layered team against the baseline, or with layer 3 the
two kinds named, half the games on each side (:func:`robotsoccer.experiments.match.run_series`),
with ``report.md``. *One match* plays the two kinds named, into ``results.csv``. The layered
team's files are found by :class:`LayerFiles` (given, or the newest in a run folder), a layer-3
team's options by :func:`layer3_options` (how its table learned).
"""

from __future__ import annotations

import json
import time
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from field_models.arena import FieldOptions
from field_models.registry import DEFAULT_OPTIONS, default_preset
from robotsoccer.experiments.context import RunInterrupted
from robotsoccer.experiments.match import Game, run_series, write_report
from robotsoccer.runs.folders import prepare_run_folder
from robotsoccer.runs.pool import default_workers, run_trials
from robotsoccer.runs.runner import DrillOption, TrialResult, TrialSpec, check_spec

MATCH_FLAGS = frozenset({"left", "right", "players", "half_time_s", "net", "tree", "tpot"})
"""Match options the command sets from its own flags, so ``--option`` may not name them."""


@dataclass(frozen=True)
class LayerFiles:
    """Where the layered team's net and tree come from.

    Attributes:
        net: Layer 1's net (.npz); None: the newest in the models folder.
        tree: Layer 2's pass tree (.json); None: the one in the models folder.
        models: A run folder with ``models/<field>/``; None: the first of
            ``runs/reproduce-seed<S>`` and ``runs/transfer-seed<S>`` that has them.
    """

    net: Path | None = None
    tree: Path | None = None
    models: Path | None = None

    def find(self, field: str, seed: int) -> tuple[Path, Path]:
        """The net and tree on `field` for experiment `seed`: given, or found in a run folder.

        Raises:
            ValueError: None found (the message says how to make them).
        """
        if self.net is not None and self.tree is not None:
            return self.net, self.tree
        folders = (
            [self.models]
            if self.models is not None
            else [Path("runs") / f"{kind}-seed{seed}" for kind in ("reproduce", "transfer")]
        )
        for folder in folders:
            models = folder / "models" / field
            nets = sorted(models.glob("net_*.npz"), key=lambda p: _net_size(p.stem))
            tree = models / "pass_tree.json"
            if nets and tree.exists():
                return self.net or nets[-1], self.tree or tree
        where = ", ".join(str(f / "models" / field) for f in folders)
        raise ValueError(
            f"no trained layers for {field} in {where}: run `robotsoccer transfer "
            f"--no-ablations --no-gap-closing` first, or give --net and --tree"
        )


def _net_size(stem: str) -> int:
    tail = stem.rpartition("_")[2]
    return int(tail) if tail.isdigit() else -1


def layer3_options(table: Path | None) -> dict[str, Any]:
    """The match drill's options for a layer3 team playing `table`.

    The table's provenance says how it learned (every spell on the ball or only where blocked,
    its SUCCESS cut, its reward window, shot-range guard and loss penalty); it plays the same
    way.

    Raises:
        ValueError: No table given, or not a readable TPOT-RL table
            (:func:`learning.tpot.load_table`'s one line), or one of another game's actions.
    """
    from learning.tpot import N_ACTIONS, load_table
    from robotsoccer.drills.match_options import PASS_THRESHOLD

    if table is None:
        raise ValueError(
            "a layer3 team needs its table: --tpot FILE (from `robotsoccer learn team`)"
        )
    learned = load_table(table)
    if learned.actions != N_ACTIONS:
        raise ValueError(
            f"{table}: a table of {learned.actions} actions, not the match's {N_ACTIONS} ball "
            "destinations (a half-field offense table?)"
        )
    plan = learned.provenance.get("plan", {})
    plan = plan if isinstance(plan, dict) else {}
    options: dict[str, Any] = {
        "tpot": str(table),
        "tpot_every": bool(plan.get("every", False)),
        "tpot_success": float(plan.get("success", PASS_THRESHOLD)),
        "tpot_window": str(plan.get("window", "choice")),
    }
    # Named only when set, as the study names them (team_study.TeamPlan.drill_options).
    if plan.get("guard", False):
        options["tpot_guard"] = True
    if plan.get("loss", 0.0):
        options["tpot_loss"] = float(plan["loss"])
    if plan.get("features_tree"):
        options["tpot_tree"] = str(plan["features_tree"])
    return options


@dataclass(frozen=True)
class MatchRun:
    """What ``robotsoccer match`` plays, and where.

    Attributes:
        field: The field model.
        preset: Its preset; None: the model's default.
        seed: The experiment seed.
        games: 1: one match of `left` against `right`; more: a series (sides swap).
        left: One match: the left team's kind (:data:`robotsoccer.cli.options.TEAM_KINDS`).
        right: ... the right team's.
        players: Players a side (0: the field's full side).
        half_time_s: One half [s]; None: the drill's.
        layers: Where the layered team's files come from (needed by a series, a layered or a
            layer3 team).
        tpot: Layer 3's table, for a layer3 team.
        options: Further match options for both teams' minds, (name, value) pairs in the order
            given (a later one of a name wins); none may name :data:`MATCH_FLAGS`.
        field_options: Settings changed on the field model.
        record: Record the first game of each side (a rerun recording, on the server's pitch
            an ``.rcg`` game log too).
        out: The run folder; None: ``runs/<match|series>-<field>-<preset>-seed<S>``.
        resume: Continue the run in `out`.
        overwrite: Replace the run in `out`.
        workers: A series' processes (None: all cores); one match plays in this process.
        progress: Show progress.
    """

    field: str
    preset: str | None = None
    seed: int = 0
    games: int = 1
    left: str = "layered"
    right: str = "baseline"
    players: int = 0
    half_time_s: float | None = None
    layers: LayerFiles = LayerFiles()
    tpot: Path | None = None
    options: tuple[tuple[str, DrillOption], ...] = ()
    field_options: FieldOptions = DEFAULT_OPTIONS
    record: bool = False
    out: Path | None = None
    resume: bool = False
    overwrite: bool = False
    workers: int | None = None
    progress: bool = True

    @property
    def preset_name(self) -> str:
        """The preset (resolved: never None)."""
        return self.preset or default_preset(self.field)

    @property
    def folder(self) -> Path:
        """The run folder: `out`, or one named after the kind, field, preset and seed."""
        kind = "series" if self.games > 1 else "match"
        default = f"{kind}-{self.field}-{Path(self.preset_name).stem}-seed{self.seed}"
        return self.out or Path("runs") / default

    @property
    def teams(self) -> tuple[str, str]:
        """A series' two kinds: layered against baseline, or with layer 3 the two named."""
        return (self.left, self.right) if self.layer3 else ("layered", "baseline")

    @property
    def layer3(self) -> bool:
        """A layer3 team plays (it needs its table)."""
        return "layer3" in (self.left, self.right)

    def match_options(self) -> dict[str, Any]:
        """The match drill's options (sides set later): players, halves, layers, ``--option``.

        Raises:
            ValueError: No layers found, no or a bad layer-3 table, a table without a layer3
                team, or an ``--option`` that has its own flag.
        """
        options: dict[str, Any] = {"players": self.players}
        if self.half_time_s is not None:
            options["half_time_s"] = self.half_time_s
        if self.games > 1 or "layered" in (self.left, self.right) or self.layer3:
            net, tree = self.layers.find(self.field, self.seed)
            options |= {"net": str(net), "tree": str(tree)}
        if self.layer3:
            options |= layer3_options(self.tpot)
        elif self.tpot is not None:
            raise ValueError("--tpot is layer 3's table: name layer3 in --left or --right")
        extra = dict(self.options)
        flagged = sorted(set(extra) & (set(options) | MATCH_FLAGS))
        if flagged:
            raise ValueError(
                f"--option {flagged[0]}: it has its own flag (see robotsoccer match -h)"
            )
        return options | extra


@dataclass(frozen=True)
class MatchOutcome:
    """What a match or a series left: its folder, the games, and the lines to show.

    Attributes:
        out: The run folder.
        games: A series' games (empty after one match).
        result: One match's result (None after a series).
        lines: What the command prints: the series' report and its time, or the match's
            result and measures; then where the recordings are.
    """

    out: Path
    games: tuple[Game, ...]
    result: TrialResult | None
    lines: tuple[str, ...]


def run_match(request: MatchRun) -> MatchOutcome:
    """Check the request, prepare the run folder, play the match or the series.

    Every option is checked (trial 0 set up) before the folder is touched.

    Raises:
        ValueError: A bad option, preset, layer file or table, or a run folder in the way (one
            line each).
        RunInterrupted: Ctrl-C during a series; its finished games are kept.
    """
    options = request.match_options()
    out = request.folder
    record_dir = out / "recordings" if request.record else None
    base = TrialSpec(
        drill="match",
        field_model=request.field,
        preset=request.preset,
        seed=request.seed,
        field=request.field_options,
        record_dir=str(record_dir) if record_dir else None,
        record_trials=1 if request.record else 0,
    ).with_options(**options)
    games: list[Game] = []
    result: TrialResult | None = None
    if request.games > 1:
        games, lines = _series(request, base, options, out)
    else:
        result, lines = _one_match(request, base, out)
    if record_dir is not None:
        lines.append(f"recordings: {record_dir}/ (open with: robotsoccer replay FILE)")
    return MatchOutcome(out, tuple(games), result, tuple(lines))


def _series(
    request: MatchRun, base: TrialSpec, options: dict[str, Any], out: Path
) -> tuple[list[Game], list[str]]:
    """A series into `out` with ``config.json`` and ``report.md``; the games and the lines."""
    check_spec(base)
    prepare_run_folder(out, resume=request.resume, overwrite=request.overwrite)
    preset = request.preset_name
    config = {"command": "robotsoccer match", "games": request.games, "field": request.field,
              "preset": preset, "seed": request.seed, "options": options}  # fmt: skip
    (out / "config.json").write_text(json.dumps(config, indent=2) + "\n")
    teams = request.teams
    start = time.perf_counter()
    try:
        games = run_series(
            base, request.games, out, workers=request.workers or default_workers(),
            resume=request.resume, progress=request.progress, teams=teams,
        )  # fmt: skip
    except KeyboardInterrupt:
        raise RunInterrupted(f"interrupted; finished games are kept in {out}") from None
    title = (f"{teams[0].capitalize()} vs {teams[1]} on {request.field} "
             f"({Path(preset).stem}), seed {request.seed}")  # fmt: skip
    lines: list[str] = []
    write_report(games, out, title, lines.append, names=teams)
    lines.append(f"\n{len(games)} games in {time.perf_counter() - start:.1f} s; report: {out}")
    return games, lines


def _one_match(request: MatchRun, base: TrialSpec, out: Path) -> tuple[TrialResult, list[str]]:
    """One match of the two kinds named into ``<out>/results.csv``; its result and lines."""
    spec = base.with_options(left=request.left, right=request.right)
    check_spec(spec)
    prepare_run_folder(out, resume=request.resume, overwrite=request.overwrite)
    start = time.perf_counter()
    (result,) = run_trials(
        spec, 1, workers=1, results_path=out / "results.csv", resume=request.resume,
        progress=request.progress,
    )  # fmt: skip
    wall = time.perf_counter() - start
    lines = [
        f"{result.label}: {result.reason} ({result.time_s:.0f} simulated s in {wall:.1f} s)",
        *(f"  {name} = {value:g}" for name, value in result.measures),
    ]
    return result, lines
