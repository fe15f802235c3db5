"""Matplotlib figures of a gait analysis, for the energy report
(:mod:`hexaleg.commands.report.write`).

Every function returns a :class:`matplotlib.figure.Figure` built with the object-oriented API
on the Agg canvas — no ``pyplot``, so nothing is registered in pyplot's global figure manager and
repeated calls do not leak figures. Angles are plotted in degrees (converted through
:mod:`hexaleg.units`, the edge of the SI computation); everything else is in SI.

Joint series are laid out as one row per joint class (coxa, femur, tibia) or one panel per leg and
class, with the legs in the robot's order and one colour per leg.
"""

from __future__ import annotations

import base64
import io
from collections.abc import Mapping, Sequence
from pathlib import Path

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

from hexaleg.config import write_file
from hexaleg.robot.model import Robot
from hexaleg.units import rad_to_deg

LEG_COLOURS = ("#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd", "#8c564b")
"""One colour per leg, in the robot's leg order (matplotlib's tab10 palette)."""
CONTACT_MARGIN = 0.25
"""A spring's contact angle is drawn on the joint-angle plot within this fraction of the joint's
swing beyond its extremes."""
METRIC_COLOURS = ("#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#8c564b", "#17becf")
"""Colours of the metrics of the stiffness curve, in the order given."""


def _figure(width: float, height: float, **margins: float) -> Figure:
    # Fixed margins instead of a layout engine: constrained/tight layout doubles the drawing time.
    fig = Figure(figsize=(width, height), dpi=100)
    FigureCanvasAgg(fig)
    fig.subplots_adjust(**{"left": 0.08, "right": 0.98, "top": 0.95, "bottom": 0.08,
                           "hspace": 0.35, **margins})
    return fig


def _colour(i: int) -> str:
    return LEG_COLOURS[i % len(LEG_COLOURS)]


def joint_angles(robot: Robot, t: np.ndarray, q: np.ndarray,
                 dead_zones: Mapping[str, tuple[float, float]],
                 contacts: Mapping[str, Sequence[float]] | None = None) -> Figure:
    """Joint angles over the cycle, one row per joint class, with the springs' dead zones shaded
    and the other springs' contact angles dotted.

    Args:
        robot: The robot (joint classes, legs, columns).
        t: Sample times, shape (T,), s.
        q: Joint angles, shape (T, nj), rad (Pinocchio joint order).
        dead_zones: Sprung joint → (lower, upper) absolute angle of its dead zone, rad
            (``neutral + θ⁻``, ``neutral + θ⁺``).
        contacts: Sprung joint → the absolute angles where its spring engages or its torque is
            zero (a one-sided spring's contact, a linear spring's equilibrium), rad; drawn when
            within :data:`CONTACT_MARGIN` of the joint's swing (a linear spring's equilibrium
            far outside it would squash the plot).

    Returns:
        The figure (angles in degrees).
    """
    classes = robot.joint_classes
    fig = _figure(9, 2.3 * len(classes))
    axes = fig.subplots(len(classes), 1, sharex=True, squeeze=False)[:, 0]
    for ax, (kind, joints) in zip(axes, classes.items(), strict=True):
        dotted = False
        for i, joint in enumerate(joints):
            c = _colour(i)
            ax.plot(t, rad_to_deg(q[:, robot.column(joint)]), color=c, lw=1.2,
                    label=joint.split("_")[0])
            if joint in dead_zones:
                lo, hi = dead_zones[joint]
                ax.axhspan(rad_to_deg(lo), rad_to_deg(hi), color=c, alpha=0.04, lw=0)
                for edge in (lo, hi):
                    ax.axhline(rad_to_deg(edge), color=c, lw=0.6, ls=":")
            swing = q[:, robot.column(joint)]
            margin = CONTACT_MARGIN * float(np.ptp(swing))
            for angle in (contacts or {}).get(joint, ()):
                if swing.min() - margin <= angle <= swing.max() + margin:
                    ax.axhline(rad_to_deg(angle), color=c, lw=0.6, ls=":")
                    dotted = True
        shaded = any(j in dead_zones for j in joints)
        ax.set_title(f"{kind}" + (" (shaded: spring dead zone, dotted: contact angles)"
                                   if shaded else " (dotted: where the spring engages or its "
                                   "torque is zero)" if dotted else ""), fontsize=10)
        ax.set_ylabel("angle (deg)")
        ax.grid(alpha=0.3)
    axes[0].legend(ncol=len(robot.legs), fontsize=8, loc="upper right")
    axes[-1].set_xlabel("time (s)")
    return fig


def joint_torques(robot: Robot, t: np.ndarray, tau_motor: np.ndarray, tau_spring: np.ndarray,
                  tau_baseline: np.ndarray) -> Figure:
    """Motor against spring torque per joint: one panel per leg (rows) and joint class (columns).

    Args:
        robot: The robot.
        t: Sample times, shape (T,), s.
        tau_motor: Motor torques with the springs, shape (T, nj), N·m.
        tau_spring: Spring torques, shape (T, nj), N·m.
        tau_baseline: Motor torques of the same gait without springs, shape (T, nj), N·m.

    Returns:
        The figure.
    """
    classes = robot.joint_classes
    fig = _figure(11, 1.6 * len(robot.legs) + 0.6, top=0.96, bottom=0.06, hspace=0.45,
                  wspace=0.18)
    axes = fig.subplots(len(robot.legs), len(classes), sharex=True, sharey="col", squeeze=False)
    for col, joints in enumerate(classes.values()):
        for row, joint in enumerate(joints):
            ax, c = axes[row, col], robot.column(joint)
            ax.plot(t, tau_baseline[:, c], color="0.6", lw=1.0, ls="--", label="motor, no springs")
            ax.plot(t, tau_spring[:, c], color="#2ca02c", lw=1.0, label="spring")
            ax.plot(t, tau_motor[:, c], color="#1f77b4", lw=1.2, label="motor, with springs")
            ax.axhline(0.0, color="0.3", lw=0.5)
            ax.set_title(joint, fontsize=9)
            ax.tick_params(labelsize=8)
            ax.grid(alpha=0.3)
        axes[-1, col].set_xlabel("time (s)")
    for row in range(len(robot.legs)):
        axes[row, 0].set_ylabel("N·m", fontsize=8)
    axes[0, 0].legend(fontsize=7, loc="upper right")
    return fig


def joint_power(robot: Robot, t: np.ndarray, power: np.ndarray, power_baseline: np.ndarray
                ) -> Figure:
    """Motor mechanical power per joint, one row per joint class, legs as colours.

    Args:
        robot: The robot.
        t: Sample times, shape (T,), s.
        power: Motor power ``τ_motor q̇`` with the springs, shape (T, nj), W.
        power_baseline: The same without springs, shape (T, nj), W (thin dashed lines).

    Returns:
        The figure.
    """
    classes = robot.joint_classes
    fig = _figure(9, 2.3 * len(classes))
    axes = fig.subplots(len(classes), 1, sharex=True, squeeze=False)[:, 0]
    for ax, (kind, joints) in zip(axes, classes.items(), strict=True):
        for i, joint in enumerate(joints):
            c = robot.column(joint)
            ax.plot(t, power_baseline[:, c], color=_colour(i), lw=0.7, ls="--")
            ax.plot(t, power[:, c], color=_colour(i), lw=1.2, label=joint.split("_")[0])
        ax.axhline(0.0, color="0.3", lw=0.5)
        ax.set_title(f"{kind} (solid: with springs, dashed: without)", fontsize=10)
        ax.set_ylabel("power (W)")
        ax.grid(alpha=0.3)
    axes[0].legend(ncol=len(robot.legs), fontsize=8, loc="upper right")
    axes[-1].set_xlabel("time (s)")
    return fig


def foot_forces(leg_names: Sequence[str], t: np.ndarray, forces: np.ndarray,
                stance: np.ndarray, usage: np.ndarray) -> Figure:
    """Normal foot forces and friction usage ``|f_t| / (μ f_n)`` per leg over the cycle.

    Args:
        leg_names: Leg names, in the order of the force arrays.
        t: Sample times, shape (T,), s.
        forces: World-frame foot forces, shape (T, n_legs, 3), N.
        stance: Stance flags, shape (T, n_legs), bool (usage is drawn for stance samples only).
        usage: Friction usage, shape (T, n_legs), 1 (1 = on the friction cone).

    Returns:
        The figure.
    """
    fig = _figure(9, 5)
    ax_n, ax_u = fig.subplots(2, 1, sharex=True)
    for i, leg in enumerate(leg_names):
        ax_n.plot(t, forces[:, i, 2], color=_colour(i), lw=1.2, label=leg)
        ax_u.plot(t, np.ma.masked_where(~stance[:, i], usage[:, i]), color=_colour(i), lw=1.2)
    ax_n.set_ylabel("normal force f_n (N)")
    ax_n.set_title("ground reaction forces", fontsize=10)
    ax_n.legend(ncol=len(leg_names), fontsize=8, loc="upper right")
    ax_u.axhline(1.0, color="k", lw=0.8, ls="--")
    ax_u.set_ylim(0.0, 1.1)
    ax_u.set_ylabel("|f_t| / (μ f_n)")
    ax_u.set_title("friction usage of the stance feet (1 = slipping limit)", fontsize=10)
    ax_u.set_xlabel("time (s)")
    for ax in (ax_n, ax_u):
        ax.grid(alpha=0.3)
    return fig


def energy_bars(joint_names: Sequence[str], with_springs: np.ndarray,
                baseline: np.ndarray, metric: str, unit: str) -> Figure:
    """Per-joint bars of one metric with and without springs.

    Args:
        joint_names: Joint names, shape (nj,).
        with_springs: The metric per joint with the springs, shape (nj,).
        baseline: The same without springs, shape (nj,).
        metric: Metric name, for the title.
        unit: Unit of the metric, for the axis label.

    Returns:
        The figure.
    """
    n = len(joint_names)
    fig = _figure(10, 3.6, bottom=0.3, top=0.92)
    ax = fig.subplots()
    x = np.arange(n)
    ax.bar(x - 0.2, baseline, 0.4, color="0.65", label="without springs")
    ax.bar(x + 0.2, with_springs, 0.4, color="#1f77b4", label="with springs")
    ax.set_xticks(x, joint_names, rotation=60, ha="right", fontsize=8)
    ax.set_ylabel(f"{metric} ({unit})")
    ax.set_title(f"{metric} per joint over one cycle", fontsize=10)
    top = float(max(np.max(with_springs), np.max(baseline), 0.0))
    if top > 0:
        ax.set_ylim(top=1.2 * top)  # room for the legend above the bars
    ax.legend(fontsize=8, ncol=2, loc="upper center")
    ax.grid(axis="y", alpha=0.3)
    return fig


def stiffness_curve_figure(stiffness: np.ndarray, savings: Mapping[str, np.ndarray],
                           k_M: float, joints: str) -> Figure:
    """Saving of each metric against the stiffness of one joint class, k_M and minima marked.

    Args:
        stiffness: Stiffnesses, shape (K,), N·m/rad.
        savings: Metric → saving against no springs, shape (K,), % (NaN where the forces were
            infeasible; those points are left out).
        k_M: The eq. 19 stiffness of the class, N·m/rad (vertical line).
        joints: The joint class, for the title.

    Returns:
        The figure; each metric's best point (least energy = largest saving) is marked.
    """
    fig = _figure(8, 4, left=0.1, bottom=0.12, top=0.92)
    ax = fig.subplots()
    for i, (metric, s) in enumerate(savings.items()):
        c = METRIC_COLOURS[i % len(METRIC_COLOURS)]
        ok = np.isfinite(s)
        ax.plot(stiffness[ok], s[ok], color=c, lw=1.4, marker=".", ms=3, label=metric)
        if ok.any():
            best = int(np.flatnonzero(ok)[np.argmax(s[ok])])
            ax.plot(stiffness[best], s[best], "o", color=c, ms=8, mfc="none", mew=2)
    ax.axvline(k_M, color="k", ls="--", lw=1.0, label=f"k_M (eq. 19) = {k_M:.4g} N·m/rad")
    ax.axhline(0.0, color="0.3", lw=0.5)
    ax.set_xlabel(f"{joints} spring stiffness k (N·m/rad)")
    ax.set_ylabel("saving against no springs (%)")
    ax.set_title(f"stiffness curve of the {joints} springs (circles: best k per metric)",
                 fontsize=10)
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    return fig


def png_bytes(fig: Figure) -> bytes:
    """The figure as PNG bytes."""
    buf = io.BytesIO()
    fig.savefig(buf, format="png")
    return buf.getvalue()


def data_uri(png: bytes) -> str:
    """A ``data:image/png;base64,…`` URI for embedding a PNG in HTML."""
    return "data:image/png;base64," + base64.b64encode(png).decode("ascii")


def save(fig: Figure, path: str | Path, *, svg: bool = False) -> tuple[bytes, list[Path]]:
    """Write the figure as ``path`` (PNG) and, with ``svg``, next to it as SVG.

    Args:
        fig: The figure.
        path: The PNG file.
        svg: Also write ``path`` with the suffix ``.svg``.

    Returns:
        The PNG bytes and the files written.

    Raises:
        OutputError: a file cannot be written (names the path).
    """
    path = Path(path)
    png = png_bytes(fig)
    files = [write_file(path, png, "the plot")]  # a link at the path is replaced, not followed
    if svg:
        buf = io.BytesIO()
        fig.savefig(buf, format="svg")
        files.append(write_file(path.with_suffix(".svg"), buf.getvalue(), "the plot"))
    return png, files
