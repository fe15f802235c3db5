"""Sanity checks of joint torques, as data: peak torques against the URDF effort limits.

:func:`torque_findings` returns one :class:`~hexaleg.robot.sanity.Finding` per joint over its
limit — empty when all is well — and never raises on a bad torque: unlike the force solver's
``ContactParams(torque_limits=True)``, which makes the limits constraints (and raises
:class:`~hexaleg.errors.TorqueLimitError` when none can be met), it reports what a motion asks
of the actuators. Pass the motor torques (``Analysis.tau_motor``): the URDF effort limit is the
actuator's; a spring in parallel carries ``Analysis.tau_spring`` on its own.
"""

from __future__ import annotations

import numpy as np

from hexaleg.errors import InvalidParameterError
from hexaleg.motion.sanity import NO_LIMIT
from hexaleg.robot.model import Robot
from hexaleg.robot.sanity import Finding


def torque_findings(robot: Robot, tau: np.ndarray, t: np.ndarray | None = None
                    ) -> list[Finding]:
    """Joints whose peak torque magnitude exceeds the URDF effort limit (``model.effortLimit``).

    A joint is over its limit when ``max_k |τ_k| > τ_max`` (the URDF ``<limit effort>``, the
    largest torque the actuator may apply, ROS URDF specification ``joint/limit``). One finding
    per joint over its limit, at its largest torque. A joint whose URDF gives no usable limit
    (effort ≤ 0, missing or infinite: Pinocchio stores 0 or ``inf``) cannot be checked; it gets a
    finding of its own, ``"effort_limit_missing"``, so that no joint goes unchecked silently.

    Args:
        robot: The robot.
        tau: Joint torques, shape (T, nj), N·m, columns in ``robot.joint_names`` order (e.g.
            ``Analysis.tau_motor``).
        t: Sample times, shape (T,), s, to name the instant; default the sample index.

    Returns:
        The findings; empty when every joint has a limit and stays within it.

    Raises:
        InvalidParameterError: ``tau`` is not (T, nj) or ``t`` not (T,).
    """
    tau = np.asarray(tau, dtype=float)
    if tau.ndim != 2 or tau.shape[1] != robot.nj:
        raise InvalidParameterError("tau", f"array of shape {tau.shape}",
                                    f"shape (T, {robot.nj}): one column per actuated joint")
    if t is not None and np.shape(t) != (tau.shape[0],):
        raise InvalidParameterError("t", f"array of shape {np.shape(t)}",
                                    f"shape ({tau.shape[0]},): one time per torque sample")
    model, found = robot.model, []
    for j, name in enumerate(robot.joint_names):
        limit = float(model.effortLimit[model.joints[model.getJointId(name)].idx_v])
        peak = np.abs(tau[:, j])
        k = int(np.argmax(peak)) if len(peak) else 0
        if not 0.0 < limit < NO_LIMIT:
            found.append(Finding(
                "effort_limit_missing", f"joint {name}", limit, "N·m",
                "a URDF effort limit > 0 N·m",
                f"torques of {name} are not checked: give it <limit effort=…> in the URDF"
                + (f" (peak |τ| here {peak[k]:.4g} N·m)" if len(peak) else "")))
            continue
        if len(peak) and peak[k] > limit:
            when = f"t = {float(t[k]):.4g} s" if t is not None else f"sample {k}"
            found.append(Finding(
                "joint_torque", f"joint {name} at {when}", float(peak[k]), "N·m",
                f"|τ| ≤ {limit:.4g} N·m (URDF effort limit)",
                f"use an actuator rated ≥ {peak[k]:.4g} N·m for {name}, carry part of the load "
                "with a spring, or ask less: slow the gait (inertial torques fall as 1/period², "
                "Hollerbach 1984) or shorten the stride"))
    return found
