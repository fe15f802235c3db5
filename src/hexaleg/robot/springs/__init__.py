"""Springs at the joints: spring laws (one module a family) and the set a robot carries.

Every law is conservative — its torque is −dU/dq exactly — and vectorised over samples. For a
fixed geometry each law is linear in its magnitudes (:mod:`hexaleg.robot.springs.terms`), which is
what the design layer's convex program uses.
"""

from hexaleg.robot.springs.dead_zone import CONVENTIONS, DeadZoneSpring, TorqueBasis
from hexaleg.robot.springs.law import TermSpring
from hexaleg.robot.springs.linear import LinearSpring
from hexaleg.robot.springs.one_sided import SIDES, OneSidedSpring
from hexaleg.robot.springs.preloaded import PreloadedSpring
from hexaleg.robot.springs.spring_set import Spring, SpringSet
from hexaleg.robot.springs.stiffening import StiffeningSpring
from hexaleg.robot.springs.terms import KINDS, Term, basis

__all__ = ["CONVENTIONS", "KINDS", "SIDES", "DeadZoneSpring", "LinearSpring", "OneSidedSpring",
           "PreloadedSpring", "Spring", "SpringSet", "StiffeningSpring", "Term", "TermSpring",
           "TorqueBasis", "basis"]
