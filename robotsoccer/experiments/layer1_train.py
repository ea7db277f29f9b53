"""Layer 1's training step (§5): the paper's 3-4-1 nets on nested prefixes, and the lookup table.

:func:`train_series` trains the net on the first n saves for each n of Figure 7 (100 … 1000)
and on all of them; :func:`build_lookup` builds the §5 table from the main net. Subsets are
*prefixes* in trial order: the net on 300 saves learns what the drill had produced after its
300th save, as if collection had stopped there, and the subsets are nested.
"""

from __future__ import annotations

import dataclasses
import time
from collections.abc import Iterable, Sequence
from dataclasses import dataclass
from pathlib import Path

from learning.datasets import InterceptionDataset
from learning.lookup import PAPER_GRID_DEG, LookupTable
from robotsoccer.experiments.layer1_plan import Layer1Plan, Log, PipelineError


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


def train(plan: Layer1Plan, dataset: InterceptionDataset, model_dir: Path, log: Log) -> Trained:
    """The Figure 7 series of nets, the main net's choice and its lookup table."""
    seconds: dict[int, float] = {}
    sizes = training_sizes(plan, len(dataset))
    nets = train_series(dataset, sizes, plan.epochs, model_dir, log, seconds)
    main = net_for_figures(plan, nets)
    lookup = build_lookup(nets[main], dataset, model_dir / "lookup.json")
    return Trained(nets, main, lookup, seconds)
