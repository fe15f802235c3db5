"""Tests of hexaleg.paper.figures: the data of the Figs 5–13 analogues."""

from __future__ import annotations

import numpy as np
import pytest

from hexaleg.paper.figures import make_figures
from hexaleg.paper.joint import PaperJoint
from hexaleg.paper.metrics import metric
from hexaleg.paper.readings import k_M_paper_number, paper_number_to_si

J0 = PaperJoint()


@pytest.fixture(scope="module")
def figs():
    return make_figures(J0, 64)


def test_figs_5_to_13_in_writing_order(figs):
    assert [name[:5] for name in figs] == ["fig05", "fig06", "fig07", "fig08", "fig11", "fig09",
                                           "fig10", "fig12", "fig13"]
    assert all(name.endswith(".png") for name in figs)


def test_curves_are_the_joints_torques_and_costs(figs):
    t = J0.times(64)
    rigid = figs["fig05_rigid_torque.png"].axes[0].get_lines()
    np.testing.assert_array_equal(rigid[0].get_ydata(), 1e3 * J0.baseline_torque(t, False))
    np.testing.assert_array_equal(rigid[1].get_ydata(), 1e3 * J0.baseline_torque(t, True))
    around = figs["fig08_torque_around_kM.png"].axes[0]
    assert f"{k_M_paper_number(J0):.1f}" in around.get_title()
    k_m_line = around.get_lines()[2]  # rigid, 0.8 k_M, k_M, 740, 1.2 k_M
    assert k_m_line.get_label() == f"k = {k_M_paper_number(J0):g}"
    np.testing.assert_array_equal(
        k_m_line.get_ydata(),
        1e3 * J0.motor_torque(t, float(paper_number_to_si(k_M_paper_number(J0))), False))
    mean = figs["fig09_mean_torque_vs_stiffness.png"].axes[0].get_lines()[0]
    k = mean.get_xdata()
    assert k[0] == 0.0 and k[-1] == 3000.0 and k.size == 301
    np.testing.assert_array_equal(mean.get_ydata(),
                                  1e3 * metric(J0, "mean_abs", paper_number_to_si(k), False, 64))


def test_forward_figures_draw_the_studys_runs_beside_the_analytic(forward):
    from hexaleg.paper.figures import PANEL_TITLES, forward_figures
    from hexaleg.paper.metrics import energy_ratio

    figs = forward_figures(forward, 64)
    assert list(figs) == ["sim_fig05_08_required_torque.png",
                          "sim_fig09_10_mean_torque_vs_stiffness.png",
                          "sim_fig12_13_epsilon_vs_stiffness.png"]
    panels = figs["sim_fig05_08_required_torque.png"].axes
    for ax, r in zip(panels, forward.torques, strict=True):
        assert ax.get_title() == PANEL_TITLES[r.key]
        for line, tau in zip(ax.get_lines(), r.torque, strict=True):
            np.testing.assert_array_equal(line.get_ydata(), 1e3 * tau)
    for name, scale in (("mean_abs", 1e3), ("epsilon", 1.0)):
        file = ("sim_fig09_10_mean_torque_vs_stiffness.png" if name == "mean_abs"
                else "sim_fig12_13_epsilon_vs_stiffness.png")
        analytic, simulated, friction, *marks = figs[file].axes[0].get_lines()
        k = analytic.get_xdata()
        expected = (metric(J0, "mean_abs", paper_number_to_si(k), False, 64) if name == "mean_abs"
                    else energy_ratio(J0, paper_number_to_si(k), False, 64))
        np.testing.assert_allclose(analytic.get_ydata(), scale * expected, rtol=1e-15)
        np.testing.assert_array_equal(simulated.get_xdata(), [0.0, *forward.grid])
        np.testing.assert_array_equal(
            friction.get_ydata(), scale * np.array([forward.baseline[name][2],
                                                    *forward.curves[name][2]]))
        o = forward.optima[name]
        assert [m.get_xdata()[0] for m in marks] == [o.closed_form, o.simulated, o.friction,
                                                     o.paper]
