"""Matplotlib analogues of the paper's Figs 5–13 (the single elastic joint), from plain arrays.

The paper study (:mod:`hexaleg.paper.figures`) computes the curves; these functions only
draw them. Every function returns a :class:`matplotlib.figure.Figure` built with the
object-oriented API on the Agg canvas — no ``pyplot``, no global figure manager — laid out with
``tight_layout``; :func:`save_png` writes one. Torques are given in N·m and drawn in mN·m;
stiffness axes are in the paper's eq. 19 units (kg·mm²·s⁻²/rad = 1e-6 N·m/rad), the paper's
convention κ = kα.
"""

from __future__ import annotations

import io
from collections.abc import Mapping, Sequence
from pathlib import Path

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

from hexaleg.config import write_file

DPI = 110
"""Resolution of the saved PNGs, dots per inch."""
_MILLI = 1e3  # N·m → mN·m on the torque axes
_MARK_COLOURS = ("C1", "C2", "C3", "C4")


def _figure(width: float, height: float) -> Figure:
    fig = Figure(figsize=(width, height))
    FigureCanvasAgg(fig)
    return fig


def baseline_torque(t: np.ndarray, no_gravity: np.ndarray, hanging: np.ndarray,
                 upright: np.ndarray) -> Figure:
    """Fig. 5 analogue: the motor torque of the rigid joint (eq. 13 with k = 0).

    Args:
        t: Times, s, shape (T,).
        no_gravity: Torque without gravity, N·m, shape (T,).
        hanging: Torque with gravity, hanging lever (eq. 13), N·m, shape (T,).
        upright: Torque with gravity, upright lever, N·m, shape (T,).
    """
    fig = _figure(7, 4)
    ax = fig.subplots()
    ax.plot(t, _MILLI * no_gravity, label="no gravity")
    ax.plot(t, _MILLI * hanging, label="gravity, hanging (eq. 13)")
    ax.plot(t, _MILLI * upright, label="gravity, upright")
    ax.set(xlabel="t (s)", ylabel="M (mN·m)", title="Fig. 5 analogue: rigid joint torque")
    ax.legend(fontsize=8)
    fig.tight_layout()
    return fig


def table4_spring(t: np.ndarray, baseline: np.ndarray, true_units: np.ndarray,
                  paper_units: np.ndarray) -> Figure:
    """Fig. 6 analogue: torque with Table 4's 400 N·mm/deg spring, read in both units (no gravity).

    Args:
        t: Times, s, shape (T,).
        baseline: Torque without the spring, N·m, shape (T,).
        true_units: Torque with k = 400 N·mm/deg (22.9 N·m/rad), N·m, shape (T,).
        paper_units: Torque with k = 400 eq. 19 units (4e-4 N·m/rad), N·m, shape (T,).
    """
    fig = _figure(10, 4)
    axes = fig.subplots(1, 2)
    axes[0].plot(t, _MILLI * baseline, "k--", label="baseline (no spring)")
    axes[0].plot(t, _MILLI * true_units, label="k = 400 N·mm/deg (22.9 N·m/rad)")
    axes[0].set(xlabel="t (s)", ylabel="M (mN·m)", title="Table 4 spring in true units")
    axes[1].plot(t, _MILLI * baseline, "k--", label="baseline (no spring)")
    axes[1].plot(t, _MILLI * paper_units, label="k = 400 in eq. 19 units (4e-4 N·m/rad)")
    axes[1].set(xlabel="t (s)", title="400 read in the unit of eq. 19")
    for ax in axes:
        ax.legend(fontsize=7)
    fig.suptitle("Fig. 6 analogue: torque with the spring, no gravity")
    fig.tight_layout()
    return fig


def torques_by_stiffness(t: np.ndarray, baseline: np.ndarray,
                         torques: Sequence[tuple[float, np.ndarray]], title: str) -> Figure:
    """Figs 7, 8, 11 analogues: the motor torque for several stiffnesses and without the spring.

    Args:
        t: Times, s, shape (T,).
        baseline: Torque without the spring, N·m, shape (T,).
        torques: (stiffness in eq. 19 units, torque N·m of shape (T,)) pairs, one line each.
        title: Figure title.
    """
    fig = _figure(7, 4)
    ax = fig.subplots()
    ax.plot(t, _MILLI * baseline, "k--", label="baseline (no spring)")
    for kp, tau in torques:
        ax.plot(t, _MILLI * tau, label=f"k = {kp:g}")
    ax.set(xlabel="t (s)", ylabel="motor torque M (mN·m)", title=title)
    ax.legend(fontsize=7, title="k in eq. 19 units\n(1e-6 N·m/rad)", title_fontsize=7)
    fig.tight_layout()
    return fig


def mean_torque_vs_stiffness(k: np.ndarray, mean_abs: np.ndarray, marks: Mapping[str, float],
                             title: str) -> Figure:
    """Figs 9, 10 analogues: the mean |M| over a period against stiffness (no gravity).

    Args:
        k: Stiffnesses, eq. 19 units, increasing, shape (K,).
        mean_abs: Mean |M| at each, N·m, shape (K,).
        marks: Label → stiffness (eq. 19 units) drawn as a vertical line if within ``k``.
        title: Figure title.
    """
    return _versus_stiffness(k, _MILLI * mean_abs, "mean |M| over a period (mN·m)", marks, title)


def epsilon_vs_stiffness(k: np.ndarray, epsilon: np.ndarray, marks: Mapping[str, float],
                         title: str) -> Figure:
    """Figs 12, 13 analogues: the energy ratio ε of eq. 24 against stiffness (no gravity).

    Args:
        k: Stiffnesses in eq. 19 units, increasing, shape (K,).
        epsilon: ε at each stiffness, 1/s², shape (K,).
        marks: Label → stiffness (eq. 19 units), a vertical line where within ``k``.
        title: The figure's title.
    """
    return _versus_stiffness(k, epsilon, "ε = positive work / (J · 4A)  (1/s²)", marks, title)


def _versus_stiffness(k: np.ndarray, y: np.ndarray, ylabel: str, marks: Mapping[str, float],
                      title: str) -> Figure:
    """One no-gravity quantity against stiffness, with the marked stiffnesses as dotted lines."""
    fig = _figure(7, 4)
    ax = fig.subplots()
    ax.plot(k, y, label="no gravity")
    ax.set_ylabel(ylabel)
    kmax = k[-1]
    for (label, x), color in zip(marks.items(), _MARK_COLOURS, strict=False):
        if x <= kmax:
            ax.axvline(x, ls=":", color=color, label=f"{label} = {x:.1f}")
    ax.set(xlabel="k (eq. 19 units, 1e-6 N·m/rad), paper convention κ = kα", title=title)
    ax.legend(fontsize=8)
    fig.tight_layout()
    return fig


FORWARD_STYLES = (("k--", "analytic (eq. 13/14)"), ("C0-", "forward (MuJoCo)"),
                  ("C3-", "forward, Table 2 friction"))
"""(matplotlib format, label) of the analytic model and the two forward runs, in that order."""
_FORWARD_MARK_COLOURS = ("k", "C0", "C3", "C4")  # the analytic, forward, friction optima, paper


def forward_torques(t: np.ndarray, panels: Sequence[tuple[str, np.ndarray]], title: str
                    ) -> Figure:
    """Figs 5–8 forward: the required torque over a period, analytic beside the forward runs.

    Args:
        t: Times, s, shape (T,).
        panels: (title, torques N·m of shape (3, T): analytic, forward, forward with friction),
            one panel each, up to four.
        title: Figure title.
    """
    fig = _figure(10, 7)
    axes = fig.subplots(2, 2, sharex=True).ravel()
    for ax, (name, torques) in zip(axes, panels, strict=False):
        for tau, (fmt, label) in zip(torques, FORWARD_STYLES, strict=True):
            ax.plot(t, _MILLI * tau, fmt, lw=1, label=label)
        ax.set(ylabel="M (mN·m)", title=name)
    for ax in axes[len(panels):]:
        ax.set_visible(False)
    for ax in axes[2:]:
        ax.set_xlabel("t (s)")
    axes[0].legend(fontsize=7)
    fig.suptitle(title)
    fig.tight_layout()
    return fig


def forward_mean_torque(k: np.ndarray, analytic: np.ndarray, k_runs: np.ndarray,
                        runs: np.ndarray, marks: Mapping[str, float], title: str) -> Figure:
    """Figs 9–10 forward: the mean |M| over a period against stiffness, the analytic curve and
    the forward runs' points, the optima marked (no gravity).

    Args:
        k: Stiffnesses of the analytic curve, eq. 19 units, increasing, shape (K,).
        analytic: Its mean |M|, N·m, shape (K,).
        k_runs: Stiffnesses of the forward runs, eq. 19 units, shape (R,).
        runs: Their mean |M| without and with friction, N·m, shape (2, R).
        marks: Label → stiffness (eq. 19 units), a vertical line where within ``k``, coloured
            as the analytic, forward, forward-with-friction optima and the paper's reading, in
            that order.
        title: The figure's title.
    """
    return _forward_versus(k, _MILLI * analytic, k_runs, _MILLI * np.asarray(runs),
                           "mean |M| over a period (mN·m)", marks, title)


def forward_epsilon(k: np.ndarray, analytic: np.ndarray, k_runs: np.ndarray, runs: np.ndarray,
                    marks: Mapping[str, float], title: str) -> Figure:
    """Figs 12–13 forward: the energy ratio ε of eq. 24 against stiffness, as
    :func:`forward_mean_torque` (ε in 1/s²)."""
    return _forward_versus(k, analytic, k_runs, runs, "ε = positive work / (J · 4A)  (1/s²)",
                           marks, title)


def _forward_versus(k: np.ndarray, analytic: np.ndarray, k_runs: np.ndarray, runs: np.ndarray,
                    ylabel: str, marks: Mapping[str, float], title: str) -> Figure:
    """The analytic curve, the forward runs' points (without, with friction), marks as lines."""
    fig = _figure(7, 4)
    ax = fig.subplots()
    ax.plot(k, analytic, FORWARD_STYLES[0][0], label=FORWARD_STYLES[0][1])
    for y, (fmt, label) in zip(runs, FORWARD_STYLES[1:], strict=True):
        ax.plot(k_runs, y, fmt[:2] + "o-", ms=3, lw=1, label=label)
    for (label, x), color in zip(marks.items(), _FORWARD_MARK_COLOURS, strict=False):
        if x <= k[-1]:
            ax.axvline(x, ls=":", color=color, label=f"{label} = {x:.0f}")
    ax.set(xlabel="k (eq. 19 units, 1e-6 N·m/rad), paper convention κ = kα", ylabel=ylabel,
           title=title)
    ax.legend(fontsize=7)
    fig.tight_layout()
    return fig


def save_png(fig: Figure, path: str | Path) -> None:
    """Write ``fig`` as a PNG at :data:`DPI` (a link at ``path`` is replaced, not followed).

    Raises:
        OutputError: the file cannot be written (named).
    """
    buf = io.BytesIO()
    fig.savefig(buf, dpi=DPI)
    write_file(path, buf.getvalue(), "the figure")
