"""Tests of hexaleg.dynamics.solver: the quadratic program's gains and the fast path's checks."""

from __future__ import annotations

import numpy as np
import pytest

import hexaleg
from hexaleg.dynamics.prepare import prepare
from hexaleg.dynamics.solver import quadratic_gains
from hexaleg.errors import InfeasibleForcesError


def test_quadratic_gains_give_the_constrained_optimum(robot, walk200):
    """KKT: base rows hold and no direction in their null space lowers Σ w τ²."""
    prepared = prepare(robot, walk200)
    sys = prepared.system
    w = prepared.weights("joule")
    gains = quadratic_gains(sys, w)
    f = gains.f0
    assert np.max(np.abs(np.einsum("tik,tk->ti", sys.A, f) - sys.b_base)) <= 1e-9
    rng = np.random.default_rng(0)
    for k in rng.choice(walk200.n_samples, 10, replace=False):
        cols = np.flatnonzero(np.repeat(sys.stance[k], 3))
        A = sys.A[k][:, cols]
        null = np.linalg.svd(A)[2][6:].T  # basis of A's null space
        tau = sys.b_joint[k] - sys.D[k] @ f[k]
        grad = -2 * sys.D[k][:, cols].T @ (w * tau)
        assert np.max(np.abs(null.T @ grad)) <= 1e-9 * np.max(np.abs(grad))


@pytest.mark.parametrize("objective", ["joule", "positive_work"])
def test_unreachable_wrench_is_caught_on_every_path(robot, walk200, objective):
    """LF and LM alone: gravity has a moment about the line through them that no foot force can
    balance (the KKT system is singular). Both the KKT path and the conic path (which drops
    redundant base rows) say so with the time and the feet, not a numpy traceback."""
    motion = walk200
    stance = motion.stance.copy()
    stance[5] = False
    stance[5, [0, 1]] = True  # LF, LM
    two = hexaleg.Motion(t=motion.t, q=motion.q, v=motion.v, a=motion.a, stance=stance,
                         feet=motion.feet, period=motion.period, distance=motion.distance)
    expected = r"feet LF, LM cannot .*\(sample 5\).*miss the base rows"
    with pytest.raises(InfeasibleForcesError, match=expected):
        prepare(robot, two).evaluate(objective=objective)


def _one_foot(robot, one_foot, force):
    """The one-foot gait (conftest), its base wrench at sample 5 the one ``force`` gives (so
    that it is reachable), prepared."""
    prepared = prepare(robot, one_foot)
    f = np.zeros(prepared.system.A.shape[2])
    f[:3] = force
    prepared.system.b_base[5] = prepared.system.A[5] @ f  # before anything is reduced
    return prepared


@pytest.mark.parametrize("objective", ["joule", "torque_squared", "electrical"])
def test_one_foot_gets_the_only_force_its_base_rows_allow(robot, one_foot, objective):
    """One stance foot (#38, #39): no freedom, its force is the one the base wrench fixes — on
    the fast path, in the cvxpy reference, in the design program's gains."""
    from hexaleg.dynamics.reference import solve_reference

    force = np.array([0.5, 0.2, 12.0])
    prepared = _one_foot(robot, one_foot, force)
    analysis = prepared.evaluate({}, objective)
    np.testing.assert_allclose(analysis.forces[5, 0], force, atol=1e-9)
    s = prepared.system
    ref = solve_reference(s, np.zeros_like(s.b_joint), objective, prepared.weights(objective),
                          prepared.contact, samples=np.array([5]))
    np.testing.assert_allclose(ref[5, :3], force, atol=1e-5)
    np.testing.assert_allclose(prepared.gains("joule").f0[5, :3], force, atol=1e-9)


def test_one_foot_outside_its_cone_is_named(robot, one_foot):
    prepared = _one_foot(robot, one_foot, np.array([9.0, 0.0, 10.0]))  # 0.9 > μ = 0.6
    with pytest.raises(InfeasibleForcesError, match=r"sample 5"):
        prepared.baseline()


def test_two_joint_legs_get_the_reference_torques():
    """A two-joint leg's foot force along its joint axes loads no joint (issue #39): the motor
    energy leaves it free, and the fast path must still find the optimum — its joint torques
    D f those of the cvxpy reference (which takes no force across the legs' planes) — where the
    KKT matrix it solved was singular (LinAlgError in the co-design's search)."""
    from pathlib import Path

    import hexaleg
    from hexaleg.dynamics.reference import solve_reference

    quad = str(Path(__file__).resolve().parents[1] / "data" / "quad2dof.toml")
    prepared = hexaleg.Scenario.from_tables(
        quad, {"gait": {"period": 0.6, "samples": 200}, "contact": {"mu": 1.0}}).prepare()
    robot, s = prepared.robot, prepared.system
    knees = robot.joints("joint2")
    springs = hexaleg.SpringSet({j: hexaleg.LinearSpring(
        stiffness=0.5, reference=float(prepared.motion.q[:, 7 + robot.column(j)].mean()))
        for j in knees})
    analysis = prepared.evaluate(springs, "joule")
    samples = np.arange(0, 200, 10)
    ref = solve_reference(s, analysis.tau_spring, "joule", prepared.weights("joule"),
                          prepared.contact, samples=samples)
    fast = analysis.forces.reshape(200, -1)[samples]
    torque = np.einsum("tjk,tk->tj", s.D[samples], fast)
    np.testing.assert_allclose(torque, np.einsum("tjk,tk->tj", s.D[samples], ref[samples]),
                               atol=1e-8)
