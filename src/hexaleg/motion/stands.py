"""A gait's longest stand on its fewest point feet (one or two), as a linear inverted pendulum.

On one point contact the ground's force passes through the foot, so the body's angular momentum
about the foot changes by gravity alone, ``L̇ = m g × (c − p)``: the centre of mass c moves off
the foot p as ``c̈ = ω₀² (c − p)``, ``ω₀ = √(g / h)``, h the centre of mass's height over the
foot (the linear inverted pendulum: Kajita, Kanehiro, Kaneko, Yokoi & Hirukawa, "The 3D linear
inverted pendulum mode", IROS 2001, eq. 5–6), and an error of the plan grows as ``e^{ω₀ t}``.
On two point feet the forces pass through the line between them, so the same holds across that
line (the moment about it is gravity's alone: the trot's diagonal, the bound's line across the
body). No force at the feet rights it; the field balances such a robot by where it sets the
next foot down (the capture point ``c + ċ/ω₀``: Pratt, Carff, Drakunov & Goswami, "Capture
point: a step toward humanoid push recovery", Humanoids 2006; Raibert, *Legged robots that
balance*, 1986) within a stand short against ``1/ω₀``, or by an ankle torque on a sole.

:data:`HOLDS` is how long a stand on two point feet the simulated balance controller
(:mod:`hexaleg.simulation.balance`) holds; the default gaits sized to a robot
(:mod:`hexaleg.motion.scaling`) keep their stands within it.
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass

import numpy as np
import pinocchio as pin

from hexaleg.motion.trajectory import Motion
from hexaleg.robot.model import Robot
from hexaleg.units import G

HOLDS = 2.0
"""ω₀ T: a stand on two point feet of this many of the pendulum's time constants (an error
×e² ≈ 7.4 over it) is one the balance controller holds, measured: the registered quadrupeds'
own trots stand ω₀ T = 1.4–1.6, and the X-configured and pitch–roll–yaw test quadrupeds' trots
walk at the periods that make it 2.0 (0.86 s and 0.52 s) and at 1.9 and 2.3 (0.8 s and 0.6 s),
under both servos (``docs/simulate.md``, "Stands on two point feet")."""


@dataclass(frozen=True)
class Stand:
    """A gait's longest stand on its fewest point feet (one or two), as a linear inverted
    pendulum (module docstring).

    Attributes:
        duration: The longest time on those feet, s.
        height: The centre of mass's height over the stance feet at the gait's start, m.
        omega: ω₀ = √(g / h), 1/s.
        feet: 1 or 2.
        period: The gait's period, s.
    """

    duration: float
    height: float
    omega: float
    feet: int = 1
    period: float = 0.0

    @property
    def growth(self) -> float:
        """``e^{ω₀ T}``: how much an error grows over the stand."""
        return float(np.exp(self.omega * self.duration))

    @property
    def constants(self) -> float:
        """``ω₀ T``: the stand in the pendulum's time constants."""
        return self.omega * self.duration

    @property
    def holding_period(self) -> float:
        """The period, s, at which the stand lasts :data:`HOLDS` time constants (the stand
        scales with the period at a fixed duty factor)."""
        return self.period * HOLDS / self.constants


def longest_stand(robot: Robot, motion: Motion) -> Stand | None:
    """The longest stand of ``motion`` on its fewest feet (cyclic), one or two, or None where
    it always stands on three or more (:class:`Stand`); with two, a stand is a run of samples
    on the same two feet. None too for a robot whose every foot has a sole
    (:mod:`hexaleg.robot.soles`): its centre of pressure moves within the soles, so no stand of
    it is an inverted pendulum on a point or a line.

    Args:
        robot: The robot the motion is for.
        motion: One cycle of its gait (``stance``, shape (T, n_legs); ``feet``, shape
            (T, n_legs, 3), m; ``q[0]`` for the centre of mass).
    """
    stance = np.asarray(motion.stance, dtype=bool)
    counts = stance.sum(axis=1)
    fewest = int(counts.min())
    if fewest not in (1, 2) or len(robot.soles) == len(robot.legs):
        return None
    weights = 1 << np.arange(stance.shape[1])
    feet = np.where(counts == fewest, stance @ weights, -1)  # the feet's set as bits, or −1
    if (feet == feet[0]).all():
        longest = len(feet)
    else:
        start = int(np.flatnonzero(feet != feet[-1])[0])  # a run's first sample: none wraps
        rolled = np.roll(feet, -start)
        edges = np.flatnonzero(np.diff(np.r_[-2, rolled, -2]))  # where the feet change
        longest = max(int(b - a) for a, b in itertools.pairwise(edges) if rolled[a] >= 0)
    model = robot.model
    com = pin.centerOfMass(model, model.createData(), motion.q[0])
    height = float(com[2] - np.mean(np.asarray(motion.feet)[0, stance[0], 2]))
    return Stand(longest * motion.dt, height, float(np.sqrt(G / max(height, 1e-6))),
                 fewest, motion.period)
