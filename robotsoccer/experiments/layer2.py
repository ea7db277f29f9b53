"""Layer 2 end to end: collect passes, train the tree, run Table 2's conditions, report (§6).

The pipeline for one field model, on top of layer 1's net from the same run:

1. :func:`collect_passes` — the pass drill (:mod:`robotsoccer.drills.passing`) with a random
   receiver: the plan's trials (paper: 5000). Each trial that passed becomes a row of 174
   attributes and the coach's label, saved as a :class:`~learning.pass_dataset.PassDataset`
   with its provenance.
2. :func:`~robotsoccer.experiments.layer2_training.train_tree` — the C4.5-like tree
   (:func:`learning.pass_tree_grow.fit_pass_tree`), saved as JSON with its provenance: its node
   count and training error go beside the paper's 87 nodes and 26%, and its first levels are
   printed in Figure 14's style (the learning steps:
   :mod:`robotsoccer.experiments.layer2_training`).
3. The test conditions (:func:`layer2_conditions`), the plan's trials each (paper: 5000), on one
   evaluation seed, so trial i places every player identically whatever the chooser (paired):
   the tree forced to pass (Table 2), a random receiver, the closest teammate, the analytic
   evaluator (beyond the paper) and the tree with the defenders standing still.
   "Pass only when confidence > .8" is the tree run's trials above .8, as in the paper.
4. :func:`layer2_markdown` — Table 2 and the comparison rows with n and 95% intervals beside the
   paper's numbers, the reliability of the tree's confidence, and what this run measured where
   we differ.

Seeds: collection uses the run's derived collection seed, evaluation the experiment seed
(:func:`robotsoccer.experiments.layer1_plan.seeds_for`), so the tree is never tested on its own
placements.
"""

from __future__ import annotations

import dataclasses
import math
import time
from collections import Counter
from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from learning.pass_dataset import PassDataset
from learning.pass_tree import LABELS, PassTree
from robotsoccer.experiments import paper
from robotsoccer.experiments.context import Field, RunContext
from robotsoccer.experiments.layer1_evaluate import evaluate
from robotsoccer.experiments.layer1_plan import Condition
from robotsoccer.experiments.layer2_training import (
    dataset_from,
    passer_half_only,
    passes,
    tests_by_side,
    train_boost,
    train_tree,
)
from robotsoccer.experiments.report_cells import (
    paired_difference,
    percent_cell,
    versus_cell,
    versus_paper,
)
from robotsoccer.experiments.report_records import StageTiming
from robotsoccer.experiments.report_tables import field_setting
from robotsoccer.runs.runner import TrialResult, TrialSpec
from robotsoccer.stats import reliability

DRILL = "pass"
RELIABILITY_BINS = tuple(round(0.1 * k, 1) for k in range(11))
"""Bins of the reliability table and plot: tenths of confidence."""


@dataclass(frozen=True)
class Layer2Plan:
    """What a layer-2 run does on each field model.

    Attributes:
        name: ``"quick"``, ``"full"`` or a free name (tests).
        collect_trials: Training trials with a random receiver (paper: 5000).
        eval_trials: Trials per test condition (paper: 5000).
        confident: The "pass only when confident" threshold (paper: .8).
        tree_depth_shown: Levels of the tree printed in the report.
        client: The receivers' and defenders' client in every trial, collection and tests:
            ``see`` (the paper's) or ``cycle`` (the per-cycle client, issue 28; the pass
            drill's option ``client``).
    """

    name: str
    collect_trials: int
    eval_trials: int
    confident: float = 0.8
    tree_depth_shown: int = 4
    client: str = "see"

    def to_dict(self) -> dict[str, Any]:
        """The plan as plain JSON types."""
        return dataclasses.asdict(self)


def layer2_plan(quick: bool) -> Layer2Plan:
    """The paper's 5000 and 5000, or a quick 1000 and 500."""
    if quick:
        return Layer2Plan("quick", collect_trials=1000, eval_trials=500)
    return Layer2Plan("full", collect_trials=paper.LAYER2_TRIALS, eval_trials=paper.LAYER2_TRIALS)


@dataclass
class Layer2Section:
    """Everything the report shows for one field model's layer 2."""

    field_model: str
    preset: str
    net: str
    collected: Counter[str] = field(default_factory=Counter)
    dataset_rows: int = 0
    tree_nodes: int = 0
    tree_leaves: int = 0
    training_error: float = math.nan
    holdout_error: float = math.nan
    passer_only_nodes: int = 0
    tree_text: str = ""
    receiver_tests: int = 0
    passer_tests: int = 0
    results: dict[str, list[TrialResult]] = field(default_factory=dict)
    stages: list[StageTiming] = field(default_factory=list)
    reports_heard: float = math.nan


def pass_spec(
    field_model: str, preset: str, seed: int, net: Path, client: str = "see"
) -> TrialSpec:
    """The pass drill on a field model, receivers and defenders intercepting with `net`.

    On the per-cycle client the spec carries ``client=cycle``; the see client's spec names no
    client, so its trials (and their stored results) are the ones it always had.
    """
    spec = TrialSpec(drill=DRILL, field_model=field_model, preset=preset, seed=seed)
    spec = spec.with_options(interceptor="net", net=str(net.resolve()))
    return spec if client == "see" else spec.with_options(client=client)


def layer2_conditions(
    base: TrialSpec, n: int, tree: Path, passer_only: Path, boost: Path
) -> dict[str, Condition]:
    """Table 2's conditions and those beyond it, by name (module docstring, step 3)."""
    model = str(tree.resolve())
    own = str(passer_only.resolve())
    specs = {
        "tree": base.with_options(chooser="tree", model=model),
        "boost": base.with_options(chooser="boost", model=str(boost.resolve())),
        "tree_passer_only": base.with_options(chooser="tree", model=own, receiver_half="ignore"),
        "random": base.with_options(chooser="random"),
        "closest": base.with_options(chooser="closest"),
        "analytic": base.with_options(chooser="analytic"),
        "tree_no_defenders": base.with_options(chooser="tree", model=model, defenders="still"),
    }
    return {name: Condition(name, spec, n) for name, spec in specs.items()}


def collect_passes(
    base: TrialSpec, plan: Layer2Plan, results_dir: Path, path: Path, workers: int | None,
    progress: bool,
) -> tuple[PassDataset, list[TrialResult], StageTiming]:  # fmt: skip
    """The training drill: a random receiver for the plan's trials; save the dataset."""
    spec = base.with_options(chooser="random")
    cond = Condition("collect_random", spec, plan.collect_trials)
    results, ran, wall = evaluate(cond, results_dir, workers, progress)
    provenance = {
        "field_model": base.field_model,
        "preset": base.preset_name,
        "seed": base.seed,
        "chooser": "random",
        "drill": DRILL,
        "n_trials": plan.collect_trials,
        "interceptor_net": Path(str(dict(base.drill_options)["net"])).name,
    }
    client = dict(base.drill_options).get("client")
    if client is not None:
        # Only a cycle run names its client, so the see client's dataset stays byte-identical.
        provenance["client"] = client
    dataset = dataset_from(results, provenance)
    dataset.save(path)
    return dataset, results, StageTiming("collect (random receiver)", ran, wall)


@dataclass(frozen=True)
class MainTree:
    """A field model's training passes and the tree fitted on them (:func:`train_main_tree`).

    Attributes:
        dataset: The passes (attributes and labels).
        collected: Labels of the training trials.
        collection: The collection stage's timing.
        path: The tree's file.
        tree: The tree.
        holdout_error: Error of the same procedure fitted on 70% and tested on 30%.
        train_s: Wall seconds of fitting.
    """

    dataset: PassDataset
    collected: Counter[str]
    collection: StageTiming
    path: Path
    tree: PassTree
    holdout_error: float
    train_s: float


def train_main_tree(field: Field, net: Path, plan: Layer2Plan, ctx: RunContext) -> MainTree:
    """Layer 2's collection and its tree only (no tests), into the run folder's usual places.

    The same files and seeds as :func:`run_layer2_model`, so either resumes the other's work.
    """
    field_model, preset = field
    out, seeds = ctx.out, ctx.seeds
    ctx.log(f"[{field_model}] layer 2: collect {plan.collect_trials} passes to a random receiver")
    base = pass_spec(field_model, preset, seeds.collection, net, plan.client)
    dataset, collected, timing = collect_passes(
        base, plan, out / "results" / field_model / "layer2",
        out / "datasets" / field_model / "passes.npz", ctx.workers, ctx.progress,
    )  # fmt: skip
    labels = Counter(r.label for r in collected)
    ctx.log(f"  {len(dataset)} passes: {dict(labels)} ({timing.wall_s:.1f} s)")
    start = time.perf_counter()
    path = out / "models" / field_model / "pass_tree.json"
    tree, holdout = train_tree(dataset, path, seeds.collection)
    return MainTree(dataset, labels, timing, path, tree, holdout, time.perf_counter() - start)


def run_layer2_model(field: Field, net: Path, plan: Layer2Plan, ctx: RunContext) -> Layer2Section:
    """Collect, train and test layer 2 on one field model (module docstring)."""
    field_model, preset = field
    seeds, log = ctx.seeds, ctx.log
    results_dir = ctx.results_dir(field_model) / "layer2"
    section = Layer2Section(field_model, preset, net.name)
    main = train_main_tree(field, net, plan, ctx)
    dataset, tree, tree_path = main.dataset, main.tree, main.path
    section.stages.append(main.collection)
    section.collected = main.collected
    section.dataset_rows = len(dataset)
    section.holdout_error = main.holdout_error

    start = time.perf_counter() - main.train_s
    own_path = tree_path.with_name("pass_tree_passer_only.json")
    own, _ = train_tree(passer_half_only(dataset), own_path, seeds.collection)
    section.passer_only_nodes = own.n_nodes
    boost_path = tree_path.with_name("pass_boost.json")
    train_boost(dataset, boost_path, seeds.collection)
    section.tree_nodes, section.tree_leaves = tree.n_nodes, tree.n_leaves
    section.training_error = tree.training_error(dataset.x, dataset.y)
    section.tree_text = tree.render(max_depth=plan.tree_depth_shown)
    section.passer_tests, section.receiver_tests = tests_by_side(tree)
    (tree_path.parent / "pass_tree.txt").write_text(tree.render() + "\n")
    section.stages.append(StageTiming("train tree", 0, time.perf_counter() - start))
    log(
        f"  tree: {tree.n_nodes} nodes, training error {100 * section.training_error:.1f}% "
        f"({time.perf_counter() - start:.1f} s)"
    )

    test_base = pass_spec(field_model, preset, seeds.evaluation, net, plan.client)
    conditions = layer2_conditions(test_base, plan.eval_trials, tree_path, own_path, boost_path)
    for name, cond in conditions.items():
        results, ran, wall = evaluate(cond, results_dir, ctx.workers, ctx.progress)
        section.results[name] = results
        section.stages.append(StageTiming(name, ran, wall))
        counts = Counter(r.label for r in results)
        log(f"  {name}: {dict(counts)} ({wall:.1f} s)")
    heard = [r.data[3] for r in passes(section.results["tree"])]
    section.reports_heard = float(np.mean(heard)) if heard else math.nan
    return section


# ----------------------------------------------------------------------------- the report


def confidence_of(result: TrialResult) -> float:
    """The tree's success confidence in the chosen receiver (nan where none was recorded)."""
    return result.data[1] if len(result.data) > 1 else math.nan


def label_cells(results: Sequence[TrialResult]) -> list[str]:
    """SUCCESS / FAILURE / MISS as percentages with 95% intervals, then n."""
    counts = Counter(r.label for r in results)
    n = len(results)
    return [percent_cell(counts[label], n) for label in LABELS] + [str(n)]


def in_bin(results: Sequence[TrialResult], low: float, high: float) -> list[TrialResult]:
    """The trials whose success confidence lies in [low, high)."""
    return [r for r in results if low <= confidence_of(r) < high]


def versus_labels(results: Sequence[TrialResult], ref: dict[str, float]) -> str:
    """The vs-paper cell of SUCCESS / FAILURE / MISS against the paper's percentages."""
    counts = Counter(r.label for r in results)
    n = len(results)
    return versus_cell([versus_paper(counts[label], n, ref.get(label)) for label in LABELS])


def table2_lines(section: Layer2Section) -> list[str]:
    """Table 2: the tree forced to pass, overall and by confidence bin, beside the paper."""
    tree = section.results.get("tree", [])
    rows = [("overall", tree, paper.TABLE_2["overall"])]
    for low, high in paper.TABLE_2_BINS:
        key = f".{round(10 * low)}-.{round(10 * high)}"
        rows.append((key, in_bin(tree, low, high), paper.TABLE_2[key]))
    others = [r for r in tree if not 0.6 <= confidence_of(r) < 0.9]
    setting = field_setting(section.field_model, section.preset)
    lines = [
        "| confidence | SUCCESS (%) | paper | FAILURE (%) | paper | MISS (%) | paper | n "
        "| paper n | setting | vs paper |",
        "|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for key, results, ref in rows:
        s, f, m, n = label_cells(results)
        lines.append(
            f"| {key} | {s} | {ref['SUCCESS']:g} | {f} | {ref['FAILURE']:g} | {m} | "
            f"{ref['MISS']:g} | {n} | {ref['n']:g} | {setting} | {versus_labels(results, ref)} |"
        )
    s, f, m, n = label_cells(others)
    lines.append(f"| outside .6-.9 | {s} | — | {f} | — | {m} | — | {n} | 280 | — | — |")
    return lines


def comparison_lines(section: Layer2Section, plan: Layer2Plan) -> list[str]:
    """Success of every chooser beside the paper's (§6 text), with n and 95% intervals."""
    res = section.results
    confident = [r for r in res.get("tree", []) if confidence_of(r) > plan.confident]
    rows = [
        ("DT, forced to pass (Table 2)", res.get("tree", []), paper.PASS_SUCCESS_PCT["tree"]),
        ("random receiver", res.get("random", []), paper.PASS_SUCCESS_PCT["random"]),
        ("closest teammate", res.get("closest", []), paper.PASS_SUCCESS_PCT["closest"]),
        (
            f"DT, only passes with confidence > {plan.confident:g}",
            confident,
            paper.PASS_SUCCESS_PCT["tree_confident"],
        ),
        (
            "DT, defenders still",
            res.get("tree_no_defenders", []),
            paper.PASS_SUCCESS_PCT["tree_no_defenders"],
        ),
        ("DT on the passer's half only (ours)", res.get("tree_passer_only", []), None),
        ("gradient-boosted trees (ours)", res.get("boost", []), None),
        ("analytic: can a defender reach the path first? (ours)", res.get("analytic", []), None),
    ]
    setting = field_setting(section.field_model, section.preset)
    # The paper's figure with defenders is for none at all; ours stand still on the field.
    settings = {"DT, defenders still": f"{setting}; defenders still (paper: no defenders)"}
    lines = [
        "| receiver chosen by | SUCCESS (%) | paper | FAILURE (%) | MISS (%) | n | setting "
        "| vs paper |",
        "|---|---|---|---|---|---|---|---|",
    ]
    for name, results, ref in rows:
        s, f, m, n = label_cells(results)
        theirs = ("—", "—", "—")  # paper, setting, vs paper: none without a paper figure
        if ref is not None:
            k = sum(r.label == "SUCCESS" for r in results)
            theirs = (f"{ref:g}", settings.get(name, setting), versus_paper(k, len(results), ref))
        ref_cell, setting_cell, versus = theirs
        lines.append(f"| {name} | {s} | {ref_cell} | {f} | {m} | {n} | {setting_cell} | {versus} |")
    return lines


def reliability_lines(section: Layer2Section, run: str = "tree") -> list[str]:
    """A run's success confidence against the success observed, in tenths."""
    tree = passes(section.results.get(run, []))
    if not tree:
        return []
    conf = np.array([confidence_of(r) for r in tree])
    success = np.array([r.label == "SUCCESS" for r in tree])
    lines = [
        "| confidence | n | mean confidence | observed success (%) |",
        "|---|---|---|---|",
    ]
    for b in reliability(conf, success, RELIABILITY_BINS):
        if b.n == 0:
            continue
        k = round(b.observed * b.n)
        lines.append(f"| {b.lo:.1f}-{b.hi:.1f} | {b.n} | {b.mean_confidence:.3f} | "
                     f"{percent_cell(k, b.n)} |")  # fmt: skip
    return lines


def differences_lines(section: Layer2Section, plan: Layer2Plan) -> list[str]:
    """What this run measured where it differs from the paper (generated from the numbers)."""
    out = []
    n = sum(section.collected.values())
    shares = ", ".join(
        f"{label} {percent_cell(section.collected[label], n)}"
        f" (paper {paper.LAYER2_TRAINING_SHARES[label]:g})"
        for label in LABELS
    )
    out.append(f"- **Training passes** ({n} trials, random receiver): {shares}.")
    out.append(
        f"- **Tree size**: {section.tree_nodes} nodes, {section.tree_leaves} leaves "
        f"(paper: {paper.TREE_NODES} nodes); training error "
        f"{100 * section.training_error:.1f}% (paper: {paper.TREE_TRAINING_ERROR_PCT:g}%); "
        f"the same procedure on the first 70% of the passes errs on "
        f"{100 * section.holdout_error:.1f}% of the last 30%. "
        f"Its tests use the passer's attributes {section.passer_tests} times and the "
        f"receiver's {section.receiver_tests} times."
    )
    if not math.isnan(section.reports_heard):
        out.append(
            f"- **Receivers' reports**: the passer had heard {section.reports_heard:.2f} of 3 "
            "reports, on average, when it chose (tree run)."
        )
    both, own = section.results.get("tree", []), section.results.get("tree_passer_only", [])
    gain = paired_difference(both, own, "SUCCESS")
    if gain is not None:
        mid, low, high, _ = gain
        out.append(
            f"- **What the receivers' reports add**: the tree on both halves minus a tree "
            f"({section.passer_only_nodes} nodes) on the passer's half only, trial by trial on "
            f"the same placements: {mid:+.1f} [{low:+.1f}, {high:+.1f}] "
            "points of success (95% paired interval)."
        )
    still = section.results.get("tree_no_defenders", [])
    if still:
        counts = Counter(r.label for r in still)
        out.append(
            f"- **Defenders still** (percentages): the tree's passes succeed in "
            f"{percent_cell(counts['SUCCESS'], len(still))} (paper, with no defenders: "
            f"{paper.PASS_SUCCESS_PCT['tree_no_defenders']:g}). Ours stay on the field, so a "
            f"pass played into one still counts as a FAILURE "
            f"({percent_cell(counts['FAILURE'], len(still))}), and a ball that stops short of "
            f"everyone is a MISS ({percent_cell(counts['MISS'], len(still))})."
        )
    return out


def layer2_markdown(
    sections: Sequence[Layer2Section],
    plan: Layer2Plan,
    plots: Sequence[tuple[str, str]] = (),
) -> str:
    """Layer 2's part of the report: per field model, Table 2, the comparison rows, the tree.

    `plots` are (caption, path relative to the report) of the images to show first.
    """
    client = (
        "the per-cycle client of issue 28 (`client=cycle`: a command every cycle from a "
        "world model kept between sees)"
        if plan.client == "cycle"
        else "the paper's see-triggered client (`client=see`: turn, then dash, at each see)"
    )
    out = [
        "## Layer 2: pass evaluation (§6)",
        "",
        f"Plan `{plan.name}`: {plan.collect_trials} training trials (random receiver), "
        f"{plan.eval_trials} trials per test condition, all conditions on one evaluation seed "
        "(paired placements). Receivers and defenders intercept with this run's layer-1 net. "
        "Percentages carry 95% Wilson intervals; paper numbers are the Soccer Server's (1996).",
        "",
        f"Receivers' and defenders' client, in every trial (collection and tests): {client}.",
        "",
    ]
    for caption, path in plots:
        out += [f"![{caption}]({path})", ""]
    for s in sections:
        out += [f"### {s.field_model} (`{s.preset}`), interception net `{s.net}`", ""]
        out += ["**Table 2**: the tree forced to pass, by its success confidence in the "
                "chosen receiver.", "", *table2_lines(s), ""]  # fmt: skip
        out += ["**Choosing the receiver**:", "", *comparison_lines(s, plan), ""]
        for run, what in (("tree", "the tree's confidence"), ("boost", "the boosted trees")):
            rel = reliability_lines(s, run)
            if rel:
                out += [f"**Reliability** of {what} ({run} run):", "", *rel, ""]
        whole = f"`models/{s.field_model}/pass_tree.txt`"
        out += [f"**The tree** (first levels, Figure 14's style; the whole tree is in {whole}):"]
        out += ["", "```", s.tree_text, "```", ""]
        out += ["**Where we differ, measured**:", "", *differences_lines(s, plan), ""]
        out += ["| stage | trials | wall (s) | trials/s |", "|---|---|---|---|"]
        out += [f"| {t.name} | {t.trials} | {t.wall_s:.1f} | {t.rate()} |" for t in s.stages]
        out += [""]
    return "\n".join(out).rstrip() + "\n"
