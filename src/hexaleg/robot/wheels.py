"""Wheels at the feet, locked: a wheeled leg walks on its wheel as a round foot.

A wheeled-legged robot (ANYmal on wheels, Centauro, a Tiago base) ends some legs in a URDF
``continuous`` joint — a wheel, unbounded, whose angle Pinocchio stores as ``(cos, sin)``. hexaleg
analyses walking: the feet stay put in stance, so a wheel does not turn. Every ``continuous``
joint at a leaf of the tree (no joint below it), and every revolute one there whose URDF gives
no range (``lower = upper = 0``, a wheel written as revolute), is therefore locked at angle 0
when the robot is loaded: the model is reduced with the wheel welded to its parent
(``pinocchio.buildReducedModel``: the wheel's inertia is added to the parent body's and its
frames and geometry are moved onto it; Carpentier et al., "The Pinocchio C++ library", SII
2019), and the note says so. A leg found or listed without a foot then stands on its wheel: a
round foot of the wheel's radius centred on the wheel's axis, touching the ground at its
lowest point in the stand pose (:class:`~hexaleg.robot.feet.SphereFoot`; for a wheel whose axis
is horizontal that is the rim's lowest point, ``c − r ẑ``, the support point of the disc in
−z, Ericson, *Real-Time Collision Detection*, 2005, §3.8).

A wheel turns about its own centre: its body's centre of mass lies on its axis (a tyre, a
hub: Centauro's four ``j_wheel_*`` to 0.0 m). A range-less revolute joint at a leaf whose body's
centre of mass lies off its axis by more than :data:`BALANCE` of its radius is a limb without
limits, not a wheel — example-robot-data's ``quadruped_description`` gives its knees no
``lower``/``upper`` (read as 0, the URDF default) and its shank's centre of mass is 0.103 m off the
knee's axis: locked as a "wheel" of radius 0.185 m (the shank), its stand was then asked of a
one-joint leg. Such a joint stays a joint, its range the URDF's (none), and the stand names it.

A joint a description lists in a leg is the leg's, never locked. Any other joint Pinocchio
cannot treat as one angle — a ``continuous`` joint with joints below it, a ``floating`` or
``planar`` one — is refused by name: hexaleg's joint vectors hold one value
per joint (``q[7:]``), which such a joint breaks.
"""

from __future__ import annotations

from collections.abc import Collection, Sequence
from dataclasses import dataclass

import numpy as np
import pinocchio as pin

from hexaleg.errors import RobotModelError

BALANCE = 0.05
"""The largest distance of a wheel's centre of mass from its axis, as a share of its radius
(module docstring): a range-less revolute joint beyond it is not a wheel."""


@dataclass(frozen=True)
class Wheel:
    """A wheel locked at load.

    Attributes:
        name: The URDF joint that turned it.
        parent: The joint it is welded to (the leg's last joint), by name.
        centre: The wheel's centre (its joint's origin) in the parent joint's frame, m, (3,).
        radius: Its radius: of its cylinder or sphere, or the farthest vertex of a mesh from
            its axis, m; 0 when it carries no geometry.
    """

    name: str
    parent: str
    centre: np.ndarray
    radius: float


def _radius(gmodels: Sequence[pin.GeometryModel], joint: int, axis: np.ndarray) -> float:
    """The largest radius about the wheel's axis (in its joint frame) of the geometry on
    ``joint``: a cylinder's or sphere's radius, a box's or mesh's farthest point from the axis."""
    best = 0.0
    for gmodel in gmodels:
        for obj in gmodel.geometryObjects:
            if obj.parentJoint != joint:
                continue
            shape, kind, m = obj.geometry, type(obj.geometry).__name__, obj.placement
            if kind in ("Cylinder", "Sphere", "Capsule"):
                best = max(best, float(shape.radius))
                continue
            if kind == "Box":
                h = np.asarray(shape.halfSide, dtype=float)
                points = np.array([m.act(np.array([sx, sy, sz]) * h) for sx in (-1, 1)
                                   for sy in (-1, 1) for sz in (-1, 1)])
            elif hasattr(shape, "vertices") and shape.num_vertices:
                points = np.array([m.act(v) for v in np.asarray(shape.vertices(), dtype=float)])
            else:
                continue
            off = points - np.outer(points @ axis, axis)
            best = max(best, float(np.linalg.norm(off, axis=1).max()))
    return best


def _revolute(model: pin.Model, joint: int) -> bool:
    """Whether 1-DoF ``joint`` turns (its motion subspace is a rotation)."""
    data = model.createData()
    pin.computeJointJacobians(model, data, pin.neutral(model))
    s = pin.getJointJacobian(model, data, joint, pin.LOCAL)[:, model.joints[joint].idx_v]
    return bool(np.linalg.norm(s[3:]) > 0 and np.linalg.norm(s[:3]) < 1e-12)


def _axis(model: pin.Model, joint: int) -> np.ndarray:
    """The unit axis of revolute ``joint`` in its own frame."""
    data = model.createData()
    pin.computeJointJacobians(model, data, pin.neutral(model))
    s = pin.getJointJacobian(model, data, joint, pin.LOCAL)[3:, model.joints[joint].idx_v]
    return np.asarray(s / np.linalg.norm(s), dtype=float)


def _balanced(model: pin.Model, geometry: Sequence[pin.GeometryModel], joint: int) -> bool:
    """Whether revolute ``joint``'s body has its centre of mass on its axis, within
    :data:`BALANCE` of its radius (a massless body: no evidence against a wheel)."""
    inertia = model.inertias[joint]
    if not inertia.mass > 0:
        return True
    axis = _axis(model, joint)
    lever = np.asarray(inertia.lever, dtype=float)
    off = float(np.linalg.norm(lever - (lever @ axis) * axis))
    return off <= max(BALANCE * _radius(geometry, joint, axis), 1e-9)


def lock_wheels(model: pin.Model, geometry: Sequence[pin.GeometryModel],
                keep: Collection[str] = ()
                ) -> tuple[pin.Model, list[pin.GeometryModel], tuple[Wheel, ...], str | None]:
    """The model with every wheel locked at 0: a ``continuous`` joint at a leaf of the tree, or
    a revolute one there whose URDF gives it no range (``lower = upper = 0``: a wheel written as
    revolute, as Centauro's "actually continuous" ``j_wheel_*``) and whose body's centre of mass
    is on its axis (:data:`BALANCE`).

    Args:
        model: The model with its free-flyer base (joint 1).
        geometry: Its geometry models (visual, collision), reduced with it.
        keep: Joints not to lock: those a description lists in its legs (a leg's own joint,
            whatever its type; the leg's kinematics then says what it can do with it).

    Returns:
        The model and geometry models (the same objects when there is no wheel), the wheels
        locked, and a note naming them (None when there is none).

    Raises:
        RobotModelError: a joint other than a wheel that is not one angle (a ``continuous``
            joint with joints below it, a ``floating`` or ``planar`` one): names it and what to
            change.
    """
    has_child = {int(model.parents[j]) for j in range(2, model.njoints)}
    wheels: list[int] = []
    for j in range(2, model.njoints):
        joint = model.joints[j]
        if model.names[j] in keep:
            continue
        if joint.nq == joint.nv == 1:
            iq = joint.idx_q
            if (j not in has_child and model.lowerPositionLimit[iq] == 0.0
                    and model.upperPositionLimit[iq] == 0.0 and _revolute(model, j)
                    and _balanced(model, geometry, j)):
                wheels.append(j)  # a wheel written as a revolute joint without a range
            continue
        if joint.nq == 2 and joint.nv == 1 and j not in has_child:
            wheels.append(j)
            continue
        raise RobotModelError(
            f"joint {model.names[j]} is a {joint.shortname()} ({joint.nq} configuration values, "
            f"{joint.nv} velocities) with joints below it; hexaleg takes joints of one angle "
            "(revolute or prismatic) and wheels (a continuous joint at a leaf of the tree, "
            "locked): make it revolute with <limit lower=… upper=…> in the URDF")
    if not wheels:
        return model, list(geometry), (), None
    found = []
    for j in wheels:
        axis = _axis(model, j)
        found.append(Wheel(model.names[j], model.names[int(model.parents[j])],
                           np.array(model.jointPlacements[j].translation, dtype=float),
                           _radius(geometry, j, axis)))
    try:
        reduced, gmodels = pin.buildReducedModel(model, list(geometry), wheels,
                                                 pin.neutral(model))
    except (RuntimeError, ValueError) as e:
        raise RobotModelError(f"locking the wheels {', '.join(w.name for w in found)}: "
                              f"Pinocchio cannot weld them to their parents: {e}; give each "
                              "wheel's link a name no joint has") from None
    names = ", ".join(f"{w.name} (r = {w.radius:.4g} m, on {w.parent})" for w in found)
    note = (f"{len(found)} wheel(s) locked at angle 0, walking as round feet: {names} — a "
            "continuous joint at a leaf of the tree, or a revolute one there without a range "
            "and its centre of mass on its axis, is a wheel; its inertia is carried by the joint "
            "it is welded to")
    return reduced, list(gmodels), tuple(found), note
