"""The set play of Figure 15 measured: the layered minds against the baseline, on each field (§7).

The paper ran its set play "several times" and reports no numbers: the attackers "can
sometimes successfully string together three passes and a shot on goal", and the defenders,
with the same interception skill, "are sometimes able to break up the play". This study
counts how often, on each field model it is given, with two sets of minds:

* ``layered`` — layer 2's tree chooses the passes (``chooser=tree`` with that field's
  ``pass_tree.json``) and everyone intercepts with layer 1's net (``interceptor=net`` with
  that field's ``net_750.npz``), the defenders included: the paper's set-up ("the defenders
  are all equipped with the same ball-interception skill as the receivers", §7);
* ``layered_fixed`` — the same layered attackers against the baseline's defenders (straight
  interception): only the attackers' layers differ from the baseline, so the paired
  difference is what the learned layers do for the team that uses them;
* ``baseline`` — the closest receiver (the paper's heuristic) and straight interception.

All conditions of a field share the experiment seed, so play i places every player
identically in each (paired). Each condition's plays go through the process pool
(:func:`robotsoccer.runs.pool.run_trials`), streamed to ``results/<model>/<condition>.csv``;
rerunning the study on its folder resumes them (finished plays are kept, and a table another
run made is refused). The folder also gets ``config.json`` (what ran; a folder holding another
study's configuration is refused), a few rerun recordings under ``recordings/<model>/`` and
``report.md``: per field and condition the number of plays, the shares of plays completing at
least 1, 2 and 3 of the play's passes and exactly 1, 2 or 3, shots, goals and the labels of
:class:`robotsoccer.drills.setplay.SetPlayDrill`, each with its 95% Wilson interval, and the
differences of each other condition from the baseline, paired play by play. Every number in it
comes from the run.

**Client** (``client``): the Soccer Server's players on the paper's see-triggered client
(``see``, the default) or the per-cycle client (``cycle``, issue 28 item 3: the drill's option
``client``, every condition of a Soccer Server field); the robots' minds are unchanged (their
host already acts on every tick). The option is in each condition's drill options, so the
configuration and report say which client each table used.

**Looking** (``look``): the Soccer Server's attackers look with the body (``body``, the default,
the paper's client) or with the neck (``neck``: the drill's option ``look``); the robots, which
have no neck, keep theirs. Like the client it is in each condition's drill options.

The study names no field model: the caller passes the (model, preset) pairs.
"""

from __future__ import annotations

import dataclasses
import json
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from field_models.registry import field_facts
from robotsoccer.drills.setplay import SetPlayDrill
from robotsoccer.experiments.context import Field, Log, RunContext
from robotsoccer.experiments.layer1 import claim_folder
from robotsoccer.experiments.layer1_plan import PipelineError
from robotsoccer.experiments.report_cells import paired_difference, percent_cell
from robotsoccer.runs.pool import run_trials
from robotsoccer.runs.provenance import code_version
from robotsoccer.runs.runner import TrialResult, TrialSpec, run_trial

DRILL = "setplay"
"""The registered name of the set-play drill."""
TREE_FILE = "pass_tree.json"
NET_FILE = "net_750.npz"
"""A field's layer-2 tree and layer-1 net inside ``<models>/<field model>/`` (the layout the
transfer study writes)."""
QUICK_PLAYS = 40
"""Plays per condition in a quick run (at most)."""
RECORDED_PLAYS = 3
"""Plays recorded per field and condition (the first ones)."""
PASS_COUNTS = (1, 2, 3)
"""The play's passes: to a first receiver, to the winger, to a last receiver."""


@dataclass(frozen=True)
class PlayCondition:
    """One set of minds on one field: its name (its CSV file) and what to run."""

    name: str
    spec: TrialSpec


@dataclass
class FieldResults:
    """Every condition's plays on one field, and how long each took.

    Attributes:
        model: The field model.
        preset: Its preset.
        plays: Condition name → results, sorted by index.
        wall_s: Condition name → wall seconds spent on it in this run.
        recordings: Paths of the recordings made.
    """

    model: str
    preset: str
    plays: dict[str, list[TrialResult]] = dataclasses.field(default_factory=dict)
    wall_s: dict[str, float] = dataclasses.field(default_factory=dict)
    recordings: list[Path] = dataclasses.field(default_factory=list)


def model_files(models: Path, field_model: str) -> tuple[Path, Path]:
    """(pass tree, interception net) of a field model under `models`.

    Raises:
        PipelineError: A file is missing.
    """
    tree, net = models / field_model / TREE_FILE, models / field_model / NET_FILE
    missing = [str(p) for p in (tree, net) if not p.is_file()]
    if missing:
        raise PipelineError(f"missing model file(s): {', '.join(missing)}")
    return tree, net


def play_conditions(
    field: Field, models: Path | None, seed: int, client: str = "see", look: str = "body"
) -> list[PlayCondition]:
    """The layered minds (when `models` is given) and the baseline on one field, paired.

    `client`: the Soccer Server's client, `look` how its attackers look (module docstring); a
    field with walls (the robots) keeps its own.
    """
    model, preset = field
    base = TrialSpec(drill=DRILL, field_model=model, preset=preset, seed=seed)
    server = not field_facts(model, preset).walled
    if client != "see" and server:
        base = base.with_options(client=client)
    if look != "body" and server:
        base = base.with_options(look=look)
    conditions = []
    if models is not None:
        tree, net = model_files(models, model)
        layered = base.with_options(
            chooser="tree", model=str(tree.resolve()), interceptor="net", net=str(net.resolve())
        )
        conditions.append(PlayCondition("layered", layered))
        fixed = layered.with_options(defenders="straight")
        conditions.append(PlayCondition("layered_fixed", fixed))
    baseline = base.with_options(chooser="closest", interceptor="straight")
    conditions.append(PlayCondition("baseline", baseline))
    return conditions


def run_setplay_study(
    ctx: RunContext,
    *,
    fields: Sequence[Field],
    models: Path | None,
    plays: int = 1000,
    quick: bool = False,
    client: str = "see",
    look: str = "body",
) -> Path:
    """Run the set play on each field with both sets of minds; write the run; return the report.

    Args:
        ctx: The run: its folder (made ready by the caller; rerunning resumes it), its
            evaluation seed (shared by the conditions: paired plays), workers, log, progress.
        fields: (field model, preset) pairs, in report order.
        models: The folder holding ``<field model>/pass_tree.json`` and ``net_750.npz`` for
            every field; None runs the baseline only.
        plays: Plays per field and condition.
        quick: At most :data:`QUICK_PLAYS` plays per condition.
        client: The Soccer Server fields' client, ``see`` or ``cycle`` (module docstring).
        look: How the Soccer Server fields' attackers look, ``body`` or ``neck``.

    Raises:
        PipelineError: A model file is missing, or `out` holds another study's run.
        ValueError: `plays` is not positive.
    """
    if plays <= 0:
        raise ValueError(f"plays must be > 0, got {plays!r}")
    n = min(plays, QUICK_PLAYS) if quick else plays
    out, seed, workers, log = ctx.out, ctx.seeds.evaluation, ctx.workers, ctx.log
    conditions = {field: play_conditions(field, models, seed, client, look) for field in fields}
    header = study_header(conditions, n, seed, quick)
    claim_folder(out, header)
    start = time.perf_counter()
    sections = []
    for (model, preset), conds in conditions.items():
        section = FieldResults(model, preset)
        for cond in conds:
            log(f"[setplay] {model} {cond.name}: {n} plays")
            began = time.perf_counter()
            path = out / "results" / model / f"{cond.name}.csv"
            section.plays[cond.name] = run_trials(
                cond.spec, n, workers=workers, results_path=path, resume=True,
                progress=ctx.progress,
            )  # fmt: skip
            section.wall_s[cond.name] = time.perf_counter() - began
            section.recordings += record_plays(cond, out / "recordings" / model, log)
        sections.append(section)
    wall = time.perf_counter() - start
    report = out / "report.md"
    report.write_text(setplay_markdown(sections, seed=seed, workers=workers, wall_s=wall))
    config = {**header, "wall_s": round(wall, 1)}
    (out / "config.json").write_text(json.dumps(config, indent=2) + "\n")
    return report


def study_header(
    conditions: dict[Field, list[PlayCondition]], plays: int, seed: int, quick: bool
) -> dict[str, Any]:
    """What defines the run (a resumed folder must hold the same)."""
    return {
        "study": DRILL,
        "plays": plays,
        "seed": seed,
        "quick": quick,
        "fields": [list(field) for field in conditions],
        "conditions": {
            field[0]: {c.name: dict(c.spec.drill_options) for c in conds}
            for field, conds in conditions.items()
        },
        "code_version": code_version(),
    }


def record_plays(cond: PlayCondition, folder: Path, log: Log) -> list[Path]:
    """Rerun the first :data:`RECORDED_PLAYS` plays of `cond` with a rerun recording each.

    A play is a function of its seed and index, so the rerun is the same play. The files are
    ``<condition>_play<index>_<label>.rrd``; ones already there are kept.
    """
    from robotsoccer.replay.recording import recording_name  # the rerun SDK loads late

    folder.mkdir(parents=True, exist_ok=True)
    made = []
    for index in range(RECORDED_PLAYS):
        done = sorted(folder.glob(f"{cond.name}_play{index:04d}_*.rrd"))
        if done:
            made.append(done[0])
            continue
        spec = dataclasses.replace(cond.spec, record_dir=str(folder), record_trials=index + 1)
        result = run_trial(spec, index)
        target = folder / f"{cond.name}_play{index:04d}_{result.label}.rrd"
        (folder / recording_name(index, result.label)).replace(target)
        log(f"  recorded {target}")
        made.append(target)
    return made


# ----------------------------------------------------------------------------- the report


def passes_of(result: TrialResult) -> int:
    """The play's passes completed (0–3)."""
    return int(result.measure("passes"))


Predicate = Callable[[TrialResult], bool]


def at_least(k: int) -> Predicate:
    """Plays completing at least `k` passes."""
    return lambda r: passes_of(r) >= k


def exactly(k: int) -> Predicate:
    """Plays completing exactly `k` passes."""
    return lambda r: passes_of(r) == k


def labelled(label: str) -> Predicate:
    """Plays the coach labelled `label`."""
    return lambda r: r.label == label


def measures() -> list[tuple[str, Predicate]]:
    """The report's rows of shares: (name, which plays count)."""
    rows = [(f"≥ {k} pass{'es' if k > 1 else ''}", at_least(k)) for k in PASS_COUNTS]
    rows += [(f"exactly {k}", exactly(k)) for k in PASS_COUNTS]
    rows.append(("shot on goal", lambda r: r.measure("shot") == 1.0))
    rows.append(("goal", labelled("GOAL")))
    rows += [(f"label {label}", labelled(label)) for label in SetPlayDrill.labels]
    return rows


def share_cell(results: Sequence[TrialResult], predicate: Predicate) -> str:
    """``count — percent [interval]`` of the plays `predicate` holds for."""
    k = sum(1 for r in results if predicate(r))
    return f"{k} — {percent_cell(k, len(results))}"


def paired_cell(a: Sequence[TrialResult], b: Sequence[TrialResult], predicate: Predicate) -> str:
    """`a` − `b` in points of the plays `predicate` holds for, paired play by play, 95%."""
    marked_a = [dataclasses.replace(r, label="YES" if predicate(r) else "NO") for r in a]
    marked_b = [dataclasses.replace(r, label="YES" if predicate(r) else "NO") for r in b]
    found = paired_difference(marked_a, marked_b, label="YES")
    if found is None:
        return "—"
    diff, low, high, _ = found
    return f"{diff:+.1f} [{low:+.1f}, {high:+.1f}]"


def field_lines(section: FieldResults) -> list[str]:
    """One field's tables (module docstring)."""
    names = list(section.plays)
    lines = [f"## {section.model} (`{section.preset}`)", ""]
    timing = ", ".join(
        f"{name} {len(section.plays[name])} plays in {section.wall_s[name]:.0f} s" for name in names
    )
    lines += [f"Plays per condition and wall time in this run: {timing}.", ""]
    compared = [n for n in names if n != "baseline"] if "baseline" in section.plays else []
    head = ["measure", *(f"{name} (n={len(section.plays[name])})" for name in names)]
    head += [f"{name} − baseline, paired [points]" for name in compared]
    lines += ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    for title, predicate in measures():
        cells = [share_cell(section.plays[name], predicate) for name in names]
        cells += [
            paired_cell(section.plays[name], section.plays["baseline"], predicate)
            for name in compared
        ]
        lines.append(f"| {title} | " + " | ".join(cells) + " |")
    lines.append("")
    if section.recordings:
        lines.append("Recordings: " + ", ".join(f"`{p.name}`" for p in section.recordings))
        lines.append("")
    return lines


def setplay_markdown(
    sections: Sequence[FieldResults], *, seed: int, workers: int | None, wall_s: float
) -> str:
    """The study's report (module docstring)."""
    lines = [
        "# The set play of Figure 15 (§7)",
        "",
        "Cells: plays counted — percent of the plays [95% Wilson interval]. Passes are the "
        "play's own, in order (`robotsoccer.drills.setplay`): to a first receiver, to the "
        "winger, to a last receiver. A paired column is the mean of the play-by-play "
        "difference from the baseline with a normal 95% interval (same seed: play i is placed "
        "identically in every condition). `layered`: layered attackers and defenders (the "
        "paper's set-up); `layered_fixed`: layered attackers against the baseline's straight "
        "defenders.",
        "",
        f"Seed {seed}; {workers or 'all'} worker(s); {wall_s:.0f} s of wall time in this run "
        "(resumed plays cost none).",
        "",
    ]
    for section in sections:
        lines += field_lines(section)
    return "\n".join(lines)
