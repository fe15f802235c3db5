"""The figure of ``hexaleg codesign``: electrical energy per metre against speed, for the
default and the co-designed gait, with and without their springs."""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np
from matplotlib.figure import Figure

from hexaleg.outputs.plots import _figure

STYLES = {"default": "#1f77b4", "co-design": "#d62728"}
"""Colour of each gait's curves (solid with springs, dashed without)."""


def speed_curve(curves: Mapping[str, tuple[Sequence[float], Sequence[float], Sequence[float]]],
                speed: float) -> Figure:
    """Energy per metre (J/m) against speed (m/s).

    Args:
        curves: Gait label → (speeds m/s, J/m without springs, J/m with springs); NaN for a
            speed where the gait fails a constraint (left as a gap).
        speed: The required speed, m/s (marked).
    """
    fig = _figure(6.4, 3.6, left=0.11, bottom=0.14)
    ax = fig.add_subplot(1, 1, 1)
    for i, (label, (v, bare, sprung)) in enumerate(curves.items()):
        colour = STYLES.get(label, f"C{i}")
        ax.plot(v, np.asarray(bare, dtype=float), "--o", color=colour, ms=3,
                label=f"{label} gait, no springs")
        ax.plot(v, np.asarray(sprung, dtype=float), "-o", color=colour, ms=3,
                label=f"{label} gait, its springs")
    ax.axvline(speed, color="0.6", lw=0.8)
    ax.set_xlabel("speed [m/s]")
    ax.set_ylabel("electrical energy per metre [J/m]")
    ax.set_ylim(bottom=0)
    if curves:
        ax.legend(fontsize=8)
    else:  # codesign(curve=False): say so rather than an empty legend
        ax.text(0.5, 0.5, "speed curve not computed (curve = false)", ha="center",
                va="center", transform=ax.transAxes, color="0.4")
    return fig


__all__ = ["STYLES", "speed_curve"]
