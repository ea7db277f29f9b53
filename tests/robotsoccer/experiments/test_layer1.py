"""Layer-1 experiments: the report in the paper's layout, the plans, a tiny pipeline end to end."""

from __future__ import annotations

import dataclasses
import json
import subprocess
import sys
from pathlib import Path

import pytest

from learning.datasets import InterceptionDataset
from learning.lookup import LookupTable
from robotsoccer.experiments import paper
from robotsoccer.experiments.context import RunContext
from robotsoccer.experiments.layer1 import run_layer1
from robotsoccer.experiments.layer1_evaluate import experiments, unique_conditions
from robotsoccer.experiments.layer1_plan import (
    Layer1Plan,
    PipelineError,
    base_spec,
    full_plan,
    quick_plan,
    seeds_for,
)
from robotsoccer.experiments.layer1_train import Trained, training_sizes
from robotsoccer.experiments.paper import PaperRow
from robotsoccer.experiments.report import report_markdown
from robotsoccer.experiments.report_cells import (
    paper_table,
    percent_cell,
    versus_cell,
    versus_paper,
)
from robotsoccer.experiments.report_differences import claims, differences, net_lead_line
from robotsoccer.experiments.report_records import (
    OWN_SETTING,
    PAPER_SETTING,
    Counts,
    ModelSection,
    Row,
)

# ----------------------------------------------------------------------------- report writer


def test_percent_cell_is_the_wilson_interval_in_percent() -> None:
    # 53/100: Wilson 95% interval [43.28%, 62.48%] (robotsoccer.stats doctest).
    assert percent_cell(53, 100) == "53.0 [43.3, 62.5]"
    assert percent_cell(0, 0) == "—"
    assert percent_cell(10, 10) == "100.0 [72.2, 100.0]"


def test_paper_table_puts_ours_with_intervals_beside_the_papers() -> None:
    counts = Counts(saves=860, goals=90, misses=50)
    table = paper_table(("Training examples",), [Row(("750",), counts, paper.FIGURE_7[750])])
    header, rule, row = table.splitlines()
    assert header.startswith("| Training examples | Saves (%) | paper | Goals (%) | paper |")
    assert "Saves/(Goals+Saves) (%)" in header
    assert header.endswith("| n | setting | vs paper |")
    assert rule.count("---") == 10
    cells = [c.strip() for c in row.strip("|").split("|")]
    assert cells[0] == "750"
    assert cells[1] == "86.0 [83.7, 88.0]" and cells[2] == "86"
    assert cells[3] == "9.0 [7.4, 10.9]" and cells[4] == "9"
    # Saves/(Goals+Saves) = 860/950 with its own n.
    assert cells[5] == "90.5 [88.5, 92.2] of 950" and cells[6] == "91"
    assert cells[7] == "1000" and cells[8] == PAPER_SETTING
    # 86 in [83.7, 88.0], 9 in [7.4, 10.9], 91 in [88.5, 92.2]: every figure agrees.
    assert cells[9] == "agrees"
    calibrated = Row(("750",), counts, paper.FIGURE_7[750], "*calibrated* to §5")
    assert paper_table(("Training examples",), [calibrated]).endswith(
        "| *calibrated* to §5 | agrees |"
    )


def test_rows_without_paper_numbers_or_runs_show_dashes() -> None:
    table = paper_table(("Behavior",), [Row(("NN",), None, paper.AIM_4_DEG_WIDE["net"])])
    cells = [c.strip() for c in table.splitlines()[2].strip("|").split("|")]
    assert cells == ["NN", "not run", "99", "—", "—", "—", "—", "—", PAPER_SETTING, "—"]
    table = paper_table(("Behavior",), [Row(("NN",), Counts(1, 0, 0))])
    assert table.endswith("| — | — |")  # no paper number: no setting, no verdict


# The paper's 86 against 1000 trials: inside our interval, above it (ours below), below it.
@pytest.mark.parametrize(
    ("saves", "word"),
    [
        (860, "agrees"),  # 86.0 [83.7, 88.0]
        (845, "agrees"),  # 84.5 [82.1, 86.6]: 86 inside, near the top
        (612, "below (-24.8 pts)"),  # 61.2 [58.1, 64.2]: the robot NN row
        (900, "above (+4.0 pts)"),  # 90.0 [88.0, 91.7]
    ],
)
def test_vs_paper_says_agrees_above_or_below_by_the_interval(saves: int, word: str) -> None:
    assert versus_paper(saves, 1000, 86.0) == word
    row = Row(("NN",), Counts(saves, 0, 1000 - saves), PaperRow(86.0, None, None, "t"))
    cells = [c.strip() for c in paper_table(("Behavior",), [row]).splitlines()[2].split("|")]
    assert cells[-2] == word


def test_vs_paper_at_the_ends_of_the_scale() -> None:
    # 0 of 100: our interval is [0.0, 3.7] at the printed precision, so a paper 0 agrees and a
    # paper 5 lies above it.
    assert versus_paper(0, 100, 0.0) == "agrees"
    assert versus_paper(0, 100, 5.0) == "below (-5.0 pts)"
    assert versus_paper(100, 100, 100.0) == "agrees"
    assert versus_paper(100, 100, 90.0) == "above (+10.0 pts)"
    assert versus_paper(5, 10, None) == "—" and versus_paper(0, 0, 50.0) == "—"


def test_a_row_whose_figures_disagree_names_each_in_column_order() -> None:
    # Figure 8's straight row (53 / 35 / 60) beside 400 saves, 450 goals, 150 misses:
    # saves 40.0 [37.0, 43.1] below, goals 45.0 [41.9, 48.1] above, 400/850 = 47.1 below.
    row = Row(("Straight",), Counts(400, 450, 150), paper.FIGURE_8[(0.05, "straight")])
    cells = [c.strip() for c in paper_table(("B",), [row]).splitlines()[2].split("|")]
    assert cells[-2] == "below (-13.0 pts) / above (+10.0 pts) / below (-12.9 pts)"
    # Only the goals disagree: the others say agrees, each in its place.
    row = Row(("Straight",), Counts(530, 450, 20), paper.FIGURE_8[(0.05, "straight")])
    cells = [c.strip() for c in paper_table(("B",), [row]).splitlines()[2].split("|")]
    assert cells[-2].split(" / ")[0] == "agrees"
    assert cells[-2].split(" / ")[1] == "above (+10.0 pts)"
    # A missing paper figure is a dash in its place.
    assert versus_cell(["below (-1.0 pts)", "—", "agrees"]) == "below (-1.0 pts) / — / agrees"
    assert versus_cell(["agrees", "—", "—"]) == "agrees"
    assert versus_cell(["—", "—", "—"]) == "—"


def test_a_row_must_match_the_key_headers() -> None:
    with pytest.raises(ValueError, match="does not match"):
        paper_table(("Noise", "Behavior"), [Row(("0.05",), Counts(1, 0, 0))])


def test_counts_from_labels_refuses_unknown_labels() -> None:
    assert Counts.from_labels(["SAVE", "GOAL", "SAVE", "MISS"]) == Counts(2, 1, 1)
    with pytest.raises(ValueError, match="unexpected"):
        Counts.from_labels(["SAVE", "FAILURE"])


def _section() -> ModelSection:
    s = ModelSection("soccer_server", "soccer_server_1996")
    s.figure7 = [(100, "100", Counts(570, 330, 100)), (900, "all (900)", Counts(700, 100, 200))]
    s.figure8 = {
        (0.0, "net"): Counts(1000, 0, 0),
        (0.0, "straight"): Counts(990, 10, 0),
        (0.05, "net"): Counts(860, 90, 50),
        (0.05, "straight"): Counts(530, 350, 120),
        (0.1, "net"): Counts(270, 300, 430),
        (0.1, "straight"): Counts(280, 320, 400),
    }
    s.table1 = {"net": Counts(860, 90, 50), "lookup": Counts(830, 80, 90)}
    s.checks = {"random": Counts(150, 90, 760)}
    return s


def test_figure7_all_row_sits_beside_the_papers_4773_row() -> None:
    text = report_markdown("t", [], [_section()])
    row = next(line for line in text.splitlines() if line.startswith("| all (900)"))
    cells = [c.strip() for c in row.strip("|").split("|")]
    assert cells[1] == "70.0 [67.1, 72.8]" and cells[2] == "84"  # paper's 4773 row


def test_differences_list_paper_numbers_outside_our_interval() -> None:
    facts = differences(_section())
    # Figure 7 "all" sits beside the paper's 4773 row (84 / 9 / 90): saves and the on-goal
    # share are outside our intervals, goals 10.0 [8.3, 12.0] hold the paper's 9.
    assert facts[0] == (
        "- Figure 7, all (900): saves 70.0 [67.1, 72.8] (n=1000) below the paper's 84; "
        "saves/(goals+saves) 87.5 [85.0, 89.6] (n=800) below the paper's 90."
    )
    # Paper numbers inside our interval give no line: 100 examples, 57/33/63 vs ours 57/33/63.
    assert not any(f.startswith("- Figure 7, 100:") for f in facts)
    # No noise: the paper's 0% goals is inside our 0.0 [0.0, 0.4] at the printed precision.
    assert not any(f.startswith("- Figure 8, 0 / NN:") for f in facts)
    # Figure 8 at 0.1: the paper's NN 49% is far above our 27%.
    row = next(f for f in facts if f.startswith("- Figure 8, 0.1 / NN:"))
    assert row.startswith(
        "- Figure 8, 0.1 / NN: saves 27.0 [24.3, 29.8] (n=1000) below the paper's 49;"
    )
    # The random-TA defender fails to stop 85.0% (goals and misses), the paper says 76%.
    assert facts[-1] == (
        "- Training drill, Random TA: trials the random-TA defender fails to stop (%) "
        "85.0 [82.7, 87.1] (n=1000) above the paper's 76."
    )


def test_claims_are_checked_with_their_numbers() -> None:
    lines = claims(_section())
    assert lines[0].startswith("- PASS: noise .05, the net saves +33.0 points")
    assert lines[1] == "- FAIL: net ≥ straight at every noise level above 0 (not at 0.1)."
    assert lines[2].startswith("- PASS: no noise, both near 100% (net 100.0%, straight 99.0%")


def test_net_lead_is_given_per_noise_level_beside_the_papers() -> None:
    assert net_lead_line(_section()) == (
        "Net minus straight, saves in points, by ball noise: 0: +1.0 (paper +0), "
        "0.05: +33.0 (paper +33), 0.1: -1.0 (paper +21)."
    )


def test_report_has_every_section_and_the_differences() -> None:
    text = report_markdown("Layer 1", ["intro line"], [_section()], [("F7", "plots/figure7.png")])
    for heading in (
        "# Layer 1",
        "## Plots",
        "![F7](plots/figure7.png)",
        "## soccer_server (`soccer_server_1996`)",
        "### Figure 7",
        "### Figure 8",
        "### Table 1",
        "### Training-drill checks",
        "## Where we differ from the paper",
    ):
        assert heading in text, heading
    assert "| Lookup Table | 83.0 [80.5, 85.2] | 83 |" in text


# ----------------------------------------------------------------------------- plans


def test_full_plan_runs_the_papers_1000_trials_and_every_condition() -> None:
    plan = full_plan()
    assert plan.eval_trials == 1000
    assert plan.training_sizes == (100, 200, 300, 400, 500, 750, 1000)
    assert plan.include_all and plan.net_examples == 750 and plan.epochs == 3000
    assert plan.noises == (0.0, 0.05, 0.06, 0.07, 0.08, 0.09, 0.1)
    assert plan.latencies_s == (0.0, 0.05, 0.1)
    assert plan.aim_offset_deg == 4.0 and plan.noise == 0.05
    assert plan.collect_saves == 4773  # the paper's "all" saves


def test_quick_plan_is_smaller_in_every_trial_count() -> None:
    quick, full = quick_plan(), full_plan()
    assert quick.eval_trials == 200
    assert quick.collect_saves < full.collect_saves
    assert quick.noises == full.noises and quick.training_sizes == full.training_sizes


def test_training_sizes_are_capped_by_the_saves_and_include_all() -> None:
    plan = full_plan()
    assert training_sizes(plan, 620) == [100, 200, 300, 400, 500, 620]
    assert training_sizes(plan, 750) == [100, 200, 300, 400, 500, 750]
    assert training_sizes(plan, 40) == [40]


def _plan_of(field_model: str, latency_s: float | None):
    plan = full_plan()
    nets = {n: Path(f"/m/net_{n}.npz") for n in (*plan.training_sizes, 4500)}
    trained = Trained(nets, 750, Path("/m/lookup.json"))
    base = base_spec(field_model, "p", seed=7, ta_mode="hold")
    return plan, experiments(plan, base, trained, latency_s)


def test_full_plan_conditions_on_the_soccer_server() -> None:
    _, plan_of = _plan_of("soccer_server", None)
    assert list(plan_of) == [
        "Figure 7",
        "Figure 8",
        "Table 1",
        "4° wide",
        "checks (still, straight)",
    ]
    assert len(plan_of["Figure 7"]) == 8 and len(plan_of["Figure 8"]) == 14
    unique = unique_conditions(plan_of)
    # Shared: net750 at .05 (Figure 7, 8, Table 1), straight at .05 (Figure 8, Table 1, checks).
    assert len(unique) == 8 + 13 + 2 + 2 + 1
    assert all(c.n_trials == 1000 for c in unique.values())
    # Common random numbers: one evaluation seed for every behaviour and noise.
    assert {c.spec.seed for c in unique.values()} == {7}
    net = unique["net750_noise0.05"].spec
    assert dict(net.drill_options) == {
        "behaviour": "net",
        "model": str(Path("/m/net_750.npz").resolve()),
        "ta_mode": "hold",
    }
    assert net.field.ball_noise == 0.05 and net.field.sensor_latency_s is None
    wide = unique["straight_noise0_aim4"].spec
    assert dict(wide.drill_options)["aim_offset_deg"] == 4.0 and wide.field.ball_noise == 0
    assert dict(unique["lookup750_noise0.05"].spec.drill_options)["model"].endswith("lookup.json")


def test_full_plan_adds_camera_latency_on_robots() -> None:
    _, plan_of = _plan_of("robot_physics", 0.05)
    keys = [key for key, _ in plan_of["camera latency"]]
    assert keys == [(lat, b) for lat in (0.0, 0.05, 0.1) for b in ("net", "straight", "analytic")]
    unique = unique_conditions(plan_of)
    # The preset's own 50 ms runs once, shared with Table 1; 0 and 100 ms are new.
    assert len(unique) == 26 + 6
    assert unique["analytic_noise0.05_latency100ms"].spec.field.sensor_latency_s == 0.1
    assert unique["net750_noise0.05_latency0ms"].spec.field.sensor_latency_s == 0.0


def test_collection_and_evaluation_seeds_differ() -> None:
    for seed in range(20):
        seeds = seeds_for(seed)
        assert seeds.evaluation == seed
        assert seeds.collection != seed and seeds.collection == seeds_for(seed).collection


# ----------------------------------------------------------------------------- end to end


TINY = Layer1Plan(
    name="tiny",
    eval_trials=24,
    collect_saves=60,
    collect_batch=300,
    training_sizes=(10, 20),
    net_examples=20,
    noises=(0.0, 0.05),
    epochs=30,
    record_saves=1,
    record_goals=1,
)


def test_tiny_pipeline_writes_report_plots_models_and_results(tmp_path) -> None:
    out = tmp_path / "run"
    lines: list[str] = []
    ctx = RunContext.for_seed(out, 3, 1, lines.append)
    report, sections = run_layer1([("soccer_server", None)], TINY, ctx)
    assert report == out / "report.md"
    text = report.read_text()
    assert "### Figure 7" in text and "### Table 1" in text and "## Where we differ" in text
    assert (out / "plots" / "figure7.png").stat().st_size > 1000
    assert (out / "plots" / "figure8.png").stat().st_size > 1000
    models = out / "models" / "soccer_server"
    assert (models / "net_10.npz").exists() and (models / "net_20.npz").exists()
    assert (models / "lookup.json").exists()
    dataset = InterceptionDataset.load(out / "datasets" / "soccer_server" / "train.npz")
    provenance = dataset.provenance
    assert provenance.field_model == "soccer_server" and provenance.preset == "soccer_server_1996"
    assert provenance.behaviour == "random" and provenance.ball_noise == 0.05
    assert provenance.seed == seeds_for(3).collection and provenance.n_trials >= 300
    assert len(dataset) == provenance.extra["saves"] - provenance.extra["saves_without_decision"]
    assert len(dataset) >= TINY.collect_saves
    assert LookupTable.load(models / "lookup.json").built_from["net"] == "net_20.npz"
    results = out / "results" / "soccer_server"
    csv = (results / "net20_noise0.05.csv").read_text().splitlines()
    assert len(csv) == 1 + TINY.eval_trials
    config = json.loads((out / "config.json").read_text())
    assert config["plan"]["name"] == "tiny" and config["seed"] == 3
    assert "straight_noise0.05" in config["conditions"]["soccer_server"]
    section = sections[0]
    assert section.figure8[(0.05, "net")].n == TINY.eval_trials
    assert len(list((out / "recordings" / "soccer_server").glob("*.rrd"))) >= 1

    # A second run resumes: nothing new to run, the same counts.
    _, sections2 = run_layer1([("soccer_server", None)], TINY, ctx)
    assert sections2[0].figure8 == section.figure8
    assert all(stage.trials == 0 for stage in sections2[0].stages if stage.name != "record")

    # Another seed into the same folder is refused.
    with pytest.raises(PipelineError, match="another seed"):
        run_layer1([("soccer_server", None)], TINY, RunContext.for_seed(out, 4, 1, lines.append))


def test_a_cycle_client_run_collects_and_evaluates_on_that_client(tmp_path) -> None:
    """``learn intercept --client cycle``: the client option reaches collection and every
    condition, the dataset and the report say so; the see client's specs carry no option."""
    plan = dataclasses.replace(
        TINY, client="cycle", eval_trials=8, collect_saves=20, collect_batch=200, checks=False
    )
    plan = dataclasses.replace(plan, training_sizes=(10,), net_examples=10, noises=(0.05,))
    out = tmp_path / "run"
    report, _ = run_layer1(
        [("soccer_server", "rcssserver_19")], plan, RunContext.for_seed(out, 3, 1)
    )
    config = json.loads((out / "config.json").read_text())
    assert config["plan"]["client"] == "cycle"
    conditions = config["conditions"]["soccer_server"].values()
    assert all(["client", "cycle"] in c["spec"]["drill_options"] for c in conditions)
    dataset = InterceptionDataset.load(out / "datasets" / "soccer_server" / "train.npz")
    assert dataset.provenance.extra["client"] == "cycle"
    assert "Defender client, in every table below (collection and evaluation): the per-cycle" in (
        report.read_text()
    )
    assert "client" not in TINY.to_dict()
    see = base_spec("soccer_server", "rcssserver_19", 0, "hold")
    assert see.drill_options == (("ta_mode", "hold"),)
    with pytest.raises(ValueError, match=r"unknown client 'every' \(known: see, cycle\)"):
        dataclasses.replace(TINY, client="every")


def test_cli_learn_and_reproduce_refuse_bad_input_in_one_line() -> None:
    for args in (
        ("learn", "intercept", "--field", "soccer_server", "--client", "every"),
        ("learn", "intercept", "--field", "mars"),
        ("learn", "tackle", "--field", "soccer_server"),
        ("learn", "pass", "--field", "soccer_server", "--net", "no-such-net.npz"),
        ("reproduce", "--workers", "0"),
        ("learn", "intercept", "--field", "soccer_server", "--field-preset", "nope"),
    ):
        done = subprocess.run(
            [sys.executable, "-m", "robotsoccer.cli", *args],
            capture_output=True,
            text=True,
            timeout=120,
        )
        assert done.returncode == 2, args
        assert "Traceback" not in done.stderr
        assert len(done.stderr.strip().splitlines()) == 1, done.stderr


def test_the_soccer_server_gets_a_pass_through_check_on_the_swept_preset() -> None:
    plan = full_plan()
    nets = {n: Path(f"/m/net_{n}.npz") for n in plan.training_sizes}
    trained = Trained(nets, 750, Path("/m/lookup.json"))
    base = base_spec("soccer_server", "soccer_server_1996", seed=7, ta_mode="hold")
    plan_of = experiments(plan, base, trained, None)
    swept = plan_of["swept collisions"]
    assert [key for key, _ in swept] == [
        (0.0, "net"),
        (0.0, "straight"),
        (0.05, "net"),
        (0.05, "straight"),
    ]
    for _, cond in swept:
        assert cond.spec.preset == "soccer_server_1996_swept"
        assert cond.name.endswith("_swept")
    assert "swept collisions" not in _plan_of("robot_physics", 0.05)[1]


def test_the_straight_baseline_at_the_main_noise_is_marked_calibrated() -> None:
    section = _section()
    section.table1["straight"] = Counts(530, 350, 120)
    section.checks["straight"] = Counts(530, 350, 120)
    text = report_markdown("t", [], [section])
    calibrated = f"| *calibrated* to {paper.CALIBRATED[('straight', 0.05)]} | agrees |"
    rows = [line for line in text.splitlines() if line.startswith("| Straight")]
    assert rows and all(row.endswith(calibrated) for row in rows)
    f8 = [line for line in text.splitlines() if line.startswith("| 0.1 | Straight")]
    assert f8 and f8[0].split(" | ")[-2] == PAPER_SETTING  # other noise levels were not tuned


def test_rows_on_another_field_state_its_own_setting() -> None:
    section = _section()
    section.field_model, section.preset = "robot_physics", "small_size_1997"
    section.table1 = {"net": Counts(612, 200, 188), "straight": Counts(530, 350, 120)}
    text = report_markdown("t", [], [section])
    nn = next(line for line in text.splitlines() if line.startswith("| NN |"))
    # The robot NN row of the issue: 61.2 against the paper's 86 is below, and nothing there
    # was calibrated (the straight row neither: the blocking defender was chosen on the server).
    verdict = "below (-24.8 pts) / above (+11.0 pts) / below (-15.6 pts)"
    assert nn.endswith(f"| {OWN_SETTING} | {verdict} |")
    straight = next(line for line in text.splitlines() if line.startswith("| Straight |"))
    assert f"| {OWN_SETTING} | agrees |" in straight


def test_why_lines_come_from_this_runs_trials_and_facts() -> None:
    from field_models.registry import field_facts
    from robotsoccer.experiments.report_cells import paired_difference
    from robotsoccer.experiments.report_differences import why_lines
    from robotsoccer.runs.runner import TrialResult

    def trial(i: int, label: str, travel: float) -> TrialResult:
        measures = (("defender_travel_units", travel), ("updates_after_trigger", 5.0))
        return TrialResult(i, label, "", 10, 1.0, (), measures)

    section = _section()
    section.facts = field_facts("soccer_server")
    section.trials = {
        "net": [trial(i, "SAVE" if i % 2 else "GOAL", 2.0 * i) for i in range(10)],
        "straight": [trial(i, "GOAL", 1.0) for i in range(10)],
    }
    diff, low, high, n = paired_difference(section.trials["net"], section.trials["straight"])
    assert (diff, n) == (50.0, 10) and low < 50.0 < high
    lines = why_lines(section)
    lead = next(line for line in lines if line.startswith("- **Net vs straight**"))
    assert "+50.0 points" in lead and "(n = 10)" in lead and "a gain" in lead
    travel = next(line for line in lines if "How far the defender gets" in line)
    assert "Straight 1.00 units" in travel and "NN 9.00 units" in travel
    target = next(line for line in lines if "Target and speed" in line)
    assert "0.89 units" in target  # (0.8 + 0.085) m on the 105 m pitch
