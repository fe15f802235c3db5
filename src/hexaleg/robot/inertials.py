"""The URDF's ``<inertial>``\\ s, checked where they are read: refused with the fix, or repaired.

A URDF link's inertia that no mass distribution can have (a negative principal moment, or
principal moments that violate the triangle inequality ``I1 + I2 ≥ I3``; the tests and their
tolerances are :func:`hexaleg.robot.sanity.inertia_findings`') loads in Pinocchio, gives
plausible-looking energies and then stops MuJoCo ("inertia must satisfy A + B >= C") after the
analysis has run. It is caught here, per URDF link, before anything uses it — when it reaches
the Pinocchio body the link is merged into (the inertia the dynamics and the simulation use).
:func:`load_robot <hexaleg.robot.model.load_robot>`'s ``inertias``:

* ``"refuse"`` (default): a :class:`~hexaleg.errors.RobotModelError` naming each bad link, its
  mass and principal moments, what is allowed, and the replacement the ``"repair"`` rule would
  write (numbers one can paste into the URDF);
* ``"repair"`` (opt-in): each bad link's rotational inertia is replaced by :func:`box_inertia` —
  that of a solid box filling the axis-aligned bounding box of the link's collision geometry
  (its visual geometry when it has none), with the link's own mass and centre of mass; the robot
  carries a note naming every link and the numbers written, because the inertia is then
  invented, not measured;
* ``"keep"``: loaded as written (the sanity warnings still list them; the simulation refuses).

Why a box and not a refusal only: a placeholder inertia (a copy-pasted ``1e-3`` diagonal) is the
usual defect, while mass and CoM are usually right (weighed, or from CAD); a uniform box around
the link's geometry is the crudest body that is physically possible and of the right size. A
negative mass cannot be repaired this way (the rule needs the mass) and is always refused.
"""

from __future__ import annotations

import xml.etree.ElementTree as ET
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pinocchio as pin

from hexaleg.errors import InvalidParameterError, RobotModelError
from hexaleg.robot.sanity import DEFINITE_TOL, TRIANGLE_TOL, aabb_corners

MODES = ("refuse", "repair", "keep")
"""Values of ``load_robot(..., inertias=…)``."""
KEYS = ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")
SHOWN = 3
"""Repaired links whose new inertia the note spells out; the rest it names (a robot with a dozen
bad links made a 3000-character warning line)."""
REPAIRED_MARK = "inertias repaired"
"""How the robot's loading note of a repair begins (what marks a run's robot as repaired)."""


@dataclass(frozen=True)
class BadInertial:
    """One URDF link whose ``<inertial>`` no rigid body can have.

    Attributes:
        link: URDF link name.
        mass: Its mass, kg.
        moments: Principal moments about its CoM, ascending, shape (3,), kg·m².
        com: Its centre of mass in the link frame, shape (3,), m.
        problem: What fails, with the allowed range.
    """

    link: str
    mass: float
    moments: np.ndarray
    com: np.ndarray
    problem: str

    def describe(self) -> str:
        moments = ", ".join(f"{m:.4g}" for m in self.moments)
        return (f"link {self.link!r}: mass {self.mass:.4g} kg, principal moments {moments} kg·m² "
                f"about the CoM: {self.problem}")


def _floats(element: ET.Element | None, attribute: str, default: str) -> np.ndarray:
    text = default if element is None else element.get(attribute, default)
    return np.array([float(w) for w in text.split()])


def bad_inertials(root: ET.Element) -> list[BadInertial]:
    """The links of the URDF ``root`` whose inertia is impossible, in file order.

    A link with positive mass must have a positive semi-definite rotational inertia (smallest
    principal moment ≥ −:data:`~hexaleg.robot.sanity.DEFINITE_TOL` · I3; a point mass or a thin
    rod has zero moments and is possible) whose principal moments satisfy the triangle inequality
    ``I1 + I2 ≥ (1 − TRIANGLE_TOL) I3`` (``I1 + I2 − I3 = 2 ∫ r_3² dm ≥ 0``; Traversaro et al.,
    IROS 2016); a negative mass is impossible. The principal moments do not depend on the
    ``<origin rpy>`` of the inertial frame (a rotation keeps the eigenvalues). Massless links
    are left alone (a frame without a body); the sanity checks report them.
    """
    found = []
    for link in root.iter("link"):
        inertial = link.find("inertial")
        if inertial is None:
            continue
        mass = float(_floats(inertial.find("mass"), "value", "0")[0])
        element = inertial.find("inertia")
        i = {k: float(_floats(element, k, "0")[0]) for k in KEYS}
        tensor = np.array([[i["ixx"], i["ixy"], i["ixz"]], [i["ixy"], i["iyy"], i["iyz"]],
                           [i["ixz"], i["iyz"], i["izz"]]])
        moments = np.linalg.eigvalsh(tensor)
        com = _floats(inertial.find("origin"), "xyz", "0 0 0")
        problem = ""
        if mass < 0:
            problem = "negative mass (allowed: ≥ 0 kg; the box rule cannot repair it)"
        elif mass > 0 and moments[0] < -DEFINITE_TOL * max(abs(moments[2]), 1e-300):
            problem = "a negative principal moment (allowed: all ≥ 0 kg·m²)"
        elif mass > 0 and moments[0] + moments[1] < (1.0 - TRIANGLE_TOL) * moments[2]:
            problem = (f"I1 + I2 = {moments[0] + moments[1]:.4g} < I3 (allowed: I1 + I2 ≥ "
                       f"{1.0 - TRIANGLE_TOL:g} · I3, the triangle inequality; no mass "
                       "distribution has these moments)")
        if problem:
            found.append(BadInertial(link.get("name", "(unnamed)"), mass, moments, com, problem))
    return found


def box_inertia(mass: float, lower: np.ndarray, upper: np.ndarray, com: np.ndarray
                ) -> np.ndarray:
    """Rotational inertia about ``com`` of a solid box of ``mass`` filling ``[lower, upper]``.

    A uniform cuboid of sides ``a, b, c`` along x, y, z has, about its centre, the principal
    moments ``m (b² + c²) / 12``, ``m (a² + c²) / 12``, ``m (a² + b²) / 12`` (e.g. Meriam &
    Kraige, *Engineering Mechanics: Dynamics*, table D/4). Moved to a point at ``d = com − centre``
    by Steiner's parallel-axis theorem ``I_P = I_C + m (|d|² E − d dᵀ)`` (ibid., §7/7; the box's
    centre of mass is its centre). The result satisfies the triangle inequality (a sum of two
    physical inertias about the same point is one).

    Args:
        mass: kg, ≥ 0.
        lower: One corner of the box, shape (3,), m (axes of the frame used).
        upper: The opposite corner, shape (3,), m.
        com: The point about which the inertia is taken, shape (3,), m.

    Returns:
        The 3 × 3 inertia tensor, kg·m².
    """
    a, b, c = np.asarray(upper, dtype=float) - np.asarray(lower, dtype=float)
    centre = (np.asarray(upper, dtype=float) + np.asarray(lower, dtype=float)) / 2
    d = np.asarray(com, dtype=float) - centre
    own = mass / 12.0 * np.diag([b * b + c * c, a * a + c * c, a * a + b * b])
    return own + mass * (float(d @ d) * np.eye(3) - np.outer(d, d))


def _link_box(link: str, model: pin.Model, geometry: tuple[pin.GeometryModel, ...]
              ) -> tuple[np.ndarray, np.ndarray, str] | None:
    """The bounding box of ``link``'s collision geometry (else visual) in the link frame, and
    which geometry it came from; None without geometry."""
    if not model.existFrame(link, pin.FrameType.BODY):
        return None
    frame_id = model.getFrameId(link, pin.FrameType.BODY)
    placement = model.frames[frame_id].placement
    for kind, gmodel in zip(("collision", "visual"), geometry, strict=True):
        corners = [aabb_corners(g) for g in gmodel.geometryObjects if g.parentFrame == frame_id]
        points = np.vstack([np.zeros((0, 3)), *corners])
        if len(points):  # joint frame → link frame: p_link = Rᵀ (p − t)
            local = (points - placement.translation) @ np.asarray(placement.rotation)
            return local.min(axis=0), local.max(axis=0), kind
    return None


def _replacement(bad: BadInertial, model: pin.Model,
                 geometry: tuple[pin.GeometryModel, ...]) -> tuple[np.ndarray, str] | None:
    """The box rule's inertia of ``bad`` (link axes, about its CoM) and its description."""
    box = _link_box(bad.link, model, geometry) if bad.mass >= 0 else None
    if box is None:
        return None
    lower, upper, kind = box
    tensor = box_inertia(bad.mass, lower, upper, bad.com)
    size = " × ".join(f"{s * 1e3:.4g}" for s in upper - lower)
    text = " ".join(f'{k}="{tensor[r, c]:.6g}"' for k, (r, c) in zip(
        KEYS, ((0, 0), (0, 1), (0, 2), (1, 1), (1, 2), (2, 2)), strict=True))
    return tensor, (f"the solid box of its {kind} geometry's bounding box ({size} mm) with "
                    f"its mass, about its CoM, in the link's axes (rpy=\"0 0 0\"): {text}")


def _body_fails(model: pin.Model, link: str) -> bool:
    """Whether the Pinocchio body holding ``link`` (with the links fixed to it) fails the tests
    of :func:`bad_inertials`: only then does the defect reach the dynamics and MuJoCo (a massless
    dummy link merged into a heavy one, as ANYmal's ``base``, does not)."""
    if not model.existFrame(link, pin.FrameType.BODY):
        return True
    inertia = model.inertias[model.frames[model.getFrameId(link, pin.FrameType.BODY)].parentJoint]
    moments = np.linalg.eigvalsh(np.asarray(inertia.inertia))
    return bool(inertia.mass < 0 or (inertia.mass > 0 and (
        moments[0] < -DEFINITE_TOL * max(abs(moments[2]), 1e-300)
        or moments[0] + moments[1] < (1.0 - TRIANGLE_TOL) * moments[2])))


def settle_inertials(xml: str, path: Path, mode: str, model: pin.Model,
                     geometry: tuple[pin.GeometryModel, ...]) -> tuple[str, str] | None:
    """Check the URDF text ``xml`` as Pinocchio loaded it into ``model`` (module docstring).

    Args:
        xml: The URDF text.
        path: Its file (for messages).
        mode: One of :data:`MODES`.
        model: The Pinocchio model built from ``xml`` (link frames).
        geometry: Its collision and visual geometry models, in that order.

    Returns:
        None when nothing is to change; else the repaired URDF text and a note naming every
        link repaired and the inertia written.

    Raises:
        InvalidParameterError: ``mode`` is not one of :data:`MODES`.
        RobotModelError: bad links with ``"refuse"``, or with ``"repair"`` a link the rule
            cannot repair (negative mass, no geometry); names each link, its numbers, what is
            allowed and the replacement.
    """
    if mode not in MODES:
        raise InvalidParameterError("inertias", mode, " or ".join(repr(m) for m in MODES))
    root = ET.fromstring(xml)
    bad = [b for b in bad_inertials(root) if mode != "keep" and _body_fails(model, b.link)]
    if not bad:
        return None
    fixes = {b.link: _replacement(b, model, geometry) for b in bad}
    if mode == "refuse" or any(fix is None for fix in fixes.values()):
        lines = [f"  {b.describe()}; fix: "
                 + (f"e.g. {fix[1]}" if fix else "measure or compute the link's <inertial>; "
                    "no geometry or a negative mass, so no box can stand in")
                 for b, fix in ((b, fixes[b.link]) for b in bad)]
        rule = ("" if mode == "repair" or None in fixes.values() else "; or load with "
                "load_robot(..., inertias=\"repair\") (a robot TOML: inertias = "
                "\"repair\" in [robot]) to write that box inertia for every bad link (an "
                "invented inertia, noted)")
        raise RobotModelError(f"URDF {path}: {len(bad)} link(s) with an inertia no rigid body "
                              f"can have (MuJoCo would refuse them):\n" + "\n".join(lines)
                              + f"\nfix the URDF's <inertial> of these links{rule}")
    notes = []
    for link in root.iter("link"):
        fix = fixes.get(link.get("name", ""))
        inertial = link.find("inertial")
        if fix is None or inertial is None:
            continue
        origin = inertial.find("origin")
        if origin is None:
            origin = ET.SubElement(inertial, "origin", xyz="0 0 0")
        origin.set("rpy", "0 0 0")
        element = inertial.find("inertia")
        if element is None:
            element = ET.SubElement(inertial, "inertia")
        for k, (r, c) in zip(KEYS, ((0, 0), (0, 1), (0, 2), (1, 1), (1, 2), (2, 2)), strict=True):
            element.set(k, repr(float(fix[0][r, c])))
        notes.append((str(link.get("name")), fix[1]))
    shown = "; ".join(f"{name} → {rule}" for name, rule in notes[:SHOWN])
    rest = [name for name, _ in notes[SHOWN:]]
    return ET.tostring(root, encoding="unicode"), (
        f"{REPAIRED_MARK} on {len(notes)} link(s) (inertias=\"repair\"; invented, not "
        f"measured): {shown}" + (f"; and {len(rest)} more by the same rule: {', '.join(rest)}"
                                 if rest else ""))
