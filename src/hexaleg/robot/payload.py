"""A robot carrying extra mass: a payload on the body, or the springs fitted at its joints.

The extra masses are point masses added to the Pinocchio model's link inertias (spatial inertia
is additive: ``pinocchio.Inertia`` sums mass, centre of mass and rotational inertia with the
parallel-axis theorem), so RNEA, the total mass and every energy metric see them; the
kinematics — and so a gait's joint motion — are unchanged. The robot given is not modified.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np
import pinocchio as pin

from hexaleg.checks import finite_array, real
from hexaleg.errors import InvalidParameterError
from hexaleg.robot.model import Robot

BASE_JOINT = 1
"""Pinocchio joint index of the free-flyer base (0 is the universe)."""


def with_point_masses(robot: Robot, masses: Mapping[str, float], note: str = "") -> Robot:
    """``robot`` with point masses at joint origins (e.g. the springs coaxial with them).

    Args:
        robot: The robot (not modified).
        masses: Joint name → mass, kg, ≥ 0, placed at that joint's origin on its child link
            (a point on the joint axis, fixed in both links it joins).
        note: Appended to the robot's notes (empty: none).

    Returns:
        A copy with the masses added; ``mass`` includes them.

    Raises:
        UnknownNameError: a joint the robot does not have (lists them).
        InvalidParameterError: a mass that is not a finite number ≥ 0.
    """
    model = pin.Model(robot.model)
    for joint, m in masses.items():
        robot.column(joint)  # UnknownNameError listing the joints
        m = real(f"mass at {joint}", m, low=0.0, allowed="a finite mass >= 0 kg")
        jid = model.getJointId(joint)
        model.inertias[jid] = model.inertias[jid] + pin.Inertia(m, np.zeros(3), np.zeros((3, 3)))
    return _copy(robot, model, note)


def with_payload(robot: Robot, mass: float, position: np.ndarray | None = None,
                 note: str = "", inertia: np.ndarray | None = None) -> Robot:
    """``robot`` carrying a payload rigidly on its body: a point mass, or a rigid body with
    ``inertia`` about its centre of mass (:class:`Payload` checks one from a config).

    Args:
        robot: The robot (not modified).
        mass: Payload, kg, ≥ 0.
        position: Where on the body (its centre of mass), base frame, shape (3,), m; default
            the base origin.
        note: Appended to the robot's notes.
        inertia: Its rotational inertia about its centre of mass, base-frame axes, (3, 3),
            kg·m²; default zero (a point mass).

    Returns:
        A copy with the payload; ``mass`` includes it.

    Raises:
        InvalidParameterError: a mass that is not a finite number ≥ 0.
    """
    mass = real("payload mass", mass, low=0.0, allowed="a finite mass >= 0 kg")
    model = pin.Model(robot.model)
    c = np.zeros(3) if position is None else np.asarray(position, dtype=float).reshape(3)
    rot = np.zeros((3, 3)) if inertia is None else np.asarray(inertia, dtype=float)
    model.inertias[BASE_JOINT] = model.inertias[BASE_JOINT] + pin.Inertia(mass, c, rot)
    return _copy(robot, model, note)


def _copy(robot: Robot, model: pin.Model, note: str) -> Robot:
    notes = (*robot.notes, note) if note else robot.notes
    return dataclasses.replace(robot, model=model, data=model.createData(), notes=notes,
                               poses={k: v.copy() for k, v in robot.poses.items()})


@dataclass(frozen=True)
class Payload:
    """A payload carried rigidly on the base (a report config's ``[payload]`` table): a point
    mass (``inertia`` zero) or a rigid body.

    Its spatial inertia is added to the base link's (:func:`with_payload`), so the dynamics,
    the force program (``Σ f = (m + m_p)(a_com − g)``), the balance of two-foot gaits, the body
    shift of crawls, the energy metrics and the spring design all carry it.

    Attributes:
        mass: m_p, kg (≥ 0).
        com: Its centre of mass in the base frame, (x, y, z), m.
        inertia: Its rotational inertia about its centre of mass, base-frame axes, rows of a
            symmetric 3 × 3 matrix, kg·m²: positive semi-definite, its principal moments
            obeying the triangle inequality ``I₁ + I₂ ≥ I₃`` (a physical rigid body; Traversaro
            et al., "Identification of fully physical consistent inertial parameters", IROS
            2016); default zero, a point mass.
    """

    mass: float = 0.0
    com: tuple[float, ...] = (0.0, 0.0, 0.0)
    inertia: tuple[tuple[float, ...], ...] = ((0.0, 0.0, 0.0),) * 3

    def __post_init__(self) -> None:
        real("payload mass", self.mass, low=0.0, allowed="a finite mass >= 0 kg")
        com = finite_array("payload com", self.com, (3,), "x, y, z in the base frame, m")
        inertia = finite_array("payload inertia", self.inertia, (3, 3),
                               "rows of a 3 × 3 matrix, kg·m²")
        scale = max(1e-12, float(np.abs(inertia).max()))
        if np.abs(inertia - inertia.T).max() > 1e-9 * scale:
            raise InvalidParameterError("payload inertia", inertia.tolist(),
                                        "a symmetric matrix (kg·m² about its centre of mass)")
        moments = np.linalg.eigvalsh(inertia)
        if moments[0] < -1e-9 * scale or moments[0] + moments[1] < moments[2] - 1e-9 * scale:
            raise InvalidParameterError(
                "payload inertia", inertia.tolist(), f"principal moments ≥ 0 with I₁ + I₂ ≥ "
                f"I₃ (a physical rigid body; these are {np.round(moments, 9).tolist()})")
        object.__setattr__(self, "com", tuple(com.tolist()))
        object.__setattr__(self, "inertia", tuple(tuple(row) for row in inertia.tolist()))

    def attach(self, robot: Robot) -> Robot:
        """``robot`` carrying this payload (:func:`with_payload`; a note says so)."""
        point = not np.any(self.inertia)
        note = (f"payload {self.mass:g} kg at {list(self.com)} m (base frame)"
                + (", a point mass" if point else ", a rigid body"))
        return with_payload(robot, self.mass, np.array(self.com), note,
                            inertia=np.array(self.inertia))
