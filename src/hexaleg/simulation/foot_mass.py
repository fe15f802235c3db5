"""The mass a foot's ground contact moves: the foot point's operational-space inertia.

A contact pushes on the foot point. Per newton along the contact's directions (world x, y and
the ground's normal z) the foot point accelerates by the contact-space inverse inertia

    A = J M(q)⁻¹ Jᵀ        (3 × 3; J the foot point's translation Jacobian, 3 × nv),

the operational-space inertia's inverse Λ⁻¹ (Khatib, "A unified approach for motion and force
control of robot manipulators: the operational space formulation", IEEE J. Robotics and
Automation, 1987; Featherstone, *Rigid Body Dynamics Algorithms*, 2008, §11, the contact-space
inverse inertia ``J H⁻¹ Jᵀ``). A foot whose friction holds it (MuJoCo's elliptic cone with
``impratio`` 10⁴: friction rows a ten-thousandth as soft as the normal one,
:mod:`~hexaleg.simulation.ground`) cannot slide, and its normal row moves with the Schur
complement of the tangential block, ``A_zz − A_zt A_tt⁻¹ A_tz = 1 / (A⁻¹)_zz``: the normal
contact moves the mass

    m = (A⁻¹)_zz = Λ_zz        (:func:`held_masses`),

more than ``1 / A_zz`` (:func:`sliding_masses`: the foot free to slide, its lever about the knee
turning the leg), and unlike MuJoCo's ``body_invweight0`` (the foot *body*'s mean inverse
weight at the model's reference pose, which sizes the contact's ``solref``) it depends on where
the foot point is: HyQ's foot at the end of its 0.35-m shank moves 0.83 kg held and 0.34 kg
sliding, on a 2-kg shank body. More contacts held at once can only add mass (a Schur
complement over more rows), so a foot's own ``Λ_zz`` bounds it from below.
"""

from __future__ import annotations

import numpy as np
import pinocchio as pin

from hexaleg.robot.model import Robot


def _jacobians(robot: Robot, q: np.ndarray, corners: bool
               ) -> tuple[list[str], np.ndarray, np.ndarray]:
    """The contact points' names, translation Jacobians (world axes, shape (k, 3, nv)) and
    ``M⁻¹`` (nv, nv) at ``q``: each leg's foot point, or with ``corners`` each corner of a
    leg's sole, ``J_v − [R_f c]× J_ω`` (the sole's corner ``c`` in the foot frame)."""
    model = robot.model
    data = model.createData()
    pin.computeJointJacobians(model, data, q)
    pin.updateFramePlacements(model, data)
    minv = pin.computeMinverse(model, model.createData(), q)
    minv = np.triu(minv) + np.triu(minv, 1).T  # Pinocchio fills the upper triangle
    names, jacs = [], []
    for leg in robot.legs:
        full = pin.getFrameJacobian(model, data, leg.foot_frame_id, pin.LOCAL_WORLD_ALIGNED)
        sole = robot.soles.get(leg.name) if corners else None
        if sole is None:
            names.append(f"{leg.name}'s foot")
            jacs.append(full[:3])
            continue
        for j, lever in enumerate(sole.corners() @ data.oMf[leg.foot_frame_id].rotation.T):
            skew = np.array([[0.0, -lever[2], lever[1]], [lever[2], 0.0, -lever[0]],
                             [-lever[1], lever[0], 0.0]])
            names.append(f"{leg.name}'s sole corner {j}")
            jacs.append(full[:3] - skew @ full[3:])
    return names, np.stack(jacs), minv


def contact_inverse_inertia(robot: Robot, q: np.ndarray) -> np.ndarray:
    """Each foot point's contact-space inverse inertia ``J M⁻¹ Jᵀ`` at configuration ``q``
    (nq,), world axes, shape (n_legs, 3, 3), 1/kg (module docstring)."""
    _, jac, minv = _jacobians(robot, q, corners=False)
    return np.asarray(jac @ minv @ jac.transpose(0, 2, 1))


def point_sliding_masses(robot: Robot, q: np.ndarray) -> tuple[list[str], np.ndarray]:
    """Each ground contact point's mass along the normal, free to slide, ``1 / (J M⁻¹ Jᵀ)_zz``
    (kg): a point foot's foot point, a sole's every corner (where MuJoCo puts its contact
    spheres), with their names. Unitree G1's toe corner moves 0.124 kg on a 0.61-kg foot that
    turns about its ankle."""
    names, jac, minv = _jacobians(robot, q, corners=True)
    rows = jac[:, 2]
    return names, 1.0 / np.einsum("ki,ij,kj->k", rows, minv, rows)


def held_masses(robot: Robot, q: np.ndarray) -> np.ndarray:
    """The mass each foot point's normal contact moves while its friction holds it,
    ``Λ_zz = ((J M⁻¹ Jᵀ)⁻¹)_zz``, kg, shape (n_legs,) (module docstring). ``J M⁻¹ Jᵀ`` is
    invertible on a free-flying robot: the base's translation alone moves the point along
    every axis."""
    return np.linalg.inv(contact_inverse_inertia(robot, q))[:, 2, 2]


def sliding_masses(robot: Robot, q: np.ndarray) -> np.ndarray:
    """The mass each foot point moves along the normal when it is free to slide,
    ``1 / (J M⁻¹ Jᵀ)_zz``, kg, shape (n_legs,) (module docstring)."""
    return 1.0 / contact_inverse_inertia(robot, q)[:, 2, 2]
