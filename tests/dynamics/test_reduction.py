"""Tests of hexaleg.dynamics.reduction: every force f_p + N z meets the base rows, the stance-leg
torques are τ₀ − E z, and the groups cover the loaded samples."""

from __future__ import annotations

import numpy as np
import pytest

import hexaleg
from hexaleg.dynamics.prepare import prepare
from hexaleg.dynamics.reduction import reduce
from hexaleg.errors import InfeasibleForcesError


def test_null_space_forces_meet_the_base_rows_and_give_the_torques(robot, walk200):
    sys = prepare(robot, walk200).system
    red = reduce(sys)
    assert reduce(sys) is red  # computed once per system
    assert red.reachable.all() and [g.m for g in red.groups] == [3]
    T = walk200.n_samples
    tau_s = np.random.default_rng(0).normal(size=(T, robot.nj))
    f = np.zeros((T, len(robot.legs), 3))
    tau = sys.b_joint - tau_s
    for g in red.groups:
        z = np.random.default_rng(1).normal(size=(g.m, g.size))
        f[g.rows[None, :], g.legs] = np.transpose(g.forces(z), (1, 2, 0))
        tau[g.rows[None, :], g.joints] = g.torques(g.tau0(tau_s), z)
        np.testing.assert_allclose(np.einsum("cfmt,cfnt->mnt", g.N, g.N),
                                   np.broadcast_to(np.eye(g.m)[..., None], (g.m, g.m, g.size)),
                                   atol=1e-12)  # orthonormal
    f = f.reshape(T, -1)
    np.testing.assert_allclose(np.einsum("tik,tk->ti", sys.A, f), sys.b_base, atol=1e-9)
    np.testing.assert_allclose(tau, sys.torques(f, tau_s), atol=1e-12)
    loaded = np.zeros((T, robot.nj), bool)  # the joints of the stance legs
    for i, leg in enumerate(robot.legs):
        loaded[:, [robot.joint_names.index(j) for j in leg.joint_names]] = walk200.stance[:, [i]]
    assert np.array_equal(~red.free, loaded)


def test_two_feet_leave_one_free_coordinate_and_an_unreachable_part(robot, walk200):
    """Two point feet: base rows of rank 5; gravity's moment about the line through them is out
    of reach (the residual), the rest has one free coordinate."""
    stance = walk200.stance.copy()
    stance[5] = False
    stance[5, [0, 1]] = True
    two = hexaleg.Motion(t=walk200.t, q=walk200.q, v=walk200.v, a=walk200.a, stance=stance,
                         feet=walk200.feet, period=walk200.period, distance=walk200.distance)
    red = reduce(prepare(robot, two).system)
    assert not red.reachable[5] and red.reachable[np.arange(walk200.n_samples) != 5].all()
    assert sorted(g.m for g in red.groups) == [1, 3]


def test_one_foot_leaves_no_free_coordinate_and_a_named_error(robot, one_foot):
    """One point foot (#38, #39): base rows of rank 3, no null space (m = 0), its force the
    least-norm one; a motion that needs a moment about the foot is refused by name, never a
    reshape traceback (it ended a quadruped's crawl at duty factor 0.3 and every biped)."""
    prepared = prepare(robot, one_foot)
    red = reduce(prepared.system)
    single = [g for g in red.groups if g.m == 0]
    assert len(single) == 1 and single[0].rows.tolist() == [5] and not red.reachable[5]
    g = single[0]
    np.testing.assert_array_equal(g.forces(np.zeros((0, 1))), g.fp)
    with pytest.raises(InfeasibleForcesError, match=r"one point foot \(LF\)"):
        prepared.baseline()


def test_long_motions_are_cut_into_cache_sized_groups(robot):
    from hexaleg.dynamics.reduction import GROUP_SIZE

    motion = hexaleg.gait(robot, hexaleg.GaitParams(samples=2 * GROUP_SIZE + 100))
    red = reduce(prepare(robot, motion).system)
    sizes = [g.size for g in red.groups]
    assert max(sizes) <= GROUP_SIZE and len(sizes) == 3
    assert np.array_equal(np.sort(np.concatenate([g.rows for g in red.groups])),
                          np.arange(motion.n_samples))
