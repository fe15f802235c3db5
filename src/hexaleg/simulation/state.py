"""Pinocchio ↔ MuJoCo: configurations, velocities, accelerations and forces of the same robot.

The two programs order the joints alike (the MJCF is written in Pinocchio's joint order,
:mod:`hexaleg.simulation.mjcf`) but differ in the free flyer and in continuous joints:

============  ==================================  ==================================
quantity      Pinocchio (hexaleg's convention)     MuJoCo
============  ==================================  ==================================
base quat     (x, y, z, w)                         (w, x, y, z)
base linear   velocity v_b in the base frame       velocity in the world frame, R v_b
velocity
base angular  ω_b in the base frame                ω_b in the base frame
velocity
acceleration  a = d(v_b, ω_b)/dt                    qacc = d(qvel)/dt: linear part
                                                   R (a_lin + ω_b × v_b)
generalised   f_b in the base frame                R f_b (the dual of the velocity map)
base force
continuous    (cos θ, sin θ)                       θ
joint q
============  ==================================  ==================================

(MuJoCo's free joint: Todorov, MuJoCo documentation, "Computation → Free joint"; Pinocchio's
free flyer: Carpentier et al., "The Pinocchio C++ library", SII 2019.) Joint columns are always
returned in hexaleg's joint order (``robot.joint_names``). Arrays may carry leading sample axes.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from hexaleg.errors import RobotModelError
from hexaleg.motion.recorded.base import rotation_from_quaternion
from hexaleg.robot.model import Robot


@dataclass(frozen=True, eq=False)
class JointMap:
    """Where each actuated joint lives in Pinocchio's and MuJoCo's vectors.

    Attributes:
        joint_names: hexaleg's joint order (``robot.joint_names``), nj names.
        pin_q: Pinocchio ``idx_q`` of each joint, shape (nj,).
        pin_v: Pinocchio ``idx_v`` of each joint, shape (nj,).
        continuous: Whether the joint is continuous (Pinocchio stores cos, sin), shape (nj,).
        qpos: MuJoCo ``qpos`` address of each joint, shape (nj,).
        dof: MuJoCo ``qvel`` address of each joint, shape (nj,).
        nq: Pinocchio nq. nv: Pinocchio nv (= MuJoCo nv). nq_mj: MuJoCo nq.
    """

    joint_names: tuple[str, ...]
    pin_q: np.ndarray
    pin_v: np.ndarray
    continuous: np.ndarray
    qpos: np.ndarray
    dof: np.ndarray
    nq: int
    nv: int
    nq_mj: int

    @classmethod
    def build(cls, robot: Robot, model: object) -> JointMap:
        """The map of ``robot`` and its compiled MuJoCo model.

        Args:
            robot: The robot.
            model: Its ``mujoco.MjModel`` (joints named as in the robot).

        Raises:
            RobotModelError: a joint of the robot is missing from the MuJoCo model, or the base is
                not a free joint at qpos 0.
        """
        import mujoco

        m = model
        assert isinstance(m, mujoco.MjModel)
        pm = robot.model
        qpos, dof = [], []
        for name in robot.joint_names:
            jid = mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_JOINT, name)
            if jid < 0:
                raise RobotModelError(f"joint {name} of {robot.name} is not in the MuJoCo model")
            qpos.append(int(m.jnt_qposadr[jid]))
            dof.append(int(m.jnt_dofadr[jid]))
        if m.jnt_type[0] != mujoco.mjtJoint.mjJNT_FREE or m.jnt_qposadr[0] != 0:
            raise RobotModelError("the MuJoCo model's first joint must be the base's free joint")
        ids = [pm.getJointId(n) for n in robot.joint_names]
        return cls(joint_names=robot.joint_names,
                   pin_q=np.array([pm.joints[i].idx_q for i in ids]),
                   pin_v=np.array([pm.joints[i].idx_v for i in ids]),
                   continuous=np.array([pm.joints[i].nq == 2 for i in ids]),
                   qpos=np.array(qpos), dof=np.array(dof), nq=pm.nq, nv=pm.nv, nq_mj=m.nq)

    def joint_angles(self, q: np.ndarray) -> np.ndarray:
        """Joint angles (…, nj), rad (or m), from Pinocchio configurations (…, nq)."""
        q = np.asarray(q, dtype=float)
        out = q[..., self.pin_q]
        c = self.continuous
        if c.any():
            out[..., c] = np.arctan2(q[..., self.pin_q[c] + 1], q[..., self.pin_q[c]])
        return out

    def to_mujoco(self, q: np.ndarray, v: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """MuJoCo ``(qpos (…, nq_mj), qvel (…, nv))`` of Pinocchio ``q (…, nq)``, ``v (…, nv)``."""
        q, v = np.asarray(q, dtype=float), np.asarray(v, dtype=float)
        qpos = np.zeros((*q.shape[:-1], self.nq_mj))
        qpos[..., :3] = q[..., :3]
        qpos[..., 3] = q[..., 6]
        qpos[..., 4:7] = q[..., 3:6]
        qpos[..., self.qpos] = self.joint_angles(q)
        qvel = np.zeros_like(v)
        rot = rotation_from_quaternion(q[..., 3:7])
        qvel[..., :3] = np.einsum("...ij,...j->...i", rot, v[..., :3])
        qvel[..., 3:6] = v[..., 3:6]
        qvel[..., self.dof] = v[..., self.pin_v]
        return qpos, qvel

    def to_pinocchio(self, qpos: np.ndarray, qvel: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Pinocchio ``(q (…, nq), v (…, nv))`` of MuJoCo ``qpos``, ``qvel`` (inverse of
        :meth:`to_mujoco`; the quaternion is normalised)."""
        qpos, qvel = np.asarray(qpos, dtype=float), np.asarray(qvel, dtype=float)
        q = np.zeros((*qpos.shape[:-1], self.nq))
        q[..., :3] = qpos[..., :3]
        quat = np.concatenate([qpos[..., 4:7], qpos[..., 3:4]], axis=-1)
        quat = quat / np.linalg.norm(quat, axis=-1, keepdims=True)
        q[..., 3:7] = quat
        angles = qpos[..., self.qpos]
        c = self.continuous
        q[..., self.pin_q[~c]] = angles[..., ~c]
        if c.any():
            q[..., self.pin_q[c]] = np.cos(angles[..., c])
            q[..., self.pin_q[c] + 1] = np.sin(angles[..., c])
        v = np.zeros_like(qvel)
        rot = rotation_from_quaternion(quat)
        v[..., :3] = np.einsum("...ji,...j->...i", rot, qvel[..., :3])
        v[..., 3:6] = qvel[..., 3:6]
        v[..., self.pin_v] = qvel[..., self.dof]
        return q, v

    def acceleration_to_mujoco(self, q: np.ndarray, v: np.ndarray, a: np.ndarray) -> np.ndarray:
        """MuJoCo ``qacc`` (…, nv) of Pinocchio ``a = dv/dt`` at ``q``, ``v``:
        ``d(R v_b)/dt = R (a_lin + ω_b × v_b)`` for the base, the joints unchanged."""
        q, v, a = (np.asarray(x, dtype=float) for x in (q, v, a))
        out = np.zeros_like(a)
        rot = rotation_from_quaternion(q[..., 3:7])
        out[..., :3] = np.einsum("...ij,...j->...i", rot,
                                 a[..., :3] + np.cross(v[..., 3:6], v[..., :3]))
        out[..., 3:6] = a[..., 3:6]
        out[..., self.dof] = a[..., self.pin_v]
        return out

    def force_to_mujoco(self, q: np.ndarray, tau: np.ndarray) -> np.ndarray:
        """MuJoCo generalised force (…, nv) of a Pinocchio one (…, nv) at ``q``: the base force
        rotated into the world frame (``τ·v`` is the same power in both)."""
        q, tau = np.asarray(q, dtype=float), np.asarray(tau, dtype=float)
        out = np.zeros_like(tau)
        rot = rotation_from_quaternion(q[..., 3:7])
        out[..., :3] = np.einsum("...ij,...j->...i", rot, tau[..., :3])
        out[..., 3:6] = tau[..., 3:6]
        out[..., self.dof] = tau[..., self.pin_v]
        return out

    def joints_mj(self, x: np.ndarray, velocity: bool = False) -> np.ndarray:
        """The joint columns (…, nj) of a MuJoCo ``qpos`` (``velocity=False``) or ``qvel`` /
        generalised force (``velocity=True``), in hexaleg's joint order."""
        return np.asarray(x)[..., self.dof if velocity else self.qpos]
