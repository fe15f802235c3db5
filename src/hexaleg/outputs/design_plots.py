"""Matplotlib figures of the spring design (``hexaleg design``, :mod:`hexaleg.design.chain`).

Plain arrays in, a :class:`matplotlib.figure.Figure` out (object-oriented API on the Agg canvas,
as :mod:`hexaleg.outputs.plots`): the robustness heat maps, the Pareto front of saving against
spring size, the robust design against the nominal one over the box of conditions, and the
saving against a common shift of the springs' stops (the stop mounting tolerance). Savings are
plotted in %, angles in deg.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np
from matplotlib.figure import Figure
from matplotlib.patches import Rectangle

from hexaleg.outputs.plots import METRIC_COLOURS, _figure

AXIS_LABELS = {"period": "gait period (× nominal)", "stride": "stride (× nominal)",
               "payload": "payload (fraction of the robot's mass)", "mu": "friction μ",
               "slope": "ground slope, deg (uphill +)", "pattern": "gait pattern"}
"""Axis titles of the map conditions (a slope's values given in deg)."""


def _tick(v: object) -> str:
    """A condition's value on an axis: a number to 3 significant digits, a name as it is."""
    return v if isinstance(v, str) else f"{float(v):.3g}"  # type: ignore[arg-type]


def robustness_heatmap(axes: tuple[str, str], values: tuple[np.ndarray, np.ndarray],
                       saving: np.ndarray, metric: str) -> Figure:
    """A frozen design's saving over a grid of two conditions, each cell annotated, the worst
    cell outlined.

    Args:
        axes: The two conditions (rows, columns).
        values: Their values, shapes (n₁,) and (n₂,): numbers, or names (a gait pattern).
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
    ax.set_xticks(range(len(values[1])), [_tick(v) for v in values[1]])
    ax.set_yticks(range(len(values[0])), [_tick(v) for v in values[0]])
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
    """The robust and the nominal design's savings at each condition of the box: one row of
    horizontal bars per condition (the labels at 8 pt), one panel per metric, a shared axis of
    conditions.

    Args:
        labels: The conditions, length n.
        robust: Metric → the robust design's saving, shape (n,), %.
        nominal: Metric → the nominal design's saving, shape (n,), %.
    """
    n = len(labels)
    # Horizontal bars: the condition labels read at 8 pt, one row each (they were 6 pt, turned).
    height = 1.4 + 0.3 * n
    fig = _figure(9.0, height, left=0.2, right=0.98, bottom=0.55 / height, top=1 - 0.6 / height,
                  wspace=0.08)
    y = np.arange(n)
    first = None
    for k, m in enumerate(robust):
        ax = fig.add_subplot(1, len(robust), k + 1, sharey=first)
        first = first or ax
        ax.barh(y - 0.2, nominal[m], 0.4, label=f"nominal (worst {np.min(nominal[m]):+.2f} %)")
        ax.barh(y + 0.2, robust[m], 0.4, label=f"robust (worst {np.min(robust[m]):+.2f} %)")
        if k == 0:
            ax.set_yticks(y, labels, fontsize=8)
            ax.invert_yaxis()
        else:
            ax.tick_params(labelleft=False)
        ax.set_xlabel(f"{m} saving, %")
        ax.grid(alpha=0.3, axis="x")
        ax.legend(fontsize=8, loc="lower left", bbox_to_anchor=(0.0, 1.0), frameon=False)
    return fig


def tolerance_figure(shifts: np.ndarray, curves: Mapping[str, np.ndarray], tolerance: float,
                     worst: Mapping[str, float] | None = None, metric: str = "electrical"
                     ) -> Figure:
    """Saving against a common shift of every stop, the mounting tolerance shaded.

    Args:
        shifts: The common stop shifts, shape (n,), deg (added to every spring angle).
        curves: Design label → its saving at each shift, shape (n,), % (non-finite: the springs
            make the gait infeasible there; left out of the line).
        tolerance: The mounting tolerance t, deg (> 0): the band ±t is shaded.
        worst: Design label → its worst saving within the tolerance, % (in the legend), or None.
        metric: The metric's name, for the axis.
    """
    x = np.asarray(shifts, dtype=float)
    fig = _figure(7.0, 4.4, left=0.1, right=0.97, bottom=0.32, top=0.92)
    ax = fig.add_subplot()
    ax.axvspan(-tolerance, tolerance, color="#1a7f37", alpha=0.12,
               label=f"mounting tolerance ±{tolerance:g}°")
    for c, (name, y) in enumerate(curves.items()):
        y = np.asarray(y, dtype=float)
        label = name if worst is None or name not in worst else \
            f"{name} (worst in tolerance {worst[name]:+.2f} %)"
        ax.plot(x, np.where(np.isfinite(y), y, np.nan), "o-", ms=3,
                color=METRIC_COLOURS[c % len(METRIC_COLOURS)], label=label)
    ax.axvline(0.0, color="black", linewidth=0.8, linestyle=":")
    ax.axhline(0.0, color="black", linewidth=0.8)
    ax.set_xlabel("common stop shift, deg (added to every spring angle)")
    ax.set_ylabel(f"{metric} saving, %")
    ax.set_title("Saving with every stop mounted off by the same angle", fontsize=10)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.16), frameon=False)
    return fig
