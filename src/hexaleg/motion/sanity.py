"""Sanity checks of a motion on a robot, as data: joint speeds and angles against the URDF limits,
and the static margin of the gait.

:func:`motion_findings` returns one :class:`~hexaleg.robot.sanity.Finding` per problem (per joint
for the limits, per check for the support) — empty when all is well — and never raises on a bad
motion. Unlike :func:`hexaleg.motion.limits.check_joint_limits`, which stops a motion generator at
the first joint out of its range, it reports every joint with its worst sample. The static margin
is that of :func:`hexaleg.motion.support.static_margins`.
"""

from __future__ import annotations

import numpy as np

from hexaleg.motion.support import static_margins
from hexaleg.motion.trajectory import Motion
from hexaleg.robot.model import Robot
from hexaleg.robot.sanity import Finding

NO_LIMIT = 1e300
"""A URDF limit at or above this (Pinocchio's ``inf`` or largest double for a joint without one)
counts as missing, like a limit ≤ 0."""
MARGIN_TOL = 1e-9
"""Static margins down to ``−MARGIN_TOL`` m count as 0 (on the polygon's edge, e.g. a symmetric
crawl's CoM on the diagonal at a foot switch) rather than negative: rounding, not tipping."""


def motion_findings(robot: Robot, motion: Motion) -> list[Finding]:
    """Every finding of the motion checks; empty when all pass.

    :func:`speed_findings` (joint speeds over the URDF velocity limits, and joints without one),
    :func:`position_findings` (joint angles outside the URDF position limits) and
    :func:`support_findings` (negative static margin, or too few feet without balance).

    Args:
        robot: The robot the motion was made for.
        motion: The motion: ``q`` (T, nq), ``v`` (T, nv), ``t`` (T,) s, ``stance``, ``feet``.
    """
    return [*speed_findings(robot, motion), *position_findings(robot, motion),
            *support_findings(robot, motion)]


def _has_limit(value: float) -> bool:
    """Whether a URDF limit is given: finite, > 0 and below :data:`NO_LIMIT`."""
    return bool(0.0 < value < NO_LIMIT)


def speed_ratio(robot: Robot, v: np.ndarray) -> tuple[float, str | None]:
    """The largest ratio of a joint's peak speed to its URDF velocity limit, and that joint.

    Args:
        robot: The robot (joints without a usable limit, ≤ 0 or ≥ :data:`NO_LIMIT`, are left
            out).
        v: Joint-space velocities of a motion, shape (T, nv), rad/s.

    Returns:
        ``(max_k |q̇_k| / q̇_max,k, joint name)``; ``(0.0, None)`` when no joint has a limit.
    """
    worst, name = 0.0, None
    for joint in robot.joint_names:
        iv = robot.model.joints[robot.model.getJointId(joint)].idx_v
        limit = float(robot.model.velocityLimit[iv])
        if _has_limit(limit):
            ratio = float(np.abs(v[:, iv]).max()) / limit
            if ratio > worst:
                worst, name = ratio, joint
    return worst, name


def speed_findings(robot: Robot, motion: Motion) -> list[Finding]:
    """Joints whose peak speed exceeds the URDF velocity limit (``model.velocityLimit``).

    One finding per joint over its limit, at its fastest sample, and one per joint whose URDF
    gives no usable limit (≤ 0, missing or infinite: its speed is not checked, and says so).
    The remedy's period comes from time scaling: running the same path ``s`` times slower divides
    every joint speed by ``s`` (Hollerbach, "Dynamic scaling of manipulator trajectories", ASME J.
    Dyn. Syst. Meas. Control 106(1), 1984), so ``period ≥ period · max_k |q̇_k| / q̇_max`` brings
    the joint within its limit.
    """
    model, found = robot.model, []
    for name in robot.joint_names:
        iv = model.joints[model.getJointId(name)].idx_v
        limit, speed = float(model.velocityLimit[iv]), np.abs(motion.v[:, iv])
        if not _has_limit(limit):
            found.append(Finding(
                "velocity_limit_missing", f"joint {name}", limit, "rad/s",
                "a URDF velocity limit > 0 rad/s", f"joint speeds of {name} are not checked: "
                f"give it <limit velocity=…> in the URDF (peak speed of this motion "
                f"{speed.max():.4g} rad/s)"))
            continue
        k = int(np.argmax(speed))
        if speed[k] > limit:
            found.append(Finding(
                "joint_speed", f"joint {name} at t = {motion.t[k]:.4g} s", float(speed[k]),
                "rad/s", f"≤ {limit:.4g} rad/s (URDF velocity limit)",
                f"slow the motion: period ≥ {motion.period * speed[k] / limit:.4g} s (now "
                f"{motion.period:.4g} s), or shorten stride_length / lower step_height"))
    return found


def position_findings(robot: Robot, motion: Motion) -> list[Finding]:
    """Joints whose angle leaves the URDF position limits
    (``model.lowerPositionLimit``/``upperPositionLimit``).

    One finding per joint, at its sample farthest outside the range. Joints with more than one
    configuration coordinate (a URDF ``continuous`` joint: cos, sin) have no position limits and
    are skipped, as are limits beyond :data:`NO_LIMIT`.
    """
    model, found = robot.model, []
    for name in robot.joint_names:
        joint = model.joints[model.getJointId(name)]
        if joint.nq != 1:
            continue
        iq = joint.idx_q
        lo, hi, q = model.lowerPositionLimit[iq], model.upperPositionLimit[iq], motion.q[:, iq]
        excess = np.maximum(np.where(abs(lo) < NO_LIMIT, lo - q, -np.inf),
                            np.where(abs(hi) < NO_LIMIT, q - hi, -np.inf))
        k = int(np.argmax(excess))
        if excess[k] > 0:
            found.append(Finding(
                "joint_position", f"joint {name} at t = {motion.t[k]:.4g} s", float(q[k]), "rad",
                f"[{lo:.4g}, {hi:.4g}] rad (URDF position limits)",
                f"change the gait (body_height, foot_radius, stride_length, step_height) or the "
                f"stand pose so that {name} stays inside its limits, or correct the URDF <limit "
                f"lower/upper> of {name} if they are wrong"))
    return found


def support_findings(robot: Robot, motion: Motion) -> list[Finding]:
    """Samples where the stance feet do not statically support the robot.

    The static margin (McGhee & Frank, "On the stability properties of quadruped creeping gaits",
    Math. Biosci. 3, 1968) is the distance of the centre of mass's ground projection inside the
    support polygon of the stance feet (:func:`hexaleg.motion.support.static_margins`).

    * Samples on three or more stance feet: a margin < 0 (below ``−MARGIN_TOL``: the CoM
      outside the polygon, the robot tips over unless it is balanced dynamically) gives one
      ``"static_margin"`` finding, at the worst sample, with the number of such samples.
    * Samples on fewer than three feet have no support polygon. A gait balanced on two feet by
      the body sway (``motion.info["balance"]["mode"] == "sway"``, a trot of
      :func:`hexaleg.motion.legged.tripod_gait`) or on one foot by the ZMP walking pattern
      (``"zmp"``, :mod:`hexaleg.motion.zmp`) is dynamically balanced there and not flagged; any
      other motion gets one ``"static_support"`` finding (value: the fewest stance feet).
    * Samples where the base is held (``motion.supported``, e.g. a fixed-base motion) are skipped.
    """
    free = ~np.asarray(motion.supported)
    counts = motion.stance.sum(axis=1)
    found = []
    polygon = free & (counts >= 3)
    if polygon.any():
        idx = np.flatnonzero(polygon)
        margins = static_margins(robot, motion.q[idx], motion.feet[idx], motion.stance[idx])
        bad = margins < -MARGIN_TOL
        if bad.any():
            k = int(idx[np.argmin(margins)])
            legs = ", ".join(n for n, on in zip(robot.leg_names, motion.stance[k], strict=True)
                             if on)
            found.append(Finding(
                "static_margin", f"CoM at t = {motion.t[k]:.4g} s on feet {legs} "
                f"({int(bad.sum())} of {len(idx)} samples negative)", float(margins.min()), "m",
                "≥ 0 m (the CoM's ground projection inside the stance feet's support polygon)",
                "raise duty_factor (more feet on the ground), widen foot_radius or shorten "
                "stride_length; or balance the gait dynamically"))
    balanced = motion.info.get("balance", {}).get("mode") in ("sway", "zmp")
    few = free & (counts < 3)
    if few.any() and not balanced:
        k = int(np.flatnonzero(few)[np.argmin(counts[few])])
        found.append(Finding(
            "static_support", f"t = {motion.t[k]:.4g} s ({int(few.sum())} of {len(free)} "
            "samples on fewer than 3 feet, no balancing sway)", float(counts[k]), "feet",
            "≥ 3 stance feet (a support polygon), or a dynamically balanced gait",
            "raise duty_factor so that at least three feet stand at every instant, or let "
            "the gait balance dynamically (GaitParams.balance = 'auto': a body sway on two "
            "feet, the ZMP walking pattern on one)"))
    return found

