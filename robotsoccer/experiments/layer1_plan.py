"""Layer 1's set-up (§5): the run plans, the experiment seeds, the evaluation conditions.

What the plans hold (:func:`quick_plan`, :func:`full_plan`): see :class:`Layer1Plan`. Seeds
(common random numbers): every evaluation condition of a field model uses the same
experiment seed, so trial i places shooter, ball and defender identically whatever the
behaviour (paired comparisons). Collection uses a different seed derived from it
(:func:`seeds_for`), so the nets are never tested on the placements they were trained on.
A :class:`Condition` is one named thing to evaluate (:func:`condition`).
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from robotsoccer.experiments import paper

# Re-exported: the experiments imported these from here before the context had a module.
from robotsoccer.experiments.context import Field as Field
from robotsoccer.experiments.context import Log as Log
from robotsoccer.experiments.context import Seeds as Seeds
from robotsoccer.experiments.context import seeds_for as seeds_for
from robotsoccer.runs.runner import TrialSpec
from robotsoccer.skills.intercept import TaMode

DRILL = "intercept"
"""The registered name of the interception drill (paper Figure 6)."""

CLIENTS = ("see", "cycle")
"""The drill's defender clients (:class:`robotsoccer.drills.intercept_options.ClientKind`)."""

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
        client: The defender's client (the drill's ``client`` option): ``"see"``, the
            paper's see-triggered client (every shipped plan, ``reproduce``), or ``"cycle"``,
            the per-cycle client of issue 28 (``learn intercept --client cycle``).
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
    client: str = "see"

    def __post_init__(self) -> None:
        if self.client not in CLIENTS:
            raise ValueError(f"unknown client {self.client!r} (known: {', '.join(CLIENTS)})")

    def to_dict(self) -> dict[str, Any]:
        """The plan as plain JSON types (``client`` only where it is not the paper's)."""
        plan = dataclasses.asdict(self)
        if self.client == "see":  # run folders of the see client keep their config (resume)
            del plan["client"]
        return plan


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
class Condition:
    """One evaluation condition: a name (its CSV file), what to run and how many trials."""

    name: str
    spec: TrialSpec
    n_trials: int


def base_spec(
    field_model: str, preset: str, seed: int, ta_mode: TaMode | str, client: str = "see"
) -> TrialSpec:
    """The interception drill on a field model, before behaviour, noise and latency.

    The see client is the drill's default, so its specs carry no ``client`` option (they stay
    those of earlier runs, which resume).
    """
    spec = TrialSpec(drill=DRILL, field_model=field_model, preset=preset, seed=seed)
    spec = spec.with_options(ta_mode=str(ta_mode))
    return spec if client == "see" else spec.with_options(client=client)


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
