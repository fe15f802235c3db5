"""The outer geometry search against a dense grid of geometries."""

import numpy as np

from hexaleg.design.codesign import optimal_springs
from hexaleg.design.search import _geometry, _grid


def test_search_is_at_least_as_good_as_a_dense_geometry_grid(prepared200):
    searched = optimal_springs(prepared200, ["tibia"], "one_sided")
    q = prepared200.q[:, [prepared200.robot.column(j) for j in prepared200.robot.joints("tibia")]]
    half = ((q.max(0) - q.min(0)) / 2).max()
    best = min(optimal_springs(prepared200, ["tibia"], "one_sided",
                               geometry={"tibia": {"contact": float(c), "side": side}}).value
               for c in np.linspace(-half, half, 41) for side in ("above", "below"))
    assert searched.value <= best * (1 + 1e-9)


def test_grid_and_sorted_geometry():
    ticks = np.linspace(-1, 1, 3)
    assert len(_grid(1, ticks)) == 3 and len(_grid(2, ticks)) == 6 and len(_grid(4, ticks)) == 36
    g = _geometry("dead_zone", np.array([0.2, 0.2]), "above")
    assert g["theta_minus"] < g["theta_plus"]
    s = _geometry("stiffening", np.array([0.3, 0.1, -0.4, -0.2]), "above")
    assert s["above_1"] < s["above_2"] and s["below_1"] > s["below_2"]
