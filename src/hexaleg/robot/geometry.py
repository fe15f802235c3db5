"""Geometry of a robot's shapes at a configuration: self-collisions, extent, lowest points.

Exact for the primitive shapes (box, sphere, cylinder) of the built-in robot; the support-point
formulas are those of convex-geometry collision detection (e.g. Ericson, *Real-Time Collision
Detection*, 2005, §3.8: support mappings of spheres, boxes and cylinders). :class:`Robot
<hexaleg.robot.model.Robot>` exposes them as methods.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
import pinocchio as pin

from hexaleg.errors import UnknownNameError


def self_collisions(model: pin.Model, data: pin.Data, collision_model: pin.GeometryModel,
                    q: np.ndarray) -> list[tuple[str, str]]:
    """Pairs of links whose collision geometries intersect at ``q`` (SRDF pairs excluded).

    Args:
        model: The robot's Pinocchio model.
        data: A Pinocchio data of ``model`` (overwritten).
        collision_model: Its collision geometry, with the SRDF's disabled pairs removed.
        q: Configuration, shape (nq,).

    Returns:
        Sorted list of (link, link) name pairs in collision; empty when collision-free.
    """
    gdata = pin.GeometryData(collision_model)
    pin.computeCollisions(model, data, collision_model, gdata,
                          np.asarray(q, dtype=float), False)
    hits = []
    for k, pair in enumerate(collision_model.collisionPairs):
        if gdata.collisionResults[k].isCollision():
            a = collision_model.geometryObjects[pair.first]
            b = collision_model.geometryObjects[pair.second]
            names = sorted((model.frames[a.parentFrame].name,
                            model.frames[b.parentFrame].name))
            hits.append((names[0], names[1]))
    return sorted(set(hits))


def max_extent(model: pin.Model, data: pin.Data, gmodel: pin.GeometryModel,
               q: np.ndarray) -> float:
    """Largest distance of any geometry point from the base origin at ``q``, m.

    Exact for the primitive shapes the built-in robot uses: a box's farthest point is a
    corner; a sphere's is at ``|c| + r``; a cylinder's lies on a rim circle, at
    ``sqrt(|p|² + r² + 2 r |p⊥|)`` for rim centre ``p`` (``p⊥`` its part normal to the axis).

    Args:
        model: The robot's Pinocchio model.
        data: A Pinocchio data of ``model`` (overwritten).
        gmodel: The visual or collision geometry model.
        q: Configuration, shape (nq,).

    Raises:
        UnknownNameError: a shape is not a box, sphere or cylinder.
    """
    gdata = pin.GeometryData(gmodel)
    pin.updateGeometryPlacements(model, data, gmodel, gdata,
                                 np.asarray(q, dtype=float))
    base = data.oMi[1]
    extent = 0.0
    for k, obj in enumerate(gmodel.geometryObjects):
        placement = base.actInv(gdata.oMg[k])  # geometry frame in the base frame
        shape, kind = obj.geometry, type(obj.geometry).__name__
        c, rot = placement.translation, placement.rotation
        if kind == "Sphere":
            d = float(np.linalg.norm(c) + shape.radius)
        elif kind == "Box":
            signs = np.array(np.meshgrid([-1, 1], [-1, 1], [-1, 1])).reshape(3, -1).T
            d = float(np.max(np.linalg.norm(c + (signs * shape.halfSide) @ rot.T, axis=1)))
        elif kind == "Cylinder":
            axis = rot[:, 2]
            d = 0.0
            for s in (-1.0, 1.0):
                p = c + s * shape.halfLength * axis
                p_perp = np.linalg.norm(p - (p @ axis) * axis)
                d = max(d, float(np.sqrt(p @ p + shape.radius**2
                                         + 2 * shape.radius * p_perp)))
        else:
            raise UnknownNameError("shape for max_extent", kind, ("Box", "Cylinder", "Sphere"))
        extent = max(extent, d)
    return extent

def lowest_points(model: pin.Model, data: pin.Data, gmodel: pin.GeometryModel, q: np.ndarray,
                  ignore: Sequence[str] = ()) -> tuple[np.ndarray, list[str]]:
    """Lowest world height of any geometry along a trajectory ``q`` (T, nq), and its object.

    Exact for the primitive shapes the built-in robot uses: the support point in −z of a
    shape with centre ``c`` and rotation ``R`` lies at ``c_z − s``, with ``s = r`` for a
    sphere, ``s = Σ_i |R_zi| h_i`` for a box of half-sides ``h``, and
    ``s = h |R_zz| + r sqrt(1 − R_zz²)`` for a cylinder of half-length ``h`` along its z axis.

    Args:
        model: The robot's Pinocchio model.
        data: A Pinocchio data of ``model`` (overwritten).
        gmodel: The visual or collision geometry model.
        q: Configurations (the base placement included), shape (T, nq).
        ignore: Names of links whose geometry is left out.

    Raises:
        UnknownNameError: every geometry ignored; or a shape is not a box, sphere or cylinder.

    Returns:
        Heights (T,), m, and the name of the lowest geometry object at each sample.
    """
    objects = [(k, obj) for k, obj in enumerate(gmodel.geometryObjects)
               if model.frames[obj.parentFrame].name not in ignore]
    if not objects:
        raise UnknownNameError("geometry left after ignore", "(none)",
                               sorted({model.frames[o.parentFrame].name
                                       for o in gmodel.geometryObjects}))
    # Per object: half-extents along its local axes for |R_z·|, a rim radius, a ball radius.
    n_obj = len(objects)
    half, rim, ball = np.zeros((n_obj, 3)), np.zeros(n_obj), np.zeros(n_obj)
    for n, (_, obj) in enumerate(objects):
        kind = type(obj.geometry).__name__
        if kind == "Sphere":
            ball[n] = obj.geometry.radius
        elif kind == "Box":
            half[n] = obj.geometry.halfSide
        elif kind == "Cylinder":
            half[n, 2], rim[n] = obj.geometry.halfLength, obj.geometry.radius
        else:
            raise UnknownNameError("shape for lowest_point", kind,
                                   ("Box", "Cylinder", "Sphere"))
    gdata = pin.GeometryData(gmodel)
    q = np.asarray(q, dtype=float)
    lowest, names = np.empty(len(q)), []
    for t, qt in enumerate(q):
        pin.updateGeometryPlacements(model, data, gmodel, gdata, qt)
        placements = [gdata.oMg[k] for k, _ in objects]
        c_z = np.array([m.translation[2] for m in placements])
        r_z = np.array([m.rotation[2] for m in placements])  # (n, 3): rows R_z·
        z = c_z - ball - np.sum(np.abs(r_z) * half, axis=1) \
            - rim * np.sqrt(np.maximum(0.0, 1.0 - r_z[:, 2] ** 2))
        n = int(np.argmin(z))
        lowest[t] = z[n]
        names.append(objects[n][1].name)
    return lowest, names


def link_width(model: pin.Model, gmodel: pin.GeometryModel, joint: str) -> float | None:
    """How wide the link a joint moves is: room for a part coaxial with the joint, m.

    For every collision shape on the joint's child link (primitives and meshes alike), the
    smallest side of its local axis-aligned bounding box (hpp-fcl's ``aabb_local``: a cylinder of
    radius r gives 2r, a box its smallest side); the link's width is the largest of these, so a
    thin plate beside a thick tube does not count. Falls back to the parent link when the child
    has no collision shape.

    Args:
        model: The robot's Pinocchio model.
        gmodel: Its collision geometry.
        joint: A joint name of ``model``.

    Returns:
        The width, m; None when neither link has a collision shape.

    Raises:
        UnknownNameError: ``joint`` is not a joint of the model (lists them).
    """
    if not model.existJointName(joint):
        raise UnknownNameError("joint", joint, list(model.names)[1:])
    jid = model.getJointId(joint)
    for link in (jid, model.parents[jid]):
        widths = []
        for obj in gmodel.geometryObjects:
            if obj.parentJoint == link:
                obj.geometry.computeLocalAABB()
                box = obj.geometry.aabb_local
                widths.append(float(np.min(np.asarray(box.max_) - np.asarray(box.min_))))
        if widths:
            return max(widths)
    return None
