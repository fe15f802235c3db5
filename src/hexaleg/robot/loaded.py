"""The loaded robot: a Pinocchio model with a free-flyer base, its legs and reference poses.

:class:`Robot` and its legs (:class:`Leg`) are what :func:`hexaleg.robot.model.load_robot`
makes and every layer above takes. The type lives apart from its loader because modules the
loader uses (:mod:`~hexaleg.robot.sphere_feet`, :mod:`~hexaleg.robot.root`,
:mod:`~hexaleg.robot.sanity`) take a loaded robot in turn; :mod:`hexaleg.robot.model` imports
both names, so they are importable from there too.
"""
from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import pinocchio as pin

from hexaleg.errors import UnknownNameError
from hexaleg.robot import geometry as _geometry
from hexaleg.robot.feet import SphereFoot
from hexaleg.robot.fields import horizontal_axis
from hexaleg.robot.soles import Sole

JOINT_KINDS: tuple[str, ...] = ("coxa", "femur", "tibia")
"""The joints of a hexaleg leg, from the body outward (a robot's default joint classes)."""


@dataclass(frozen=True)
class Leg:
    """One leg of a loaded robot, with its indices into Pinocchio's vectors.

    Attributes:
        name: Leg name.
        joint_names: Joint names from the body outward.
        joint_ids: Pinocchio joint ids, shape (n,).
        q_index: Indices of the leg's joints in the configuration q (nq,), shape (n,).
        v_index: Indices of the leg's joints in the velocity v (nv,), shape (n,).
        columns: Indices of the leg's joints among the actuated joints (``v_index - 6``),
            shape (n,).
        foot_frame: Foot frame name.
        foot_frame_id: Pinocchio frame id of the foot.
    """

    name: str
    joint_names: tuple[str, ...]
    joint_ids: tuple[int, ...]
    q_index: np.ndarray
    v_index: np.ndarray
    columns: np.ndarray
    foot_frame: str
    foot_frame_id: int


@dataclass(eq=False)
class Robot:
    """A legged robot loaded into Pinocchio with a free-flyer base.

    Attributes:
        name: Robot name (from the URDF).
        model: Pinocchio model; nq = 7 + n joints, nv = 6 + n joints.
        data: Pinocchio data for ``model`` (scratch space; not thread-safe).
        visual_model: Visual geometry.
        collision_model: Collision geometry with all pairs except those the SRDF disables.
        legs: The legs, in the order given at load time.
        poses: Reference configurations from the SRDF ``group_state``s, each shape (nq,), base at
            the origin with identity orientation.
        urdf_path: The URDF file.
        srdf_path: The SRDF file, or None.
        joint_kinds: Name of the k-th joint of every leg (``coxa, femur, tibia`` for the
            hexapod); the joints of one kind form a joint class (:attr:`joint_classes`).
        heading: The base axis that points forward, a horizontal unit vector in the base frame,
            shape (3,); gaits walk along it (``+x`` unless a description says otherwise).
        notes: What loading found or assumed (feet found, meshes replaced, legs discovered).
        foot_spheres: Leg → its round foot (found on a sphere or capsule end), whose frame is the
            sphere's lowest point in the stand pose (:func:`.sphere_feet.place_sphere_feet`).
        moves: Joint on no leg → (amplitude, phase), rad: it swings ``q_stand + amplitude ·
            sin(2π t / T + phase)`` over every gait cycle of period ``T``
            (:func:`hexaleg.motion.legged.sample_gait`); the others are held at the stand.
        soles: Leg → its flat sole centred on its foot frame (:mod:`hexaleg.robot.soles`);
            legs not named stand on point feet (all of them by default).
    """

    name: str
    model: pin.Model
    data: pin.Data
    visual_model: pin.GeometryModel
    collision_model: pin.GeometryModel
    legs: tuple[Leg, ...]
    poses: dict[str, np.ndarray]
    urdf_path: Path
    srdf_path: Path | None
    joint_kinds: tuple[str, ...] = JOINT_KINDS
    heading: np.ndarray = field(default_factory=lambda: np.array([1.0, 0.0, 0.0]))
    notes: tuple[str, ...] = ()
    foot_spheres: dict[str, SphereFoot] = field(default_factory=dict)
    moves: dict[str, tuple[float, float]] = field(default_factory=dict)
    soles: dict[str, Sole] = field(default_factory=dict)
    mass: float = field(init=False)
    joint_names: tuple[str, ...] = field(init=False)

    def __post_init__(self) -> None:
        heading = horizontal_axis("heading", self.heading)
        self.heading = heading / np.linalg.norm(heading)
        self.mass = float(pin.computeTotalMass(self.model))
        # Actuated joints: every joint after the universe (0) and the free flyer (1).
        self.joint_names = tuple(self.model.names[2:])

    def __getstate__(self) -> dict[str, object]:
        """The robot pickled without ``data``, which is scratch space rebuilt from the model on
        unpickling: pin 4.0.0's ``Data`` does not survive a pickle round trip (``RuntimeError:
        input stream error``; pin 4.1's does), and the ``optimal`` extra pins pin 4.0 — where a
        co-design's forked spring rules send their result, robot included, back pickled."""
        state = dict(self.__dict__)
        del state["data"]
        return state

    def __setstate__(self, state: dict[str, object]) -> None:
        """Restore a pickled robot (:meth:`__getstate__`), with fresh ``data`` for its model."""
        self.__dict__.update(state)
        self.data = self.model.createData()

    @property
    def nj(self) -> int:
        """Number of actuated joints (nv − 6)."""
        return self.model.nv - 6

    @property
    def joint_classes(self) -> dict[str, tuple[str, ...]]:
        """Joint class name → the joints of that kind on every leg, in leg order.

        E.g. ``{"coxa": ("LF_coxa", …), "femur": (…), "tibia": (…)}``; a spring design for a class
        goes on all its joints (left/right symmetric).
        """
        return {kind: tuple(leg.joint_names[i] for leg in self.legs)
                for i, kind in enumerate(self.joint_kinds)}

    def joints(self, spec: str) -> tuple[str, ...]:
        """Joints named by ``spec``: a joint class (``"femur"``) or one joint (``"LF_femur"``).

        Raises:
            UnknownNameError: neither; the message lists the classes and joints.
        """
        classes = self.joint_classes
        if spec in classes:
            return classes[spec]
        if spec in self.joint_names:
            return (spec,)
        raise UnknownNameError("joint class or joint", spec, [*classes, *self.joint_names])

    @property
    def other_joints(self) -> tuple[str, ...]:
        """The actuated joints on no leg — an arm's, a torso's, a head's — in column order.

        They are held at the stand pose through every motion, or swing as :attr:`moves` says
        (a description's ``moves``); their inertia is carried by the dynamics, and each gets
        its own actuator (:func:`hexaleg.robot.motor_set.class_motors`), which counts its
        torque.
        """
        on_legs = {j for leg in self.legs for j in leg.joint_names}
        return tuple(j for j in self.joint_names if j not in on_legs)

    @property
    def leg_names(self) -> tuple[str, ...]:
        return tuple(leg.name for leg in self.legs)

    def leg(self, name: str) -> Leg:
        """The leg called ``name``.

        Raises:
            UnknownNameError: no such leg; the message lists the legs.
        """
        for leg in self.legs:
            if leg.name == name:
                return leg
        raise UnknownNameError("leg", name, self.leg_names)

    def column(self, joint: str) -> int:
        """Column of actuated joint ``joint`` in (…, nj) arrays (Pinocchio joint order).

        Raises:
            UnknownNameError: no such actuated joint; the message lists them.
        """
        try:
            return self.joint_names.index(joint)
        except ValueError:
            raise UnknownNameError("joint", joint, self.joint_names) from None

    def pose(self, name: str) -> np.ndarray:
        """A copy of SRDF reference configuration ``name``, shape (nq,).

        Raises:
            UnknownNameError: no such pose; the message lists the poses.
        """
        if name not in self.poses:
            raise UnknownNameError("pose", name, self.poses)
        return self.poses[name].copy()

    def foot_positions(self, q: np.ndarray) -> np.ndarray:
        """World positions of the feet at configuration ``q`` (nq,), shape (n_legs, 3), m."""
        pin.framesForwardKinematics(self.model, self.data, np.asarray(q, dtype=float))
        return np.array([self.data.oMf[leg.foot_frame_id].translation for leg in self.legs])

    def self_collisions(self, q: np.ndarray) -> list[tuple[str, str]]:
        """Pairs of links whose collision geometries intersect at ``q`` (nq,), SRDF pairs
        excluded: sorted (link, link) name pairs, empty when collision-free
        (:func:`hexaleg.robot.geometry.self_collisions`)."""
        return _geometry.self_collisions(self.model, self.data, self.collision_model, q)

    def max_extent(self, q: np.ndarray, geometry: str = "visual") -> float:
        """Largest distance of any ``"visual"`` or ``"collision"`` geometry point from the base
        origin at ``q`` (nq,), m (:func:`hexaleg.robot.geometry.max_extent`)."""
        return _geometry.max_extent(self.model, self.data, self._geometry_model(geometry), q)

    def lowest_point(self, q: np.ndarray, geometry: str = "visual",
                     ignore: Sequence[str] = ()) -> tuple[float, str]:
        """Lowest world height of any geometry at ``q``, and the geometry object it belongs to
        (exact for boxes, spheres and cylinders: :func:`hexaleg.robot.geometry.lowest_points`).

        Args:
            q: Configuration, shape (nq,) (the base placement included).
            geometry: ``"visual"`` or ``"collision"``.
            ignore: Names of links whose geometry is left out (e.g. the feet, whose contact is
                the foot point rather than the ball around it).

        Returns:
            ``(z, name)``: height in m (negative: below the ground plane z = 0) and the geometry
            object's name.

        Raises:
            UnknownNameError: ``geometry`` is neither; or a shape is not a box, sphere or cylinder.
        """
        z, names = self.lowest_points(np.asarray(q, dtype=float)[None], geometry, ignore)
        return float(z[0]), names[0]

    def lowest_points(self, q: np.ndarray, geometry: str = "visual",
                      ignore: Sequence[str] = ()) -> tuple[np.ndarray, list[str]]:
        """:meth:`lowest_point` along a trajectory ``q`` of shape (T, nq).

        Returns:
            Heights (T,), m, and the name of the lowest geometry object at each sample.
        """
        return _geometry.lowest_points(self.model, self.data, self._geometry_model(geometry),
                                       np.asarray(q, dtype=float), ignore)

    def _geometry_model(self, geometry: str) -> pin.GeometryModel:
        """The visual or collision model, by name."""
        models = {"visual": self.visual_model, "collision": self.collision_model}
        if geometry not in models:
            raise UnknownNameError("geometry", geometry, models)
        return models[geometry]

    def summary(self) -> str:
        """A human-readable summary: links and masses, joints and limits, legs, poses."""
        m = self.model
        lines = [f"robot {self.name}: {self.urdf_path}",
                 f"  nq = {m.nq}, nv = {m.nv}, actuated joints = {self.nj}, "
                 f"total mass = {self.mass:.4f} kg",
                 "  bodies (mass kg, CoM m in the joint frame):"]
        for jid in range(1, m.njoints):
            inert = m.inertias[jid]
            com = ", ".join(f"{c:+.4f}" for c in inert.lever)
            lines.append(f"    {m.names[jid]:<14} {inert.mass:8.5f}  [{com}]")
        lines.append("  joints (lower, upper rad; effort N·m; velocity rad/s; every angle here is "
                     "the joint's coordinate, from its zero in the URDF, not from the stand):")
        for name in self.joint_names:
            jid = m.getJointId(name)
            iq, iv = m.joints[jid].idx_q, m.joints[jid].idx_v
            lines.append(f"    {name:<14} [{m.lowerPositionLimit[iq]:+.4f}, "
                         f"{m.upperPositionLimit[iq]:+.4f}]  {m.effortLimit[iv]:.3f}  "
                         f"{m.velocityLimit[iv]:.3f}")
        lines.append("  legs (joints → foot frame):")
        for leg in self.legs:
            sole = self.soles.get(leg.name)
            on = "" if sole is None else \
                f" (a {sole.length * 1e3:g} × {sole.width * 1e3:g} mm sole, flat in the stand)"
            lines.append(f"    {leg.name}: {', '.join(leg.joint_names)} → {leg.foot_frame}{on}")
        others = self.other_joints
        if others:
            held = ("held at the stand pose" if not self.moves else
                    "held at the stand pose or swinging about it ([robot] moves)")
            lines.append(f"  other joints ({len(others)}, on no leg: {held}, "
                         "their inertia in the dynamics, each torque drawn by its own "
                         "actuator):")
            q = self.poses.get("stand")
            for name in others:
                at = ("" if q is None else
                      f"  stand {q[m.joints[m.getJointId(name)].idx_q]:+.4f} rad from its zero")
                if name in self.moves:
                    amplitude, phase = self.moves[name]
                    at += (f", swings ±{amplitude:.4f} rad about the stand with phase "
                           f"{phase:+.4f} rad each gait cycle")
                lines.append(f"    {name:<20}{at}")
        lines.append(f"  poses: {', '.join(self.poses) or '(none)'}; heading (forward) "
                     f"[{', '.join(f'{v:+.3g}' for v in self.heading)}] in the base frame")
        lines += [f"  note: {n}" for n in self.notes]
        return "\n".join(lines)


__all__ = ["JOINT_KINDS", "Leg", "Robot"]
