"""Tests of hexaleg.design.studies.optimise: the optimiser against a fine grid, and the free neutral
offset (a preloaded spring) against the centred design."""

from __future__ import annotations

import math

import numpy as np
import pytest

from hexaleg.design.evaluator import evaluator
from hexaleg.design.studies.optimise import optimise
from hexaleg.errors import InvalidParameterError
from hexaleg.scenario.scenario import Scenario

RUN = Scenario.load()


def test_optimum_matches_a_fine_grid_minimum():
    """Coxa springs at a 0.5 s period: the optimiser's (k, θ_k) is at least as good as the best of
    a fine 40 × 12 grid over the same box, and lies next to it."""
    ev = evaluator(RUN.with_gait({"samples": 100, "period": 0.5}))
    joints = ev.robot.joints("coxa")
    k_bounds, t_bounds = (0.01, 1.0), (0.002, 0.05)
    opt = optimise(ev, "coxa", joints, k_bounds=k_bounds, theta_bounds=t_bounds, grid=(6, 3))
    ks, ts = np.geomspace(*k_bounds, 40), np.linspace(*t_bounds, 12)
    grid = np.array([[ev.value({"coxa": joints}, {"coxa": {"k": k, "theta_k": t}}) for t in ts]
                     for k in ks])
    i, j = np.unravel_index(np.argmin(grid), grid.shape)
    assert opt.value <= grid[i, j] + 1e-9 * grid[i, j]
    # …and not much better: the grid's minimum is the same valley, within 2 % of the saving
    assert grid[i, j] - opt.value < 0.02 * (opt.baseline - opt.value)
    assert abs(math.log(opt.k / ks[i])) <= 1.5 * math.log(ks[1] / ks[0])
    assert abs(opt.theta_k - ts[j]) <= 1.5 * (ts[1] - ts[0])
    assert opt.saving > 0.01 and opt.value < opt.grid_value


def test_free_offset_preload_beats_the_centred_design_on_the_tibia():
    """On the slow default gait the tibia motors mostly hold the body up: a centred dead-zone
    spring (zero mean torque over a symmetric motion) can barely help, while a spring whose
    neutral is moved off the motion carries part of that steady load."""
    ev = evaluator(RUN.with_gait({"samples": 100}))
    joints = ev.robot.joints("tibia")
    centred = optimise(ev, "tibia", joints, k_bounds=(0.01, 1.0), grid=(4, 3))
    free = optimise(ev, "tibia", joints, k_bounds=(0.01, 1.0), offset_bounds=(-1.0, 1.0),
                    grid=(4, 3, 3))
    assert centred.offset == 0.0 and -1.0 <= free.offset <= 1.0
    assert centred.saving < 0.01 < 0.05 < free.saving
    row = ev.row({"tibia": joints}, {"tibia": free.design()})
    assert row["electrical"] == free.value
    with pytest.raises(InvalidParameterError, match="offset_bounds"):
        optimise(ev, "tibia", joints, offset_bounds=(0.5, -0.5))
    with pytest.raises(InvalidParameterError, match="start"):
        optimise(ev, "tibia", joints, offset_bounds=(-1.0, 1.0), start=(0.1, 0.01))  # no offset
