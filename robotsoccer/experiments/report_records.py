"""The layer-1 report's records: counts, rows, stage timings and a field model's section (§5).

:mod:`robotsoccer.experiments.layer1` fills a :class:`ModelSection` per field model; the rest of
the report renders it (:mod:`~robotsoccer.experiments.report_cells`,
:mod:`~robotsoccer.experiments.report_tables`, :mod:`~robotsoccer.experiments.report_differences`,
:mod:`~robotsoccer.experiments.report`). The words every table shares live here too: the
behaviours' names in the paper's words and the setting and vs-paper cells' fixed texts.
"""

from __future__ import annotations

from collections import Counter
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field

from field_models.arena import FieldFacts
from robotsoccer.experiments.paper import PaperRow
from robotsoccer.runs.runner import TrialResult

BEHAVIOUR_NAMES = {
    "net": "NN",
    "straight": "Straight",
    "lookup": "Lookup Table",
    "analytic": "Analytic",
    "random": "Random TA",
    "still": "Still",
}
"""How each defender behaviour is named in the tables (the paper's words)."""

PAPER_SETTING = "the paper's setting"
"""Setting cell of a row run as the paper ran it, on the paper's own field."""
OWN_SETTING = "our field's own setting"
"""Setting cell of a row on another field: the drill carried there, nothing tuned to the paper."""
SWEPT_SETTING = "our variant: swept collisions"
"""Setting cell of the pass-through check's swept rows (a diagnostic preset of ours)."""
AGREES = "agrees"
"""The vs-paper word when the paper's figure lies inside our 95% interval."""


@dataclass(frozen=True, slots=True)
class Counts:
    """How many trials of one condition ended in each label."""

    saves: int
    goals: int
    misses: int

    @property
    def n(self) -> int:
        """All trials."""
        return self.saves + self.goals + self.misses

    @property
    def on_goal(self) -> int:
        """Shots on goal: saves + goals."""
        return self.saves + self.goals

    @classmethod
    def from_labels(cls, labels: Iterable[str]) -> Counts:
        """Count SAVE/GOAL/MISS labels (anything else is an error)."""
        counts = Counter(labels)
        unknown = set(counts) - {"SAVE", "GOAL", "MISS"}
        if unknown:
            raise ValueError(f"unexpected labels {sorted(unknown)}")
        return cls(counts["SAVE"], counts["GOAL"], counts["MISS"])

    def saves_pct(self) -> float:
        """Saves as a percentage of all trials (0 when there are none)."""
        return 100.0 * self.saves / self.n if self.n else 0.0


@dataclass(frozen=True, slots=True)
class Row:
    """One table row: its key cells, our counts (None: not run), the paper's row, the setting.

    `setting` is the row's setting cell (:func:`setting_of`); it shows only where the row has a
    paper number.
    """

    keys: tuple[str, ...]
    counts: Counts | None
    paper: PaperRow | None = None
    setting: str = PAPER_SETTING


@dataclass(frozen=True, slots=True)
class StageTiming:
    """Wall time of one stage of the pipeline and the trials it ran (resumed ones excluded)."""

    name: str
    trials: int
    wall_s: float

    def rate(self) -> str:
        """Trials per second, or "—" when the stage ran no trials."""
        if self.trials == 0 or self.wall_s <= 0.0:
            return "—"
        return f"{self.trials / self.wall_s:,.0f}"


@dataclass
class ModelSection:
    """Everything the report shows for one field model.

    Attributes:
        field_model: The field model's registered name.
        preset: The preset name.
        figure7: (training examples, row label, counts) per trained net, ascending.
        figure8: (noise, behaviour) → counts.
        table1: behaviour → counts (ball noise .05).
        wide: behaviour → counts (no noise, the shooter aiming 4° wide).
        latency: (camera latency [s], behaviour) → counts (robots only).
        swept: (noise, behaviour) → counts on the swept-collision variant preset (Soccer Server).
        checks: behaviour → counts of the training-drill checks (still, straight, random).
        noise: The ball noise of Figure 7, Table 1 and the checks.
        noise_period_s: How often the ball noise acts in the drill on this field [s].
        net_examples: Training examples of the net used in Figure 8, Table 1, 4° wide, latency.
        stages: Timing of each stage.
        notes: Free markdown lines (scaling, presets, ...), printed under the model's heading.
        facts: The field's facts (its geometry and speeds, for the "why" lines).
        trials: behaviour → the per-trial results at the main noise (Table 1 and the checks),
            whose measures the "why" lines summarise.
        train_seconds: training examples → wall seconds its net took in this run.
    """

    field_model: str
    preset: str
    figure7: list[tuple[int, str, Counts]] = field(default_factory=list)
    figure8: dict[tuple[float, str], Counts] = field(default_factory=dict)
    table1: dict[str, Counts] = field(default_factory=dict)
    wide: dict[str, Counts] = field(default_factory=dict)
    latency: dict[tuple[float, str], Counts] = field(default_factory=dict)
    swept: dict[tuple[float, str], Counts] = field(default_factory=dict)
    checks: dict[str, Counts] = field(default_factory=dict)
    noise: float = 0.05
    noise_period_s: float = 0.0
    net_examples: int = 750
    stages: list[StageTiming] = field(default_factory=list)
    notes: list[str] = field(default_factory=list)
    facts: FieldFacts | None = None
    trials: dict[str, Sequence[TrialResult]] = field(default_factory=dict)
    train_seconds: dict[int, float] = field(default_factory=dict)
