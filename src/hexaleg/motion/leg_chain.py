"""A leg as a serial chain of 1-DoF joints, with forward kinematics vectorised over samples.

Pinocchio evaluates one configuration a call; a gait's inverse kinematics needs the foot of one
leg at hundreds of samples, many times over (the body sway iterates on the whole gait). With the
rest of the robot held at its reference pose, a leg is a fixed chain: the base → first joint
placement, the placement of each joint in the previous joint's frame, each joint's motion
(rotation about an axis or translation along one) and the foot in the last joint's frame. This
module reads that chain from the Pinocchio model once (:func:`leg_chain`), evaluates the
foot's position, its translation Jacobian and its bias acceleration ``J̇ q̇`` for a whole stack
of configurations with numpy; :mod:`hexaleg.motion.leg_ik` solves the leg's inverse kinematics
on it by Newton's method (the solver of every leg the closed form of
:mod:`hexaleg.motion.kinematics` does not fit).

A leg has three joints (a foot anywhere in a volume), two (a planar hip–knee leg: its foot
moves in a plane, the one its two axes leave it; a target off that plane by more than
:data:`~hexaleg.motion.leg_ik.PLANE_TOL` is out of reach, named with its distance) or four and
more (redundant: a foot position leaves n − 3 joint motions free, and a stated secondary
objective fixes them — the leg's redundant directions at the reference pose hold their
reference values, :class:`LegChain`).

Source: the product of exponentials / screw form of serial-chain kinematics and the geometric
Jacobian with its time derivative (Siciliano et al., *Robotics: Modelling, Planning and
Control*, 2009, §2.9 and §3.1–3.2: the column of a revolute joint is ``z × (p − o)``, of a
prismatic joint ``z``). :func:`leg_chain` checks the chain against Pinocchio's forward kinematics
before it is used; the tests check the Jacobian and ``J̇ q̇`` against Pinocchio too.
"""

from __future__ import annotations

import weakref
from dataclasses import dataclass, field, replace

import numpy as np
import pinocchio as pin

from hexaleg.errors import RobotModelError
from hexaleg.robot.model import Leg, Robot

CHAIN_CHECK_TOL = 1e-12
"""Foot position tolerance, m, of the check of the chain against Pinocchio's forward kinematics."""
MIN_JOINTS = 2
"""The fewest joints a leg may have for foot-position inverse kinematics."""
REDUNDANT_SINGULAR = 1e-8
"""Smallest ratio of the foot Jacobian's least to largest singular value at the reference pose
for a leg of four or more joints: below it the leg is stretched (or folded) there and its
redundant directions are not defined."""


def _cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """``a × b`` over the last axis (length 3) with broadcasting: numpy's ``cross`` costs more in
    its checks than in the arithmetic at these sizes."""
    a0, a1, a2 = a[..., 0], a[..., 1], a[..., 2]
    b0, b1, b2 = b[..., 0], b[..., 1], b[..., 2]
    return np.stack([a1 * b2 - a2 * b1, a2 * b0 - a0 * b2, a0 * b1 - a1 * b0], axis=-1)


def _rotations(axis: np.ndarray, angle: np.ndarray) -> np.ndarray:
    """Rotations by ``angle`` about unit ``axis`` (Rodrigues' formula), shape (T, 3, 3)."""
    k = np.array([[0.0, -axis[2], axis[1]], [axis[2], 0.0, -axis[0]], [-axis[1], axis[0], 0.0]])
    s, c = np.sin(angle)[:, None, None], np.cos(angle)[:, None, None]
    return np.eye(3) + s * k + (1.0 - c) * (k @ k)


@dataclass(frozen=True, eq=False)
class LegChain:
    """One leg's n joints (2 or more) as a fixed serial chain in the base frame (module docstring).

    A leg of n ≥ 4 joints is redundant for its foot position; its secondary objective is linear in
    the joints: ``N₀ᵀ (q − q_ref) = 0``, with ``N₀`` (:attr:`redundant`) the right-singular
    vectors of the foot's translation Jacobian ``J₀ = J(q_ref)`` at the reference pose
    (:attr:`reference`) for its n − 3 smallest singular values (the null space of the 3 × n
    ``J₀``): the leg's self-motion at the reference pose stays at its reference value. Stacked
    under ``J`` it gives the square augmented Jacobian ``Ĵ = [J; N₀ᵀ]`` (:meth:`augmented`) of the
    augmented-Jacobian (extended-Jacobian) method; to first order in the foot's displacement
    from the reference, its solution is the joint configuration nearest ``q_ref`` that puts the
    foot on the target (the minimum-norm ``J₀⁺ Δp`` lies in the row space of ``J₀``, orthogonal
    to ``N₀``). Source: Siciliano et al., *Robotics: Modelling, Planning and Control*, 2009,
    §3.4–3.5 (redundancy, and the inverse differential kinematics of redundant manipulators:
    the minimum-norm solution and constraint tasks added to the end-effector's), Baillieul,
    "Kinematic programming alternatives for redundant manipulators", ICRA 1985 (the extended
    Jacobian: the end-effector's Jacobian with rows of a secondary objective, made square), and
    Sciavicco & Siciliano, "A solution algorithm to the inverse kinematic problem for redundant
    manipulators", IEEE J. Robotics and Automation 4(4), 1988 (the augmented task space). A
    leg of three joints or fewer has no redundant direction (``N₀`` of shape (n, 0)), and
    ``Ĵ = J``.

    A leg with a sole (:mod:`hexaleg.robot.soles`) keeps its sole flat instead: ``N₀`` spans the
    row space of the foot's angular Jacobian ``J_ω`` at the reference (the flat stand), so the
    rows hold the foot's orientation to first order — exactly for a hip that turns yaw, roll,
    pitch above a knee and an ankle that turns pitch, roll (the foot's roll is then the sum of
    the roll angles and its pitch the sum of the pitch angles, linear in q), not for one that
    turns pitch, roll, yaw (Unitree G1). :func:`~hexaleg.motion.leg_ik.newton_leg_ik` starts
    from them and holds the foot's whole pose by Newton's method on it
    (:meth:`pose_jacobian`), exact for every six-joint leg.

    Attributes:
        placements: Per joint, its frame at zero angle in the previous joint's frame (the first
            in the base frame, with every joint before it at the reference pose): rotations,
            shape (n, 3, 3), and translations, shape (n, 3), m.
        angular: Per joint, its rotation axis in its own frame (zero for a prismatic joint),
            shape (n, 3).
        linear: Per joint, its translation axis in its own frame (zero for a revolute joint),
            shape (n, 3).
        foot: The foot point in the last joint's frame, shape (3,), m.
        reference: The leg's joint values at the reference pose ``q_ref``, shape (n,), rad or m.
        redundant: ``N₀``, the leg's redundant directions at the reference pose, orthonormal
            columns, shape (n, max(n − 3, 0)) (class docstring).
        sole: Whether the leg has a sole (``N₀`` then holds the foot's orientation).
        turn_rows: A sole leg's ``S⁻¹ Uᵀ`` of ``J_ω = U S N₀ᵀ``, shape (n − 3, 3): the
            objective's rows ``N₀ᵀ (q − q_ref)`` that turn the foot by a rotation vector θ
            (base frame) from its reference orientation are ``S⁻¹ Uᵀ θ``.
    """

    placements: tuple[np.ndarray, np.ndarray]
    angular: np.ndarray
    linear: np.ndarray
    foot: np.ndarray
    reference: np.ndarray
    redundant: np.ndarray
    sole: bool = False
    turn_rows: np.ndarray = field(default_factory=lambda: np.zeros((0, 3)))

    def rotation(self, q: np.ndarray) -> np.ndarray:
        """The foot's orientation in the base frame, shape (T, 3, 3), at joint values ``q``
        (T, n)."""
        rot = np.broadcast_to(np.eye(3), (len(q), 3, 3))
        for i in range(len(self.angular)):
            rot = rot @ self.placements[0][i]
            if self.angular[i].any():
                rot = rot @ _rotations(self.angular[i], q[:, i])
        return rot

    def frames(self, q: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """The foot and the joints' axes in the base frame.

        Args:
            q: Joint values, shape (T, n), rad or m.

        Returns:
            Foot positions (T, 3) m; joint origins (T, n, 3) m, angular axes (T, n, 3) and
            linear axes (T, n, 3), each ``[:, i]`` of joint i, in the base frame.
        """
        n, joints = len(q), len(self.angular)
        rot = np.broadcast_to(np.eye(3), (n, 3, 3))
        pos = np.zeros((n, 3))
        origins, angular, linear = (np.empty((n, joints, 3)) for _ in range(3))
        for i in range(joints):
            pos = pos + rot @ self.placements[1][i]
            rot = rot @ self.placements[0][i]
            origins[:, i] = pos
            angular[:, i] = rot @ self.angular[i]
            linear[:, i] = rot @ self.linear[i]
            pos = pos + linear[:, i] * q[:, i:i + 1]
            if self.angular[i].any():
                rot = rot @ _rotations(self.angular[i], q[:, i])
        return pos + rot @ self.foot, origins, angular, linear

    def position_jacobian(self, q: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """The foot's position and its translation Jacobian ``∂p/∂q``.

        Args:
            q: Joint values, shape (T, n).

        Returns:
            Foot positions (T, 3) m and Jacobians (T, 3, n) (rows x y z, columns the joints).
        """
        p, origins, angular, linear = self.frames(q)
        cols = linear + _cross(angular, p[:, None, :] - origins)
        return p, np.swapaxes(cols, 1, 2)

    def augmented(self, jac: np.ndarray) -> np.ndarray:
        """The augmented Jacobian ``Ĵ = [J; N₀ᵀ]`` (class docstring).

        Args:
            jac: Translation Jacobians ``J``, shape (T, 3, n).

        Returns:
            ``Ĵ``, shape (T, 3 + max(n − 3, 0), n): square for n ≥ 3, ``J`` itself for n ≤ 3.
        """
        rows = np.broadcast_to(self.redundant.T, (len(jac), *self.redundant.T.shape))
        return np.concatenate([jac, rows], axis=1)

    def task(self, q: np.ndarray, e: np.ndarray, reference: np.ndarray | None = None
             ) -> np.ndarray:
        """The Newton right-hand side ``[e; −N₀ᵀ (q − q_ref)]``: a foot displacement and what
        the secondary objective's rows miss by (class docstring).

        Args:
            q: Joint values, shape (T, n). e: Foot displacements, shape (T, 3), m.
            reference: Per sample, the reference the rows hold, shape (T, n) (a sole leg's
                turning with the body, :func:`~hexaleg.motion.leg_ik.newton_leg_ik`); default
                :attr:`reference`.

        Returns:
            Shape (T, 3 + max(n − 3, 0)).
        """
        at = self.reference if reference is None else reference
        return np.concatenate([e, (at - q) @ self.redundant], axis=1)

    def pose_jacobian(self, q: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The foot's position, orientation and its 6 × n frame Jacobian (base frame): the
        translation rows ``∂p/∂q`` over the angular rows ``J_ω``, whose column i is joint i's
        rotation axis (zero for a prismatic joint; Siciliano et al., *Robotics*, 2009, §3.1.3,
        the geometric Jacobian).

        Args:
            q: Joint values, shape (T, n).

        Returns:
            Foot positions (T, 3) m, orientations (T, 3, 3) and Jacobians (T, 6, n).
        """
        p, origins, angular, linear = self.frames(q)
        cols = np.concatenate([linear + _cross(angular, p[:, None, :] - origins), angular],
                              axis=2)
        return p, self.rotation(q), np.swapaxes(cols, 1, 2)

    def angular_bias(self, q: np.ndarray, qd: np.ndarray) -> np.ndarray:
        """The foot's angular acceleration at zero joint acceleration, ``J̇_ω q̇``, in the base
        frame: joint i's axis turns with the body carrying it, ``ȧ_i = Ω_i × a_i`` with
        ``Ω_i = Σ_{j<i} a_j q̇_j`` (:meth:`bias`), so ``J̇_ω q̇ = Σ_i q̇_i Ω_i × a_i``.

        Args:
            q: Joint values, shape (T, n). qd: Joint velocities, shape (T, n).

        Returns:
            Shape (T, 3), rad/s².
        """
        _, _, angular, _ = self.frames(q)
        omega = np.zeros((len(q), 3))
        out = np.zeros((len(q), 3))
        for i in range(len(self.angular)):
            out += _cross(omega, angular[:, i]) * qd[:, i:i + 1]
            omega = omega + angular[:, i] * qd[:, i:i + 1]
        return out

    def bias(self, q: np.ndarray, qd: np.ndarray) -> np.ndarray:
        """The foot's acceleration at zero joint acceleration, ``J̇ q̇``, in the base frame.

        Each column ``c_i = l_i + a_i × (p − o_i)`` moves with the body carrying joint i, whose
        angular velocity is ``Ω_i = Σ_{j<i} a_j q̇_j``: ``ȧ_i = Ω_i × a_i``, ``l̇_i = Ω_i × l_i``,
        ``ȯ_i = Σ_{j<i} c_j(o_i) q̇_j`` and ``ṗ = J q̇``, so
        ``J̇ q̇ = Σ_i q̇_i (Ω_i × l_i + (Ω_i × a_i) × (p − o_i) + a_i × (ṗ − ȯ_i))``.

        Args:
            q: Joint values, shape (T, n).
            qd: Joint velocities, shape (T, n).

        Returns:
            Bias accelerations, shape (T, 3), m/s².
        """
        p, origins, angular, linear = self.frames(q)
        pd = np.einsum("tjx,tj->tx", linear + _cross(angular, p[:, None, :] - origins), qd)
        omega = np.zeros_like(p)
        out = np.zeros_like(p)
        for i in range(len(self.angular)):
            o = origins[:, i]
            od = sum((linear[:, j] + _cross(angular[:, j], o - origins[:, j])) * qd[:, j:j + 1]
                     for j in range(i)) if i else np.zeros_like(p)
            term = (_cross(omega, linear[:, i]) + _cross(_cross(omega, angular[:, i]), p - o)
                    + _cross(angular[:, i], pd - od))
            out += term * qd[:, i:i + 1]
            omega = omega + angular[:, i] * qd[:, i:i + 1]
        return out


def _sole_rows(leg: Leg, chain: LegChain, at: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """A sole leg's secondary objective (:class:`LegChain`): an orthonormal basis of the row
    space of its foot's angular Jacobian ``J_ω = U S Vᵀ`` (3 × n, base frame) at the
    reference pose, ``V`` of shape (n, n − 3), and ``S⁻¹ Uᵀ``, shape (n − 3, 3)
    (:attr:`LegChain.turn_rows`).

    Raises:
        RobotModelError: ``J_ω`` does not have rank n − 3 (a leg of other than six joints, or
            one that cannot turn its foot about every axis): the foot's position and a flat
            sole are then not n equations in its n joints.
    """
    n = len(at)
    omega = chain.frames(at[None])[2][0].T  # (3, n): the joints' axes, base frame
    u, sigma, vt = np.linalg.svd(omega)
    rank = int(np.sum(sigma > REDUNDANT_SINGULAR * max(float(sigma[0]), 1e-300)))
    if rank != n - 3:
        raise RobotModelError(
            f"leg {leg.name} has a sole and {n} joints that turn its foot about {rank} "
            f"independent axes at the stand; keeping a sole flat while the foot moves takes "
            f"{n - 3} (a leg of six joints: hip yaw, roll and pitch, knee, ankle pitch and roll)")
    return vt[:rank].T.copy(), (u[:, :rank] / sigma[:rank]).T.copy()


def _motion_axes(model: pin.Model, jid: int) -> tuple[np.ndarray, np.ndarray]:
    """Joint ``jid``'s angular and linear axes in its own frame (its motion subspace), each (3,)."""
    data = model.createData()
    q = pin.neutral(model)
    pin.computeJointJacobians(model, data, q)
    s = np.array(pin.getJointJacobian(model, data, jid, pin.LOCAL)[:, model.joints[jid].idx_v])
    return s[3:], s[:3]


_Key = tuple[tuple[int, ...], int, bytes]
_CHAINS: weakref.WeakKeyDictionary[Robot, dict[_Key, LegChain]] = weakref.WeakKeyDictionary()
"""Chains read per robot, by the leg's joints and foot frame, the reference pose and the
placements the chain is made of (a foot frame moved in place is read again): a gait's body sway
solves each leg's inverse kinematics many times."""


def leg_chain(robot: Robot, leg: Leg, reference: np.ndarray) -> LegChain:
    """The chain of ``leg`` with every other joint at ``reference``, checked against Pinocchio
    (read once per robot, leg and reference, then kept while the robot lives).

    Args:
        robot: The robot.
        leg: One of ``robot.legs``, two or more joints each the ancestor of the next and of the
            foot.
        reference: The configuration the other joints keep, shape (nq,), base at the origin.

    Returns:
        The chain.

    Raises:
        RobotModelError: the leg does not have two or more 1-DoF revolute or prismatic joints
            in one chain to its foot (the message names the joint), the chain does not reproduce
            Pinocchio's forward kinematics, or a leg of four or more joints is stretched or
            folded at the reference pose (its redundant directions are not defined there).
    """
    model = robot.model
    foot = model.frames[leg.foot_frame_id]
    placements = [model.jointPlacements[j].homogeneous for j in model.supports[foot.parentJoint]]
    key = (leg.joint_ids, leg.foot_frame_id, np.asarray(reference, dtype=float).tobytes()
           + np.array([*placements, foot.placement.homogeneous]).tobytes())
    known = _CHAINS.setdefault(robot, {})
    if key not in known:
        known[key] = _read_chain(robot, leg, reference)
    return known[key]


def _read_chain(robot: Robot, leg: Leg, reference: np.ndarray) -> LegChain:
    """:func:`leg_chain` without the memory."""
    model = robot.model
    if len(leg.joint_ids) < MIN_JOINTS:
        raise RobotModelError(
            f"leg {leg.name} has {len(leg.joint_ids)} joint(s); foot-position inverse kinematics "
            f"needs {MIN_JOINTS} or more (2: a planar hip–knee leg, 3: a foot anywhere, 4 or "
            "more: redundant, the stand pose's redundant directions held)")
    foot = model.frames[leg.foot_frame_id]
    chain = (*leg.joint_ids, foot.parentJoint)
    below = (*leg.joint_names[1:], f"foot frame {leg.foot_frame}")
    for name, jid, child, child_name in zip(leg.joint_names, chain, chain[1:], below,
                                            strict=False):
        joint = model.joints[jid]
        angular, linear = _motion_axes(model, jid) if joint.nq == joint.nv == 1 else (None, None)
        if angular is None or linear is None or (angular.any() and linear.any()):
            raise RobotModelError(f"leg {leg.name}: joint {name} is a {joint.shortname()} "
                                  f"({joint.nq} configuration values, {joint.nv} velocities); "
                                  "the leg's inverse kinematics needs 1-DoF revolute or "
                                  "prismatic joints (a URDF continuous joint is not one)")
        if jid not in model.supports[child]:
            raise RobotModelError(f"leg {leg.name}: {child_name} does not hang below joint "
                                  f"{name}; a leg's joints and foot must be one chain")
    q = np.array(reference, dtype=float)
    q[leg.q_index] = 0.0
    data = model.createData()
    pin.framesForwardKinematics(model, data, q)
    frames = [pin.SE3.Identity(), *(data.oMi[j] for j in leg.joint_ids)]
    rel = [frames[i].actInv(frames[i + 1]) for i in range(len(leg.joint_ids))]
    axes = [_motion_axes(model, j) for j in leg.joint_ids]
    n = len(leg.joint_ids)
    at = np.asarray(reference, dtype=float)[leg.q_index]
    out = LegChain(placements=(np.array([m.rotation for m in rel]),
                               np.array([m.translation for m in rel])),
                   angular=np.array([a for a, _ in axes]), linear=np.array([b for _, b in axes]),
                   foot=np.array(data.oMi[leg.joint_ids[-1]].actInv(data.oMf[leg.foot_frame_id])
                                 .translation),
                   reference=at, redundant=np.zeros((n, 0)))
    if leg.name in robot.soles:
        rows, turn = _sole_rows(leg, out, at)
        out = replace(out, redundant=rows, sole=True, turn_rows=turn)
    elif n > 3:
        _, sigma, vt = np.linalg.svd(out.position_jacobian(at[None])[1][0])
        if sigma[-1] < REDUNDANT_SINGULAR * sigma[0]:
            raise RobotModelError(
                f"leg {leg.name}: at the stand pose (joints {np.round(at, 4).tolist()}) the "
                f"foot's Jacobian has singular values {np.round(sigma, 6).tolist()} m/rad — the "
                f"leg is stretched or folded, so its {n - 3} redundant direction(s) are not "
                "defined there; a leg of four or more joints needs a stand with the leg bent "
                "(an SRDF group_state or [robot] stand)")
        out = replace(out, redundant=vt[3:].T.copy())
    rng = np.random.default_rng(0)
    trial = (rng.uniform(-1.5, 1.5, (5, len(leg.joint_ids)))
             * np.where(out.angular.any(axis=1), 1.0, 0.05))
    for q_leg, p in zip(trial, out.frames(trial)[0], strict=True):
        q[leg.q_index] = q_leg
        pin.framesForwardKinematics(model, data, q)
        miss = float(np.linalg.norm(data.oMf[leg.foot_frame_id].translation - p))
        if miss > CHAIN_CHECK_TOL:
            raise RobotModelError(f"leg {leg.name}: the chain read from the model misses "
                                  f"Pinocchio's foot by {miss:.3g} m")
    return out
