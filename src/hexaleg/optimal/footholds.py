"""The footholds as decisions of the optimal motion: a deterministic search over where the feet
land, each candidate solved by optimal control with its footholds held.

The optimal-control problem (:mod:`~hexaleg.optimal.problem`) holds each stance foot on the point
where its warm start's foot lands, and Crocoddyl fixes the initial state, whose stance feet the
terminal periodicity cost ties to the next cycle's footholds: inside one solve a foothold cannot
move (a foot that lands off it is pulled onto it within one knot, and the stance feet at the
cycle's start are the warm start's). The footholds are therefore moved outside the solve, on the
warm start itself: :func:`moved_footholds` moves each leg's whole foot path by a constant
horizontal offset ``δ_j`` (world axes) and solves the leg's inverse kinematics again, the base's
path unchanged. A constant offset keeps the cycle periodic — the next cycle's foothold is this
one's moved by the stride, as before — and the solve then holds the feet on the moved points.

:func:`search_footholds` chooses the offsets by a compass search (Kolda, Lewis & Torczon,
"Optimization by direct search", *SIAM Review* 45(3), 2003, §3, the coordinate search with a
halving step): the offsets are coordinates on a lattice of ``smallest`` (mirrored legs — ``L…``
and ``R…`` of one name — share their fore-aft offset and mirror their lateral one, so the robot's
left–right symmetry is kept and the coordinates halve), each poll tries every coordinate ± the
step in a fixed order and moves to the first candidate whose value is lower, and the step halves
when none is, down to ``smallest``. The value of a candidate is the caller's (the alternation's
judge: hexaleg's prediction of the solved cycle rebuilt in task space). The answer is the
least value found on the lattice: a local optimum of the lattice, stated as such, the same on any
machine (no random start; integer lattice points, so an input moved by 1e-9 tries the same
candidates).
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
import pinocchio as pin

from hexaleg.checks import integer, positive
from hexaleg.errors import InvalidParameterError
from hexaleg.motion.kinematics import leg_ik
from hexaleg.motion.trajectory import Motion
from hexaleg.robot.mirror import mirror
from hexaleg.robot.model import Robot


def moved_footholds(robot: Robot, motion: Motion, offsets: np.ndarray) -> Motion:
    """``motion`` with each leg's foot moved by a constant horizontal offset, (module docstring).

    The foot's position in the base frame becomes ``p_b + Rᵀ [δ_j, 0]`` (``R`` the base's
    orientation at the sample, from ``q``), with its time derivatives ``ṗ_b − ω × Rᵀδ`` and
    ``p̈_b − ω̇ × Rᵀδ − ω × (−ω × Rᵀδ)`` (``ω`` the base's angular velocity in its own frame,
    ``Ṙᵀ = −[ω]× Rᵀ``; ``p_b``, ``ṗ_b``, ``p̈_b`` the leg's own motion, by Pinocchio's
    kinematics with the base held), and the leg's joints by hexaleg's leg inverse kinematics
    (:func:`~hexaleg.motion.kinematics.leg_ik`). The base and the stance timing are unchanged;
    ``feet`` moves by the offsets; ``info["foothold_offsets"]`` holds them, m.

    Args:
        robot: The robot.
        motion: A periodic motion on the floating base, on level ground (``normal`` None).
        offsets: Each leg's offset in world x and y, (n_legs, 2), m, legs in ``robot.legs``
            order.

    Raises:
        InvalidParameterError: a motion that is not periodic, on a fixed base or on a slope, or
            offsets of another shape or not finite.
        UnreachableTargetError: a moved foot out of its leg's reach or joint limits.
    """
    legs = len(robot.legs)
    offsets = np.asarray(offsets, dtype=float)
    if offsets.shape != (legs, 2) or not np.isfinite(offsets).all():
        raise InvalidParameterError("offsets", offsets.tolist(),
                                    f"finite world x, y offsets of each of the {legs} legs, m")
    if not motion.periodic or motion.fixed_base or motion.normal is not None:
        raise InvalidParameterError("motion", "not periodic on the floating base on level ground",
                                    "a periodic gait on the floating base on level ground")
    model, data = robot.model, robot.data
    n = len(motion.t)
    q, v, a = motion.q.copy(), motion.v.copy(), motion.a.copy()
    p = np.zeros((3, n, legs, 3))  # the feet relative to the base, in its frame: p, ṗ, p̈
    r = np.zeros((3, n, 3, 3))  # Rᵀ δ's factors: Rᵀ, ω, ω̇ (ω the base's, in its frame)
    world = pin.LOCAL_WORLD_ALIGNED
    for k in range(n):
        held = motion.q[k].copy()  # the base at the origin, at rest: the legs' own motion
        held[:7] = pin.SE3ToXYZQUAT(pin.SE3.Identity())
        vk, ak = motion.v[k].copy(), motion.a[k].copy()
        vk[:6] = ak[:6] = 0.0
        pin.forwardKinematics(model, data, held, vk, ak)
        pin.updateFramePlacements(model, data)
        for j, leg in enumerate(robot.legs):
            p[0, k, j] = data.oMf[leg.foot_frame_id].translation
            p[1, k, j] = pin.getFrameVelocity(model, data, leg.foot_frame_id, world).linear
            p[2, k, j] = pin.getFrameClassicalAcceleration(model, data, leg.foot_frame_id,
                                                          world).linear
        r[0, k] = pin.XYZQUATToSE3(motion.q[k, :7]).rotation.T
        r[1, k] = pin.skew(motion.v[k, 3:6])
        r[2, k] = pin.skew(motion.a[k, 3:6])
    for j, leg in enumerate(robot.legs):
        d0 = r[0] @ np.append(offsets[j], 0.0)  # Rᵀ δ, (n, 3)
        d1 = -np.einsum("kij,kj->ki", r[1], d0)  # d/dt Rᵀ δ = −ω × Rᵀ δ
        d2 = -np.einsum("kij,kj->ki", r[2], d0) - np.einsum("kij,kj->ki", r[1], d1)
        q[:, leg.q_index], v[:, leg.v_index], a[:, leg.v_index], _ = leg_ik(
            robot, leg, p[0, :, j] + d0, p[1, :, j] + d1, p[2, :, j] + d2, t=motion.t)
    world = motion.feet + np.concatenate([offsets, np.zeros((legs, 1))], axis=1)
    return dataclasses.replace(motion, q=q, v=v, a=a, feet=world,
                               info={**motion.info, "foothold_offsets": offsets.tolist()})


def mirrored_legs(robot: Robot) -> list[tuple[int, int | None]]:
    """The search's coordinates' legs: ``(j, m)`` pairs in leg order, ``m`` the leg mirrored
    across the sagittal plane (its twin by the hips' geometry,
    :func:`hexaleg.robot.mirror.mirror`, whatever the legs' names) or None when it has none;
    each pair once."""
    names = robot.leg_names
    twins = mirror(robot).twins
    out: list[tuple[int, int | None]] = []
    seen: set[int] = set()
    for j, name in enumerate(names):
        if j in seen:
            continue
        m = None if twins[name] == name else names.index(twins[name])
        out.append((j, m))
        seen.update({j} if m is None else {j, m})
    return out


def _sides(robot: Robot) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The robot's forward and left axes in the plane (its heading, and ``up × heading``), (2,)
    each, and each leg's side, (n_legs,): +1 for a hip left of the base's sagittal plane or on
    it, −1 right of it (the robot standing, its base at the origin: ``stand`` pose, else
    Pinocchio's neutral)."""
    q = robot.pose("stand") if "stand" in robot.poses else pin.neutral(robot.model)
    q = np.array(q, dtype=float)
    q[:7] = [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0]
    pin.forwardKinematics(robot.model, robot.data, q)
    forward = np.asarray(robot.heading, dtype=float)
    left = np.cross([0.0, 0.0, 1.0], forward)
    side = np.array([-1.0 if float(robot.data.oMi[leg.joint_ids[0]].translation @ left) < 0.0
                     else 1.0 for leg in robot.legs])
    return forward[:2], left[:2], side


@dataclass(frozen=True)
class FootholdSearch:
    """The compass search's lattice and steps.

    Attributes:
        step: The first step, m, a multiple of ``smallest``.
        smallest: The lattice's spacing and the last step, m.
        bound: The largest offset of any coordinate, m (the legs' reach bounds it further: a
            candidate out of reach has no value).
        polls: Polls at most (each tries up to two candidates a coordinate).
    """

    step: float = 8e-3
    smallest: float = 2e-3
    bound: float = 0.04
    polls: int = 40

    def __post_init__(self) -> None:
        for key in ("step", "smallest", "bound"):
            positive(f"FootholdSearch.{key}", getattr(self, key))
        integer("FootholdSearch.polls", self.polls, low=1)
        ratio = self.step / self.smallest
        if abs(ratio - round(ratio)) > 1e-9 or round(ratio) & (round(ratio) - 1):
            raise InvalidParameterError("FootholdSearch.step", self.step,
                                        f"a power-of-two multiple of smallest = {self.smallest}")


@dataclass(frozen=True)
class FootholdAnswer:
    """The search's answer.

    Attributes:
        offsets: Each leg's offset, (n_legs, 2), m (world x, y).
        value: Its value (the least found), or None when no candidate, the start included, had
            one.
        start: The start's value.
        tried: Every candidate evaluated in order: ``(offsets (n_legs, 2) m, value or None)``.
        polls: Polls run.
        point: The answer's lattice point (:func:`offsets_of`'s steps).
    """

    offsets: np.ndarray
    value: float | None
    start: float | None
    tried: list[tuple[np.ndarray, float | None]]
    polls: int
    point: tuple[int, ...]


def offsets_of(robot: Robot, point: tuple[int, ...], smallest: float) -> np.ndarray:
    """The legs' offsets in world x and y (n_legs, 2), m, of a lattice point: per
    :func:`mirrored_legs` pair its fore-aft (along the robot's heading) and outward (away from
    the sagittal plane) steps; the mirrored leg takes the same fore-aft step and the same outward
    one on its own side."""
    out = np.zeros((len(robot.legs), 2))
    forward, left, side = _sides(robot)
    for c, (j, m) in enumerate(mirrored_legs(robot)):
        ahead, outward = point[2 * c] * smallest, point[2 * c + 1] * smallest
        for leg in (j,) if m is None else (j, m):
            out[leg] = ahead * forward + outward * side[leg] * left
    return out


def search_footholds(robot: Robot, value: Callable[[np.ndarray], float | None],
                     params: FootholdSearch | None = None,
                     say: Callable[[str], None] | None = None,
                     start: tuple[int, ...] | None = None) -> FootholdAnswer:
    """The compass search over the footholds' offsets (module docstring).

    Args:
        robot: The robot (its legs' names give the mirrored pairs).
        value: A candidate's value from its offsets (n_legs, 2), m: lower is better; None for
            a candidate with none (out of reach, not rebuilt). Called once per lattice point.
        params: The lattice and steps; defaults when None.
        say: Where one line per candidate goes.
        start: The lattice point to start from (:func:`offsets_of`'s steps, two a
            :func:`mirrored_legs` pair, each within the bound); None: no offsets.

    Raises:
        InvalidParameterError: a start of another length or beyond the bound.
    """
    params = params or FootholdSearch()
    tell = say or (lambda _line: None)
    dims = 2 * len(mirrored_legs(robot))
    limit = round(params.bound / params.smallest)
    if start is not None and (len(start) != dims or any(abs(int(c)) > limit for c in start)):
        raise InvalidParameterError("start", start, f"{dims} integer steps, each of at most "
                                                    f"{limit} in size (the bound)")
    known: dict[tuple[int, ...], float | None] = {}
    tried: list[tuple[np.ndarray, float | None]] = []

    def at(point: tuple[int, ...]) -> float | None:
        if point not in known:
            offsets = offsets_of(robot, point, params.smallest)
            known[point] = value(offsets)
            tried.append((offsets, known[point]))
            shown = "—" if known[point] is None else f"{known[point]:.4f}"
            tell(f"candidate {len(tried)}: steps {point} × {1e3 * params.smallest:g} mm: "
                 f"{shown}")
        return known[point]

    best = tuple([0] * dims) if start is None else tuple(int(c) for c in start)
    first = best_value = at(best)
    step = round(params.step / params.smallest)
    polls = 0
    while polls < params.polls:
        polls += 1
        moved = False
        for c in range(dims):
            for sign in (1, -1):
                point = list(best)
                point[c] += sign * step
                if abs(point[c]) > limit:
                    continue
                found = at(tuple(point))
                if found is not None and (best_value is None or found < best_value):
                    best, best_value, moved = tuple(point), found, True
                    break
        if not moved:
            if step == 1:
                break
            step //= 2
    return FootholdAnswer(offsets_of(robot, best, params.smallest), best_value, first, tried,
                          polls, best)
