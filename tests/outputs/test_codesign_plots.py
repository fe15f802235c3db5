"""The energy-vs-speed figure of hexaleg codesign."""

from __future__ import annotations

import math

from hexaleg.outputs.codesign_plots import speed_curve


def test_speed_curve_draws_both_gaits_with_gaps():
    fig = speed_curve({"default": ([0.03, 0.06], [30.0, 28.0], [26.0, 24.0]),
                       "co-design": ([0.03, 0.06], [math.nan, 18.0], [math.nan, 11.0])}, 0.06)
    ax = fig.axes[0]
    assert len(ax.lines) == 5  # two curves a gait and the speed marker
    assert ax.get_xlabel() == "speed [m/s]"
