"""The body's roll about a two-point support line: its kinematics against finite differences,
the boundary-value solve against a closed form, the fade against its end conditions, the phases
of a trot. The whole robot's case (Solo-12's trot rebuilt) is in ``test_task_space.py``."""

from __future__ import annotations

import numpy as np
import pinocchio as pin
import pytest

from hexaleg.errors import InfeasibleForcesError
from hexaleg.motion.body import Body
from hexaleg.optimal.support_line import MOMENT_TOL, balance, blend, phases, roll

SPEED, YAW_RATE = 0.3, 0.5
AXIS = np.array([1.0, 0.5, 0.0]) / np.hypot(1.0, 0.5)
POINT = np.array([0.1, -0.1, 0.0])


def _turning(t: np.ndarray) -> Body:
    """A base moving along x at SPEED while it yaws at YAW_RATE: exact LOCAL rates."""
    n = len(t)
    rot = np.array([pin.exp3(np.array([0.0, 0.0, YAW_RATE * x])) for x in t])
    v = np.einsum("nji,j->ni", rot, [SPEED, 0.0, 0.0])
    w = np.tile([0.0, 0.0, YAW_RATE], (n, 1))
    return Body(base=np.column_stack([SPEED * t, np.zeros(n), np.full(n, 0.25)]),
                yaw=YAW_RATE * t, rot=rot, v=v, w=w, a=-np.cross(w, v), alpha=np.zeros((n, 3)))


def _rolled(t: np.ndarray) -> Body:
    th = 0.2 * np.sin(2.0 * t)
    return roll(_turning(t), POINT, AXIS, th, 0.4 * np.cos(2.0 * t), -0.8 * np.sin(2.0 * t))


def test_the_rolled_bodys_rates_are_the_derivatives_of_its_placements():
    """Central differences of the rolled placements (world position, orientation by log3) give
    its LOCAL velocities, of those its accelerations; a wrong sign of any term of ``roll``
    (the Coriolis ``2 θ̇ u × Q ṗ``, the centripetal ``θ̇ u × (θ̇ u × r)``) fails it."""
    t = np.linspace(0.1, 1.0, 7)
    eps = 1e-5
    mid, plus, minus = _rolled(t), _rolled(t + eps), _rolled(t - eps)
    v = np.einsum("nji,nj->ni", mid.rot, (plus.base - minus.base) / (2 * eps))
    w = np.array([pin.log3(a.T @ b) for a, b in zip(minus.rot, plus.rot, strict=True)]) / (2 * eps)
    np.testing.assert_allclose(mid.v, v, atol=1e-8)
    np.testing.assert_allclose(mid.w, w, atol=1e-8)
    np.testing.assert_allclose(mid.a, (plus.v - minus.v) / (2 * eps), atol=1e-7)
    np.testing.assert_allclose(mid.alpha, (plus.w - minus.w) / (2 * eps), atol=1e-7)
    # the line itself does not move: a point on it keeps its world position
    on_line = POINT + 0.3 * AXIS
    local = np.einsum("nji,nj->ni", _turning(t).rot, on_line - _turning(t).base)
    moved = mid.base + np.einsum("nij,nj->ni", mid.rot, local)
    np.testing.assert_allclose(moved, np.tile(on_line, (len(t), 1)), atol=1e-12)


def test_no_roll_leaves_the_body_as_it_was():
    t = np.linspace(0.0, 1.0, 5)
    body, zero = _turning(t), np.zeros(5)
    same = roll(body, POINT, AXIS, zero, zero, zero)
    for a, b in ((same.base, body.base), (same.rot, body.rot), (same.v, body.v),
                 (same.w, body.w), (same.a, body.a), (same.alpha, body.alpha)):
        np.testing.assert_allclose(a, b, atol=1e-15)


def test_the_boundary_value_solve_meets_the_closed_form():
    """``θ̈ − k² θ = f`` with ``θ(0) = θ(T) = 0`` (an inverted pendulum about its line, pushed
    by a constant moment) has ``θ = f/k² (cosh k(t − T/2) / cosh kT/2 − 1)``: the solve is within
    the second-order differences' error of it and zeroes the moment at every sample."""
    k, f, period, samples = 6.0, 0.7, 0.3, 97
    h = period / (samples - 1)

    def moment(th, thd, thdd):
        return 0.05 * (thdd - k**2 * th - f)  # 0.05 kg m²: the inertia about the line

    th, thd, thdd = balance(moment, samples, h)
    t = np.arange(samples) * h
    exact = f / k**2 * (np.cosh(k * (t - period / 2)) / np.cosh(k * period / 2) - 1.0)
    exact_d = f / k * np.sinh(k * (t - period / 2)) / np.cosh(k * period / 2)
    assert np.abs(th - exact).max() <= 1e-4 * np.abs(exact).max()
    assert np.abs(thd - exact_d).max() <= 1e-3 * np.abs(exact_d).max()
    assert np.abs(moment(th, thd, thdd)).max() <= MOMENT_TOL
    assert th[0] == th[-1] == 0.0


def test_the_boundary_value_solve_is_newtons_on_a_nonlinear_moment():
    """A pendulum's ``sin θ`` and a rate-dependent term: the moment is zeroed at every sample."""

    def moment(th, thd, thdd):
        return 0.03 * thdd - 2.5 * np.sin(th + 0.2) + 0.01 * thd**2

    th, thd, thdd = balance(moment, 61, 0.005)
    assert np.abs(moment(th, thd, thdd)).max() <= MOMENT_TOL
    assert np.abs(th).max() > 1e-3  # it did roll


def test_a_moment_the_roll_cannot_change_is_refused():
    with pytest.raises(InfeasibleForcesError, match="does not depend on the roll"):
        balance(lambda th, thd, thdd: np.ones_like(th), 21, 0.01)


def test_the_fade_meets_its_end_conditions():
    s = np.linspace(0.0, 0.08, 401)
    th, thd, thdd = blend(s, 0.3, -2.0)
    assert th[0] == 0.0 and thd[0] == pytest.approx(0.3) and thdd[0] == pytest.approx(-2.0)
    np.testing.assert_allclose([th[-1], thd[-1], thdd[-1]], 0.0, atol=1e-12)
    h = s[1] - s[0]
    np.testing.assert_allclose(np.gradient(th, h)[1:-1], thd[1:-1], atol=1e-5)
    np.testing.assert_allclose(np.gradient(thd, h)[1:-1], thdd[1:-1], atol=1e-3)


def test_a_trots_two_point_phases_have_their_diagonal_as_support_line():
    """Four legs LF, RF, LH, RH at a rectangle's corners: the LF–RH pair, all four, the RF–LH
    pair (a trot at duty factor above one half), then three feet, a phase that runs past the
    cycle's end."""
    corners = np.array([[0.2, 0.15, 0.0], [0.2, -0.15, 0.0], [-0.2, 0.15, 0.0],
                        [-0.2, -0.15, 0.0]])
    stance = np.ones((10, 4), dtype=bool)
    stance[1:4, [1, 2]] = False  # LF, RH
    stance[6:9, [0, 3]] = False  # RF, LH
    stance[[9, 0]] = [True, True, False, True]  # three feet: not on a line
    footholds = np.where(stance[..., None], corners, 0.0)
    found = phases(stance, footholds)
    assert [(p.start, p.end) for p in found] == [(1, 4), (4, 6), (6, 9), (9, 11)]
    lines = [p for p in found if p.axis is not None]
    assert [(p.start, p.end) for p in lines] == [(1, 4), (6, 9)]
    for p, (a, b) in zip(lines, ((0, 3), (1, 2)), strict=True):
        u = (corners[b] - corners[a]) / np.linalg.norm(corners[b] - corners[a])
        assert abs(abs(p.axis @ u) - 1.0) <= 1e-12
        assert np.linalg.norm(np.cross(p.point - corners[a], u)) <= 1e-12
    assert phases(np.ones((6, 4), dtype=bool), np.tile(corners, (6, 1, 1))) == []
