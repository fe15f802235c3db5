"""Matplotlib figures of the spring design (``hexaleg design``, :mod:`hexaleg.studies.design`).

Plain arrays in, a :class:`matplotlib.figure.Figure` out (object-oriented API on the Agg canvas,
as :mod:`hexaleg.outputs.plots`): the robustness heat maps, the Pareto front of saving against
spring size, and the robust design against the nominal one over the box of conditions. Savings
are plotted in %.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np
from matplotlib.figure import Figure
from matplotlib.patches import Rectangle

from hexaleg.outputs.plots import METRIC_COLOURS, _figure

AXIS_LABELS = {"period": "gait period (× nominal)", "stride": "stride (× nominal)",
               "payload": "payload (fraction of the robot's mass)", "mu": "friction μ"}
"""Axis titles of the map conditions."""


def robustness_heatmap(axes: tuple[str, str], values: tuple[np.ndarray, np.ndarray],
                       saving: np.ndarray, metric: str) -> Figure:
    """A frozen design's saving over a grid of two conditions, each cell annotated, the worst
    cell outlined.

    Args:
        axes: The two conditions (rows, columns).
        values: Their values, shapes (n₁,) and (n₂,).
        saving: Saving per cell, shape (n₁, n₂), % (NaN: outside the envelope; −inf: the springs
            make the gait infeasible).
        metric: The metric's name, for the title.
    """
    s = np.asarray(saving, dtype=float)
    fig = _figure(5.6, 4.2, left=0.16, right=0.9, bottom=0.14, top=0.9)
    ax = fig.add_subplot()
    shown = np.where(np.isfinite(s), s, np.nan)
    lim = max(float(np.nanmax(np.abs(shown))) if np.isfinite(shown).any() else 1.0, 1e-9)
    im = ax.imshow(shown, cmap="RdYlGn", vmin=-lim, vmax=lim, origin="lower", aspect="auto")
    for (i, j), v in np.ndenumerate(s):
        text = "n/a" if np.isnan(v) else ("infeasible" if np.isinf(v) else f"{v:+.1f}")
        ax.text(j, i, text, ha="center", va="center", fontsize=8)
    if not np.isnan(s).all():
        i, j = np.unravel_index(int(np.nanargmin(np.where(np.isnan(s), np.inf, s))), s.shape)
        ax.add_patch(_outline(ax, int(i), int(j)))
    ax.set_xticks(range(len(values[1])), [f"{v:g}" for v in values[1]])
    ax.set_yticks(range(len(values[0])), [f"{v:g}" for v in values[0]])
    ax.set_xlabel(AXIS_LABELS.get(axes[1], axes[1]))
    ax.set_ylabel(AXIS_LABELS.get(axes[0], axes[0]))
    ax.set_title(f"{metric} saving of the recommended springs, % (worst outlined)", fontsize=9)
    fig.colorbar(im, ax=ax, label="saving, %")
    return fig


def _outline(ax: object, i: int, j: int) -> Rectangle:
    return Rectangle((j - 0.5, i - 0.5), 1, 1, fill=False, edgecolor="black", linewidth=2)


def pareto_figure(peak_torque: np.ndarray, stored_energy: np.ndarray,
                  savings: Mapping[str, np.ndarray], chosen: int | None = None) -> Figure:
    """Saving against spring size: the optimum with the spring torque bounded.

    Args:
        peak_torque: Largest spring torque of each design over the gait, shape (n,), N·m.
        stored_energy: Largest energy stored in one spring, shape (n,), J.
        savings: Metric → saving of each design, shape (n,), %.
        chosen: Index of the recommended design, or None.
    """
    order = np.argsort(peak_torque)
    fig = _figure(9.0, 3.6, left=0.07, right=0.98, bottom=0.16, top=0.88, wspace=0.25)
    for k, (x, label) in enumerate(((peak_torque, "peak spring torque, N·m"),
                                    (1e3 * np.asarray(stored_energy), "peak stored energy, mJ"))):
        ax = fig.add_subplot(1, 2, k + 1)
        x = np.asarray(x)
        for c, (m, s) in enumerate(savings.items()):
            s = np.asarray(s)
            ax.plot(x[order], s[order], "o-", color=METRIC_COLOURS[c % len(METRIC_COLOURS)],
                    label=m)
            if chosen is not None:
                ax.plot(x[chosen], s[chosen], "*", ms=14, color="black",
                        label="recommended" if c == 0 else None)
        ax.set_xlabel(label)
        ax.set_ylabel("saving, %")
        ax.grid(alpha=0.3)
        if k == 0:
            ax.legend(fontsize=8)
    fig.suptitle("What a smaller spring gives up", fontsize=10)
    return fig


def robust_figure(labels: Sequence[str], robust: Mapping[str, np.ndarray],
                  nominal: Mapping[str, np.ndarray]) -> Figure:
    """The robust and the nominal design's savings at each condition of the box.

    Args:
        labels: The conditions, length n.
        robust: Metric → the robust design's saving, shape (n,), %.
        nominal: Metric → the nominal design's saving, shape (n,), %.
    """
    n = len(labels)
    fig = _figure(9.0, 4.2, left=0.07, right=0.98, bottom=0.3, top=0.92, wspace=0.2)
    for k, m in enumerate(robust):
        ax = fig.add_subplot(1, len(robust), k + 1)
        x = np.arange(n)
        ax.bar(x - 0.2, nominal[m], 0.4, label=f"nominal (worst {np.min(nominal[m]):+.1f} %)")
        ax.bar(x + 0.2, robust[m], 0.4, label=f"robust (worst {np.min(robust[m]):+.1f} %)")
        ax.set_xticks(x, labels, rotation=90, fontsize=6)
        ax.set_title(f"{m} saving, %", fontsize=9)
        ax.grid(alpha=0.3, axis="y")
        ax.legend(fontsize=7)
    return fig
