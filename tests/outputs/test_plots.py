"""Tests of hexaleg.outputs.plots: what each figure draws (data of its artists), file output and
errors, and that no figure leaks into pyplot's global state."""

from __future__ import annotations

import base64

import matplotlib.pyplot as plt
import numpy as np
import pytest

from hexaleg.errors import OutputError
from hexaleg.outputs import plots


@pytest.fixture(scope="module")
def series(robot):
    t = np.linspace(0.0, 1.0, 50, endpoint=False)
    q = np.outer(np.sin(2 * np.pi * t), np.arange(1, robot.nj + 1)) * 0.01
    return t, q


def test_joint_angles_in_degrees_with_dead_zones(robot, series):
    t, q = series
    zone = {"LF_femur": (0.1, 0.3)}
    fig = plots.joint_angles(robot, t, q, zone)
    axes = fig.axes
    assert [ax.get_title().split()[0] for ax in axes] == list(robot.joint_classes)
    femur = axes[list(robot.joint_classes).index("femur")]
    lf = femur.get_lines()[0]  # the first leg's line, in degrees
    np.testing.assert_allclose(lf.get_ydata(), np.degrees(q[:, robot.column("LF_femur")]))
    (span,) = femur.patches  # one shaded dead zone
    ys = span.get_path().transformed(span.get_patch_transform()).vertices[:, 1]
    assert min(ys) == pytest.approx(np.degrees(0.1)) and max(ys) == pytest.approx(np.degrees(0.3))
    assert not axes[0].patches  # coxa: no springs, no zone
    assert "dead zone" in femur.get_title() and "dead zone" not in axes[0].get_title()


def test_torque_panels_one_per_joint(robot, series):
    t, q = series
    fig = plots.joint_torques(robot, t, q, -q, 2 * q)
    assert len(fig.axes) == robot.nj
    titles = {ax.get_title(): ax for ax in fig.axes}
    assert set(titles) == set(robot.joint_names)
    rigid, spring, motor = titles["RM_tibia"].get_lines()[:3]
    c = robot.column("RM_tibia")
    np.testing.assert_allclose(motor.get_ydata(), q[:, c])
    np.testing.assert_allclose(spring.get_ydata(), -q[:, c])
    np.testing.assert_allclose(rigid.get_ydata(), 2 * q[:, c])


def test_friction_usage_is_drawn_for_stance_feet_only(robot):
    t = np.linspace(0.0, 1.0, 10, endpoint=False)
    n = len(robot.legs)
    forces = np.zeros((10, n, 3))
    forces[..., 2] = 2.0
    stance = np.zeros((10, n), dtype=bool)
    stance[:5] = True
    usage = np.full((10, n), 0.5)
    fig = plots.foot_forces(robot.leg_names, t, forces, stance, usage)
    ax_u = fig.axes[1]
    y = ax_u.get_lines()[0].get_ydata()
    assert np.ma.count_masked(y) == 5 and np.all(y[:5] == 0.5)


def test_stiffness_curve_figure_marks_the_best_point_and_skips_infeasible_ones():
    k = np.linspace(0.0, 1.0, 5)
    s = np.array([0.0, 3.0, 5.0, np.nan, 1.0])
    fig = plots.stiffness_curve_figure(k, {"joule": s}, 0.25, "femur")
    ax = fig.axes[0]
    line, best, kline = ax.get_lines()[:3]
    np.testing.assert_allclose(line.get_xdata(), [0.0, 0.25, 0.5, 1.0])
    assert best.get_xdata()[0] == 0.5 and best.get_ydata()[0] == 5.0
    assert kline.get_xdata()[0] == 0.25 and "k_M" in kline.get_label()


def test_energy_bars_heights(robot):
    names = robot.joint_names
    w, wo = np.arange(robot.nj, dtype=float), np.ones(robot.nj)
    fig = plots.energy_bars(names, w, wo, "electrical", "J")
    heights = [p.get_height() for p in fig.axes[0].patches]
    np.testing.assert_allclose(heights, [*wo, *w])


def test_save_png_svg_and_data_uri(tmp_path, series):
    t, q = series
    fig = plots.stiffness_curve_figure(t, {"joule": q[:, 0]}, 0.5, "femur")
    png, files = plots.save(fig, tmp_path / "p.png", svg=True)
    assert [f.name for f in files] == ["p.png", "p.svg"]
    assert png[:8] == b"\x89PNG\r\n\x1a\n" and (tmp_path / "p.png").read_bytes() == png
    assert "<svg" in (tmp_path / "p.svg").read_text()[:500]
    uri = plots.data_uri(png)
    assert base64.b64decode(uri.split(",", 1)[1]) == png
    with pytest.raises(OutputError, match="missing"):
        plots.save(fig, tmp_path / "missing" / "p.png")


def test_no_figure_leaks_into_pyplot(robot, series):
    t, q = series
    before = plt.get_fignums()
    plots.joint_power(robot, t, q, q)
    plots.stiffness_curve_figure(t, {"joule": t}, 0.5, "femur")
    assert plt.get_fignums() == before


def test_a_link_at_a_plot_path_is_replaced_not_written_through(tmp_path):
    """#28: files hexaleg writes into its output directory do not follow a link planted there —
    the PNG (and SVG) replace the link, the file it pointed to is untouched."""
    from matplotlib.figure import Figure

    from hexaleg.outputs.plots import save

    victim = tmp_path / "victim.txt"
    victim.write_text("keep me")
    out = tmp_path / "out"
    out.mkdir()
    for name in ("plot.png", "plot.svg"):
        (out / name).symlink_to(victim)
    fig = Figure()
    fig.add_subplot().plot([0, 1], [1, 0])
    png, files = save(fig, out / "plot.png", svg=True)
    assert victim.read_text() == "keep me"
    assert [f.name for f in files] == ["plot.png", "plot.svg"]
    assert not any(f.is_symlink() for f in files)
    assert (out / "plot.png").read_bytes() == png
