"""The footholds as decisions: the warm start's feet moved by constant offsets (on their points,
at rest in stance, the cycle still periodic), the problem built on it holding the moved points,
and the compass search over the offsets (deterministic, the least on its lattice, within its
bound); bad input named."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pinocchio as pin
import pytest

import hexaleg
from hexaleg.errors import InvalidParameterError
from hexaleg.optimal.footholds import (
    FootholdSearch,
    mirrored_legs,
    moved_footholds,
    offsets_of,
    search_footholds,
)
from hexaleg.optimal.periodic import cycle_displacement

OFFSETS = np.array([[4e-3, 3e-3], [-2e-3, 5e-3], [-4e-3, 2e-3],
                    [4e-3, -3e-3], [-2e-3, -5e-3], [-4e-3, -2e-3]])


@pytest.fixture(scope="module")
def turning(robot):
    """A tripod that turns (the base rotates, so the offsets rotate in the base frame)."""
    return hexaleg.gait(robot, hexaleg.GaitParams(yaw_rate=0.2, samples=200))


def _feet(robot, q, v=None, a=None):
    """World foot positions (n_legs, 3) and, with v and a, velocities and classical
    accelerations."""
    model, data = robot.model, robot.data
    pin.forwardKinematics(model, data, q, *(() if v is None else (v, a)))
    pin.updateFramePlacements(model, data)
    p = np.array([data.oMf[leg.foot_frame_id].translation for leg in robot.legs])
    if v is None:
        return p
    w = pin.LOCAL_WORLD_ALIGNED
    vel = np.array([pin.getFrameVelocity(model, data, leg.foot_frame_id, w).linear
                    for leg in robot.legs])
    acc = np.array([pin.getFrameClassicalAcceleration(model, data, leg.foot_frame_id, w).linear
                    for leg in robot.legs])
    return p, vel, acc


def test_no_offset_is_the_motion_itself(robot, walk200):
    same = moved_footholds(robot, walk200, np.zeros((6, 2)))
    np.testing.assert_allclose(same.q, walk200.q, atol=1e-12)
    np.testing.assert_allclose(same.v, walk200.v, atol=1e-10)
    np.testing.assert_allclose(same.a, walk200.a, atol=1e-8)


def test_the_feet_move_by_their_offsets_and_rest_in_stance(robot, turning):
    """Catches an offset applied in the base frame without the base's rotation (the feet then
    turn with the body), or derivatives without the ``ω × Rᵀδ`` terms (stance feet slide)."""
    moved = moved_footholds(robot, turning, OFFSETS)
    shift = np.hstack([OFFSETS, np.zeros((6, 1))])
    for k in range(0, len(moved.t), 7):
        p, vel, acc = _feet(robot, moved.q[k], moved.v[k], moved.a[k])
        np.testing.assert_allclose(p, _feet(robot, turning.q[k]) + shift, atol=1e-9)
        np.testing.assert_allclose(p, moved.feet[k], atol=1e-9)
        on = moved.stance[k]
        np.testing.assert_allclose(vel[on], 0.0, atol=1e-9)
        np.testing.assert_allclose(acc[on], 0.0, atol=1e-7)


def test_the_moved_cycle_stays_periodic(robot):
    """A foothold of the next cycle is this one's moved by the stride: a leg standing across
    the cycle's end stands at its first sample where it landed, moved back by a stride."""
    long = hexaleg.gait(robot, hexaleg.GaitParams(duty_factor=0.8, samples=200))
    moved = moved_footholds(robot, long, OFFSETS)
    h = cycle_displacement(moved)
    first = _feet(robot, moved.q[0])
    crossing = [j for j in range(6) if moved.stance[0, j] and moved.stance[-1, j]]
    assert crossing
    for j in crossing:
        landed = int(np.flatnonzero(~moved.stance[:, j])[-1]) + 1  # its last touch-down
        p = _feet(robot, moved.q[landed])[j]
        np.testing.assert_allclose(h[:3, :3] @ first[j] + h[:3, 3], p, atol=1e-9)


def test_the_problem_holds_the_moved_footholds(robot, walk200, hexaleg_run):
    """Catches footholds that do not move: the problem's foothold of every stance foot is the
    warm start's moved by its leg's offset."""
    pytest.importorskip("crocoddyl")
    from hexaleg.optimal.problem import OptimalParams, build_problem

    params = OptimalParams(nodes=20)
    before = build_problem(robot, walk200, hexaleg_run.actuator, hexaleg.SpringSet(), params)
    after = build_problem(robot, moved_footholds(robot, walk200, OFFSETS), hexaleg_run.actuator,
                          hexaleg.SpringSet(), params)
    shift = np.hstack([OFFSETS, np.zeros((6, 1))])
    np.testing.assert_array_equal(after.stance, before.stance)
    expected = (before.footholds + shift) * before.stance[..., None]
    np.testing.assert_allclose(after.footholds, expected, atol=1e-9)


@pytest.fixture(scope="module")
def hexaleg_run():
    return hexaleg.Scenario.load("hexaleg")


def test_mirrored_legs_pair_left_and_right(robot):
    assert [(robot.leg_names[j], robot.leg_names[m]) for j, m in mirrored_legs(robot)] == \
        [("LF", "RF"), ("LM", "RM"), ("LH", "RH")]
    o = offsets_of(robot, (1, 2, 0, 0, -1, 3), 2e-3)
    np.testing.assert_allclose(o, [[2e-3, 4e-3], [0, 0], [-2e-3, 6e-3],
                                   [2e-3, -4e-3], [0, 0], [-2e-3, -6e-3]])


def _quadratic(robot, target):
    """A value with its least at the lattice point ``target`` (6 steps of 2 mm)."""
    goal = offsets_of(robot, target, 2e-3)
    calls = []

    def value(offsets):
        calls.append(offsets)
        return float(np.sum((offsets - goal) ** 2) * np.arange(1, 13).reshape(6, 2).sum())
    return value, goal, calls


def test_the_search_finds_the_least_on_its_lattice(robot):
    """Catches a search that does not move, or stops before its smallest step."""
    value, goal, calls = _quadratic(robot, (-3, 2, 5, 0, 1, -4))
    answer = search_footholds(robot, value, FootholdSearch(step=8e-3, smallest=2e-3, bound=0.02))
    np.testing.assert_allclose(answer.offsets, goal, atol=1e-15)
    assert answer.value == pytest.approx(0.0, abs=1e-20)
    assert answer.start == value(np.zeros((6, 2)))
    assert len(calls) - 1 == len(answer.tried)  # each lattice point once (and the check above)
    again = search_footholds(robot, _quadratic(robot, (-3, 2, 5, 0, 1, -4))[0],
                             FootholdSearch(step=8e-3, smallest=2e-3, bound=0.02))
    assert [v for _, v in again.tried] == [v for _, v in answer.tried]


def test_a_search_started_at_its_least_stays_there(robot):
    """Catches a start that is ignored (the search would walk from no offsets)."""
    target = (-3, 2, 5, 0, 1, -4)
    value, goal, _ = _quadratic(robot, target)
    answer = search_footholds(robot, value, FootholdSearch(step=8e-3, smallest=2e-3,
                                                           bound=0.02), start=target)
    np.testing.assert_allclose(answer.offsets, goal, atol=1e-15)
    assert answer.point == target
    assert answer.start == pytest.approx(0.0, abs=1e-20)
    assert len(answer.tried) == 1 + 2 * 6 * 3  # the start, then ± each coordinate at 3 steps
    with pytest.raises(InvalidParameterError, match="start"):
        search_footholds(robot, value, FootholdSearch(bound=0.02), start=(11, 0, 0, 0, 0, 0))


def test_the_search_keeps_its_bound_and_skips_unreachable_candidates(robot):
    def value(offsets):
        if offsets[0, 0] > 0:  # a leg out of reach forward
            return None
        return float(np.sum((offsets - 0.05) ** 2))  # least far beyond the bound

    answer = search_footholds(robot, value, FootholdSearch(step=4e-3, smallest=2e-3,
                                                           bound=6e-3))
    assert np.abs(answer.offsets).max() <= 6e-3 + 1e-15
    assert answer.offsets[0, 0] == 0.0
    assert answer.value is not None and answer.value < answer.start  # type: ignore[operator]


@pytest.mark.parametrize("offsets", [np.zeros((5, 2)), np.full((6, 2), np.nan)])
def test_bad_offsets_are_named(robot, walk200, offsets):
    with pytest.raises(InvalidParameterError, match="offsets"):
        moved_footholds(robot, walk200, offsets)


@pytest.mark.parametrize("key, value", [("step", 6e-3), ("smallest", -1e-3), ("polls", 0)])
def test_bad_search_settings_are_named(key, value):
    with pytest.raises(InvalidParameterError, match=key):
        FootholdSearch(**{key: value})


@pytest.mark.parametrize("name", ["solo12", str(Path(__file__).resolve().parents[1] / "data"
                                                 / "spider.toml")])
def test_mirrored_legs_are_the_robots_mirror_twins(name):
    """The search's pairs are the robot's mirror twins by the hips' geometry
    (:func:`hexaleg.robot.mirror.mirror`), and a pair's outward step points away from the
    sagittal plane on both sides, across the robot's heading (the spider walks along y).
    Catches an outward step along world y whatever the heading."""
    from hexaleg.robot.mirror import mirror

    robot = hexaleg.load(name)
    twins = mirror(robot).twins
    pairs = mirrored_legs(robot)
    assert all(m is not None and twins[robot.leg_names[j]] == robot.leg_names[m]
               for j, m in pairs)
    o = offsets_of(robot, (0, 1) * len(pairs), 2e-3)
    pin.forwardKinematics(robot.model, robot.data, robot.pose("stand"))
    left = np.cross([0.0, 0.0, 1.0], robot.heading)[:2]
    for leg, step in zip(robot.legs, o, strict=True):
        hip = robot.data.oMi[leg.joint_ids[0]].translation - robot.pose("stand")[:3]
        side = np.sign(hip[:2] @ left)
        np.testing.assert_allclose(step, 2e-3 * side * left, atol=1e-15, err_msg=leg.name)
