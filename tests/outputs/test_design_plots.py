"""Tests of hexaleg.outputs.design_plots: the figures draw from plain arrays."""

from __future__ import annotations

import numpy as np
import pytest

from hexaleg.outputs import design_plots
from hexaleg.outputs.plots import png_bytes


def test_heat_map_marks_the_worst_cell_and_the_gaps():
    s = np.array([[10.0, np.nan], [-np.inf, 3.0]])
    fig = design_plots.robustness_heatmap(("period", "mu"), (np.array([0.5, 1.0]),
                                                             np.array([0.3, 0.6])), s, "joule")
    ax = fig.axes[0]
    texts = [t.get_text() for t in ax.texts]
    assert texts == ["+10.0", "n/a", "infeasible", "+3.0"]
    (patch,) = ax.patches
    assert patch.get_xy() == (-0.5, 0.5)  # the infeasible cell, row 1, column 0
    assert png_bytes(fig)[:4] == b"\x89PNG"


def test_pareto_and_robust_figures():
    fig = design_plots.pareto_figure(np.array([0.02, 0.05, 0.08]), np.array([0.01, 0.02, 0.03]),
                                     {"electrical": np.array([9.0, 14.0, 15.0])}, chosen=2)
    assert len(fig.axes) == 2
    for ax, x in zip(fig.axes, ([0.02, 0.05, 0.08], [10.0, 20.0, 30.0]), strict=True):
        curve, star = ax.lines  # the front in order of torque, the recommended point starred
        np.testing.assert_allclose(curve.get_xdata(), x)
        np.testing.assert_allclose(curve.get_ydata(), [9.0, 14.0, 15.0])
        assert star.get_marker() == "*" and star.get_xdata()[0] == pytest.approx(x[2])
    fig = design_plots.robust_figure(["nominal", "P×0.5"], {"joule": np.array([30.0, 20.0])},
                                     {"joule": np.array([32.0, 10.0])})
    assert "worst +20.00 %" in fig.axes[0].get_legend().get_texts()[1].get_text()


def test_robust_figure_labels_every_condition_readably():
    """One row per condition, its label at 8 pt and unturned (they were 6 pt, at 90°); the
    metrics share the axis of conditions and only the first panel labels it."""
    labels = [f"P×{p} S×{s} μ 0.5" for p in (0.75, 1.5) for s in (0.75, 1.25)]
    fig = design_plots.robust_figure(labels, {m: np.arange(4.0) for m in ("electrical", "joule")},
                                     {m: np.arange(4.0) + 1 for m in ("electrical", "joule")})
    first, second = fig.axes
    ticks = first.get_yticklabels()
    assert [t.get_text() for t in ticks] == labels
    assert all(t.get_fontsize() == 8 and t.get_rotation() == 0 for t in ticks)
    assert second.yaxis.get_tick_params()["labelleft"] is False
    assert fig.get_figheight() >= 0.3 * len(labels)


def test_tolerance_figure_shades_the_tolerance_and_names_the_worst_cases():
    shifts = np.linspace(-2.0, 2.0, 9)
    tolerant = np.full(9, 15.0)
    blind = np.array([14.0, 14.5, 15.0, 15.5, 16.0, 4.0, -np.inf, 0.5, 0.6])
    fig = design_plots.tolerance_figure(shifts, {"tolerant": tolerant, "blind": blind}, 1.0,
                                        {"tolerant": 14.9, "blind": -0.29})
    ax = fig.axes[0]
    (band,) = ax.patches  # the ±1° band
    x0, x1 = band.get_x(), band.get_x() + band.get_width()
    assert (x0, x1) == pytest.approx((-1.0, 1.0))
    lines = {line.get_label(): line for line in ax.lines if not line.get_label().startswith("_")}
    assert set(lines) == {"tolerant (worst in tolerance +14.90 %)",
                          "blind (worst in tolerance -0.29 %)"}
    y = lines["blind (worst in tolerance -0.29 %)"].get_ydata()
    assert np.isnan(y[6]) and y[5] == 4.0  # an infeasible shift is a gap, not a point
    np.testing.assert_allclose(lines["tolerant (worst in tolerance +14.90 %)"].get_xdata(), shifts)
    assert "deg" in ax.get_xlabel() and "%" in ax.get_ylabel()
    assert png_bytes(fig)[:4] == b"\x89PNG"


def test_heat_map_takes_named_conditions():
    """A gait-pattern axis has names, not numbers: its ticks read the names; numbers read at 3
    significant digits (a slope of −7.5°)."""
    s = np.array([[5.0, 4.0, 3.0], [6.0, 2.0, 1.0]])
    fig = design_plots.robustness_heatmap(
        ("slope", "pattern"), (np.array([-7.5, 15.0]), np.array(["tripod", "ripple", "wave"])),
        s, "electrical")
    ax = fig.axes[0]
    assert [t.get_text() for t in ax.get_xticklabels()] == ["tripod", "ripple", "wave"]
    assert [t.get_text() for t in ax.get_yticklabels()] == ["-7.5", "15"]
    assert ax.get_ylabel() == design_plots.AXIS_LABELS["slope"]
