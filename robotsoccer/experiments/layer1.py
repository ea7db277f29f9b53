"""Layer 1 end to end: collect saves, train nets, evaluate every condition, write one folder (§5).

The pipeline for one field model, as small functions:

1. :func:`collect` — the training drill (paper Figure 6): the defender turns a random TA in
   [−45°, 45°] once the ball is within 14 units; trials run in batches until the saves reach the
   plan's target (the paper's 4773), and the saves' (BD, BA, previous BD, TA) become an
   :class:`~learning.datasets.InterceptionDataset` with its provenance.
2. :func:`train_series` — the paper's 3-4-1 net trained on the first n saves for each n of
   Figure 7 (100 … 1000) and on all of them; plus :func:`build_lookup`, the BA → TA table of §5.
   Subsets are *prefixes* in trial order: the net on 300 saves learns what the drill had produced
   after its 300th save, as if collection had stopped there, and the subsets are nested.
3. :func:`evaluate` — one condition (behaviour, model file, noise, aim, latency) for the plan's
   trials through :func:`robotsoccer.runs.pool.run_trials`: parallel, streamed to
   ``<out>/results/<model>/<condition>.csv`` and resumable.
4. :func:`run_layer1` — the orchestration: per field model the stages above, then a few rerun
   recordings of the net's saves and goals, ``report.md``, the Figure 7/8 plots and
   ``config.json``.

Seeds (common random numbers): every evaluation condition of a field model uses the same
experiment seed, so trial i places shooter, ball and defender identically whatever the behaviour
(paired comparisons). Collection uses a different seed derived from it (:func:`seeds_for`), so the
nets are never tested on the placements they were trained on.

Noise: on every field the ball's velocity gets a uniform change in ±noise·|v| per axis once per
noise period (:attr:`field_models.arena.FieldFacts.ball_noise`; the Soccer Server's
``ball_rand``). Layer 1 passes the same noise value to every field model, and the drill sets the
period where it scales the drill (:mod:`robotsoccer.drills.intercept`), so a noise level means
the same wander per shot on every field.

What the plans hold (:func:`quick_plan`, :func:`full_plan`): see :class:`Layer1Plan`.
"""

from __future__ import annotations

import dataclasses
import json
import math
import time
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np

from field_models.registry import default_preset, field_facts, has_preset
from learning.datasets import InterceptionDataset, Provenance
from learning.lookup import PAPER_GRID_DEG, LookupTable
from robotsoccer.drills import make_drill
from robotsoccer.drills.intercept import InterceptDrill
from robotsoccer.drills.intercept_plan import launch_plan
from robotsoccer.experiments import paper
from robotsoccer.experiments.report import Counts, ModelSection, StageTiming
from robotsoccer.runs.folders import lock_run_folder
from robotsoccer.runs.pool import run_trials
from robotsoccer.runs.provenance import code_version
from robotsoccer.runs.runner import TrialResult, TrialSpec, run_trial
from robotsoccer.runs.table import iter_results
from robotsoccer.skills.intercept import TaMode

Log = Callable[[str], None]
"""Where progress lines go (the CLI prints them)."""
Field = tuple[str, str]
"""A field model and its preset."""

DRILL = "intercept"
"""The registered name of the interception drill (paper Figure 6)."""

COLLECT_BEHAVIOUR = "random"
"""The defender behaviour of the training drill: random TA in [−45°, 45°]."""


class PipelineError(ValueError):
    """The pipeline cannot go on: too few saves to train, or --out holds another run.

    A ValueError, so the CLI reports it as one line.
    """


@dataclass(frozen=True)
class Layer1Plan:
    """What a layer-1 run does, for each field model.

    Attributes:
        name: ``"quick"``, ``"full"`` or a free name (tests).
        eval_trials: Trials per evaluation condition (paper: 1000).
        collect_saves: The training drill runs until its saves reach this many (paper: 4773).
        collect_batch: Trials of the training drill's first batch; later batches are sized
            from its save rate (multiples of 500).
        training_sizes: Figure 7's training-set sizes; sizes above the saves collected are
            skipped.
        include_all: Also train on all collected saves (the paper's 4773 row).
        net_examples: Saves of the net used for Figure 8, Table 1, 4° wide and latency (paper:
            750); the largest trained size up to it when fewer were collected.
        noise: Ball noise of collection, Figure 7, Table 1, checks and latency (paper: .05).
        noises: Figure 8's noise levels.
        latencies_s: Robots only: camera latencies for the latency table [s].
        aim_offset_deg: The "aim wide" experiment's offset (paper: 4°), with no noise.
        epochs: Training epochs of every net (paper: 3000).
        checks: Run the training-drill checks (still, straight) of the §5 text.
        record_saves: Net saves recorded with rerun per field model.
        record_goals: Net goals recorded with rerun per field model.
        ta_mode: The drill's TA timing (``"hold"``: chosen once, at BD ≤ 14 units).
    """

    name: str
    eval_trials: int
    collect_saves: int
    collect_batch: int = 4000
    training_sizes: tuple[int, ...] = tuple(
        sorted(n for n in paper.FIGURE_7 if n != paper.PAPER_ALL_SAVES)
    )
    include_all: bool = True
    net_examples: int = paper.PAPER_NET_EXAMPLES
    noise: float = paper.PAPER_NOISE
    noises: tuple[float, ...] = paper.FIGURE_8_NOISES
    latencies_s: tuple[float, ...] = (0.0, 0.05, 0.1)
    aim_offset_deg: float = paper.AIM_OFFSET_DEG
    epochs: int = 3000
    checks: bool = True
    record_saves: int = 2
    record_goals: int = 2
    ta_mode: TaMode = TaMode.HOLD

    def to_dict(self) -> dict[str, Any]:
        """The plan as plain JSON types."""
        return dataclasses.asdict(self)


def quick_plan() -> Layer1Plan:
    """200 trials per condition, 1500 saves collected per model (a few minutes on 2 cores)."""
    return Layer1Plan(name="quick", eval_trials=200, collect_saves=1500, collect_batch=2000)


def full_plan() -> Layer1Plan:
    """1000 trials per condition, the paper's 4773 saves collected per model."""
    return Layer1Plan(name="full", eval_trials=1000, collect_saves=paper.PAPER_ALL_SAVES)


def plan_for(quick: bool) -> Layer1Plan:
    """The quick or the full plan."""
    return quick_plan() if quick else full_plan()


@dataclass(frozen=True)
class Seeds:
    """The experiment seeds of one run: evaluation (shared by all conditions) and collection."""

    evaluation: int
    collection: int


def seeds_for(seed: int) -> Seeds:
    """Evaluation uses `seed`; collection a 32-bit seed derived from it, never `seed` itself.

    The derived seed is the first word of ``SeedSequence([seed, 1])`` that differs from `seed`,
    so a run's nets are never tested on the placements they were trained on.
    """
    words = np.random.SeedSequence([seed, 1]).generate_state(2).tolist()
    derived = next(int(w) for w in words if w != seed)
    return Seeds(evaluation=seed, collection=derived)


# ----------------------------------------------------------------------------- conditions


@dataclass(frozen=True)
class Condition:
    """One evaluation condition: a name (its CSV file), what to run and how many trials."""

    name: str
    spec: TrialSpec
    n_trials: int


def base_spec(field_model: str, preset: str, seed: int, ta_mode: TaMode | str) -> TrialSpec:
    """The interception drill on a field model, before behaviour, noise and latency."""
    spec = TrialSpec(drill=DRILL, field_model=field_model, preset=preset, seed=seed)
    return spec.with_options(ta_mode=str(ta_mode))


def condition(
    base: TrialSpec,
    n_trials: int,
    behaviour: str,
    *,
    noise: float,
    model: Path | None = None,
    tag: str = "",
    aim_offset_deg: float = 0.0,
    camera_latency_s: float | None = None,
) -> Condition:
    """A named condition; the name says everything that differs between conditions.

    Args:
        base: From :func:`base_spec`.
        n_trials: Trials to run.
        behaviour: The defender behaviour (``net``, ``lookup``, ``analytic``, ``straight``, ...).
        noise: Ball noise (every model: fraction of speed per axis per noise period).
        model: Model file for ``net`` / ``lookup``.
        tag: Names the model in the condition (e.g. ``"750"`` for net_750).
        aim_offset_deg: The shooter aims this far wide [deg].
        camera_latency_s: Sensor latency override [s]; None keeps the preset's.
    """
    options: dict[str, str | float] = {"behaviour": behaviour}
    if model is not None:
        options["model"] = str(model.resolve())
    if aim_offset_deg:
        options["aim_offset_deg"] = aim_offset_deg
    spec = base.with_options(**options).with_field(
        ball_noise=noise, sensor_latency_s=camera_latency_s
    )
    name = f"{behaviour}{tag}_noise{noise:g}"
    if aim_offset_deg:
        name += f"_aim{aim_offset_deg:g}"
    if camera_latency_s is not None:
        name += f"_latency{1000 * camera_latency_s:.0f}ms"
    return Condition(name, spec, n_trials)


# ----------------------------------------------------------------------------- stages


def evaluate(
    cond: Condition, results_dir: Path, workers: int | None, progress: bool = False
) -> tuple[list[TrialResult], int, float]:
    """Run one condition through the pool, streamed to ``results_dir/<name>.csv`` and resumed.

    Returns:
        (results sorted by index, trials actually run now, wall seconds).
    """
    path = results_dir / f"{cond.name}.csv"
    before = _rows_in(path)
    start = time.perf_counter()
    results = run_trials(
        cond.spec,
        cond.n_trials,
        workers=workers,
        results_path=path,
        resume=True,
        progress=progress,
    )
    return results, max(0, cond.n_trials - before), time.perf_counter() - start


def _rows_in(path: Path) -> int:
    # rows, not lines: a quoted reason may hold line ends (run_trials warns of a cut-short row)
    return sum(1 for _ in iter_results(path, warn=lambda _: None))


def counts_of(results: Iterable[TrialResult]) -> Counts:
    """SAVE / GOAL / MISS counts of some results."""
    return Counts.from_labels(r.label for r in results)


def dataset_from_results(
    results: Sequence[TrialResult], provenance: Provenance
) -> InterceptionDataset:
    """The saves' recorded (BD, BA, previous BD, TA) as a dataset, in trial order (§5).

    A save the defender made before it ever chose a TA (the ball came back before it was in
    range) taught it nothing and records no example: it is left out (see :func:`decided_saves`).

    Raises:
        PipelineError: A recorded example that is not four numbers.
    """
    rows = [r.data for r in decided_saves(results)]
    if any(len(row) != 4 for row in rows):
        raise PipelineError("a save recorded something other than (BD, BA, previous BD, TA)")
    data = np.array(rows, dtype=np.float64).reshape(len(rows), 4)
    return InterceptionDataset(data[:, :3], data[:, 3], provenance)


def decided_saves(results: Iterable[TrialResult]) -> list[TrialResult]:
    """The saves in which the defender chose a TA (they carry its example)."""
    return [r for r in results if r.label == "SAVE" and r.data]


def collect(
    base: TrialSpec,
    plan: Layer1Plan,
    results_dir: Path,
    dataset_path: Path,
    workers: int | None,
    created_by: str,
    progress: bool = False,
) -> tuple[InterceptionDataset, Counts, StageTiming]:
    """The training drill: random TA until the saves reach the plan's target; save the dataset.

    Trials run in batches on one resumable table: the first of ``plan.collect_batch``, each next
    one sized from the save rate so far (rounded up to 500 trials, 5% spare). The batch sizes
    depend only on the results, so the dataset is a function of the seed.
    """
    drill = make_drill(DRILL, {k: v for k, v in base.drill_options if k in PLAN_OPTIONS})
    assert isinstance(drill, InterceptDrill)
    launch = drill.plan_for(field_facts(base.field_model, base.preset))
    cond = condition(base, plan.collect_batch, COLLECT_BEHAVIOUR, noise=plan.noise)
    cond = dataclasses.replace(cond, name=f"collect_{cond.name}")
    limit = COLLECT_LIMIT_PER_SAVE * plan.collect_saves
    ran_total, wall_total = 0, 0.0
    while True:
        results, ran, wall = evaluate(cond, results_dir, workers, progress)
        ran_total, wall_total = ran_total + ran, wall_total + wall
        saves = len(decided_saves(results))
        if saves >= plan.collect_saves or cond.n_trials >= limit:
            break
        wanted = (plan.collect_saves - saves) * cond.n_trials / max(saves, 1) * 1.05
        more = 500 * math.ceil(wanted / 500)
        cond = dataclasses.replace(cond, n_trials=min(limit, cond.n_trials + more))
    counts = counts_of(results)
    provenance = Provenance(
        field_model=base.field_model,
        preset=base.preset_name,
        seed=base.seed,
        ball_noise=plan.noise,
        behaviour=COLLECT_BEHAVIOUR,
        n_trials=cond.n_trials,
        created_by=created_by,
        extra={
            "drill": DRILL,
            "ta_range_deg": 45.0,
            "trigger_distance_units": launch.trigger_distance_m / launch.unit_m,
            "trigger_distance_m": launch.trigger_distance_m,
            "ball_noise_period_s": launch.noise_period_s,
            "ta_mode": str(dict(base.drill_options).get("ta_mode", "hold")),
            "rows": "saves only, in trial order",
            "target_saves": plan.collect_saves,
            "saves": counts.saves,
            "saves_without_decision": counts.saves - len(decided_saves(results)),
            "goals": counts.goals,
            "misses": counts.misses,
        },
    )
    dataset = dataset_from_results(results, provenance)
    dataset_path.parent.mkdir(parents=True, exist_ok=True)
    dataset.save(dataset_path)
    return dataset, counts, StageTiming("collect (random TA)", ran_total, wall_total)


PLAN_OPTIONS = frozenset({"scaling", "trigger_scale", "launch_speed_scale", "turn_tolerance_deg"})
"""The drill options that change the launch plan (named in a dataset's provenance)."""

COLLECT_LIMIT_PER_SAVE = 50
"""The training drill gives up growing after this many trials per wanted save (2% saves)."""


def training_sizes(plan: Layer1Plan, n_saves: int) -> list[int]:
    """Figure 7's sizes that the collection can supply, plus all the saves (ascending, unique)."""
    sizes = [n for n in plan.training_sizes if n <= n_saves]
    if plan.include_all or not sizes:
        sizes.append(n_saves)
    return sorted(set(sizes))


def prefix(dataset: InterceptionDataset, n: int) -> InterceptionDataset:
    """The first `n` rows (the saves in trial order), its provenance noting the subset."""
    extra = {**dataset.provenance.extra, "subset_first_n": n, "subset_of_n": len(dataset)}
    provenance = dataclasses.replace(dataset.provenance, extra=extra)
    return InterceptionDataset(dataset.x[:n], dataset.y[:n], provenance)


def train_series(
    dataset: InterceptionDataset,
    sizes: Sequence[int],
    epochs: int,
    model_dir: Path,
    log: Log,
    seconds: dict[int, float] | None = None,
) -> dict[int, Path]:
    """Train one net per size on the first n saves and save ``net_<n>.npz`` with provenance.

    `seconds`, when given, receives each net's training time (wall seconds).

    Returns:
        Size → model file.

    Raises:
        PipelineError: Fewer than 2 saves to train on.
    """
    from learning.interception import InterceptionModel  # torch loads only when training

    if not sizes or min(sizes) < 2:
        raise PipelineError(
            f"the collection gave {len(dataset)} saves: too few to train a net (need >= 2); "
            "run more collection trials"
        )
    model_dir.mkdir(parents=True, exist_ok=True)
    paths = {}
    for n in sizes:
        part = prefix(dataset, n)
        start = time.perf_counter()
        # Copies: dataset arrays are read-only, which torch.from_numpy warns about.
        model = InterceptionModel(epochs=epochs).fit(part.x.copy(), part.y.copy())
        paths[n] = model.save(model_dir / f"net_{n}.npz", part.provenance)
        wall = time.perf_counter() - start
        if seconds is not None:
            seconds[n] = wall
        log(
            f"  net_{n}: {n} saves, {epochs} epochs, final MSE "
            f"{model.loss_history_[-1]:.4g} rad², {wall:.1f} s"
        )
    return paths


def build_lookup(net_path: Path, dataset: InterceptionDataset, path: Path) -> Path:
    """The §5 lookup table BA → TA from the net at `net_path`, for BA from −7° to 7°.

    Each entry is the net's median output over the training saves' (BD, previous BD) with BA set
    to the grid angle ("the typical output of the NN for that BA").
    """
    from learning.interception import InterceptionModel

    model = InterceptionModel.load(net_path)
    n = model.n_train_
    origin = dataset.provenance
    table = LookupTable.from_model(
        model.as_function(),
        PAPER_GRID_DEG,
        ball_distance_m=dataset.x[:n, 0].tolist(),
        previous_ball_distance_m=dataset.x[:n, 2].tolist(),
        built_from={
            "net": net_path.name,
            "conditions": "training saves (BD, previous BD)",
            "field_model": origin.field_model,
            "preset": origin.preset,
        },
    )
    return table.save(path)


def net_for_figures(plan: Layer1Plan, nets: Iterable[int]) -> int:
    """The net size used for Figure 8, Table 1, 4° wide and latency: the paper's 750 or fewer.

    `nets` are the trained sizes (a mapping from size to file will do).
    """
    sizes = list(nets)
    fitting = [n for n in sizes if n <= plan.net_examples]
    return max(fitting) if fitting else min(sizes)


# ----------------------------------------------------------------------------- the experiments

Keyed = list[tuple[Any, Condition]]
"""An experiment's conditions, each under its key in the report (e.g. (noise, behaviour))."""


@dataclass(frozen=True)
class Trained:
    """What training left for the evaluations of one field model."""

    nets: dict[int, Path]
    """Training examples → net file."""
    main_examples: int
    """The net of Figure 8, Table 1, 4° wide and latency (:func:`net_for_figures`)."""
    lookup: Path
    """The lookup table built from the main net."""
    seconds: dict[int, float] = dataclasses.field(default_factory=dict)
    """Training examples → wall seconds its net took to train in this run."""


def experiments(
    plan: Layer1Plan, base: TrialSpec, trained: Trained, default_latency_s: float | None
) -> dict[str, Keyed]:
    """Every evaluation of one field model, in report order: experiment → keyed conditions.

    Conditions of the same name in two experiments (e.g. the net on 750 saves at noise .05 in
    Figure 7, Figure 8 and Table 1) are one run. `default_latency_s` is the robot preset's
    camera latency (None on the Soccer Server: no latency experiment); a latency equal to it
    runs as the preset's own, so it shares its condition with the other experiments.
    """
    n, noise, aim = plan.eval_trials, plan.noise, plan.aim_offset_deg
    nets = trained.nets

    def run(behaviour: str, examples: int | None = None, **kw: Any) -> Condition:
        if behaviour == "net":
            examples = examples or trained.main_examples
            return condition(base, n, "net", model=nets[examples], tag=str(examples), **kw)
        if behaviour == "lookup":
            tag = str(trained.main_examples)
            return condition(base, n, "lookup", model=trained.lookup, tag=tag, **kw)
        return condition(base, n, behaviour, **kw)

    plan_of: dict[str, Keyed] = {
        "Figure 7": [(size, run("net", size, noise=noise)) for size in sorted(nets)],
        "Figure 8": [
            ((level, b), run(b, noise=level)) for level in plan.noises for b in ("net", "straight")
        ],
        "Table 1": [(b, run(b, noise=noise)) for b in ("net", "lookup", "analytic", "straight")],
        f"{aim:g}° wide": [(b, run(b, noise=0.0, aim_offset_deg=aim)) for b in ("net", "straight")],
    }
    if default_latency_s is not None and plan.latencies_s:
        plan_of["camera latency"] = [
            (
                (lat, b),
                run(b, noise=noise, camera_latency_s=_latency(lat, default_latency_s)),
            )
            for lat in plan.latencies_s
            for b in ("net", "straight", "analytic")
        ]
    swept = swept_variant(base)
    if swept is not None:
        plan_of[SWEPT_EXPERIMENT] = [
            ((level, b), _on_preset(run(b, noise=level), swept, "_swept"))
            for level in (0.0, noise)
            for b in ("net", "straight")
        ]
    if plan.checks:
        plan_of["checks (still, straight)"] = [
            (b, run(b, noise=noise)) for b in ("still", "straight")
        ]
    return plan_of


SWEPT_EXPERIMENT = "swept collisions"
"""The pass-through diagnostic: Figure 8's noise 0 and the main noise with swept collisions."""


def swept_variant(base: TrialSpec) -> str | None:
    """The ``<preset>_swept`` variant of `base`'s preset, if its field model ships one.

    With swept ball–player collisions a ball cannot pass *through* a dashing defender between
    two cycles, which the real server allows (spec §4); running the same conditions on it
    measures how much of a gap to the paper that artefact explains.
    """
    name = f"{base.preset}_swept"
    return name if has_preset(base.field_model, name) else None


def _on_preset(cond: Condition, preset: str, suffix: str) -> Condition:
    """`cond` on a variant preset; a model trained on the base preset is used there on purpose."""
    spec = dataclasses.replace(cond.spec, preset=preset)
    if "model" in dict(spec.drill_options):
        spec = spec.with_options(transfer=True)
    return Condition(cond.name + suffix, spec, cond.n_trials)


def _latency(latency_s: float, default_s: float) -> float | None:
    return None if math.isclose(latency_s, default_s) else latency_s


def unique_conditions(plan_of: dict[str, Keyed]) -> dict[str, Condition]:
    """The distinct conditions of an experiment plan, by name, in first-use order."""
    unique: dict[str, Condition] = {}
    for keyed in plan_of.values():
        for _, cond in keyed:
            unique.setdefault(cond.name, cond)
    return unique


def _fill(
    section: ModelSection, experiment: str, counts: dict[Any, Counts], include_all: bool
) -> None:
    """Put one experiment's counts into its place in the report section."""
    if experiment == "Figure 7":
        largest = max(counts)
        section.figure7 = [
            (size, f"all ({size})" if include_all and size == largest else str(size), c)
            for size, c in sorted(counts.items())
        ]
    elif experiment == "Figure 8":
        section.figure8 = counts
    elif experiment == "Table 1":
        section.table1 = counts
    elif experiment.endswith("wide"):
        section.wide = counts
    elif experiment == "camera latency":
        section.latency = counts
    elif experiment == SWEPT_EXPERIMENT:
        section.swept = counts
    else:
        section.checks.update(counts)


# ----------------------------------------------------------------------------- one field model


def run_model(
    field_model: str,
    preset: str,
    plan: Layer1Plan,
    out: Path,
    seeds: Seeds,
    workers: int | None,
    log: Log,
    created_by: str = "robotsoccer reproduce",
    progress: bool = False,
) -> tuple[ModelSection, dict[str, Condition]]:
    """Collect, train and evaluate layer 1 on one field model; record a few trials.

    Returns:
        The report section and the conditions that ran (for ``config.json``).
    """
    results_dir = out / "results" / field_model
    facts = field_facts(field_model, preset)
    section = ModelSection(
        field_model,
        preset,
        noise=plan.noise,
        noise_period_s=launch_plan(facts).noise_period_s,
        facts=facts,
    )
    section.notes = scaling_notes(field_model, preset)

    dataset, collected, timing = collect_into(
        field_model, preset, plan, out, seeds, workers, log, created_by, progress
    )
    section.checks["random"] = collected
    section.stages.append(timing)

    log(f"[{field_model}] train")
    start = time.perf_counter()
    trained = train(plan, dataset, out / "models" / field_model, log)
    section.stages.append(StageTiming("train nets + lookup", 0, time.perf_counter() - start))
    section.net_examples = trained.main_examples
    section.train_seconds = trained.seconds

    base = base_spec(field_model, preset, seeds.evaluation, plan.ta_mode)
    plan_of = experiments(plan, base, trained, facts.sensor_latency_s)
    done: dict[str, list[TrialResult]] = {}
    for experiment, keyed in plan_of.items():
        log(f"[{field_model}] {experiment}")
        ran, wall = 0, 0.0
        for _, cond in keyed:
            if cond.name in done:
                continue
            done[cond.name], n_run, seconds = evaluate(cond, results_dir, workers, progress)
            ran, wall = ran + n_run, wall + seconds
            c = counts_of(done[cond.name])
            log(f"  {cond.name}: {c.saves} SAVE, {c.goals} GOAL, {c.misses} MISS ({seconds:.1f} s)")
        counts = {key: counts_of(done[c.name]) for key, c in keyed}
        _fill(section, experiment, counts, plan.include_all)
        section.stages.append(StageTiming(experiment, ran, wall))

    for experiment in ("Table 1", "checks (still, straight)"):
        for key, cond in plan_of.get(experiment, []):
            section.trials[key] = done[cond.name]
    main = plan_of["Table 1"][0][1]
    start = time.perf_counter()
    recorded = record_examples(main, done[main.name], out / "recordings" / field_model, plan, log)
    section.stages.append(StageTiming("record", recorded, time.perf_counter() - start))
    return section, unique_conditions(plan_of)


def train(plan: Layer1Plan, dataset: InterceptionDataset, model_dir: Path, log: Log) -> Trained:
    """The Figure 7 series of nets, the main net's choice and its lookup table."""
    seconds: dict[int, float] = {}
    sizes = training_sizes(plan, len(dataset))
    nets = train_series(dataset, sizes, plan.epochs, model_dir, log, seconds)
    main = net_for_figures(plan, nets)
    lookup = build_lookup(nets[main], dataset, model_dir / "lookup.json")
    return Trained(nets, main, lookup, seconds)


def record_examples(
    cond: Condition,
    results: Sequence[TrialResult],
    record_dir: Path,
    plan: Layer1Plan,
    log: Log,
) -> int:
    """Rerun the first saves and goals of `cond` with rerun recording on; return how many.

    A trial is a pure function of its seed and index, so the rerun is the same trial. The
    runner names each file with its outcome (``trial_<index>_<LABEL>.rrd``); here it becomes
    ``<condition>_trial<index>_<label>.rrd``.
    """
    # Needed only when recording (the module itself never loads the rerun SDK).
    from robotsoccer.replay.recording import recording_name

    chosen = [r for r in results if r.label == "SAVE"][: plan.record_saves]
    chosen += [r for r in results if r.label == "GOAL"][: plan.record_goals]
    record_dir.mkdir(parents=True, exist_ok=True)
    for first in chosen:
        spec = dataclasses.replace(
            cond.spec, record_dir=str(record_dir), record_trials=first.index + 1
        )
        again = run_trial(spec, first.index)
        raw = record_dir / recording_name(first.index, again.label)
        target = record_dir / f"{cond.name}_trial{first.index:04d}_{again.label}.rrd"
        raw.replace(target)
        if again.label != first.label:  # would mean a trial is not a function of its seed
            log(f"  warning: trial {first.index} gave {again.label} recorded, {first.label} before")
        log(f"  recorded {target}")
    return len(chosen)


def scaling_notes(field_model: str, preset: str) -> list[str]:
    """Markdown lines on the drill's geometry, launch and noise period on this field.

    From the drill's ``launch_plan``; adds how many times the ball-motion noise acts during a
    shot of the mean distance (the drill scales the robots' noise period so that it matches the
    Soccer Server's cycles in flight).
    """
    plan = launch_plan(field_facts(field_model, preset))
    lines = [
        "Drill geometry and launch (`robotsoccer.drills.intercept.launch_plan`; distances in "
        "metres, one unit = pitch length / 105; the scaling rule is in that module's "
        "docstring):",
        "",
        "| quantity | value |",
        "|---|---|",
    ]
    lines += [f"| {key} | {_fmt(value)} |" for key, value in dataclasses.asdict(plan).items()]
    lines += [
        f"| noise applications during a shot (arrival_time_s / noise_period_s) "
        f"| {plan.arrival_time_s / plan.noise_period_s:.1f} |",
        f"| trigger distance [units] | {plan.trigger_distance_m / plan.unit_m:.2f} |",
        f"| decisions after the trigger (trigger_to_arrival_s / decision period) "
        f"| {plan.trigger_to_arrival_s / (plan.decision_period_s or plan.sensor_period_s):.1f} |",
    ]
    return lines


def _fmt(value: object) -> str:
    if isinstance(value, float):
        return f"{value:.4g}"
    return str(value)


# ----------------------------------------------------------------------------- the whole run


def run_layer1(
    models: Sequence[tuple[str, str | None]],
    plan: Layer1Plan,
    out: Path,
    seed: int,
    workers: int | None,
    log: Log,
    title: str = "Layer 1 reproduction",
    created_by: str = "robotsoccer reproduce",
    progress: bool = False,
) -> tuple[Path, list[ModelSection]]:
    """Run layer 1 on each (field model, preset) and write one folder.

    The folder: ``config.json`` (plan, seeds, presets, every condition), ``datasets/``,
    ``models/``, ``results/``, ``recordings/``, ``plots/figure7.png``, ``plots/figure8.png`` and
    ``report.md``. Rerunning with the same plan and seed resumes (finished trials are kept).

    Returns:
        The report's path and the sections.

    Raises:
        PipelineError: `out` holds a run of another plan or seed.
    """
    from robotsoccer.experiments.plots import plot_figure7, plot_figure8
    from robotsoccer.experiments.report import report_markdown

    named = [(m, p or default_preset(m)) for m, p in models]
    seeds = seeds_for(seed)
    header = {
        "plan": plan.to_dict(),
        "seed": seed,
        "seeds": dataclasses.asdict(seeds),
        "models": [list(m) for m in named],
        "code_version": code_version(),
    }
    claim_folder(out, header)
    start = time.perf_counter()
    sections, conditions = [], {}
    for field_model, preset in named:
        section, conds = run_model(
            field_model, preset, plan, out, seeds, workers, log, created_by, progress
        )
        sections.append(section)
        conditions[field_model] = {
            name: {"n_trials": c.n_trials, "spec": dataclasses.asdict(c.spec)}
            for name, c in conds.items()
        }
    plots = []
    for caption, draw, name in (
        ("Figure 7: saves vs training examples", plot_figure7, "figure7.png"),
        ("Figure 8: saves vs ball noise", plot_figure8, "figure8.png"),
    ):
        if draw(sections, out / "plots" / name) is not None:
            plots.append((caption, f"plots/{name}"))
    wall = time.perf_counter() - start
    intro = intro_lines(plan, seeds, named, wall, workers, sections)
    report = out / "report.md"
    report.write_text(report_markdown(title, intro, sections, plots))
    config = {**header, "wall_s": round(wall, 1), "conditions": conditions}
    (out / "config.json").write_text(json.dumps(config, indent=2) + "\n")
    return report, sections


def claim_folder(out: Path, header: dict[str, Any]) -> None:
    """Refuse a folder holding another run's results; mark it as this run's and hold it.

    The folder's lock (:func:`~robotsoccer.runs.folders.lock_run_folder`) stays held until the
    command ends, so no other run writes there meanwhile, and the run's manifests store paths
    relative to it.

    Raises:
        PipelineError: ``config.json`` there differs in what defines the run.
        FolderInUseError: Another process holds the folder.
    """
    out.mkdir(parents=True, exist_ok=True)
    lock_run_folder(out)
    path = out / "config.json"
    if path.exists():
        try:
            old = json.loads(path.read_text())
        except ValueError:
            old = {}
        new = json.loads(json.dumps(header))
        differ = [k for k in new if old.get(k) != new[k]]
        if differ:
            raise PipelineError(
                f"{out} holds a run with another {', '.join(d.replace('_', ' ') for d in differ)};"
                " choose another --out or remove it"
            )
    path.write_text(json.dumps(header, indent=2) + "\n")


def intro_lines(
    plan: Layer1Plan,
    seeds: Seeds,
    models: Sequence[tuple[str, str]],
    wall_s: float,
    workers: int | None,
    sections: Sequence[ModelSection] = (),
) -> list[str]:
    """The report's introduction: what ran, seeds, presets, noise meaning, training set-up."""
    from robotsoccer.runs.pool import default_workers

    presets = ", ".join(f"{m} `{p}`" for m, p in models)
    return [
        f"Plan **{plan.name}**: {plan.eval_trials} trials per evaluation condition; the "
        f"training drill runs until {plan.collect_saves} saves. Field models and presets: "
        f"{presets}. Wall time {wall_s / 60:.1f} min with {workers or default_workers()} "
        "worker(s).",
        "",
        f"Seeds: evaluation seed {seeds.evaluation}, shared by every condition (trial i has the "
        "same placement whatever the behaviour: paired comparisons); training collection seed "
        f"{seeds.collection} (derived; never an evaluation seed).",
        "",
        f"Ball noise: {plan.noise:g} unless varied. On every field model it is a uniform "
        "perturbation of the ball's velocity in ±noise·|v| per axis (the Soccer Server's "
        "`ball_rand`), applied once per `noise_period_s` of the drill's launch plan (each "
        "model's table below): one server cycle on the paper's field, one *scaled* cycle "
        "elsewhere, so the noise acts as many times per shot on every field.",
        "",
        "Calibrated settings (chosen to match the paper, not reproduced): the defender stops "
        "the ball with its body instead of kicking it clear, chosen so that the training "
        "drill's baselines match §5 (rows whose setting reads *calibrated*: the still and "
        "straight defenders at the main noise on the paper's field); the placement sector of "
        "±45° around the defender (the paper draws it without a number). Every other row was "
        "not tuned.",
        "",
        "Percentages are of all trials (misses count in n); each carries its 95% Wilson "
        "interval in brackets; Saves/(Goals+Saves) is a share of the shots on goal, with its "
        "own n. The paper's number sits in the column beside ours. **setting** says how the "
        "row was run: the paper's setting, *calibrated* to a paper number (and to which), or "
        "another field's own setting. **vs paper** says `agrees` where the paper's figure "
        "lies inside our 95% interval, otherwise whether ours is `above` or `below` it and by "
        "how many points (ours minus the paper's); a row with several paper figures gives "
        "each in column order (saves / goals / saves of the shots on goal), unless all agree.",
        "",
        *training_lines(plan, sections),
    ]


def training_lines(plan: Layer1Plan, sections: Sequence[ModelSection] = ()) -> list[str]:
    """The net's training set-up and why it differs from the paper's (learning.interception)."""
    from learning.interception import DEFAULT_LEARNING_RATES, InterceptionModel

    params = InterceptionModel(epochs=plan.epochs).get_params()
    rate = params["learning_rate"] or DEFAULT_LEARNING_RATES[params["optimizer"]]
    return [
        f"Training: the paper's net (3 inputs → {params['hidden']} sigmoid → 1 linear), "
        f"{params['optimizer']} at learning rate {rate:g}, full batch, {params['epochs']} "
        f"epochs, input-to-hidden weight decay {100 * params['weight_decay']:g}% per update "
        "falling linearly to 0, none on the output; float64, one thread, seed "
        f"{params['random_state']}. Nets train on the first n saves of the collection (nested "
        "subsets). The paper used plain back-propagation at a learning rate of 1e-6 on raw "
        "inputs (distances in units, angles in degrees), 3000 epochs, the same decay. We "
        "standardise the inputs (the scaler is stored in the model file) so that one rate "
        "suits fields of any size, and train with the optimizer above (`learning/"
        "interception.py` says why).",
        *_training_times(sections),
    ]


def _training_times(sections: Sequence[ModelSection]) -> list[str]:
    """This run's training time of each field model's largest net, as a line (or none)."""
    parts = []
    for s in sections:
        if s.train_seconds:
            n = max(s.train_seconds)
            parts.append(f"{s.field_model}: {n} saves in {s.train_seconds[n]:.1f} s")
    if not parts:
        return []
    return ["", "Training time of the largest net in this run: " + "; ".join(parts) + "."]


def train_main_net(
    field_model: str,
    preset: str,
    plan: Layer1Plan,
    out: Path,
    seeds: Seeds,
    workers: int | None,
    log: Log,
    progress: bool = False,
    created_by: str = "robotsoccer learn pass",
) -> Path:
    """Layer 1's collection and its main net only (no evaluations), for a layer-2 run.

    The same collection and training as :func:`run_model` (same seeds, same files), so a later
    ``reproduce`` into the same folder resumes them. Returns the net's file.
    """
    dataset, _, _ = collect_into(
        field_model, preset, plan, out, seeds, workers, log, created_by, progress
    )
    main = net_for_figures(plan, training_sizes(plan, len(dataset)))
    return train_series(dataset, [main], plan.epochs, out / "models" / field_model, log)[main]


def collect_into(
    field_model: str,
    preset: str,
    plan: Layer1Plan,
    out: Path,
    seeds: Seeds,
    workers: int | None,
    log: Log,
    created_by: str,
    progress: bool = False,
) -> tuple[InterceptionDataset, Counts, StageTiming]:
    """:func:`collect` for one field model into the run folder's usual places, logged."""
    log(f"[{field_model}] collect: random TA until {plan.collect_saves} saves")
    dataset, collected, timing = collect(
        base_spec(field_model, preset, seeds.collection, plan.ta_mode),
        plan,
        out / "results" / field_model,
        out / "datasets" / field_model / "train.npz",
        workers,
        created_by,
        progress,
    )
    log(f"  {collected.saves} saves of {collected.n} trials ({timing.wall_s:.1f} s)")
    return dataset, collected, timing
