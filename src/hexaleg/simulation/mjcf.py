"""The robot's kinematic tree as MJCF, from its Pinocchio model (the URDF as hexaleg loaded it).

MuJoCo can read a URDF itself, but hexaleg's :class:`~hexaleg.robot.model.Robot` is already the URDF
as the analysis sees it: fixed links merged into their parent joints, meshes that were missing
replaced, feet found. Writing the MJCF from that model makes the simulated robot the analysed one
by construction:

* one ``<body>`` per Pinocchio joint, in Pinocchio's depth-first order, placed at
  ``model.jointPlacements[i]``, with the inertia ``model.inertias[i]`` (mass, centre of mass,
  rotational inertia about the centre of mass, in the joint frame) and the joint's rotor inertia
  ``model.armature`` as MuJoCo armature;
* the free flyer as ``<freejoint>``; a 1-DoF joint as a ``hinge`` (revolute, continuous) or
  ``slide`` (prismatic) about the axis of its motion subspace ``S`` (the joint Jacobian column in
  the joint frame at the neutral configuration: the angular part for a revolute joint, the linear
  part for a prismatic one); joint limits are not enforced (the analysis does not either);
* the collision geometry: boxes, spheres and cylinders as such, a mesh as the box of its local
  bounding box (a stand-in, noted); the geometry of the foot links is left out — the foot is a
  contact sphere centred on the foot frame (:mod:`hexaleg.simulation.model`);
* a ``<site>`` at every foot frame (foot positions are read there);
* a sole (:mod:`hexaleg.robot.soles`) as four contact spheres and sites at its corners instead
  of the one at its centre: the exact contact of a rectangle on a plane (the sum of its corner
  forces, each in its friction cone: Caron et al., ICRA 2015), in the point contacts the
  ground already models;
* before any of it is compiled, what MuJoCo's compiler refuses (:func:`check_inertias`,
  :func:`check_size`) as a :class:`~hexaleg.errors.RobotModelError` naming the link and value.

The tree's shape (which joints exist, in which order) is the same in both programs, and
:mod:`hexaleg.simulation.state` maps the vectors between them by joint name.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass
from xml.sax.saxutils import quoteattr

import numpy as np
import pinocchio as pin

from hexaleg.errors import RobotModelError
from hexaleg.robot.model import Robot

FREE_JOINT = "root"
"""Name of the MuJoCo free joint of the base."""
GEOM_CLASS = "robot"
"""MJCF default class of the robot's collision geoms (no automatic contacts: ground pairs only)."""
FOOT_CLASS = "foot"
"""MJCF default class of the foot contact spheres."""


def fmt(x: object) -> str:
    """Numbers as an MJCF attribute value: full precision (``repr``), space separated."""
    return " ".join(map(repr, np.asarray(x, dtype=float).ravel().tolist()))


def wxyz(rotation: np.ndarray) -> str:
    """A rotation matrix (3, 3) as an MJCF ``quat`` (w x y z)."""
    q = pin.Quaternion(np.asarray(rotation, dtype=float))
    return fmt([q.w, q.x, q.y, q.z])


def foot_geom(leg: str) -> str:
    """Name of a leg's foot contact sphere."""
    return f"{leg}_foot_contact"


def foot_site(leg: str) -> str:
    """Name of the site at a leg's foot frame."""
    return f"{leg}_foot"


def corner_geom(leg: str, corner: int) -> str:
    """Name of the contact sphere at corner ``corner`` (0–3, :meth:`Sole.corners
    <hexaleg.robot.soles.Sole.corners>`' order) of a leg's sole."""
    return f"{leg}_sole{corner}_foot_contact"


def corner_site(leg: str, corner: int) -> str:
    """Name of the site at corner ``corner`` of a leg's sole."""
    return f"{leg}_sole{corner}"


def contact_sites(robot: Robot) -> list[str]:
    """The sites of the robot's contact points, legs in robot order: a point foot's foot site,
    a sole's four corner sites."""
    return [name for leg in robot.legs for name in (
        [corner_site(leg.name, j) for j in range(4)] if leg.name in robot.soles
        else [foot_site(leg.name)])]


def contact_geoms(robot: Robot) -> list[list[str]]:
    """Per leg in robot order, the names of its foot's contact spheres: one for a point foot,
    four for a sole (its corners)."""
    return [[corner_geom(leg.name, j) for j in range(4)] if leg.name in robot.soles
            else [foot_geom(leg.name)] for leg in robot.legs]


@dataclass(frozen=True)
class TreeXml:
    """The robot's ``<body>`` tree and what it contains.

    Attributes:
        xml: The MJCF of the base body and its descendants (to go in ``<worldbody>``).
        geoms: Names of the robot's collision geoms (foot spheres excluded), in XML order.
        notes: What was replaced or approximated (a mesh as its bounding box).
    """

    xml: str
    geoms: tuple[str, ...]
    notes: tuple[str, ...]


def motion_axis(robot: Robot, joint: int, data: pin.Data | None = None
                ) -> tuple[str, np.ndarray]:
    """The MJCF joint type and axis of a 1-DoF Pinocchio joint.

    Args:
        robot: The robot.
        joint: Pinocchio joint id (≥ 2).
        data: The robot's Pinocchio data with the joint Jacobians at the neutral configuration
            (``pin.computeJointJacobians``; one for every joint of a tree), or None: computed.

    Returns:
        ``("hinge" | "slide", axis (3,))``, the axis a unit vector in the joint frame.

    Raises:
        RobotModelError: the joint is neither a revolute nor a prismatic 1-DoF joint.
    """
    model = robot.model
    jm = model.joints[joint]
    if jm.nv != 1:
        raise RobotModelError(f"joint {model.names[joint]} has {jm.nv} degrees of freedom; the "
                              "simulation takes 1-DoF revolute or prismatic joints")
    if data is None:
        data = model.createData()
        pin.computeJointJacobians(model, data, pin.neutral(model))
    s = pin.getJointJacobian(model, data, joint, pin.ReferenceFrame.LOCAL)[:, jm.idx_v]
    lin, ang = s[:3], s[3:]
    if np.linalg.norm(ang) > 0.5 and np.linalg.norm(lin) < 1e-9:
        return "hinge", ang / np.linalg.norm(ang)
    if np.linalg.norm(lin) > 0.5 and np.linalg.norm(ang) < 1e-9:
        return "slide", lin / np.linalg.norm(lin)
    raise RobotModelError(f"joint {model.names[joint]} ({jm.shortname()}) is neither revolute "
                          "nor prismatic; the simulation cannot build it")


def _shape(obj: pin.GeometryObject) -> tuple[str, np.ndarray, np.ndarray, np.ndarray, str]:
    """(MJCF type, size, position, rotation, note) of a collision object in its joint frame."""
    g, placement = obj.geometry, obj.placement
    kind = type(g).__name__
    pos, rot = placement.translation.copy(), placement.rotation.copy()
    if kind == "Box":
        return "box", np.asarray(g.halfSide), pos, rot, ""
    if kind == "Sphere":
        return "sphere", np.array([g.radius]), pos, rot, ""
    if kind == "Cylinder":
        return "cylinder", np.array([g.radius, g.halfLength]), pos, rot, ""
    if kind == "Capsule":
        return "capsule", np.array([g.radius, g.halfLength]), pos, rot, ""
    g.computeLocalAABB()
    lo, hi = np.asarray(g.aabb_local.min_), np.asarray(g.aabb_local.max_)
    return ("box", np.maximum((hi - lo) / 2, 1e-6), pos + rot @ ((hi + lo) / 2), rot,
            f"{obj.name}: {kind} collision shape simulated as its bounding box")


def _feet_links(robot: Robot) -> set[int]:
    """Frame ids of the foot frames and of the links they are (geometry there is the foot's)."""
    model = robot.model
    feet = {leg.foot_frame_id for leg in robot.legs}
    names = {model.frames[f].name for f in feet}
    return feet | {i for i, f in enumerate(model.frames) if f.name in names}


MJ_MINVAL = 1e-15
"""MuJoCo's ``mjMINVAL``: the mass of a moving body must be larger (compiler check)."""
MJ_EPS = 1e-14
"""kg·m²: MuJoCo's ``mjEPS``, the absolute tolerance of its triangle inequality
``A + B ≥ C − mjEPS`` (measured on MuJoCo 4.0: ``1 1 2`` compiles, ``1 1 2.0000000000001``
does not)."""


def check_inertias(robot: Robot) -> None:
    """What MuJoCo's compiler refuses of a body's inertia, checked before compiling.

    MuJoCo requires of every moving body a mass > ``mjMINVAL`` (:data:`MJ_MINVAL`), a
    ``fullinertia`` with positive eigenvalues, and principal moments with ``A + B ≥ C − mjEPS``
    (:data:`MJ_EPS`; MuJoCo documentation, XML reference, ``inertial`` and ``balanceinertia``).
    The bodies are Pinocchio's (links fixed to a joint merged), as :func:`tree_xml` writes them.

    Raises:
        RobotModelError: names the body, its mass or principal moments and what MuJoCo allows.
    """
    from hexaleg.robot.sanity import body_name, principal_moments

    model = robot.model
    for jid in range(1, model.njoints):
        mass = float(model.inertias[jid].mass)
        moments = principal_moments(model, jid)
        text = ", ".join(f"{m:.6g}" for m in moments)
        problem = ""
        if not mass > MJ_MINVAL:
            problem = f"mass {mass:.4g} kg (allowed: > {MJ_MINVAL:g} kg)"
        elif not moments[0] > 0:
            problem = f"principal moments {text} kg·m² (allowed: all > 0 kg·m²)"
        elif moments[0] + moments[1] < moments[2] - MJ_EPS:
            problem = (f"principal moments {text} kg·m², I1 + I2 < I3 (allowed: I1 + I2 ≥ I3 − "
                       f"{MJ_EPS:g} kg·m², the triangle inequality)")
        if problem:
            raise RobotModelError(
                f"{robot.name}: MuJoCo cannot simulate {body_name(model, jid)}: {problem}; fix "
                "the URDF <inertial> of its link(s), or load with load_robot(..., "
                "inertias=\"repair\") (hexaleg.robot.inertials)")


def check_size(robot: Robot, obj: pin.GeometryObject, kind: str, size: np.ndarray) -> None:
    """A geom's MJCF ``size`` as MuJoCo's compiler requires it, checked before compiling.

    MuJoCo refuses a sphere, capsule, cylinder or box with a size that is not positive
    (compiler: "size … must be positive in geom"; MuJoCo documentation, XML reference,
    ``geom/size``); a URDF ``<sphere radius="0"/>`` or ``<box size="0.1 0 0.1"/>`` loads in
    Pinocchio. ``size`` is :func:`_shape`'s (half-sizes and radii, m).

    Raises:
        RobotModelError: names the geometry, its link, the size and what MuJoCo allows.
    """
    if np.all(size > 0):
        return
    link = robot.model.frames[obj.parentFrame].name
    raise RobotModelError(
        f"{robot.name}: MuJoCo cannot simulate collision geometry {obj.name} of link {link}: "
        f"{kind} size {fmt(size)} m (MJCF half-sizes and radii; allowed: all > 0 m); give the "
        "URDF <collision> a positive size, or remove it")


def tree_xml(robot: Robot, foot_radius: float) -> TreeXml:
    """The MJCF ``<body>`` tree of ``robot`` (module docstring).

    Args:
        robot: The robot.
        foot_radius: Radius of the foot contact spheres, m.

    Returns:
        The tree, its collision geom names and notes.

    Raises:
        RobotModelError: a joint that is not a free flyer at the root or a 1-DoF joint below, an
            inertia MuJoCo refuses (:func:`check_inertias`) or a geom size it refuses
            (:func:`check_size`).
    """
    model = robot.model
    check_inertias(robot)
    if model.joints[1].shortname() != "JointModelFreeFlyer":
        raise RobotModelError(f"{robot.name}: the simulation needs a free-flyer base joint, "
                              f"found {model.joints[1].shortname()}")
    children: dict[int, list[int]] = {i: [] for i in range(model.njoints)}
    for i in range(2, model.njoints):
        children[model.parents[i]].append(i)
    feet = _feet_links(robot)
    neutral = model.createData()
    pin.computeJointJacobians(model, neutral, pin.neutral(model))
    geoms: list[str] = []
    notes: list[str] = []
    by_joint: dict[int, list[pin.GeometryObject]] = {}
    for obj in robot.collision_model.geometryObjects:
        if obj.parentFrame not in feet:
            by_joint.setdefault(obj.parentJoint, []).append(obj)

    def body(i: int) -> Iterator[str]:
        placement, inertia = model.jointPlacements[i], model.inertias[i]
        c = inertia.inertia
        yield (f'<body name={quoteattr(model.names[i])} pos="{fmt(placement.translation)}" '
               f'quat="{wxyz(placement.rotation)}">')
        yield (f'<inertial pos="{fmt(inertia.lever)}" mass="{fmt(inertia.mass)}" fullinertia="'
               f'{fmt([c[0, 0], c[1, 1], c[2, 2], c[0, 1], c[0, 2], c[1, 2]])}"/>')
        if i == 1:
            yield f'<freejoint name="{FREE_JOINT}"/>'
        else:
            kind, axis = motion_axis(robot, i, neutral)
            armature = float(model.armature[model.joints[i].idx_v])
            yield (f'<joint name={quoteattr(model.names[i])} type="{kind}" axis="{fmt(axis)}" '
                   f'limited="false" armature="{fmt(armature)}"/>')
        for obj in by_joint.get(i, []):
            kind, size, pos, rot, note = _shape(obj)
            check_size(robot, obj, kind, size)
            geoms.append(obj.name)
            if note:
                notes.append(note)
            yield (f'<geom name={quoteattr(obj.name)} class="{GEOM_CLASS}" type="{kind}" '
                   f'size="{fmt(size)}" pos="{fmt(pos)}" quat="{wxyz(rot)}"/>')
        for leg in robot.legs:
            frame = model.frames[leg.foot_frame_id]
            if frame.parentJoint == i:
                p = frame.placement.translation
                yield f'<site name="{foot_site(leg.name)}" pos="{fmt(p)}"/>'
                sole = robot.soles.get(leg.name)
                if sole is None:
                    yield (f'<geom name="{foot_geom(leg.name)}" class="{FOOT_CLASS}" '
                           f'type="sphere" size="{fmt(foot_radius)}" pos="{fmt(p)}"/>')
                    continue
                for j, c in enumerate(sole.corners()):
                    at = p + frame.placement.rotation @ c
                    yield f'<site name="{corner_site(leg.name, j)}" pos="{fmt(at)}"/>'
                    yield (f'<geom name="{corner_geom(leg.name, j)}" class="{FOOT_CLASS}" '
                           f'type="sphere" size="{fmt(foot_radius)}" pos="{fmt(at)}"/>')
        for child in children[i]:
            yield from body(child)
        yield "</body>"

    xml = "\n".join(body(1))
    return TreeXml(xml=xml, geoms=tuple(geoms), notes=tuple(notes))
