"""A robot's springs: which joint carries which spring, and their torques and energies.

:class:`SpringSet` maps actuated joint names to springs; given a robot it turns joint trajectories
into the spring torque (T, nj) and stored energy (T, nj) of every joint, in the Pinocchio model's
joint order (zero where no spring sits).
"""

from __future__ import annotations

from collections.abc import Callable, Iterator, Mapping
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import ArrayLike

from hexaleg.checks import finite_array
from hexaleg.config import from_mapping
from hexaleg.errors import ConfigError, InvalidParameterError, UnknownNameError
from hexaleg.robot.springs.dead_zone import DeadZoneSpring
from hexaleg.robot.springs.law import TermSpring

if TYPE_CHECKING:
    from hexaleg.robot.model import Robot

Spring = DeadZoneSpring | TermSpring
"""Any spring law hexaleg has: the paper's dead zone (with α, k₂ and damping) or a family built
from basis terms (linear, preloaded, one-sided, stiffening)."""


ENGAGES_BELOW = ("above", "step_above")
"""Term kinds that act above their angle (the rest of their kind act below it, or everywhere)."""
ENGAGES_ABOVE = ("below", "step_below")


def _term_engages(kind: str, angle: float, lo: float, hi: float) -> bool:
    """Whether a basis term acts somewhere inside the joint's range ``(lo, hi)``."""
    if kind in ENGAGES_BELOW:
        return angle < hi
    if kind in ENGAGES_ABOVE:
        return angle > lo
    return True  # linear, constant: everywhere


def _check_engages(joint: str, spring: Spring, robot: Robot) -> None:
    """Refuse a spring that cannot act anywhere in the joint's range of motion (its URDF
    limits), whatever its family: a dead zone that holds the whole range, a one-sided spring
    whose contact angle lies beyond the range on the side it engages (degrees written as
    radians), stages or preloads past the limits. It could never engage, on any motion, and
    the "saving" would be a silent 0 %. A spring whose magnitudes are all zero is no spring and
    is not refused; terms of zero magnitude do not count."""
    model = robot.model
    iq = model.joints[model.getJointId(joint)].idx_q
    lo, hi = float(model.lowerPositionLimit[iq]), float(model.upperPositionLimit[iq])
    if not (np.isfinite(lo) and np.isfinite(hi) and lo < hi) or abs(hi - lo) > 1e6:
        return  # no limits: any spring may engage
    limits = f"the joint's range [{lo:.4g}, {hi:.4g}] rad (URDF limits)"
    if not np.any(spring.magnitudes()):
        return  # no spring: e.g. a design's group whose geometry never engages in the gait
    if isinstance(spring, DeadZoneSpring):
        low, high = spring.neutral + spring.th_minus, spring.neutral + spring.th_plus
        if low <= lo and high >= hi:
            raise InvalidParameterError(
                f"dead zone of the spring on {joint}", f"[{low:.4g}, {high:.4g}] rad",
                f"a dead zone that ends inside {limits}: this one holds the whole range, so the "
                "spring can never engage; narrow theta_k (or theta_minus/theta_plus) or move its "
                "neutral")
        return
    acting = [(t, x) for t, x in zip(spring.terms(), spring.magnitudes(), strict=True) if x != 0]
    if not acting or any(_term_engages(t.kind, t.angle, lo, hi) for t, _ in acting):
        return
    angles = ", ".join(f"{t.name or t.kind} acts {'above' if t.kind in ENGAGES_BELOW else 'below'}"
                       f" {t.angle:.4g} rad" for t, _ in acting)
    raise InvalidParameterError(
        f"{type(spring).__name__} on {joint}", angles,
        f"a spring that engages inside {limits}: this one acts only beyond the limits, so it "
        "can never engage; give its contact angles (or breakpoints) inside the range, in "
        "radians (absolute joint angles)")


class SpringSet(Mapping[str, Spring]):
    """Springs assigned to actuated joints, keyed by joint name (any number, 0 to all).

    Args:
        springs: Joint name → spring. Names are checked against a robot when it is used.

    Raises:
        InvalidParameterError: a value is not a spring law (:data:`Spring`) or a key not a
            string.
    """

    def __init__(self, springs: Mapping[str, Spring] | None = None) -> None:
        if springs is not None and not isinstance(springs, Mapping):
            raise InvalidParameterError(
                "springs", springs, "a mapping joint name → spring, e.g. {'LF_femur': "
                "DeadZoneSpring(stiffness=0.5, theta_k=0.1)}, a SpringSet, or None")
        items = dict(springs or {})
        for name, spring in items.items():
            if not isinstance(name, str):
                raise InvalidParameterError("joint name", name, "a string")
            if not isinstance(spring, (DeadZoneSpring, TermSpring)):
                raise InvalidParameterError(
                    f"spring on {name}", spring, "a spring law: DeadZoneSpring, LinearSpring, "
                    "PreloadedSpring, OneSidedSpring or StiffeningSpring")
        self._springs = items

    def __getitem__(self, name: str) -> Spring:
        try:
            return self._springs[name]
        except KeyError:
            raise UnknownNameError("sprung joint", name, self._springs) from None

    def __iter__(self) -> Iterator[str]:
        return iter(self._springs)

    def __len__(self) -> int:
        return len(self._springs)

    def __repr__(self) -> str:
        return f"SpringSet({self._springs!r})"

    def dead_zones(self, purpose: str) -> dict[str, DeadZoneSpring]:
        """The springs as dead-zone springs (eq. 8), for ``purpose`` that varies their stiffness.

        Raises:
            InvalidParameterError: a spring of another family; names the joint and ``purpose``.
        """
        for name, spring in self._springs.items():
            if not isinstance(spring, DeadZoneSpring):
                raise InvalidParameterError(
                    f"spring on {name}", type(spring).__name__,
                    f"a DeadZoneSpring ({purpose} varies a dead zone's stiffness)")
        return {n: s for n, s in self._springs.items() if isinstance(s, DeadZoneSpring)}

    @classmethod
    def from_mapping(cls, data: Mapping[str, Mapping[str, object]], where: str = "springs"
                     ) -> SpringSet:
        """Springs from a TOML table of tables, SI units: ``[springs.LF_femur] stiffness = 20.0``.

        Args:
            data: Joint name → table of :class:`DeadZoneSpring` fields.
            where: Where the table came from, for error messages.

        Raises:
            ConfigError: a value has the wrong type. UnknownNameError: an unknown field.
            InvalidParameterError: a value is out of range.
        """
        if not isinstance(data, Mapping):
            raise ConfigError(f"{where}: expected a table of joint tables, got {data!r}")
        springs = {}
        for name, table in data.items():
            try:
                springs[name] = from_mapping(DeadZoneSpring, table, f"{where}.{name}")
            except InvalidParameterError as e:  # the spring's own check: name its table
                if type(e) is not InvalidParameterError:
                    raise
                raise InvalidParameterError(f"{where}.{name}: {e.name}", e.value,
                                            e.allowed) from None
        return cls(springs)

    def columns(self, robot: Robot) -> dict[str, int]:
        """Column of each sprung joint in (…, robot.nj) arrays (its velocity index − 6).

        Raises:
            UnknownNameError: a sprung joint is not an actuated joint of ``robot`` (the message
                lists ``robot.joint_names``).
            InvalidParameterError: a sprung joint has more than one degree of freedom.
        """
        cols = {}
        for name in self._springs:
            robot.column(name)  # raises UnknownNameError listing the joints
            joint = robot.model.joints[robot.model.getJointId(name)]
            if joint.nv != 1:
                raise InvalidParameterError(f"spring on {name}", f"a joint with nv = {joint.nv}",
                                            "a 1-DoF (revolute or continuous) joint")
            cols[name] = joint.idx_v - (robot.model.nv - robot.nj)
            _check_engages(name, self._springs[name], robot)
        return cols

    def _angles(self, robot: Robot, q: ArrayLike, v: ArrayLike | None
                ) -> dict[str, tuple[int, np.ndarray, np.ndarray | None]]:
        """Per sprung joint: (column, angle (T,) rad, velocity (T,) rad/s or None).

        A continuous joint stores (cos θ, sin θ) in q (Pinocchio's RUBZ); its angle is atan2.
        """
        cols = self.columns(robot)
        qa = finite_array("q", q)
        nq, nv = robot.model.nq, robot.model.nv
        if qa.ndim != 2 or qa.shape[1] != nq:
            raise InvalidParameterError("q.shape", qa.shape, f"(T, {nq})")
        va = None
        if v is not None:
            va = finite_array("v", v)
            if va.shape != (qa.shape[0], nv):
                raise InvalidParameterError("v.shape", va.shape, f"({qa.shape[0]}, {nv})")
        out = {}
        for name, c in cols.items():
            joint = robot.model.joints[robot.model.getJointId(name)]
            iq = joint.idx_q
            angle = qa[:, iq] if joint.nq == 1 else np.arctan2(qa[:, iq + 1], qa[:, iq])
            out[name] = (c, angle, None if va is None else va[:, joint.idx_v])
        return out

    def torques(self, robot: Robot, q: ArrayLike, v: ArrayLike | None = None) -> np.ndarray:
        """Spring torques on every actuated joint, N·m.

        Args:
            robot: The robot (each joint's angle and velocity found through Pinocchio's
                ``idx_q``/``idx_v``).
            q: Configurations, shape (T, nq), rad for the joints.
            v: Velocities, shape (T, nv), or None to omit damping.

        Returns:
            Shape (T, robot.nj), columns in ``robot.joint_names`` order; zero where no spring.

        Raises:
            UnknownNameError: a sprung joint is not a joint of the robot (lists the joints).
            InvalidParameterError: wrong shapes, NaN or inf.
        """
        return self._per_joint(robot, q, v, lambda s, angle, vel: s.torque(angle, vel))

    def energies(self, robot: Robot, q: ArrayLike) -> np.ndarray:
        """Stored spring energy per actuated joint, J, shape (T, robot.nj); zero where no spring.

        Args:
            robot: The robot.
            q: Configurations, shape (T, nq).

        Raises:
            UnknownNameError: a sprung joint is not a joint of the robot (lists the joints).
            InvalidParameterError: wrong shape, NaN or inf.
        """
        return self._per_joint(robot, q, None, lambda s, angle, _: s.energy(angle))

    def _per_joint(self, robot: Robot, q: ArrayLike, v: ArrayLike | None,
                   law: Callable[[Spring, np.ndarray, np.ndarray | None], np.ndarray]
                   ) -> np.ndarray:
        """``law(spring, angle, velocity)`` of every sprung joint in its column, (T, nj)."""
        out = np.zeros((np.shape(q)[0], robot.nj))
        for name, (c, angle, vel) in self._angles(robot, q, v).items():
            out[:, c] = law(self._springs[name], angle, vel)
        return out
