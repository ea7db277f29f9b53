"""Figures 7 and 8: drawn from sections, lines only between measured neighbouring noises."""

from __future__ import annotations

from robotsoccer.experiments.plots import measured_runs, plot_figure7, plot_figure8
from robotsoccer.experiments.report import Counts, ModelSection


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
