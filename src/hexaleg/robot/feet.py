"""Foot frames for URDFs that have none: a point on a link, or the far end of the leg's last link.

Real URDFs rarely define foot frames. A leg's foot may be given as a frame (``foot = "LF_FOOT"``),
as a point on a link (``foot = {link = "lf_shin", point = [0, 0, -0.12]}``, metres in the link's
frame), or found: the tip of the last joint's collision geometry (its visual geometry when it
has none) — of its shapes' tips (a cylinder's or capsule's end, a box's face centre, a sphere's
point along its centre's direction, a mesh's vertex), the one farthest from the joint's origin.
The chosen point becomes a Pinocchio operational frame ``<leg>_foot`` on the leg's last joint,
so everything downstream sees an ordinary foot frame.

A shank is long and thin: its tip is where the ground touches it, on its axis, not on a rim or
a corner (those are the farthest points of the support mappings, Ericson, *Real-Time Collision
Detection*, 2005, §3.8, which would put the foot off the leg's axis by the shank's radius).

A round foot — a sphere, or a capsule's end, at the tip — touches the ground at its lowest point,
which depends on the leg's posture: the tip along the shank is up to a radius away from it on an
inclined shank (2 cm on A1's feet). Such a foot is recorded as a :class:`SphereFoot` and its
frame placed at the sphere's lowest point in the stand pose, ``c − r ẑ`` for the centre ``c``
(the support point of a sphere in −z, Ericson §3.8; done on the loaded robot by
:mod:`hexaleg.robot.sphere_feet`): the foot frame is then a fixed point of the link, where the
ground is touched when standing.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass, replace

import numpy as np
import pinocchio as pin

from hexaleg.errors import RobotModelError

FOOT_SUFFIX = "_foot"
"""A generated foot frame is named ``<leg>`` + this."""


@dataclass(frozen=True)
class LegSpec:
    """How to find one leg in a URDF.

    Attributes:
        name: Leg name, e.g. ``"LF"``.
        joints: Joint names from the body outward.
        foot: The foot: a frame (a link, or a frame Pinocchio creates from a fixed joint); with
            ``point``, the link the point is on; None to find it (module docstring).
        point: The foot's position in the frame of link ``foot``, m, shape (3,); None when
            ``foot`` is itself the foot frame.
    """

    name: str
    joints: tuple[str, ...]
    foot: str | None = None
    point: tuple[float, float, float] | None = None

    def __post_init__(self) -> None:
        object.__setattr__(self, "joints", tuple(self.joints))
        if self.point is not None:
            p = np.asarray(self.point, dtype=float)
            if p.shape != (3,) or not np.all(np.isfinite(p)) or self.foot is None:
                raise RobotModelError(f"leg {self.name}: foot point {self.point!r}; expected "
                                      "[x, y, z] (m, finite) on the link named by foot")
            object.__setattr__(self, "point", tuple(float(v) for v in p))


@dataclass(frozen=True)
class SphereFoot:
    """A found foot that is round: a sphere, or a capsule's end, at the tip of the leg.

    Attributes:
        joint: Pinocchio id of the leg's last joint (the sphere moves with it).
        centre: The sphere's centre in that joint's frame, m, shape (3,).
        radius: Its radius, m, > 0.
    """

    joint: int
    centre: np.ndarray
    radius: float


def resolve_foot(model: pin.Model, collision: pin.GeometryModel, visual: pin.GeometryModel,
                 spec: LegSpec, wheels: Mapping[str, tuple[np.ndarray, float]] | None = None
                 ) -> tuple[LegSpec, str | None, SphereFoot | None]:
    """The leg spec with its foot as a frame of ``model`` (adding the frame when needed).

    A leg without a foot whose last joint carries a locked wheel (``wheels``: joint name →
    the wheel's centre in its frame and radius, :mod:`hexaleg.robot.wheels`) stands on the
    wheel: a round foot of its radius about its centre.

    Args:
        model: The robot model (a frame is added to it for a point or a found foot).
        collision: Its collision geometry (searched for a found foot).
        visual: Its visual geometry (when the joint has no collision geometry).
        spec: The leg.

    Returns:
        The spec with ``foot`` a frame name and no ``point``; for a found foot a note
        ``"<leg> at [x, y, z] m on joint <joint> (collision|visual)"``, else None; and the
        :class:`SphereFoot` when the found tip is a sphere's (or a capsule end's), else None
        (the frame is then at the tip until
        :func:`~hexaleg.robot.sphere_feet.place_sphere_feet` moves it).

    Raises:
        RobotModelError: the link of a point is not in the URDF (lists the links), or a leg
            without geometry on its last joint has no foot given.
    """
    if spec.foot is not None and spec.point is None:
        return spec, None, None
    last = spec.joints[-1]
    if not model.existJointName(last):
        return spec, None, None  # the leg's own check names the missing joint
    jid = model.getJointId(last)
    wheel = (wheels or {}).get(last)
    if spec.point is None and wheel is not None and wheel[1] > 0:
        centre, radius = np.asarray(wheel[0], dtype=float), float(wheel[1])
        name = _add_frame(model, spec.name, jid,
                          pin.SE3(np.eye(3), centre - radius * np.array([0.0, 0.0, 1.0])))
        at = ", ".join(f"{v:+.4f}" for v in centre)
        return (replace(spec, foot=name, point=None),
                f"{spec.name} on the wheel of radius {radius:.4g} m centred at [{at}] m on "
                f"joint {last} (locked), touching the ground at its lowest point in the stand "
                "pose", SphereFoot(jid, centre, radius))
    if spec.point is not None:
        assert spec.foot is not None
        if not model.existBodyName(spec.foot):
            links = sorted(f.name for f in model.frames if f.type == pin.FrameType.BODY)
            raise RobotModelError(f"leg {spec.name}: foot link {spec.foot!r} not in the URDF; "
                                  f"links found: {', '.join(links)}")
        body = model.frames[model.getBodyId(spec.foot)]
        placement = body.placement * pin.SE3(np.eye(3), np.array(spec.point))
        name = _add_frame(model, spec.name, body.parentJoint, placement)
        return replace(spec, foot=name, point=None), None, None
    point, obj, source = _far_end(collision, jid, "collision")
    if point is None:
        point, obj, source = _far_end(visual, jid, "visual")
    if point is None or obj is None:
        raise RobotModelError(
            f"leg {spec.name}: no foot given and joint {last} carries no geometry to find it "
            f"from; give foot = \"<frame>\" or foot = {{link = \"<link>\", point = [x, y, z]}}")
    name = _add_frame(model, spec.name, jid, pin.SE3(np.eye(3), point))
    sphere = sphere_of_tip(obj, point, jid)
    at = ", ".join(f"{v:+.4f}" for v in (point if sphere is None else sphere.centre))
    note = (f"{spec.name} at [{at}] m on joint {last} ({source})" if sphere is None else
            f"{spec.name} on the sphere of radius {sphere.radius:.4g} m centred at [{at}] m on "
            f"joint {last} ({source}), touching the ground at its lowest point in the stand "
            "pose")
    return replace(spec, foot=name, point=None), note, sphere


def resolve_feet(model: pin.Model, collision: pin.GeometryModel, visual: pin.GeometryModel,
                 legs: Sequence[LegSpec],
                 wheels: Mapping[str, tuple[np.ndarray, float]] | None = None
                 ) -> tuple[tuple[LegSpec, ...], list[str], dict[str, SphereFoot]]:
    """:func:`resolve_foot` of every leg: the specs, a note per found foot, the round feet."""
    specs, notes, spheres = [], [], {}
    for spec in legs:
        spec, note, sphere = resolve_foot(model, collision, visual, spec, wheels)
        specs.append(spec)
        if note:
            notes.append(f"foot found at the tip of the leg's last link: {note}")
        if sphere is not None:
            spheres[spec.name] = sphere
    return tuple(specs), notes, spheres


def _add_frame(model: pin.Model, leg: str, joint: int, placement: pin.SE3) -> str:
    name = leg + FOOT_SUFFIX
    while model.existFrame(name):
        name += "_"
    model.addFrame(pin.Frame(name, joint, placement, pin.FrameType.OP_FRAME))
    return name


def _far_end(gmodel: pin.GeometryModel, joint: int, source: str
             ) -> tuple[np.ndarray | None, pin.GeometryObject | None, str]:
    """The point of ``joint``'s geometry farthest from its origin, in the joint frame, and the
    geometry it is on."""
    best: np.ndarray | None = None
    owner: pin.GeometryObject | None = None
    for obj in gmodel.geometryObjects:
        if obj.parentJoint != joint:
            continue
        for p in farthest_points(obj):
            if best is None or np.linalg.norm(p) > np.linalg.norm(best) + 1e-12:
                best, owner = p, obj
    return best, owner, source


def sphere_of_tip(obj: pin.GeometryObject, tip: np.ndarray, joint: int) -> SphereFoot | None:
    """The sphere a tip of :func:`farthest_points` lies on: a sphere's own, or the end cap of a
    capsule (the hemisphere of its radius centred on the axis at ``±halfLength``, on the tip's
    side); None for the other shapes. ``tip`` and the result in the joint frame."""
    shape, kind, m = obj.geometry, type(obj.geometry).__name__, obj.placement
    if kind == "Sphere":
        return SphereFoot(joint, np.array(m.translation, dtype=float), float(shape.radius))
    if kind == "Capsule":
        axis = m.rotation[:, 2]
        side = 1.0 if float((tip - m.translation) @ axis) > 0 else -1.0
        centre = m.translation + side * shape.halfLength * axis
        return SphereFoot(joint, np.array(centre, dtype=float), float(shape.radius))
    return None


def farthest_points(obj: pin.GeometryObject) -> list[np.ndarray]:
    """Tips of one geometry, in its joint's frame (module docstring).

    Raises:
        RobotModelError: a shape this module does not know (names it).
    """
    shape, kind = obj.geometry, type(obj.geometry).__name__
    m = obj.placement
    if kind == "Box":
        h = np.asarray(shape.halfSide, dtype=float)
        return [m.act(s * h[i] * np.eye(3)[i]) for i in range(3) for s in (-1.0, 1.0)]
    if kind == "Sphere":
        c = m.translation
        n = np.linalg.norm(c)
        return [c + shape.radius * (c / n if n > 0 else np.array([0.0, 0.0, -1.0]))]
    if kind in ("Cylinder", "Capsule"):
        axis = m.rotation[:, 2]
        cap = shape.radius if kind == "Capsule" else 0.0
        return [m.translation + s * (shape.halfLength + cap) * axis for s in (-1.0, 1.0)]
    if hasattr(shape, "vertices") and shape.num_vertices:
        return [m.act(v) for v in np.asarray(shape.vertices(), dtype=float)]  # scaled on load
    raise RobotModelError(f"geometry {obj.name}: shape {kind} has no tip rule; give the leg's "
                          "foot as a frame or a point on a link")
