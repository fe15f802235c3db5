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
    assert "worst +20.0 %" in fig.axes[0].get_legend().get_texts()[1].get_text()
