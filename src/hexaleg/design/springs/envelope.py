"""Each spring over everything its joint may see: the largest wind-up, its stress, the hard stop.

A part (:class:`~hexaleg.design.springs.parts.SpringPart`) is designed over the gait, but its
joint also sees its full range of motion (the URDF limits), the stand and sphere poses, other
gaits (turning) and the conditions of the robustness maps. :func:`envelope_ranges` collects a
joint's absolute angle ranges with where they come from; :func:`part_envelope` finds, over all of
them, the largest wind-up of the part's torsion spring, its bending stress (Shigley Eq. 10-44,
inner fibre) and static safety ``S_y/σ`` (Eq. 10-57's S_y, as the design uses), the coil's
inside diameter wound up that far (§10-12, ``D' = N_b D/(N_b + θ'_c)``) against the arbor, and,
when the safety is below the design factor or the coil would close onto its arbor, the **hard
stop** that limits the wind-up.

The spring law on a joint whose centre of motion is c (u = q − c; s = +1 for a part acting
``above``, −1 ``below``; ``P`` the part's preload torque, k the bought spring's rate):

* the spring carries P at ``u_P`` (the contact angle ``engage``; for a spring engaged
  throughout, ``free + s P/k_part``), and its wind-up from free is
  ``w(u) = P/k + s (u − u_P)``;
* a spring with a contact angle rests, preloaded, on its stop short of contact: ``w ≥ P/k``;
  a spring engaged throughout goes slack past its free angle (its legs lift off): ``w ≥ 0``;
* torque ``k w``; ``w`` is monotonic in u, so the extremes of each range bound it.

The hard stop (:class:`HardStop`): the allowed stress ``S_y / n_d`` (n_d the design factor) gives
the allowed moment ``M = π d³ S_y/(32 K_i n_d)`` (Eq. 10-44 inverted), wind-up ``M/k`` and the
joint angle ``u = u_P + s (M/k − P/k)`` from each joint's centre. It is a stop on the spring's
moving leg: past it the joint turns on and the spring stays at M, so the stop holds M (a stop on
the joint instead also holds the servo's torque). The arbor bounds the wind-up too: the body
winds down to the inside diameter ``D' − d = D_p (1 + m)`` (the clearance the design demands
over the gait, ``arbor_margin`` m) at ``θ'_c = N_b (D/(D_p (1 + m) + d) − 1)`` turns, the moment
``M = θ'_c d⁴ E/(10.8 D N_b)`` (§10-12's deflection inverted); the stop is at the smaller of the
two wind-ups, and says which bounds it (:attr:`HardStop.limit`). Without it a coil the envelope
winds past that diameter closes onto its arbor (on the default robot's optimal motion the rules
bought a coxa spring whose coil came to 7.34 mm over its 7.50-mm arbor at the URDF limit).
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

from hexaleg.checks import real
from hexaleg.design.springs.materials import material
from hexaleg.design.springs.parts import SpringPart, motion_centres
from hexaleg.design.springs.torsion_spring import (
    WAHL,
    bending_stress,
    deflection_turns,
    inner_fibre_factor,
    wound_diameter,
)
from hexaleg.dynamics.prepare import Prepared
from hexaleg.errors import InvalidParameterError
from hexaleg.quantities import quantity
from hexaleg.robot.model import Robot

URDF = "URDF limits"
STRESS = "design factor"
"""A hard stop set by the spring's stress (:attr:`HardStop.limit`)."""
ARBOR = "arbor"
"""A hard stop set by the coil's clearance over its arbor (:attr:`HardStop.limit`)."""
GAIT = "gait"
POSES = ("stand", "sphere")
"""Poses of the robot checked by default (those it has)."""


@dataclass(frozen=True)
class AngleRange:
    """Absolute angles (rad) one joint may see, ``low ≤ high``, and where they come from."""

    low: float
    high: float
    source: str

    def __post_init__(self) -> None:
        real(f"{self.source} low", self.low)
        real(f"{self.source} high", self.high, low=self.low, allowed=f">= low = {self.low}")
        if not isinstance(self.source, str) or not self.source:
            raise InvalidParameterError("angle range source", self.source, "a non-empty label")


def envelope_ranges(robot: Robot, joints: Iterable[str], *, prepared: Prepared | None = None,
                    poses: Sequence[str] = POSES,
                    extra: Sequence[tuple[str, Mapping[str, tuple[float, float]]]] = ()
                    ) -> dict[str, tuple[AngleRange, ...]]:
    """Joint → every absolute angle range it may see, labelled.

    Args:
        robot: The robot: its URDF limits (finite ones; a joint without is skipped, not
            guessed) and its poses.
        joints: The joints.
        prepared: A gait to include (its joints' ranges, labelled :data:`GAIT`), or None.
        poses: Poses to include as single angles, those of ``robot.poses`` (missing ones are
            skipped).
        extra: ``(label, {joint: (low, high)})`` ranges the caller adds (the robustness maps'
            conditions, a turning gait), rad; joints not named are not in that range.

    Raises:
        UnknownNameError: a joint the robot does not have (lists them).
        InvalidParameterError: an extra range not finite or with low > high.
    """
    m = robot.model
    out: dict[str, list[AngleRange]] = {}
    for j in joints:
        iq = 7 + robot.column(j)
        lo, hi = float(m.lowerPositionLimit[iq]), float(m.upperPositionLimit[iq])
        ranges = out.setdefault(j, [])
        if math.isfinite(lo) and math.isfinite(hi) and lo < hi and hi - lo < 1e3:
            ranges.append(AngleRange(lo, hi, URDF))
        for pose in poses:
            if pose in robot.poses:
                q = float(robot.poses[pose][iq])
                ranges.append(AngleRange(q, q, f"{pose} pose"))
        if prepared is not None:
            col = prepared.q[:, robot.column(j)]
            ranges.append(AngleRange(float(col.min()), float(col.max()), GAIT))
        for label, table in extra:
            if j in table:
                lo_x, hi_x = table[j]
                ranges.append(AngleRange(float(lo_x), float(hi_x), str(label)))
    return {j: tuple(r) for j, r in out.items()}


@dataclass(frozen=True)
class HardStop:
    """The stop limiting a spring's wind-up to the design factor and its arbor's clearance
    (module docstring), SI.

    Attributes:
        angle_from_centre: Joint angle where it must act, rad from each joint's centre of motion.
        angles: Joint → that angle, absolute, rad.
        windup: The spring's wind-up there, rad. torque: The spring's torque it holds, N·m.
        limit: What sets it: :data:`STRESS` (the design factor) or :data:`ARBOR` (the coil's
            clearance over its arbor), whichever comes first.
    """

    angle_from_centre: float
    angles: Mapping[str, float]
    windup: float
    torque: float
    limit: str = STRESS


@dataclass(frozen=True)
class PartEnvelope:
    """One part over its joints' whole envelope (module docstring), SI.

    Attributes:
        group, side, role: The part's.
        max_windup: The largest wind-up from free, rad. max_torque: The spring's torque there, N·m.
        stress: σ there (inner fibre), Pa. yield_strength: S_y, Pa. safety_factor: S_y / σ.
        design_factor: The factor required.
        joint, angle, angle_from_centre, source: Where the largest wind-up is (absolute rad, rad
            from that joint's centre of motion, the range's label).
        by_source: Range label → the smallest safety factor over the part's joints there.
        wound_inner_diameter: Inside coil diameter at ``max_windup``, m.
        arbor_diameter: The spring's arbor, m (0: none).
        stop: The hard stop needed, or None when the safety meets the design factor and the
            coil clears its arbor over the whole envelope.
        problem: Why no stop can help ("" otherwise).
        held_inner_diameter: Inside coil diameter at the largest wind-up the spring reaches —
            its hard stop's where it has one, else ``max_windup``'s —, m.
    """

    group: str
    side: str
    role: str
    max_windup: float
    max_torque: float
    stress: float
    yield_strength: float
    safety_factor: float
    design_factor: float
    joint: str
    angle: float
    angle_from_centre: float
    source: str
    by_source: Mapping[str, float]
    wound_inner_diameter: float
    arbor_diameter: float
    stop: HardStop | None = None
    problem: str = field(default="")
    held_inner_diameter: float = math.nan

    @property
    def meets(self) -> bool:
        """Whether the spring holds the design factor over the whole envelope."""
        return self.safety_factor >= self.design_factor

    @property
    def clears_arbor(self) -> bool:
        """Whether the coil wound as far as it goes (to its hard stop, where it has one) still
        clears its arbor."""
        return self.held_inner_diameter > self.arbor_diameter

    def table(self) -> dict[str, Any]:
        """Every number as ``{value, unit}`` (angles in rad, the wind-up also in deg), for
        design.json's ``envelope``."""
        stop = None if self.stop is None else {
            "angle_from_centre": quantity(self.stop.angle_from_centre, "rad"),
            "angles": {j: quantity(a, "rad") for j, a in self.stop.angles.items()},
            "windup": quantity(self.stop.windup, "rad"),
            "torque": quantity(self.stop.torque, "N·m"), "limit": self.stop.limit,
            "note": "a stop on the spring's moving leg, holding the spring's torque; a stop on "
                    "the joint instead also holds the servo's torque"}
        return {"group": self.group, "side": self.side, "role": self.role,
                "max_windup": quantity(self.max_windup, "rad"),
                "max_windup_deg": quantity(math.degrees(self.max_windup), "deg"),
                "max_torque": quantity(self.max_torque, "N·m"),
                "stress": quantity(self.stress, "Pa"),
                "yield_strength": quantity(self.yield_strength, "Pa"),
                "safety_factor": quantity(self.safety_factor, "1"),
                "design_factor": quantity(self.design_factor, "1"), "meets": self.meets,
                "worst": {"joint": self.joint, "angle": quantity(self.angle, "rad"),
                          "angle_from_centre": quantity(self.angle_from_centre, "rad"),
                          "source": self.source},
                "by_source": {s: quantity(v, "1") for s, v in self.by_source.items()},
                "wound_inner_diameter": quantity(self.wound_inner_diameter, "m"),
                "held_inner_diameter": quantity(self.held_inner_diameter, "m"),
                "arbor_diameter": quantity(self.arbor_diameter, "m"),
                "clears_arbor": self.clears_arbor, "hard_stop": stop, "problem": self.problem}


def _law(part: SpringPart) -> tuple[float, float, float, bool]:
    """(s, u_P, P/k, rests on a stop) of the part's bought spring (module docstring)."""
    assert part.spring is not None
    s = 1.0 if part.side == "above" else -1.0
    pre = part.spring.preload_angle
    if part.engage is not None:
        return s, part.engage, pre, True
    assert part.free is not None
    return s, part.free + s * part.preload_torque / part.rate, pre, False


def _safety(sy: float, sigma: float) -> float:
    """S_y/σ; inf for an unloaded spring."""
    return math.inf if sigma <= 0 else sy / sigma


def part_envelope(part: SpringPart, centres: Mapping[str, float],
                  ranges: Mapping[str, Sequence[AngleRange]], *,
                  design_factor: float | None = None,
                  mirrored: frozenset[str] = frozenset()) -> PartEnvelope | None:
    """The part's spring over its joints' envelope (module docstring).

    Args:
        part: The part (its spring; a part without one — a constant torque, or none fits —
            gives None).
        centres: Joint → its centre of motion in the gait, rad
            (:func:`~hexaleg.design.springs.parts.motion_centres`).
        ranges: Joint → its angle ranges (:func:`envelope_ranges`).
        design_factor: Required S_y/σ; default the spring's design factor.
        mirrored: Joints that count their angle the other way round from the part's design
            (:mod:`hexaleg.robot.mirror`): their angle from the centre is ``c − q``.

    Raises:
        InvalidParameterError: a joint of the part without a centre or without ranges, or a
            design factor below 1.
    """
    spring = part.spring
    if spring is None:
        return None
    factor = spring.design_factor if design_factor is None else real(
        "design_factor", design_factor, low=1.0, allowed=">= 1")
    s, u_p, pre, stopped = _law(part)
    floor = pre if stopped else 0.0
    worst = (-math.inf, "", 0.0, 0.0, "")
    by_source: dict[str, float] = {}
    d, D, k, sy = spring.wire_diameter, spring.mean_diameter, spring.rate, spring.yield_strength
    for j in part.joints:
        if j not in centres or not ranges.get(j):
            raise InvalidParameterError(f"envelope of joint {j}", None,
                                        "its centre of motion and at least one angle range")
        c = float(centres[j])
        for r in ranges[j]:
            for a in (r.low, r.high):
                rel = c - a if j in mirrored else a - c
                w = max(pre + s * (rel - u_p), floor)
                by_source[r.source] = min(by_source.get(r.source, math.inf),
                                          _safety(sy, float(bending_stress(k * w, d, D))))
                if w > worst[0]:
                    worst = (w, j, a, rel, r.source)
    w, joint, angle, rel, source = worst
    torque = k * w
    sigma = float(bending_stress(torque, d, D))
    E = float(material(spring.material).young_modulus(d))
    nb = spring.body_turns

    def inner_at(windup: float) -> float:
        return float(wound_diameter(D, nb, deflection_turns(k * windup, d, D, nb, E))) - d

    inner = inner_at(w)
    limits: list[tuple[float, str]] = []  # (the wind-up allowed, what sets it)
    problem = ""
    if _safety(sy, sigma) < factor:
        m_allow = math.pi * d**3 * sy / (32 * float(inner_fibre_factor(D / d)) * factor)
        limits.append((m_allow / k, STRESS))
        if m_allow / k < pre:
            problem = (f"preloaded beyond the design factor: σ at the preload exceeds S_y/"
                       f"{factor:g}; no stop helps, the spring must be redesigned")
    clear = spring.arbor_diameter * (1 + spring.requirement.arbor_margin)
    if spring.arbor_diameter > 0 and inner < clear:
        turns = nb * (D / (clear + d) - 1)  # §10-12 inverted (module docstring)
        w_arbor = turns * d**4 * E / (WAHL * D * nb) / k
        limits.append((w_arbor, ARBOR))
        if w_arbor < floor and not problem:
            problem = (f"its coil is on its arbor at the preload (inside diameter "
                       f"{inner_at(floor) * 1e3:.2f} mm, the arbor with its clearance "
                       f"{clear * 1e3:.2f} mm); no stop helps, the spring must be redesigned")
    stop = None
    if limits and not problem:
        w_allow, limit = min(limits)
        u = u_p + s * (w_allow - pre)
        stop = HardStop(angle_from_centre=u,
                        angles={j: float(centres[j]) + (-u if j in mirrored else u)
                                for j in part.joints},
                        windup=w_allow, torque=k * w_allow, limit=limit)
    held = inner if stop is None else inner_at(min(w, stop.windup))
    return PartEnvelope(
        group=part.group, side=part.side, role=part.role, max_windup=w, max_torque=torque,
        stress=sigma, yield_strength=sy, safety_factor=_safety(sy, sigma), design_factor=factor,
        joint=joint, angle=angle, angle_from_centre=rel, source=source,
        by_source=dict(sorted(by_source.items(), key=lambda kv: kv[1])),
        wound_inner_diameter=inner, arbor_diameter=spring.arbor_diameter, stop=stop,
        problem=problem, held_inner_diameter=held)


def envelope(parts: Iterable[SpringPart], centres: Mapping[str, float],
             ranges: Mapping[str, Sequence[AngleRange]], *,
             design_factor: float | None = None,
             mirrored: frozenset[str] = frozenset()) -> tuple[PartEnvelope, ...]:
    """:func:`part_envelope` of every part that has a spring, in order."""
    out = (part_envelope(p, centres, ranges, design_factor=design_factor, mirrored=mirrored)
           for p in parts)
    return tuple(e for e in out if e is not None)


def parts_envelope(parts: Sequence[SpringPart], prepared: Prepared, *,
                   extra: Sequence[tuple[str, Mapping[str, tuple[float, float]]]] = (),
                   poses: Sequence[str] = POSES, design_factor: float | None = None,
                   mirrored: frozenset[str] = frozenset()) -> tuple[PartEnvelope, ...]:
    """The pipeline's one call: :func:`envelope` of ``parts`` with their joints' centres of
    motion in ``prepared`` (the gait they were designed on) and every range of
    :func:`envelope_ranges` — URDF limits, ``poses``, that gait, and the labelled ``extra``
    ranges (turning, the robustness maps' conditions; absolute rad); ``mirrored`` as
    :func:`part_envelope`."""
    robot = prepared.robot
    joints = sorted({j for p in parts for j in p.joints}, key=robot.column)
    ranges = envelope_ranges(robot, joints, prepared=prepared, poses=poses, extra=extra)
    return envelope(parts, motion_centres(prepared, joints), ranges, design_factor=design_factor,
                    mirrored=mirrored)
