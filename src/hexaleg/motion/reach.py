"""Why a gait's foot target is out of reach, and a gait that would reach it.

When the leg inverse kinematics fails while :func:`hexaleg.motion.legged.sample_gait` solves a
leg, :func:`explain` turns the solver's :class:`~hexaleg.errors.UnreachableTargetError` (leg,
time, target, distance) into a :class:`~hexaleg.errors.GaitReachError` that also names the phase,
the gait parameter most likely responsible and a value of it that works.

* **The stand pose** first: the gait takes its footholds (and, unless given, its body height)
  from the ``stand`` pose; a stand whose failing leg is at the edge of its workspace (straight or
  fully folded knee, foot on the first joint's axis: the foot Jacobian's σ_min / σ_max below
  :data:`STRETCHED`; Siciliano et al., *Robotics: Modelling, Planning and Control*, 2009, §3.3,
  kinematic singularities) is the cause, unless ``body_height`` and ``foot_radius`` are both
  given. The remedy, bent knees, is found by trying a few footholds at a fraction of the leg's
  length below and out from its first joint (:data:`STAND_TRIES`, :data:`STAND_TRIES_DOWN`) and
  keeping the first one with which the gait can be generated.
* **A foothold out of reach standing still** (the mid-stance foothold itself fails): the
  ``body_height``, or the ``foot_radius``, the user gave (or the stand pose if neither).
* **In swing with the target high** (at least half the step height above the ground: near the
  top of the step): ``step_height``, then the stride. **Otherwise** (stance, or swing near
  lift-off or touch-down: the ends of the stride): a ``body_height`` or ``foot_radius`` the user
  gave (the body too high or low for the legs), then ``stride_length`` (``speed`` when given),
  then ``step_height``.

A parameter is responsible when a harmless value of it — step height → 0, stride → 0, the stand
pose's body height or foot radius — makes the failing leg's targets reachable; the first in the
order above that passes is named. A bisection (:data:`BISECTIONS` halvings of the interval
between the harmless and the failing value; leg IK on at most :data:`SEARCH_SAMPLES` samples, the
balancing sway, if any, kept as it was when the IK failed) finds the value closest to the user's
that still works; it is rounded to two significant digits towards the harmless value and checked
by generating the whole gait with it (balancing sway included), stepping 10 % and then 50 % of
the way back towards the harmless value if that fails. At most :data:`VERIFICATIONS` gaits are
generated, so the diagnosis is bounded: about ten leg IK solves and one to three gaits.

When no single parameter works — each fixes the failing leg and leaves another leg or sample out
of reach — the step height and the stride are scaled down together (:data:`TOGETHER`, at most
:data:`VERIFICATIONS` more gaits) and the first pair that generates the whole gait is named; the
sized defaults (:mod:`hexaleg.motion.scaling`) take it as they take a single suggestion.
"""

from __future__ import annotations

import dataclasses
import math
from collections.abc import Callable
from typing import NamedTuple

import numpy as np
import pinocchio as pin

from hexaleg.errors import GaitReachError, HexalegError, UnreachableTargetError
from hexaleg.motion.body import heading, nominal_footholds, reference_pose, walk_direction
from hexaleg.motion.kinematics import leg_ik
from hexaleg.motion.params import GaitParams
from hexaleg.robot.model import Robot

Targets = Callable[[GaitParams, int, np.ndarray], tuple[np.ndarray, np.ndarray, np.ndarray]]
"""``targets(gait, leg, index)``: the base-frame targets p, ṗ, p̈ of leg number ``leg`` at the
failing motion's samples ``index`` for another ``gait``."""

STRETCHED = 0.05
"""σ_min / σ_max of the foot's translation Jacobian below which a leg is at its workspace edge
(hexaleg's leg: a knee bent less than about 16° from straight)."""
BISECTIONS = 6
"""Halvings of the interval between the harmless and the failing value (1.6 % of it left)."""
VERIFICATIONS = 3
"""At most this many gaits are generated to check the suggestion (the rest are leg IK solves)."""
SEARCH_SAMPLES = 200
"""At most this many samples (plus the failing one) per leg solve during the search."""
TOGETHER = (0.6, 0.4, 0.25)
"""Factors the step height and the stride are scaled down by together when no single one makes
a gait reachable (each alone fixes one leg or sample and leaves another out: Centauro's swing
too high for a front hip's pitch, its stride too long for a hind hip's yaw)."""
STAND_TRIES = ((0.6, 50.0), (0.6, 35.0), (0.6, 65.0), (0.5, 50.0), (0.7, 50.0), (0.5, 30.0))
"""Bent-knee footholds tried for a stretched stand: (distance from the leg's first joint as a
fraction of the stretched leg's length, angle below the horizontal in degrees) — for legs
stretched sideways (a hexapod's); legs stretched downwards (a quadruped's) try
:data:`STAND_TRIES_DOWN`, feet nearly under the hips."""
STAND_TRIES_DOWN = ((0.75, 80.0), (0.65, 80.0), (0.75, 65.0), (0.6, 50.0), (0.85, 80.0))


def explain(robot: Robot, gait: GaitParams, error: UnreachableTargetError, leg: int,
            t: np.ndarray, stance: np.ndarray, targets: Targets,
            verify: Callable[[GaitParams], bool]) -> GaitReachError:
    """The :class:`GaitReachError` for an IK failure of leg number ``leg`` in a gait.

    Args:
        robot: The robot.
        gait: The failing gait's parameters.
        error: The solver's error (its ``index`` is the failing sample).
        leg: Index of the failing leg in ``robot.legs``.
        t: The sample times, shape (T,), s.
        stance: The leg's stance flags at ``t``, shape (T,).
        targets: The leg targets of other gaits (:data:`Targets`).
        verify: Whether another gait can be generated (the whole gait, balancing sway included;
            called at most :data:`VERIFICATIONS` times).

    Returns:
        The error to raise (``from error``): the solver's message, then the phase, the
        parameter most likely responsible and a value that works (``suggestion``).
    """
    k = error.index if error.index is not None and 0 <= error.index < len(t) else 0
    phase = "stance" if stance[k] else "swing"
    data = _Where(error.leg or robot.legs[leg].name, float(t[k]), k, error.target,
                  error.distance, phase)
    search = _Search(robot, targets, verify, len(t), k)
    ratio, sigma, axis = _stiffness(robot, leg)
    if ratio < STRETCHED and (gait.body_height is None or gait.foot_radius is None):
        return _stand_error(robot, gait, error, leg, search, data, (sigma, axis))
    nominal = nominal_footholds(robot, gait)[leg]
    p = np.asarray(error.target if error.target is not None else nominal)
    lift, along = float(p[2] - nominal[2]), float((p - nominal) @ walk_direction(robot, gait))
    where = (f" — in {phase}, the foot "
             + ("on the ground" if phase == "stance" else f"{lift:.3g} m above the ground")
             + f", {abs(along):.3g} m {'ahead of' if along >= 0 else 'behind'} its mid-stance "
             "foothold.")
    stride = "speed" if gait.speed is not None else "stride_length"
    sizes = [name for name in ("body_height", "foot_radius") if getattr(gait, name) is not None]
    still = search.ok(gait, leg, fixed=nominal)
    if not still:
        order = sizes
    elif phase == "swing" and lift >= 0.5 * gait.step_height:
        order = ["step_height", stride, *sizes]
    else:
        order = [*sizes, stride, "step_height"]
    for name in order:
        harmless = _harmless(robot, gait, name)
        if harmless is None or not search.ok(_with(gait, name, harmless), leg):
            continue
        value = search.bisect(gait, name, harmless, leg)
        if value is None:
            continue
        current = getattr(gait, name)
        why, unit = _why(gait, name, current, harmless, still), "m/s" if name == "speed" else "m"
        message = (f"{error}{where} Most likely cause: {name} = {current:.4g} {unit}, {why}. "
                   f"{name} = {value:g} {unit} would work (GaitParams(..., {name}={value:g}); "
                   "checked by generating the gait with it).")
        return data.error(message, name, float(current), {name: value})
    if not sizes and not still:
        return _stand_error(robot, gait, error, leg, search, data, None)
    tried = ", ".join(order) or "none"
    pair = search.together(gait, ("step_height", stride), leg) if still else None
    if pair is not None:
        units = {"step_height": "m", "stride_length": "m", "speed": "m/s"}
        values = " and ".join(f"{k} = {v:g} {units[k]}" for k, v in pair.items())
        return data.error(
            f"{error}{where} No single gait parameter makes it reachable (tried {tried}: each "
            f"leaves another leg or sample out of reach); {values} together would work "
            f"(GaitParams(..., {', '.join(f'{k}={v:g}' for k, v in pair.items())}); checked "
            "by generating the gait with them).", "step_height", float(gait.step_height), pair)
    return data.error(f"{error}{where} No single gait parameter makes it reachable (tried "
                      f"{tried}); check body_height, foot_radius and the stand pose.",
                      order[0] if order else "stand", getattr(gait, order[0]) if order else None,
                      {})


class _Where(NamedTuple):
    """Where the IK failed: the fields of the :class:`GaitReachError`."""

    leg: str
    t: float
    sample: int
    target: tuple[float, ...] | None
    distance: float | None
    phase: str

    def error(self, message: str, parameter: str, value: float | None,
              suggestion: dict[str, float], stand: np.ndarray | None = None) -> GaitReachError:
        return GaitReachError(message, phase=self.phase, parameter=parameter, value=value,
                              suggestion=suggestion, stand=stand, leg=self.leg, t=self.t,
                              index=self.sample, target=self.target, distance=self.distance)


class _Search:
    """IK checks of one leg's gait targets on a subsample, and a budget of whole gaits."""

    def __init__(self, robot: Robot, targets: Targets, verify: Callable[[GaitParams], bool],
                 n: int, k: int) -> None:
        self.robot, self.targets, self.verify, self.budget = robot, targets, verify, VERIFICATIONS
        self.few = np.unique(np.r_[np.linspace(0, n - 1, min(n, SEARCH_SAMPLES)).round(), k]
                             ).astype(int)

    def ok(self, gait: GaitParams, leg: int, *, fixed: np.ndarray | None = None) -> bool:
        """Whether leg ``leg`` reaches its targets in ``gait`` on the subsample (or the fixed
        point ``fixed``, base frame)."""
        try:
            if fixed is not None:
                p, pd, pdd = fixed[None], np.zeros((1, 3)), np.zeros((1, 3))
            else:
                p, pd, pdd = self.targets(gait, leg, self.few)
            leg_ik(self.robot, self.robot.legs[leg], p, pd, pdd)
        except HexalegError:
            return False
        return True

    def ok_all(self, gait: GaitParams) -> bool:
        """Whether the whole gait can be generated (False once the budget is spent)."""
        self.budget -= 1
        return self.budget >= 0 and self.verify(gait)

    def together(self, gait: GaitParams, names: tuple[str, ...], leg: int
                 ) -> dict[str, float] | None:
        """The step height and the stride scaled down together by the first factor of
        :data:`TOGETHER` with which the failing leg reaches its targets and the whole gait can
        be generated (:data:`VERIFICATIONS` more gaits at most), rounded to two significant
        digits downwards; None when none does."""
        budget = VERIFICATIONS
        for factor in TOGETHER:
            values = {n: _round_toward(float(getattr(gait, n)) * factor, 0.0) for n in names}
            trial = dataclasses.replace(gait, **values)  # type: ignore[arg-type]
            if not self.ok(trial, leg):
                continue
            budget -= 1
            if budget < 0:
                return None
            if self.verify(trial):
                return values
        return None

    def bisect(self, gait: GaitParams, name: str, good: float, leg: int) -> float | None:
        """The value of ``name`` closest to the failing one that works, rounded; None if none."""
        bad = float(getattr(gait, name))
        start = good
        for _ in range(BISECTIONS):
            mid = 0.5 * (good + bad)
            if self.ok(_with(gait, name, mid), leg):
                good = mid
            else:
                bad = mid
        for back in (0.0, 0.1, 0.5):  # off the boundary, towards the harmless value
            value = _round_toward(good + back * (start - good), start)
            if (value > 0 or name in ("stride_length", "speed")) \
                    and self.ok_all(_with(gait, name, value)):
                return value
        return None


def _with(gait: GaitParams, name: str, value: float) -> GaitParams:
    """``gait`` with the field ``name`` set to ``value``."""
    return dataclasses.replace(gait, **{name: value})  # type: ignore[arg-type]


def _round_toward(value: float, toward: float) -> float:
    """``value`` to two significant digits, rounded in the direction of ``toward``."""
    if value == 0.0:
        return 0.0
    step = 10.0 ** (math.floor(math.log10(abs(value))) - 1)
    rounded = (math.floor if toward < value else math.ceil)(value / step) * step
    return float(f"{rounded:.12g}")


def _harmless(robot: Robot, gait: GaitParams, name: str) -> float | None:
    """The value of ``name`` that cannot be the cause (None when there is none to try)."""
    if name == "step_height":
        return gait.step_height * 1e-3
    if name in ("stride_length", "speed"):
        return 0.0
    stand = nominal_footholds(robot, dataclasses.replace(gait, body_height=None,
                                                         foot_radius=None))
    value = (-float(stand[0, 2]) if name == "body_height"
             else float(np.linalg.norm(stand[:, :2], axis=1).mean()))
    return value if value > 0 and value != getattr(gait, name) else None


def _why(gait: GaitParams, name: str, current: float, harmless: float, still: bool) -> str:
    """What the parameter does wrong, in words."""
    if name == "step_height":
        return "a swing too high for the leg (the target is near the top of the step)"
    if name in ("stride_length", "speed"):
        per = f" (stride = speed · period = {gait.stride:.4g} m)" if name == "speed" else ""
        return (f"a stride too long for the leg{per}: the target is at an end of the stride "
                f"(a stance foot is up to β · stride / 2 = {gait.duty_factor * gait.stride / 2:.3g}"
                " m from its mid-stance foothold)")
    size = ("the body too high" if current > harmless else "the body too low") \
        if name == "body_height" else \
        ("the footholds too far out" if current > harmless else "the footholds too close in")
    return f"{size} for the legs " + ("(they run out of room while stepping)" if still else
                                      "(the mid-stance foothold is out of reach standing still)")


def _stiffness(robot: Robot, leg: int) -> tuple[float, np.ndarray, np.ndarray]:
    """σ_min / σ_max of leg ``leg``'s foot Jacobian at the stand pose, its singular values and
    the base-frame direction the foot cannot move along (the left singular vector of σ_min)."""
    model, data = robot.model, robot.model.createData()
    item = robot.legs[leg]
    q = reference_pose(robot)
    pin.computeJointJacobians(model, data, q)
    pin.framesForwardKinematics(model, data, q)
    jac = pin.getFrameJacobian(model, data, item.foot_frame_id,
                               pin.LOCAL_WORLD_ALIGNED)[:3, item.v_index]
    u, sigma, _ = np.linalg.svd(jac)
    ratio = float(sigma[-1] / sigma[0]) if sigma[0] > 0 else 0.0
    return ratio, sigma, u[:, -1] * (1.0 if u[:, -1] @ np.ones(3) >= 0 else -1.0)


def _bent_stands(robot: Robot, leg: int) -> list[tuple[float, float]]:
    """(body_height, foot_radius) of the bent-knee footholds of :data:`STAND_TRIES`, m."""
    model, data = robot.model, robot.model.createData()
    q = reference_pose(robot)
    pin.forwardKinematics(model, data, q)
    hip = np.array(data.oMi[robot.legs[leg].joint_ids[0]].translation)
    reach = robot.foot_positions(q)[leg] - hip
    length = float(np.linalg.norm(reach))
    down = np.linalg.norm(reach[:2]) <= 0.3 * length and reach[2] < 0
    out = hip[:2] if down else reach[:2]
    if np.linalg.norm(out) < 1e-9:
        out = heading(robot)[:2]
    out = out / np.linalg.norm(out)
    tries = []
    for fraction, angle in STAND_TRIES_DOWN if down else STAND_TRIES:
        c, s = math.cos(math.radians(angle)), math.sin(math.radians(angle))
        foot = hip + fraction * length * np.array([c * out[0], c * out[1], -s])
        height, radius = -float(foot[2]), float(np.linalg.norm(foot[:2]))
        if height > 0.01 * length and radius > 0:
            tries.append((float(f"{height:.3g}"), float(f"{radius:.3g}")))
    return tries


def _stand_error(robot: Robot, gait: GaitParams, error: UnreachableTargetError, leg: int,
                 search: _Search, data: _Where, stiff: tuple[np.ndarray, np.ndarray] | None
                 ) -> GaitReachError:
    """The error blaming the stand pose, with bent-knee footholds that walk the gait."""
    name = robot.legs[leg].name
    feet = nominal_footholds(robot, dataclasses.replace(gait, body_height=None, foot_radius=None))
    if stiff is not None:
        sigma, axis = stiff
        state = (f"its legs are at the edge of their workspace, stretched or fully folded (leg "
                 f"{name}: foot Jacobian singular values {_r(sigma, 4)}, the foot cannot move "
                 f"along {_r(axis, 3)})")
    else:
        state = f"the gait's IK cannot reach its leg {name} foot {_r(feet[leg], 4)} m"
    message = (f"{error} — in {data.phase}. Cause: the stand pose: {state}; the gait takes its "
               f"footholds from it (feet {-feet[:, 2].mean() + 0.0:.4g} m below the base).")
    suggestion: dict[str, float] = {}
    stand = None
    for height, radius in _bent_stands(robot, leg):
        trial = dataclasses.replace(gait, body_height=height, foot_radius=radius)
        if search.ok(trial, leg) and search.ok_all(trial):
            suggestion = {"body_height": height, "foot_radius": radius}
            stand = _stand_pose(robot, trial)
            xy = nominal_footholds(robot, trial)[:, :2]
            break
    if suggestion:
        table = ", ".join(f"{leg_.name} = [{', '.join(f'{v:g}' for v in _r(foot, 3))}]"
                          for leg_, foot in zip(robot.legs, xy, strict=True))
        message += (f" Bend the knees: give a stand with the feet below the base, e.g. "
                    f"stand = {{body_height = {height:g}, feet = {{{table}}}}} in the robot's "
                    f"description, or keep this stand and walk with GaitParams(body_height="
                    f"{height:g}, foot_radius={radius:g}) (checked by generating the gait with "
                    "it).")
    else:
        message += " Bend the knees: give a stand with the feet below the base."
    return data.error(message, "stand", None, suggestion, stand)


def _r(x: np.ndarray, digits: int) -> list[float]:
    """``x`` rounded, without negative zeros, as a list (for messages)."""
    return (np.round(np.asarray(x, dtype=float), digits) + 0.0).tolist()


def _stand_pose(robot: Robot, gait: GaitParams) -> np.ndarray | None:
    """The stand configuration (nq,) with every foot on its nominal foothold of ``gait``."""
    q = reference_pose(robot)
    zero = np.zeros((1, 3))
    try:
        for leg, foot in zip(robot.legs, nominal_footholds(robot, gait), strict=True):
            q[leg.q_index] = leg_ik(robot, leg, foot[None], zero, zero)[0][0]
    except UnreachableTargetError:
        return None
    return q
