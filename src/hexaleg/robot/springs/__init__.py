"""Springs at the joints: spring laws (one module a family) and the set a robot carries.

Every law is conservative — its torque is −dU/dq exactly — and vectorised over samples.
"""

from hexaleg.robot.springs.dead_zone import CONVENTIONS, DeadZoneSpring, TorqueBasis
from hexaleg.robot.springs.spring_set import SpringSet

__all__ = ["CONVENTIONS", "DeadZoneSpring", "SpringSet", "TorqueBasis"]
