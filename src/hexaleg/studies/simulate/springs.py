"""hexaleg's spring laws in MuJoCo: native elements where MuJoCo has them, a force term otherwise.

Every spring family is a sum of basis terms with magnitudes (:mod:`hexaleg.robot.springs.terms`,
``τ(q) = Σ x_b φ_b(q)``); this module builds each term as what MuJoCo computes natively in its
passive forces where it can (MuJoCo documentation, XML reference: ``joint/stiffness`` and
``springref``, ``tendon/fixed`` with a two-valued ``springlength`` dead band):

==============  ==================================================================  ==========
term            MuJoCo element                                                      native
==============  ==================================================================  ==========
``linear``      joint ``stiffness`` x with ``springref`` a (plus a ``constant``     yes
                term of the joint folded into the reference, a + c/x, unless
                |c/x| > :data:`FOLD`)
``above``       fixed tendon L = q, ``stiffness`` x, dead band [−∞, a]: −x (q − a)₊    yes
``below``       fixed tendon, dead band [a, +∞]: +x (a − q)₊                          yes
``constant``    (no linear term to fold into) an actuator with zero gain and bias c   yes
``step_*``      the preload's jump at contact: added to ``qfrc_applied`` each step   no
damping         of a :class:`~hexaleg.robot.springs.DeadZoneSpring` (only while       no
                engaged): added to ``qfrc_applied`` each step
==============  ==================================================================  ==========

"−∞"/"+∞" are ±:data:`FAR` rad, which no joint reaches. The α transmission of a dead-zone spring
is in its magnitudes (its terms are joint-side). A set whose springs are all native runs inside
MuJoCo's step (and :func:`mujoco.rollout.rollout`); any other term makes the run step by step in
Python (:mod:`hexaleg.studies.simulate.run`). :func:`SpringPlan.python_torque` is that term.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from hexaleg.robot.model import Robot
from hexaleg.robot.springs import DeadZoneSpring, Spring, SpringSet, Term
from hexaleg.studies.simulate.mjcf import fmt

FAR = 1e6
"""rad: the open end of a one-sided tendon dead band."""
FOLD = 10.0
"""rad: a constant torque c folds into a joint spring's reference (a + c/x) only while
|c/x| ≤ this; a nearly constant-torque spring keeps its constant as an actuator."""


def tendon_name(joint: str, k: int) -> str:
    """Name of the k-th spring tendon of a joint."""
    return f"{joint}_spring_{k}"


def constant_actuator(joint: str) -> str:
    """Name of the constant-torque actuator of a joint's spring."""
    return f"{joint}_spring_torque"


@dataclass(frozen=True)
class SpringPlan:
    """A :class:`~hexaleg.robot.springs.SpringSet` as MuJoCo elements (module docstring).

    Attributes:
        tendons: ``(joint, low, high, stiffness)`` of each dead-band tendon (N·m/rad, rad).
        stiffness: ``(joint, stiffness, springref)`` of each joint spring (N·m/rad, rad).
        constants: ``(joint, torque)`` of each constant-torque actuator (N·m).
        python: ``(column, terms, magnitudes, damper)`` per joint with non-native parts: the
            step terms with their magnitudes, and the dead-zone spring whose damping acts (or
            None); column in ``robot.joint_names``.
    """

    tendons: tuple[tuple[str, float, float, float], ...] = ()
    stiffness: tuple[tuple[str, float, float], ...] = ()
    constants: tuple[tuple[str, float], ...] = ()
    python: tuple[tuple[int, tuple[Term, ...], np.ndarray, DeadZoneSpring | None], ...] = field(
        default=())

    @property
    def native(self) -> bool:
        """Whether MuJoCo computes every term itself (no per-step Python force)."""
        return not self.python

    def tendon_xml(self) -> str:
        """The ``<tendon>`` section (empty without tendons)."""
        if not self.tendons:
            return ""
        lines = ["<tendon>"]
        for k, (joint, low, high, x) in enumerate(self.tendons):
            lines.append(f'<fixed name="{tendon_name(joint, k)}" stiffness="{fmt(x)}" '
                         f'springlength="{fmt([low, high])}"><joint joint="{joint}" coef="1"/>'
                         "</fixed>")
        lines.append("</tendon>")
        return "\n".join(lines)

    def actuator_xml(self) -> str:
        """``<general>`` actuators of the constant torques (no control: gain 0, bias = τ)."""
        return "\n".join(
            f'<general name="{constant_actuator(j)}" joint="{j}" gainprm="0" biastype="affine" '
            f'biasprm="{fmt([c, 0, 0])}" ctrllimited="false" forcelimited="false"/>'
            for j, c in self.constants)

    def apply(self, model: object) -> None:
        """Set the joint springs (stiffness, springref) in a compiled ``mujoco.MjModel``."""
        import mujoco

        assert isinstance(model, mujoco.MjModel)
        for joint, x, ref in self.stiffness:
            jid = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, joint)
            model.jnt_stiffness[jid] = x
            model.qpos_spring[model.jnt_qposadr[jid]] = ref

    def python_torque(self, angles: np.ndarray, velocities: np.ndarray) -> np.ndarray:
        """The non-native spring torques at one state, shape (nj,), N·m.

        Args:
            angles: Joint angles, shape (nj,), rad, in ``robot.joint_names`` order.
            velocities: Joint velocities, shape (nj,), rad/s.
        """
        out = np.zeros(len(angles))
        for column, terms, x, damper in self.python:
            q, tau = float(angles[column]), 0.0
            for t, xi in zip(terms, x, strict=True):  # step terms: ±x past their angle
                if t.kind == "step_above" and q > t.angle:
                    tau -= float(xi)
                elif t.kind == "step_below" and q < t.angle:
                    tau += float(xi)
            if damper is not None:  # the main spring's damping, while engaged (eq. 8)
                delta = q - damper.neutral
                if delta > damper.th_plus or delta < damper.th_minus:
                    tau -= damper.transmission * damper.damping * float(velocities[column])
            out[column] = tau
        return out


def _terms(spring: Spring) -> tuple[tuple[Term, ...], np.ndarray]:
    """A spring law's basis terms and joint-side magnitudes."""
    return tuple(spring.terms()), np.asarray(spring.magnitudes(), dtype=float)


def plan_springs(robot: Robot, springs: SpringSet | None) -> SpringPlan:
    """How to build ``springs`` in MuJoCo (module docstring).

    Args:
        robot: The robot (checks the sprung joints).
        springs: The springs, or None for none.

    Returns:
        The plan.

    Raises:
        UnknownNameError: a sprung joint that the robot does not have (lists its joints).
    """
    if not springs:
        return SpringPlan()
    columns = springs.columns(robot)
    tendons: list[tuple[str, float, float, float]] = []
    stiffness: list[tuple[str, float, float]] = []
    constants: list[tuple[str, float]] = []
    python: list[tuple[int, tuple[Term, ...], np.ndarray, DeadZoneSpring | None]] = []
    for joint, spring in springs.items():
        terms, x = _terms(spring)
        linear = [i for i, t in enumerate(terms) if t.kind == "linear" and x[i] > 0]
        constant = sum(float(x[i]) for i, t in enumerate(terms) if t.kind == "constant")
        rest: list[int] = []
        for i, t in enumerate(terms):
            if x[i] == 0 or t.kind == "constant":
                continue
            if t.kind == "linear" and i == (linear[0] if linear else -1):
                fold = abs(constant) <= FOLD * x[i]  # not a near-constant-torque spring
                stiffness.append((joint, float(x[i]),
                                  float(t.angle + constant / x[i] if fold else t.angle)))
                constant = 0.0 if fold else constant
            elif t.kind == "linear":
                tendons.append((joint, t.angle, t.angle, float(x[i])))
            elif t.kind == "above":
                tendons.append((joint, -FAR, t.angle, float(x[i])))
            elif t.kind == "below":
                tendons.append((joint, t.angle, FAR, float(x[i])))
            else:
                rest.append(i)
        if constant != 0.0:
            constants.append((joint, constant))
        damper = spring if isinstance(spring, DeadZoneSpring) and spring.damping > 0 else None
        if rest or damper is not None:
            python.append((columns[joint], tuple(terms[i] for i in rest),
                           x[rest], damper))
    return SpringPlan(tuple(tendons), tuple(stiffness), tuple(constants), tuple(python))

