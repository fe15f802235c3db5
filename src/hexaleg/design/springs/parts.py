"""From an optimal spring design to the parts to buy: one helical torsion spring per element.

A family's law is made of physical spring elements (:attr:`hexaleg.design.families.Family.
elements`): a spring that engages past a contact angle with a stiffness k and a preload P (the
torque where it engages), or the linear spring ``τ = τ₀ − k u`` (u the angle from the centre of
the joint's motion). Over the group's motion — the envelope of its joints' ranges, so one part
holds up on every joint of the group — each element becomes a :class:`TorsionRequirement`:

* engaged past contact angle a (``above``: for u > a, pushing the joint down): the torque runs
  from ``P`` at contact (or ``P + k (u_near − a)`` when engaged throughout the motion) to
  ``P + k (u_far − a)``; free at ``a ∓ P / k``;
* linear, its free angle ``u_f = τ₀ / k`` outside the motion: one spring pushing one way; inside
  it: the torque changes sign, which one torsion spring cannot give (it must be loaded in the
  sense that winds it up), so an antagonistic pair: two springs of rate k/2, each free at
  ``u_f ∓ e`` (e the farthest the motion gets from u_f), together exactly ``τ₀ − k u``;
* k → 0 with a torque (k at most :data:`~hexaleg.design.families.family.ZERO_MAGNITUDE`): a
  constant torque, which needs a constant-torque spring (spiral or constant-force), not a
  torsion spring: flagged.

The outer diameter limit of a group is the smallest of its joints' classes
(:func:`spring_outer_diameter`: the robot description's ``max_outer_diameter``, else the width of
the links). The arbor a class's coils wind on (:func:`arbor_for`) is the description's
``arbor_diameter``, else the servo's output hub where the catalogue has its diameter
(:data:`hexaleg.robot.catalogue.OUTPUT_HUBS`), else :data:`ARBOR_LINK_FRACTION` of the links'
width; the wound coil clears it by ``arbor_margin`` (:data:`~hexaleg.design.springs.torsion_spring.
ARBOR_MARGIN`).
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

from hexaleg.design.families import ZERO_MAGNITUDE, family
from hexaleg.design.search.optimal import OptimalSprings
from hexaleg.design.springs.fatigue import LIFE, wire_limit
from hexaleg.design.springs.materials import MATERIALS
from hexaleg.design.springs.torsion_spring import (
    ARBOR_MARGIN,
    SAFETY_FACTOR,
    TorsionRequirement,
    TorsionSpring,
    design_torsion_spring,
)
from hexaleg.dynamics.prepare import Prepared
from hexaleg.errors import InvalidParameterError, SpringDesignError, UnknownNameError
from hexaleg.robot.actuator import EVERY_JOINT, Actuator
from hexaleg.robot.catalogue import OUTPUT_HUBS
from hexaleg.robot.catalogue import motor as catalogue_motor
from hexaleg.robot.description import RobotDescription
from hexaleg.robot.geometry import link_width
from hexaleg.robot.model import Robot

ARBOR_LINK_FRACTION = 0.25
"""The arbor rule when neither the description nor the servo's catalogue entry gives one: a pin
of this fraction of the class's narrowest link (assumed: 5 mm in the default robot's 20 mm femur
and tibia links, an M5 shoulder screw through the joint)."""


STROKE_TOL = 1e-6
"""A part whose torque rises by less than this share of its largest over the motion has no
stroke: a torsion spring there would be a constant torque (issue #55: Unitree G1's design
stopped on "max_torque = 0.0012524; allowed: > preload_torque = 0.0012524 N·m")."""


@dataclass(frozen=True)
class PartOptions:
    """How the parts are made (the fields of :class:`TorsionRequirement` the design does not
    set): materials, design factor, arbor diameter (m; every group's unless :func:`spring_parts`
    is given per-group arbors), leg length (m or None), the arbor's clearance margin, and the
    life the parts are checked for in fatigue (``[design] life_cycles``): a part is bought only
    in a wire the fatigue data at that life cover
    (:func:`hexaleg.design.springs.fatigue.wire_limit`), so the fatigue check never refuses a
    spring the design chose."""

    materials: tuple[str, ...] = tuple(MATERIALS)
    safety_factor: float = SAFETY_FACTOR
    arbor_diameter: float = 0.0
    leg_length: float | None = None
    arbor_margin: float = ARBOR_MARGIN
    life_cycles: float = LIFE


@dataclass(frozen=True)
class SpringPart:
    """One physical spring of a group (every joint of the group gets one).

    Attributes:
        group: The design group. joints: Its joints.
        side: ``"above"`` (acts at the high angles, pushes the joint down) or ``"below"``.
        role: What it is in the law (``one-sided``: it engages past a contact angle; ``single``:
            a linear spring free outside the motion; ``pair (1 of 2)``, ``stage``, ``constant
            torque``).
        rate: N·m/rad (0 for a constant torque). preload_torque: Torque where it starts acting
            in the motion, N·m. max_torque: At the far end of the motion, N·m.
        engage: Where it starts acting, rad from the centre of motion; None: throughout.
        free: Where it would be free, rad from the centre of motion; None: constant torque.
        contact: Where its moving leg rests on its stop, preloaded (the family's contact
            angle), rad from the centre of motion; None for a spring without one (a linear
            spring, free at ``free``).
        constant_torque: k → 0 with a torque: needs a constant-torque spring.
        max_outer_diameter: The group's fit limit, m.
        spring: The torsion spring to buy, or None. nearest: With ``problem``, the nearest one.
        problem: Why there is no spring (empty when there is).
    """

    group: str
    joints: tuple[str, ...]
    side: str
    role: str
    rate: float
    preload_torque: float
    max_torque: float
    engage: float | None
    free: float | None
    constant_torque: bool
    max_outer_diameter: float
    spring: TorsionSpring | None = None
    nearest: TorsionSpring | None = None
    problem: str = ""
    contact: float | None = None

    @property
    def mass(self) -> float:
        """Mass of one such spring (the nearest one when none fits), kg; 0 without either."""
        part = self.spring or self.nearest
        return part.mass if part is not None else 0.0


def spring_outer_diameter(desc: RobotDescription, robot: Robot, kind: str
                          ) -> tuple[float, str]:
    """The largest outer diameter of a spring on the joints of class ``kind``, m, and where it
    comes from: the description's ``max_outer_diameter``, else the smallest
    :func:`~hexaleg.robot.geometry.link_width` of the class's joints.

    Raises:
        UnknownNameError: ``kind`` is not a joint class of ``robot`` (lists them).
        InvalidParameterError: no value given and no collision geometry to measure.
    """
    if kind not in robot.joint_classes:
        raise UnknownNameError("joint class", kind, robot.joint_classes)
    if kind in desc.max_outer_diameter:
        return float(desc.max_outer_diameter[kind]), f"{desc.name} description"
    return _narrowest_link(robot, kind, f"{desc.name}: max_outer_diameter.{kind}"), \
        "width of its links (collision geometry)"


def _narrowest_link(robot: Robot, kind: str, name: str) -> float:
    widths = [link_width(robot.model, robot.collision_model, j) for j in robot.joint_classes[kind]]
    known = [w for w in widths if w is not None]
    if len(known) < len(widths):
        raise InvalidParameterError(name, None, "a diameter (m): its links have no collision "
                                    "geometry")
    return min(known)


def arbor_for(robot: Robot, desc: RobotDescription, motor: Actuator | str | None,
              joint_class: str) -> tuple[float, str]:
    """The diameter of the arbor a spring on ``joint_class`` winds on, m, and its source:

    (a) the description's ``arbor_diameter[joint_class]`` when it has one; (b) the output hub of
    the class's servo when :data:`~hexaleg.robot.catalogue.OUTPUT_HUBS` gives its diameter;
    (c) :data:`ARBOR_LINK_FRACTION` of the narrowest link of the class (collision geometry),
    the source then saying why (b) did not apply.

    Args:
        robot: The robot. desc: Its description.
        motor: The robot's actuators (a motor, the set of the classes' motors, a catalogue
            name) or None.
        joint_class: The class.

    Raises:
        UnknownNameError: ``joint_class`` is not a class of ``robot`` (lists them), or an
            unknown catalogue name.
        InvalidParameterError: (c) is needed and the class's links have no collision geometry.
    """
    if joint_class not in robot.joint_classes:
        raise UnknownNameError("joint class", joint_class, robot.joint_classes)
    declared = desc.arbor_diameter
    if joint_class in declared:
        return float(declared[joint_class]), f"{desc.name} description"
    if isinstance(motor, str):
        motor = catalogue_motor(motor)
    if motor is not None:  # the class's model: a set's entry, or the one model of every joint
        motor = motor.models.get(joint_class, motor.models.get(EVERY_JOINT))
    why = "no catalogue servo"
    if motor is not None and motor.name in OUTPUT_HUBS:
        hub = OUTPUT_HUBS[motor.name]
        if hub.diameter is not None:
            return hub.diameter, f"{motor.name} output hub ({hub.source})"
        why = f"{motor.name} output hub {hub.source}"
    elif motor is not None:
        why = f"{motor.name} is not in the catalogue"
    width = _narrowest_link(robot, joint_class, f"{desc.name}: arbor_diameter.{joint_class}")
    return ARBOR_LINK_FRACTION * width, (f"{ARBOR_LINK_FRACTION:g} × the width of its links "
                                         f"(collision geometry), assumed; {why}")


def motion_centres(prepared: Prepared, joints: tuple[str, ...] | list[str]) -> dict[str, float]:
    """Joint → the centre of its range of motion in the gait ``(min + max)/2`` (rad, absolute):
    the origin of a part's ``engage`` and ``free`` angles on that joint."""
    q = prepared.q[:, [prepared.robot.column(j) for j in joints]]
    return {j: float(c) for j, c in zip(joints, (q.min(0) + q.max(0)) / 2, strict=True)}


def _elements(fam_name: str, geometry: Mapping[str, float | str], x: np.ndarray, lo: float,
              hi: float) -> list[dict]:
    """The elements' requirements of one group over the relative motion [lo, hi] (rad)."""
    fam = family(fam_name)
    terms = fam.terms(geometry, 0.0)
    out: list[dict] = []
    for e in fam.elements:
        k = float(x[e.stiffness])
        p = float(x[e.preload]) if e.preload is not None else 0.0
        if e.linear:
            if k <= ZERO_MAGNITUDE:
                if abs(p) > ZERO_MAGNITUDE:
                    out.append(dict(side="above" if p < 0 else "below", role="constant torque",
                                    rate=0.0, preload_torque=abs(p), max_torque=abs(p),
                                    engage=None, free=None))
                continue
            uf: float = p / k
            if uf <= lo or uf >= hi:
                side = "above" if uf <= lo else "below"
                near, far = (lo, hi) if side == "above" else (hi, lo)
                out.append(dict(side=side, role="single", rate=k,
                                preload_torque=k * abs(near - uf), max_torque=k * abs(far - uf),
                                engage=None, free=uf))
                continue
            e_max = max(uf - lo, hi - uf)
            for side, free, near, far in (("above", uf - e_max, lo, hi),
                                          ("below", uf + e_max, hi, lo)):
                out.append(dict(side=side, role="pair (1 of 2)", rate=k / 2,
                                preload_torque=k / 2 * abs(near - free),
                                max_torque=k / 2 * abs(far - free), engage=None, free=free))
            continue
        term = terms[e.stiffness]
        a, side = float(term.angle), term.kind
        near, far = (lo, hi) if side == "above" else (hi, lo)
        reach = (far - a) if side == "above" else (a - far)
        if (reach <= 0 or (k <= ZERO_MAGNITUDE and p <= ZERO_MAGNITUDE)
                or p + k * reach <= ZERO_MAGNITUDE):
            continue  # never engaged in the motion, or nothing there: a torque of at most
            # ZERO_MAGNITUDE anywhere in it, the round-off of a magnitude the program set to 0
            # (Solo-12's 4e-9 N·m/rad carrying 5e-12 N·m was a 1.8-m coil of 14 g a joint)
        before = (near - a) if side == "above" else (a - near)  # > 0: engaged throughout
        start = p + k * max(before, 0.0)
        role = "stage" if fam_name == "stiffening" else "one-sided"
        free_at = None if k <= ZERO_MAGNITUDE else (a - p / k if side == "above" else a + p / k)
        out.append(dict(side=side, role=role if k > ZERO_MAGNITUDE else "constant torque",
                        rate=k if k > ZERO_MAGNITUDE else 0.0, preload_torque=start,
                        max_torque=p + k * reach, engage=None if before > 0 else a,
                        free=free_at, contact=a))
    return out


def spring_parts(optimum: OptimalSprings, prepared: Prepared, outer: Mapping[str, float],
                 options: PartOptions | None = None, *,
                 arbor: Mapping[str, float] | None = None) -> tuple[SpringPart, ...]:
    """The torsion springs to buy for ``optimum`` (module docstring).

    Args:
        optimum: The optimal springs.
        prepared: The gait they were designed on (the joints' ranges of motion).
        outer: Group → largest outer diameter of its springs, m.
        options: Materials, design factor, arbor, leg length, arbor margin.
        arbor: Group → the arbor its springs wind on, m (:func:`arbor_for`); groups not named
            (or None) get ``options.arbor_diameter``.

    Returns:
        One part per element of each group that acts in the motion; a part without a spring
        says why (``problem``) and names the nearest one.
    """
    options = options or PartOptions()
    parts = []
    for g, joints in optimum.groups.items():
        q = prepared.q[:, [prepared.robot.column(j) for j in joints]]
        centre = (q.min(0) + q.max(0)) / 2
        lo, hi = float((q.min(0) - centre).min()), float((q.max(0) - centre).max())
        x = np.array([optimum.magnitudes[g][m] for m in family(optimum.family).magnitudes])
        for el in _elements(optimum.family, optimum.geometry[g], x, lo, hi):
            part = SpringPart(group=g, joints=tuple(joints), constant_torque=el["rate"] == 0.0,
                              max_outer_diameter=float(outer[g]), **el)
            parts.append(_buy(part, options, float((arbor or {}).get(
                g, options.arbor_diameter))))
    return tuple(parts)


def _buy(part: SpringPart, options: PartOptions, arbor: float) -> SpringPart:
    """``part`` with its torsion spring, or the reason there is none."""
    if part.constant_torque:
        return dataclasses.replace(part, problem=(
            f"k → 0 with {part.max_torque:.4g} N·m: a constant torque needs a constant-torque "
            "spring (spiral or constant-force), not a helical torsion spring; bound "
            "max_deflection to get a torsion spring"))
    stroke = part.max_torque - part.preload_torque
    if not stroke > STROKE_TOL * max(abs(part.max_torque), 1e-300):
        return dataclasses.replace(part, problem=(
            f"it holds {part.max_torque:.4g} N·m without a stroke over the motion (it engages "
            f"only where the motion ends, {part.rate:.4g} N·m/rad over {stroke / part.rate:.3g} "
            "rad): nothing for a torsion spring to do; bound max_deflection or leave the group "
            "out ([design] classes)"))
    req = TorsionRequirement(rate=part.rate, max_torque=part.max_torque,
                             preload_torque=part.preload_torque,
                             max_outer_diameter=part.max_outer_diameter,
                             arbor_diameter=arbor, materials=options.materials,
                             safety_factor=options.safety_factor,
                             leg_length=options.leg_length, arbor_margin=options.arbor_margin,
                             max_wire_diameter=wire_limit(options.life_cycles))
    try:
        return dataclasses.replace(part, spring=design_torsion_spring(req))
    except SpringDesignError as e:
        return dataclasses.replace(part, problem=str(e),
                                   nearest=e.nearest if isinstance(e.nearest, TorsionSpring)
                                   else None)


def spring_masses(parts: tuple[SpringPart, ...]) -> dict[str, float]:
    """Joint → mass of its springs (the nearest spring where none fits), kg."""
    out: dict[str, float] = {}
    for part in parts:
        for j in part.joints:
            out[j] = out.get(j, 0.0) + part.mass
    return out
