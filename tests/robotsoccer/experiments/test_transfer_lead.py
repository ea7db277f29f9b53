"""The lead decision's transfer matrix, with the calibrated server as a third field."""

from __future__ import annotations

from pathlib import Path

import pytest

from robotsoccer.drills.intercept import InterceptDrill
from robotsoccer.experiments.context import RunContext
from robotsoccer.experiments.layer1_plan import seeds_for
from robotsoccer.experiments.lead_study import LeadPlan, StudyDrill
from robotsoccer.experiments.transfer import (
    FLIGHT_SCALED,
    LeadNet,
    arrival_time_s,
    lead_time_scale,
    lead_transfer_conditions,
)
from robotsoccer.experiments.transfer_study import calibrated_label, run_lead_study
from robotsoccer.runs.table import iter_results
from robotsoccer.skills.lead import ScaledLead

ROBOT = StudyDrill(
    "robot_physics",
    "small_size_1997_arc",
    (
        ("shot", "goal_mouth"),
        ("scaling", "task"),
        ("launch", "coach"),
        ("launch_speed_mps", 0.6),
        ("launch_speed_max_mps", 1.2),
    ),
    "robot drill",
)
SERVER = StudyDrill("soccer_server", "soccer_server_1996", (), "server drill")
TINY = LeadPlan("tiny", eval_trials=8, collect_saves=8, collect_batch=40, epochs=10)


def test_the_time_scale_is_the_ratio_of_the_drills_flights() -> None:
    scale = lead_time_scale(SERVER, ROBOT)
    assert scale == pytest.approx(arrival_time_s(ROBOT) / arrival_time_s(SERVER))
    assert scale * lead_time_scale(ROBOT, SERVER) == pytest.approx(1.0)
    assert lead_time_scale(ROBOT, ROBOT) == 1.0
    assert 0.0 < scale < 1.0  # the robots' 0.7 m shots fly shorter than the server's 25 m


def test_only_moved_nets_read_drill_units_and_a_scaled_lead(tmp_path: Path) -> None:
    nets = [LeadNet(tmp_path / "r.npz", ROBOT, "robot"), LeadNet(tmp_path / "s.npz", SERVER, "s")]
    rows = lead_transfer_conditions([("robot", ROBOT), ("s", SERVER)], nets, TINY, seeds_for(0))
    assert len(rows) == 2 * (2 + 2 + 1)
    for tested, defender, trained, cond in rows:
        options = dict(cond.spec.drill_options)
        assert cond.spec.seed == 0 and options["decision"] == "lead"
        moved = bool(trained) and trained != tested
        assert options.get("transfer", False) == moved
        if defender == FLIGHT_SCALED:
            assert moved
            source = ROBOT if trained == "robot" else SERVER
            target = ROBOT if tested == "robot" else SERVER
            assert options["lead_time_scale"] == lead_time_scale(source, target)
        else:  # baselines and the nets themselves: τ in seconds
            assert "lead_time_scale" not in options


def test_the_drill_scales_only_a_lead_net() -> None:
    with pytest.raises(ValueError, match="lead_time_scale scales a lead net"):
        InterceptDrill(behaviour="straight", decision="lead", lead_time_scale=2.0)
    with pytest.raises(ValueError, match="finite number > 0"):
        InterceptDrill(behaviour="straight", decision="lead", lead_time_scale=0.0)
    assert ScaledLead(lambda bd, angle, prev: 0.25, 3.0)(1.0, 0.0, 1.0) == 0.75


def test_the_lead_matrix_and_calibration_run_alike_on_any_worker_count(tmp_path: Path) -> None:
    texts = []
    runs = []
    for workers in (1, 2):
        out = tmp_path / f"w{workers}"
        ctx = RunContext(out, seeds_for(2), workers, created_by="a test")
        text = run_lead_study([ROBOT, SERVER], "soccer_server", "robot_physics", TINY, ctx)
        texts.append(text)
        tables = sorted((out / "results" / "transfer_lead").rglob("*.csv"))
        runs.append({p.relative_to(out): sorted(p.read_text().splitlines()) for p in tables})
    assert texts[0] == texts[1] and runs[0] == runs[1]
    # 3 columns of baselines and nets, the moved nets flight-scaled, and the TA rows on the robots
    assert len(runs[0]) == 3 * (2 + 3) + 3 * 2 + 4
    text = texts[0]
    assert (
        f"| lead net trained on {calibrated_label('soccer_server')} |" in text
        and "tested on robot_physics" in text
    )
    assert text.count("share of the gap closed") == 2 and "*calibrated* Soccer Server" in text
    assert "server turn (the paper's TA) net, transferred (calibrated)" in text
    preset = tmp_path / "w1" / "calibration" / "soccer_server_calibrated.toml"
    assert "FITTED" in preset.read_text()
    # A flight-scaled net's lead is its lead in seconds times the scale (at the same trigger).
    folder = tmp_path / "w1" / "results" / "transfer_lead" / "robot_physics"
    scaled = {r.index: r for r in iter_results(folder / "lead_net_soccer_server_flight_scaled.csv")}
    plain = {r.index: r for r in iter_results(folder / "lead_net_soccer_server.csv")}
    scale = lead_time_scale(SERVER, ROBOT)
    compared = 0
    for i, r in scaled.items():
        if r.data and plain[i].data and 0.0 < plain[i].data[3] * scale < 2.0:
            assert r.data[3] == pytest.approx(plain[i].data[3] * scale, rel=1e-9)
            compared += 1
    assert compared > 0
