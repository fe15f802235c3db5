"""Dead zones a sweep refuses up front: one too wide to ever engage on a joint of the robot.

A spring whose dead zone holds a joint's whole range of motion never touches the joint; its
sweep row would read "saving +0.00 %" as if the design had been judged and found useless.
:func:`check_dead_zones` refuses such a grid by name before any point is computed (a single
spring on a robot is checked likewise by :class:`hexaleg.robot.springs.SpringSet`).
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

from hexaleg.errors import InvalidParameterError
from hexaleg.robot.model import Robot
from hexaleg.sweep.spec import SweepSpec


def check_dead_zones(spec: SweepSpec, robot: Robot, groups: Mapping[str, Sequence[str]]
                     ) -> None:
    """Refuse, before any work, a dead zone at least as wide as a joint's whole range of
    motion (its URDF limits): wherever its neutral sits, the spring could never engage on one
    side and the sweep would report a silent "saving +0.00 %" for it.

    Raises:
        InvalidParameterError: names the group, the joint, the value and the joint's range.
    """
    model = robot.model
    def widest(params: Mapping[str, Any], name: str, sign: float) -> float:
        """The grid's value of ``name`` farthest from the neutral on the ``sign`` side."""
        return sign * float(np.max(sign * np.atleast_1d(params[name])))

    for g, params in spec.springs.items():
        if "theta_k" in params:
            plus = widest(params, "theta_k", 1)
            minus, given = -plus, "theta_k"
        elif "theta_plus" in params:
            minus, plus = widest(params, "theta_minus", -1), widest(params, "theta_plus", 1)
            given = "theta_minus/theta_plus"
        else:
            continue
        for joint in groups[g]:
            iq = model.joints[model.getJointId(joint)].idx_q
            span = float(model.upperPositionLimit[iq] - model.lowerPositionLimit[iq])
            if 0 < span < 1e6 and minus <= -span and plus >= span:
                raise InvalidParameterError(
                    f"springs.{g} dead zone", f"[{minus:.4g}, {plus:.4g}] rad ({given})",
                    f"a dead zone that ends within the range of {joint}, {span:.4g} rad wide "
                    "(URDF limits): from any neutral angle in that range, this one holds the "
                    "whole range and the spring can never engage; use smaller values")
