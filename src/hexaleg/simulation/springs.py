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
``step_above``  the preload's jump at contact, −x for q > a: an actuator with zero    yes
                gain, bias S (a − q) and ``forcerange`` [−x, 0]
``step_below``  +x for q < a: the same bias, ``forcerange`` [0, x]                    yes
damping         of a :class:`~hexaleg.robot.springs.DeadZoneSpring` (only while       no
                engaged): added to ``qfrc_applied`` each step
==============  ==================================================================  ==========

"−∞"/"+∞" are ±:data:`FAR` rad, which no joint reaches. The α transmission of a dead-zone spring
is in its magnitudes (its terms are joint-side). A step is MuJoCo's affine actuator bias clamped
by its force range (XML reference: ``general/biastype="affine"``, ``forcerange``; MuJoCo clamps
the actuator force after adding gain and bias, Computation → Actuation): with the slope
S = x / :data:`STEP_WIDTH` the clamp returns exactly the step's 0 or ±x everywhere except within
:data:`STEP_WIDTH` (1 nrad) past the contact angle, where it ramps between them — far inside the
width of one step of a simulation (q̇ dt ≈ 1e-4 rad). A set whose springs are all native runs
inside MuJoCo's step (and :func:`mujoco.rollout.rollout`); the damping of a dead-zone spring makes
the run step by step in Python (:mod:`hexaleg.simulation.run`):
:func:`SpringPlan.python_torque` is that term.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from hexaleg.robot.model import Robot
from hexaleg.robot.springs import DeadZoneSpring, Spring, SpringSet, Term
from hexaleg.simulation.mjcf import fmt

FAR = 1e6
"""rad: the open end of a one-sided tendon dead band."""
STEP_WIDTH = 1e-9
"""rad: the ramp of a native preload step (module docstring). Its bias S·a − S·q is exact to
about 1e-16·|a| rad in floating point, so the ramp sits where the step is to that precision."""
FOLD = 10.0
"""rad: a constant torque c folds into a joint spring's reference (a + c/x) only while
|c/x| ≤ this; a nearly constant-torque spring keeps its constant as an actuator."""


def tendon_name(joint: str, k: int) -> str:
    """Name of the k-th spring tendon of a joint."""
    return f"{joint}_spring_{k}"


def constant_actuator(joint: str) -> str:
    """Name of the constant-torque actuator of a joint's spring."""
    return f"{joint}_spring_torque"


def step_actuator(joint: str, k: int) -> str:
    """Name of the k-th preload-step actuator of a joint's spring."""
    return f"{joint}_spring_step_{k}"


@dataclass(frozen=True)
class SpringActuator:
    """A spring term as a MuJoCo ``general`` actuator on its joint, without a control: force
    ``b₀ + b₁ q``, clamped to ``force_range`` when it has one (module docstring).

    Attributes:
        name: Actuator name. joint: Its joint.
        bias: ``(b₀, b₁)``: N·m, N·m/rad.
        force_range: ``(low, high)``, N·m, or None (unclamped).
    """

    name: str
    joint: str
    bias: tuple[float, float]
    force_range: tuple[float, float] | None = None

    def xml(self) -> str:
        """The ``<general>`` element."""
        clamp = (f'forcelimited="true" forcerange="{fmt(self.force_range)}"'
                 if self.force_range else 'forcelimited="false"')
        return (f'<general name="{self.name}" joint="{self.joint}" gainprm="0" '
                f'biastype="affine" biasprm="{fmt([*self.bias, 0.0])}" ctrllimited="false" '
                f"{clamp}/>")


def step(joint: str, k: int, kind: str, angle: float, x: float) -> SpringActuator:
    """A preload step ``x ≥ 0`` at ``angle`` (a ``step_above`` or ``step_below`` term) as a
    clamped affine actuator with the ramp :data:`STEP_WIDTH`."""
    slope = x / STEP_WIDTH
    force_range = (-x, 0.0) if kind == "step_above" else (0.0, x)
    return SpringActuator(step_actuator(joint, k), joint, (slope * angle, -slope), force_range)


@dataclass(frozen=True)
class SpringPlan:
    """A :class:`~hexaleg.robot.springs.SpringSet` as MuJoCo elements (module docstring).

    Attributes:
        tendons: ``(joint, low, high, stiffness)`` of each dead-band tendon (N·m/rad, rad).
        stiffness: ``(joint, stiffness, springref)`` of each joint spring (N·m/rad, rad).
        actuators: The constant torques and preload steps as actuators.
        python: ``(column, spring)`` of each dead-zone spring whose damping acts (non-native),
            column in ``robot.joint_names``.
    """

    tendons: tuple[tuple[str, float, float, float], ...] = ()
    stiffness: tuple[tuple[str, float, float], ...] = ()
    actuators: tuple[SpringActuator, ...] = ()
    python: tuple[tuple[int, DeadZoneSpring], ...] = field(default=())

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
        """The ``<general>`` elements of :attr:`actuators`."""
        return "\n".join(a.xml() for a in self.actuators)

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
        for column, damper in self.python:  # the main spring's damping, while engaged (eq. 8)
            delta = float(angles[column]) - damper.neutral
            if delta > damper.th_plus or delta < damper.th_minus:
                out[column] = -damper.transmission * damper.damping * float(velocities[column])
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
    actuators: list[SpringActuator] = []
    python: list[tuple[int, DeadZoneSpring]] = []
    for joint, spring in springs.items():
        terms, x = _terms(spring)
        linear = [i for i, t in enumerate(terms) if t.kind == "linear" and x[i] > 0]
        constant = sum(float(x[i]) for i, t in enumerate(terms) if t.kind == "constant")
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
            else:  # step_above, step_below
                actuators.append(step(joint, i, t.kind, t.angle, float(x[i])))
        if constant != 0.0:
            actuators.append(SpringActuator(constant_actuator(joint), joint, (constant, 0.0)))
        if isinstance(spring, DeadZoneSpring) and spring.damping > 0:
            python.append((columns[joint], spring))
    return SpringPlan(tuple(tendons), tuple(stiffness), tuple(actuators), tuple(python))

