"""Legs and joint classes found from the kinematic tree, for a URDF described in a few lines.

A leg is a chain of 1-DoF joints from a child of the base to a leaf of the tree. Its foot is
found as :mod:`hexaleg.robot.feet` does, and the legs get hexaleg's canonical names from where
their feet are at the zero configuration, seen along the robot's heading: left or right of it,
front to back (``LF LM LH RF RM RH`` for six legs, ``LF RF LH RH`` for four, ``L1 L2 … R1 R2 …``
otherwise). Joint classes are named by their place in the leg: ``coxa femur tibia`` on a hexapod
(the paper's names), ``hip thigh knee`` on other three-joint legs, ``joint1 …`` otherwise.
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np
import pinocchio as pin

from hexaleg.errors import RobotModelError
from hexaleg.robot.feet import LegSpec, SphereFoot, resolve_foot

HEXAPOD_KINDS = ("coxa", "femur", "tibia")
THREE_JOINT_KINDS = ("hip", "thigh", "knee")


def discover_legs(model: pin.Model, collision: pin.GeometryModel, visual: pin.GeometryModel,
                  heading: np.ndarray,
                  wheels: Mapping[str, tuple[np.ndarray, float]] | None = None
                  ) -> tuple[tuple[LegSpec, ...], tuple[str, ...], str, dict[str, SphereFoot]]:
    """The legs of a model with a free-flyer base (joint 1), named from their feet.

    Args:
        model: The model (foot frames are added to it).
        collision: Its collision geometry (for the feet).
        visual: Its visual geometry (when the joint has no collision geometry).
        heading: The base axis pointing forward, shape (3,), horizontal unit vector.
        wheels: Locked wheels by the joint they are welded to: centre, radius
            (:func:`~hexaleg.robot.feet.resolve_foot`).

    Returns:
        The legs (feet resolved, canonical order), the joint classes, a note saying what was
        found, and the round feet by leg (:class:`~hexaleg.robot.feet.SphereFoot`).

    Beside chains that branch (a torso carrying arms and a head) or chains of another length
    (an arm on the back), the legs are the chains that hang below the body (:func:`_legs_among`);
    the others' joints are the robot's joints on no leg.

    Raises:
        RobotModelError: a joint with two children and no legs beside it, fewer than two legs,
            legs of different lengths, or a joint with more than one degree of freedom.
    """
    children: dict[int, list[int]] = {j: [] for j in range(model.njoints)}
    for j in range(2, model.njoints):
        children[model.parents[j]].append(j)
    chains: list[list[int]] = []
    branched: list[list[int]] = []
    for first in children[1]:
        chain = [first]
        while len(children[chain[-1]]) == 1:
            chain.append(children[chain[-1]][0])
        (branched if children[chain[-1]] else chains).append(chain)
    chains, not_legs = _legs_among(model, chains, branched, children)
    for chain in chains:
        for j in chain:
            if model.joints[j].nv != 1:
                raise RobotModelError(f"joint {model.names[j]} has {model.joints[j].nv} degrees "
                                      "of freedom; legs must be chains of 1-DoF joints")
    joints = [tuple(model.names[j] for j in chain) for chain in chains]
    probe = pin.Model(model)  # feet found on a copy to name the legs, then on the model
    provisional = [resolve_foot(probe, collision, visual, LegSpec(f"leg{k}", js), wheels)[0]
                   for k, js in enumerate(joints)]
    names = _names(probe, provisional, heading)
    legs, notes, spheres = [], [], {}
    for i in sorted(range(len(joints)), key=lambda i: _rank(names[i], len(joints))):
        spec, foot_note, sphere = resolve_foot(model, collision, visual,
                                               LegSpec(names[i], joints[i]), wheels)
        legs.append(spec)
        notes.append(foot_note)
        if sphere is not None:
            spheres[spec.name] = sphere
    kinds = default_kinds(len(chains[0]), len(legs))
    found = "; ".join(f"{leg.name} = {', '.join(leg.joints)}" for leg in legs)
    feet = [n for n in notes if n]
    note = (f"legs found from the kinematic tree: {found}; joint classes {', '.join(kinds)}"
            + (f"; not legs (branched, or not hanging below the body): the joints from "
               f"{', '.join(not_legs)}" if not_legs else "")
            + (f"; feet found at the tip of each leg's last link: {', '.join(feet)}"
               if feet else ""))
    return tuple(legs), kinds, note, spheres


LEG_DEPTH = 0.5
"""Beside an arm or a torso, a leg's chain ends at least this share of the deepest chain's
depth below the base at the zero configuration (:func:`_legs_among`)."""


def _legs_among(model: pin.Model, chains: list[list[int]], branched: list[list[int]],
                children: dict[int, list[int]]) -> tuple[list[list[int]], list[str]]:
    """The legs among the chains below the base (joint ids), and the first joints of the rest.

    Every chain unbranched and of one length: all legs (the robots of legs alone). Otherwise —
    an arm on a quadruped's back, a humanoid's torso that branches into arms and a head — the
    legs are the unbranched chains whose last joint hangs at least :data:`LEG_DEPTH` of the
    deepest one's depth below the base at the zero configuration, if they are two or more of
    one length; else the refusal asks for the legs to be listed.

    Raises:
        RobotModelError: no such set of legs (names the branching joint or the lengths).
    """
    legs, rest = chains, [c[0] for c in branched]
    if branched or len({len(c) for c in chains}) > 1:
        data = model.createData()
        pin.forwardKinematics(model, data, pin.neutral(model))
        depth = {c[0]: float(data.oMi[c[-1]].translation[2]) for c in chains}
        deepest = min(depth.values(), default=0.0)
        legs = [c for c in chains if deepest < 0 and depth[c[0]] <= LEG_DEPTH * deepest]
        rest += [c[0] for c in chains if c not in legs]
        if len(legs) < 2 or len({len(c) for c in legs}) != 1:
            if branched:
                at = branched[0][-1]
                names = [model.names[c] for c in children[at]]
                raise RobotModelError(
                    f"joint {model.names[at]} has children {names}: not a chain of leg "
                    "joints, and no two chains of one length hang below the body beside it, so "
                    "legs cannot be found automatically; list them as [[robot.legs]]")
            lengths = {model.names[c[0]]: len(c) for c in chains}
            raise RobotModelError(f"the chains below the base have different lengths {lengths}; "
                                  "list the legs as [[robot.legs]]")
    if len(legs) < 2:
        raise RobotModelError(f"found {len(legs)} chain(s) of joints below the base; a legged "
                              "robot needs two or more: list the legs as [[robot.legs]]")
    return legs, [model.names[j] for j in rest]


def default_kinds(joints: int, legs: int) -> tuple[str, ...]:
    """The joint classes of legs of ``joints`` joints on a robot of ``legs`` legs when the
    description names none: ``coxa femur tibia`` on a hexapod, ``hip thigh knee`` on other
    three-joint legs, ``joint1 …`` otherwise (docs/robots.md)."""
    if joints == 3:
        return HEXAPOD_KINDS if legs == 6 else THREE_JOINT_KINDS
    return tuple(f"joint{i + 1}" for i in range(joints))


def _names(model: pin.Model, specs: list[LegSpec], heading: np.ndarray) -> list[str]:
    """Canonical names from the feet at the zero configuration (module docstring)."""
    data = model.createData()
    pin.framesForwardKinematics(model, data, pin.neutral(model))
    feet = np.array([data.oMf[model.getFrameId(s.foot)].translation for s in specs])
    left = np.cross([0.0, 0.0, 1.0], heading)
    forward, lateral = feet @ heading, feet @ left
    sides = {"L": [i for i in range(len(specs)) if lateral[i] > 0],
             "R": [i for i in range(len(specs)) if lateral[i] <= 0]}
    names = [""] * len(specs)
    for side, members in sides.items():
        members.sort(key=lambda i: -forward[i])
        labels = {4: ("F", "H"), 6: ("F", "M", "H")}.get(len(specs))
        for rank, i in enumerate(members):
            use = labels if labels and len(members) == len(labels) else None
            names[i] = side + (use[rank] if use else str(rank + 1))
    return names


def _rank(name: str, n: int) -> tuple[int, str]:
    """hexaleg's canonical leg order: ``LF LM LH RF RM RH``, ``LF RF LH RH``, else by name."""
    order = {6: ("LF", "LM", "LH", "RF", "RM", "RH"), 4: ("LF", "RF", "LH", "RH")}.get(n, ())
    return (order.index(name), name) if name in order else (len(order), name)
