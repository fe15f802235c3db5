"""The centre-of-pressure margin of a walk on soles: the stances it is taken over, none on point
feet. (Its value on a walking biped, against the test's own centre of pressure, is in
tests/simulation/test_balance.py's slow walk.)"""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np

from hexaleg.simulation import pressure
from hexaleg.simulation.measures import LOSS_GRACE


def test_inner_stance_leaves_out_each_stances_grace_at_both_ends_across_the_cycle_end():
    """Leg 0 stands over the cycle's end (samples 70–99 and 0–29: one stance of 60), leg 1 in
    the middle (20–79), leg 2 always: the first and last ⌈2 % · 60⌉ = 2 samples of each stance
    are left out, the whole cycle of a leg that never swings is in."""
    n = 100
    stance = np.zeros((n, 3), dtype=bool)
    stance[70:, 0] = stance[:30, 0] = True
    stance[20:80, 1] = True
    stance[:, 2] = True
    inner = pressure.inner_stance(SimpleNamespace(stance=stance.astype(float)))
    grace = int(np.ceil(LOSS_GRACE * 60))
    assert grace == 2
    expected0 = np.zeros(n, dtype=bool)
    expected0[70 + grace:] = expected0[:30 - grace] = True
    np.testing.assert_array_equal(inner[:, 0], expected0)
    expected1 = np.zeros(n, dtype=bool)
    expected1[20 + grace:80 - grace] = True
    np.testing.assert_array_equal(inner[:, 1], expected1)
    assert inner[:, 2].all()


def test_point_feet_have_no_margin(feedforward):
    """The hexapod stands on point feet: no sole, no margin, and its runs record none."""
    run = feedforward.with_springs
    assert pressure.cop_margin(run.sim, feedforward.motion, run.trajectory,
                               slice(0, run.trajectory.n)) is None
    assert run.cop_margin is None and feedforward.baseline.cop_margin is None
