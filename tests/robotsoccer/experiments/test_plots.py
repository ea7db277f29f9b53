"""Figures 7 and 8: drawn from sections, lines only between measured neighbouring noises."""

from __future__ import annotations

from math import isnan, nan

from robotsoccer.experiments.plots import error_bars, measured_runs, plot_figure7, plot_figure8
from robotsoccer.experiments.report_records import Counts, ModelSection


def section(model: str) -> ModelSection:
    s = ModelSection(model, "p", noise=0.05, noise_period_s=0.0125)
    s.figure7 = [(100, "100", Counts(600, 300, 100)), (900, "all (900)", Counts(800, 150, 50))]
    s.figure8 = {
        (noise, b): Counts(int(900 - 3000 * noise - (300 if b == "straight" else 0)), 50, 50)
        for noise in (0.0, 0.05, 0.06, 0.1)
        for b in ("net", "straight")
    }
    return s


def test_lines_join_only_neighbouring_measured_noise_levels() -> None:
    assert measured_runs([0.0, 0.05, 0.06, 0.07, 0.1]) == [[0], [1, 2, 3], [4]]
    assert measured_runs([0.05, 0.06]) == [[0, 1]]
    assert measured_runs([]) == []


def test_both_figures_are_drawn_for_every_field(tmp_path) -> None:
    sections = [section("soccer_server"), section("robot_physics")]
    f7 = plot_figure7(sections, tmp_path / "f7.png")
    f8 = plot_figure8(sections, tmp_path / "f8.png")
    assert f7 is not None and f7.stat().st_size > 10_000
    assert f8 is not None and f8.stat().st_size > 10_000
    assert plot_figure7([], tmp_path / "none.png") is None


def test_no_saves_and_all_saves_draw_their_error_bars(tmp_path) -> None:
    # 0 of 3 and 10 of 10: bars a rounding error below 0 crashed matplotlib (issue 30)
    s = ModelSection("soccer_server", "p", noise=0.05, noise_period_s=0.1)
    s.figure7 = [(100, "100", Counts(0, 3, 0)), (300, "300", Counts(10, 0, 0))]
    s.figure8 = {(0.0, "net"): Counts(10, 0, 0), (0.05, "net"): Counts(0, 2, 1)}
    assert plot_figure7([s], tmp_path / "f7.png") is not None
    assert plot_figure8([s], tmp_path / "f8.png") is not None


def test_error_bars_are_never_negative() -> None:
    below, above = error_bars([0.0, 100.0, 50.0, nan], [1e-15, 99.0, 40.0, nan],
                              [5.0, 100.0 - 1e-13, 60.0, nan])  # fmt: skip
    assert below[:3] == [0.0, 1.0, 10.0] and above[:3] == [5.0, 0.0, 10.0]
    assert isnan(below[3]) and isnan(above[3])  # no bar where there is no value
