"""Tests of hexaleg.outputs.paper_figures: what each Fig. 5–13 analogue draws from plain arrays,
the PNG written, and that no figure leaks into pyplot's global state."""

from __future__ import annotations

import matplotlib.pyplot as plt
import numpy as np
import pytest
from matplotlib.figure import Figure

from hexaleg.outputs import paper_figures

T = np.linspace(0.0, np.pi, 40, endpoint=False)
BASELINE = 1e-4 * np.sin(2 * T)


def test_rigid_torque_in_mNm():
    torques = (BASELINE, 2 * BASELINE, 3 * BASELINE)
    fig = paper_figures.baseline_torque(T, *torques)
    (ax,) = fig.axes
    lines = ax.get_lines()
    assert [line.get_label() for line in lines] == ["no gravity", "gravity, hanging (eq. 13)",
                                                    "gravity, upright"]
    for line, tau in zip(lines, torques, strict=True):
        np.testing.assert_array_equal(line.get_ydata(), 1e3 * tau)
    assert ax.get_ylabel() == "M (mN·m)" and "Fig. 5" in ax.get_title()


def test_table4_spring_two_panels():
    true_units, paper_units = 5 * BASELINE, 0.5 * BASELINE
    fig = paper_figures.table4_spring(T, BASELINE, true_units, paper_units)
    left, right = fig.axes
    np.testing.assert_array_equal(left.get_lines()[1].get_ydata(), 1e3 * true_units)
    np.testing.assert_array_equal(right.get_lines()[1].get_ydata(), 1e3 * paper_units)
    assert left.get_lines()[0].get_linestyle() == "--"
    assert "Fig. 6" in fig.get_suptitle()


def test_torques_by_stiffness_one_line_per_stiffness():
    tau = 3 * BASELINE
    fig = paper_figures.torques_by_stiffness(T, BASELINE, [(100.0, 2 * BASELINE), (700.5, tau)],
                                             "title")
    (ax,) = fig.axes
    assert [line.get_label() for line in ax.get_lines()] == ["baseline (no spring)", "k = 100",
                                                            "k = 700.5"]
    np.testing.assert_array_equal(ax.get_lines()[2].get_ydata(), 1e3 * tau)
    assert ax.get_title() == "title"


@pytest.mark.parametrize("kind", ["mean_torque_vs_stiffness", "epsilon_vs_stiffness"])
def test_cost_curves_mark_only_stiffnesses_in_range(kind):
    k = np.linspace(0.0, 1600.0, 17)
    cost = 1e-4 * (1 + (k - 700) ** 2 / 1e6)
    marks = {"k_M": 713.5, "far": 2000.0, "740 (paper)": 740.0}
    fig = getattr(paper_figures, kind)(k, cost, marks, "title")
    (ax,) = fig.axes
    curve, *vertical = ax.get_lines()
    scale = 1e3 if kind.startswith("mean") else 1.0
    np.testing.assert_array_equal(curve.get_ydata(), scale * cost)
    assert [line.get_label() for line in vertical] == ["k_M = 713.5", "740 (paper) = 740.0"]
    assert [line.get_color() for line in vertical] == ["C1", "C3"]  # colour by position in marks
    assert ax.get_xlabel().startswith("k (eq. 19 units")


def test_forward_torques_one_panel_per_stiffness_three_lines_each():
    torques = [np.array([BASELINE, 2 * BASELINE, 3 * BASELINE]) * (i + 1) for i in range(3)]
    fig = paper_figures.forward_torques(T, [(f"panel {i}", tau) for i, tau in
                                            enumerate(torques)], "title")
    axes = fig.axes
    assert [ax.get_title() for ax in axes[:3]] == ["panel 0", "panel 1", "panel 2"]
    assert not axes[3].get_visible()  # four panels, three used
    for ax, tau in zip(axes, torques, strict=False):
        lines = ax.get_lines()
        assert [line.get_label() for line in lines] == [label for _, label in
                                                        paper_figures.FORWARD_STYLES]
        for line, y in zip(lines, tau, strict=True):
            np.testing.assert_array_equal(line.get_ydata(), 1e3 * y)
    assert fig.get_suptitle() == "title" and axes[2].get_xlabel() == "t (s)"


@pytest.mark.parametrize("kind", ["forward_mean_torque", "forward_epsilon"])
def test_forward_curves_analytic_line_runs_as_points_marks_coloured_by_source(kind):
    k = np.linspace(0.0, 1600.0, 17)
    analytic = 1e-4 * (1 + (k - 1300) ** 2 / 1e6)
    k_runs = np.array([0.0, 800.0, 1600.0])
    runs = np.array([[1.5e-4, 1.0e-4, 0.6e-4], [1.6e-4, 1.2e-4, 1.3e-4]])
    marks = {"closed form": 1320.1, "forward": 1350.0, "friction": 829.0, "paper": 740.0,
             "beyond": 2000.0}
    fig = getattr(paper_figures, kind)(k, analytic, k_runs, runs, marks, "title")
    (ax,) = fig.axes
    line, simulated, friction, *vertical = ax.get_lines()
    scale = 1e3 if kind == "forward_mean_torque" else 1.0
    np.testing.assert_array_equal(line.get_ydata(), scale * analytic)
    np.testing.assert_array_equal(simulated.get_ydata(), scale * runs[0])
    np.testing.assert_array_equal(friction.get_xdata(), k_runs)
    assert simulated.get_marker() == "o" and line.get_linestyle() == "--"
    assert [m.get_label() for m in vertical] == ["closed form = 1320", "forward = 1350",
                                                 "friction = 829", "paper = 740"]
    assert [m.get_color() for m in vertical] == ["k", "C0", "C3", "C4"]
    assert ax.get_title() == "title" and ax.get_xlabel().startswith("k (eq. 19 units")


def test_save_png_at_110_dpi_and_no_pyplot_figures(tmp_path):
    before = plt.get_fignums()
    fig = paper_figures.baseline_torque(T, BASELINE, BASELINE, BASELINE)
    assert isinstance(fig, Figure)
    paper_figures.save_png(fig, tmp_path / "f.png")
    png = (tmp_path / "f.png").read_bytes()
    assert png[:8] == b"\x89PNG\r\n\x1a\n"
    width, height = int.from_bytes(png[16:20], "big"), int.from_bytes(png[20:24], "big")
    assert (width, height) == (7 * paper_figures.DPI, 4 * paper_figures.DPI)
    assert plt.get_fignums() == before
