"""Tests of hexaleg.dynamics.certificate: the KKT check accepts the optimum and rejects each kind
of wrong guess."""

from __future__ import annotations

import numpy as np

from hexaleg.dynamics.active_set import empty_state, solve_state
from hexaleg.dynamics.certificate import feasible, verify
from hexaleg.dynamics.contact import ContactParams
from hexaleg.dynamics.guesses import from_interior_point
from hexaleg.dynamics.ipm import interior_point


def test_the_optimum_is_certified_and_wrong_guesses_are_not(walk200, group_data):
    _, _, data, _ = group_data(walk200, ContactParams(mu=0.3), "joule")
    guess = from_interior_point(data, interior_point(data))
    sol = solve_state(data, guess)[1]
    assert verify(data, guess, sol).ok.all()
    # Nothing active: the unconstrained optimum leaves the cones.
    empty = empty_state(data)
    check = verify(data, empty, solve_state(data, empty)[1])
    bound = guess.feet.any(axis=(0, 1))  # samples where a cone binds
    assert not check.ok[bound].any() and (check.rows[0] < 0).any(axis=0)[bound].all()
    free = solve_state(data, empty)[1]
    assert np.array_equal(feasible(data, free.tau, free.f), ~bound)
    # A surface row too many: its multiplier has the wrong sign somewhere.
    extra = guess.take(np.arange(data.tau0.shape[1]))
    extra.feet = guess.feet.copy()
    extra.feet[0] = True
    assert not verify(data, extra, solve_state(data, extra)[1]).ok.all()


def test_a_joint_off_its_piece_is_rejected(walk200, group_data):
    _, _, data, _ = group_data(walk200, ContactParams(), "positive_work")
    guess = from_interior_point(data, interior_point(data))
    sol = solve_state(data, guess)[1]
    assert verify(data, guess, sol).ok.all()
    wrong = guess.take(np.arange(data.tau0.shape[1]))
    wrong.held = np.zeros_like(guess.held)
    wrong.piece = 1 - guess.piece  # every joint on its other piece
    assert not verify(data, wrong, solve_state(data, wrong)[1]).ok.any()


def test_non_finite_forces_are_never_feasible(walk200, group_data):
    """A sample whose unconstrained gains are not finite (a singular Gram matrix,
    :func:`hexaleg.dynamics.active_set.unconstrained_gains`) is left to the certified paths:
    forces or torques that are NaN or infinite are never feasible (an infinite force had met
    its row's tolerance, scaled by the largest force; without torque limits an infinite torque
    was not checked at all)."""
    _, _, data, _ = group_data(walk200, ContactParams(mu=0.6), "joule")
    sol = solve_state(data, empty_state(data))[1]
    f, tau = sol.f.copy(), sol.tau.copy()
    f[:, :, 3] = np.nan
    tau[:, 5] = np.inf
    f[0, 0, 7] = np.inf
    ok = feasible(data, tau, f)
    assert not ok[[3, 5, 7]].any()
    assert np.array_equal(np.delete(ok, [3, 5, 7]),
                          np.delete(feasible(data, sol.tau, sol.f), [3, 5, 7]))
