"""Tests of hexaleg.dynamics.active_set: the KKT solve on a guess — one step where every row is
linear (from any start), Newton's method on a cone's surface, dependent rows dropped."""

from __future__ import annotations

import numpy as np

from hexaleg.dynamics.active_set import empty_state, solve_state, unconstrained_gains
from hexaleg.dynamics.contact import ContactParams
from hexaleg.dynamics.guesses import from_interior_point
from hexaleg.dynamics.ipm import interior_point


def test_nothing_active_is_the_unconstrained_optimum(walk200, group_data):
    _, _, data, _ = group_data(walk200, ContactParams(), "joule")
    state = empty_state(data)
    state.z[:] = 123.0  # a linear guess starts from z = 0 whatever its z
    sol = solve_state(data, state)[1]
    z = np.einsum("mjt,jt->mt", unconstrained_gains(data), data.tau0)
    np.testing.assert_allclose(sol.z, z, atol=1e-12)
    assert sol.converged.all()


def test_cone_surfaces_converge_from_the_interior_point_guess(walk200, group_data):
    """At μ = 0.3 half the samples have a foot on its cone's surface: Newton's method from the
    interior-point solution lands on it (μ f_z = ‖f_t‖ to rounding)."""
    _, _, data, _ = group_data(walk200, ContactParams(mu=0.3), "joule")
    guess = from_interior_point(data, interior_point(data))
    assert guess.feet[0].any(axis=0).mean() >= 0.4
    sol = solve_state(data, guess)[1]
    assert sol.converged.all()
    f = sol.f
    surface = guess.feet[0]
    gap = 0.3 * f[2] - np.hypot(f[0], f[1])
    assert np.max(np.abs(gap[surface])) <= 1e-12 * np.abs(f).max()
    assert np.max(np.abs(sol.z - guess.z)) <= 1e-5  # the interior point was that close (N)


def test_dependent_held_joints_keep_their_given_multipliers(walk200, group_data):
    """Positive work at mid-stance holds five joints at zero torque with three free
    coordinates: two rows depend on the others, keep the interior point's multipliers, and the
    solution still holds all five."""
    _, _, data, _ = group_data(walk200, ContactParams(), "positive_work")
    guess = from_interior_point(data, interior_point(data))
    crowded = np.flatnonzero(guess.held.sum(axis=0) > data.N.shape[2])
    assert crowded.size
    sol = solve_state(data.take(crowded), guess.take(crowded))[1]
    held = guess.held[:, crowded]
    assert np.max(np.abs(sol.tau[held] - guess.at[:, crowded][held])) <= 1e-9
    # measured ≤ 1.4e-10 W/(N·m) (multipliers up to 0.28)
    np.testing.assert_allclose(sol.y_joint[held], guess.y[:, crowded][held], atol=1e-6)
