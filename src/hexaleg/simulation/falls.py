"""Why a simulated run fell: servos at stall for the gait's demand or correcting an error that
grew, a stand on point feet the balance controller cannot hold (an inverted pendulum, Kajita et
al., IROS 2001), the missing balance feedback of an open loop, or the ground and the gains —
with what to change (:func:`fall_cause`). The measures of a run that walked are in
:mod:`hexaleg.simulation.measures`.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np

from hexaleg.motion.stands import HOLDS, Stand, longest_stand
from hexaleg.motion.trajectory import Motion
from hexaleg.simulation.model import STABILITY, SimModel, contact_point_limit
from hexaleg.simulation.stepping import Trajectory

SATURATED = 0.1
"""A run whose servos sat at their stall torque for more than this fraction of the steps before
it fell for want of torque (:func:`fall_cause`)."""
PLANNED_STALL = 0.9
"""A fall with the servos at stall is put down to the actuator when the plan's peak command on
the joint most at stall reaches this fraction of its stall torque; under it, to the error the
servos were correcting (:func:`fall_cause`). 0.9: the servos' PD correction and the tracking
error on top of the plan take the rest."""


TIPS = 3.0
"""ω₀ T beyond which a fall closed loop is blamed on a stand on two point feet (an error ×e³ ≈
20 over it): the two test quadrupeds' default trots, which fell, stand 5.4 (X-configured,
×227) and 5.5 (pitch–roll–yaw, ×245); between HOLDS and this the cause is not claimed."""


@dataclass(frozen=True)
class PointFoot(Stand):
    """A gait's longest stand on its fewest point feet (one or two), as a linear inverted
    pendulum (:mod:`hexaleg.motion.stands`: Kajita et al., IROS 2001), with what the balance
    controller makes of it."""

    @property
    def too_long(self) -> bool:
        """Whether the stand is beyond what the balance controller holds: one point foot at
        all (no force there rights the body, :class:`PointFoot`), two beyond :data:`TIPS`."""
        return self.feet == 1 or self.omega * self.duration > TIPS

    @property
    def reason(self) -> str:
        """Why balance feedback without foot placement cannot hold it, in one clause."""
        if self.feet == 1:
            return (f"on one point foot for {self.duration:.3g} s, an inverted pendulum (an "
                    f"error ×{self.growth:.3g}) that feedback without foot placement cannot "
                    "hold")
        return (f"on two point feet for {self.duration:.3g} s, an inverted pendulum across the "
                f"line between them (an error ×{self.growth:.3g}); a period of "
                f"{self.holding_period:.2g} s or less would hold it")


def point_foot(sim: SimModel, motion: Motion) -> PointFoot | None:
    """The longest stand of ``motion`` on its fewest feet (cyclic), one or two, or None where
    it always stands on three or more (:func:`hexaleg.motion.stands.longest_stand`)."""
    stand = longest_stand(sim.robot, motion)
    return None if stand is None else PointFoot(**dataclasses.asdict(stand))


def _pace(stand: PointFoot | None) -> str:
    """The advice on the gait's pace after a fall the balance controller did not hold: a
    slower gait on three or more feet; on two point feet a slower gait lengthens the stands,
    an inverted pendulum's (:class:`~hexaleg.motion.stands.Stand`), so a shorter period where
    they are beyond :data:`HOLDS`, else a gait on more feet."""
    if stand is None:
        return "or try a slower gait"
    if stand.constants > HOLDS:
        return (f"or try a period of {stand.holding_period:.2g} s or less (its stands on two "
                f"point feet last {stand.constants:.2g} time constants of the inverted "
                f"pendulum, ω₀ = √(g/h); the controller holds {HOLDS:g}); a slower gait "
                "lengthens them")
    return (f"or a gait on three or more feet ([gait] duty_factor ≥ 0.75); a slower gait "
            f"lengthens its stands on two point feet ({stand.constants:.2g} time constants of "
            f"the inverted pendulum, ω₀ = √(g/h), where the controller holds {HOLDS:g})")


@dataclass(frozen=True)
class FallCause:
    """Why a run fell (:func:`fall_cause`).

    Attributes:
        message: The cause in words, with what to change.
        stand: The stand on point feet the fall is put down to (:class:`PointFoot`), whose
            :attr:`~PointFoot.reason` a design's "unproven" line carries; None where the cause
            is elsewhere (servos at stall for the gait's demand, the ground, the gains, an open
            loop)."""

    message: str
    stand: PointFoot | None = None


def fall_cause(sim: SimModel, motion: Motion, traj: Trajectory, feedback: bool = False,
               planned: np.ndarray | None = None) -> FallCause:
    """Why a run fell, as far as the run shows it: servos at their stall torque where the plan
    asks for it (a weaker actuator than the gait needs), or — open loop (``feedback`` False) —
    a gait that stands on two feet or fewer (balanced by its plan alone: the servos follow the
    joints without feedback on the body's attitude, so an error grows until the body tips — the
    analysis of such a gait stands, its open-loop simulation cannot; ``[simulate] feedback =
    "on"`` closes the loop); with balance feedback, a gait that stands on one point foot
    (:class:`PointFoot`: an inverted pendulum the contact force cannot right, the error's
    growth over the stand named); else the ground, the servo's gains (``[simulate]``) and, with
    balance feedback, its gains.

    Servos at stall are a cause only when the plan drives them there: with ``planned`` (the
    analysis' motor torques, shape (T, nj), N·m) the joint most at stall's planned peak command
    ``|τ + D q̇|`` (the torque and the back-EMF the servo's voltage must overcome at the planned
    speed: the servo model's ``u``, :class:`~hexaleg.simulation.stepping.Trajectory`) is
    compared with its stall torque. Under :data:`PLANNED_STALL` of it the stall came with the
    fall — the servos correcting an error that grew, not the gait's demand — and the message
    says so with both torques and when the stall began and the fall came, then gives the cause
    the run shows otherwise (a stronger actuator would not be the first fix; issue #55: a
    planned peak a third of the stall torque was told to buy a stronger one)."""
    chatter = _chattered(sim, motion)
    at_stall = np.abs(traj.servo) >= sim.stall * (1.0 - 1e-6)
    share = float(at_stall.any(axis=1).mean())
    stalled = ""
    if share > SATURATED:
        j = int(np.argmax(at_stall.mean(axis=0)))
        name, stall = sim.robot.joint_names[j], float(sim.stall[j])
        peak = None if planned is None else float(np.max(np.abs(
            np.asarray(planned)[:, j] + sim.damping[j] * np.asarray(motion.v)[:, 6 + j])))
        if peak is None or peak >= PLANNED_STALL * stall:
            need = ("" if peak is None else f"; its planned peak command {peak:.3g} N·m, "
                    f"{peak / stall:.0%} of it")
            return FallCause(
                f"{chatter}the servos were at their stall torque in {share:.0%} of the steps "
                f"({name} most, {stall:.3g} N·m{need}): the gait needs a stronger actuator "
                "([motor], or the robot's own), a slower or shorter gait, or a lighter robot")
        first = float(traj.t[int(np.flatnonzero(at_stall.any(axis=1))[0])])
        stalled = (f"the servos were at their stall torque in {share:.0%} of the steps "
                   f"({name} most, {stall:.3g} N·m) from {first:.2f} s, the fall at "
                   f"{float(traj.t[-1]):.2f} s, but its planned peak command is {peak:.3g} "
                   f"N·m, {peak / stall:.0%} of it: they stalled correcting an error that "
                   "grew, not for the gait's demand, so a stronger actuator is not the fix; ")
    cause = _unbalanced(sim, motion, feedback)
    return dataclasses.replace(cause, message=chatter + stalled + cause.message)


def _chattered(sim: SimModel, motion: Motion) -> str:
    """Where the timestep is past a ground contact's explicit-stability limit at its contact
    point's own effective mass (:func:`hexaleg.simulation.model.contact_point_limit`), a
    clause saying so with the timestep to give, else "". Unitree G1's toe corners at the
    automatic 0.2 ms (limit 0.1 ms): their forces jumped 0 ↔ 1.6 kN between steps from the
    start, and it fell within 0.6 s under either servo, open or closed loop; at 40 µs they load
    smoothly. Not claimed as the cause: ANYmal's point feet are past it at the automatic
    timestep too and walk."""
    limit, point, mass = contact_point_limit(sim, motion)
    dt = sim.timestep
    if dt <= limit:
        return ""
    safe, _, _ = contact_point_limit(sim, motion, STABILITY)
    return (f"the timestep {dt:.3g} s is past the explicit-stability limit {limit:.3g} s of the "
            f"ground contact of {point} at its own effective mass {mass:.3g} kg (the foot "
            "turning about the joint above it; b dt² + 2 a dt < 4, a = B/m, b = K/m, "
            "hexaleg.simulation.model.contact_point_limit), where its force can chatter: "
            f"[simulate] timestep = {0.8 * safe:.2g} (0.8 of the limit at hexaleg's margin "
            f"b dt² + 2 a dt ≤ {STABILITY:g}, as the automatic timestep's) rules that out; ")


def _unbalanced(sim: SimModel, motion: Motion, feedback: bool) -> FallCause:
    """Why a run whose servos the plan does not drive to stall fell (:func:`fall_cause`)."""
    feet = int(motion.stance.sum(axis=1).min())
    one = point_foot(sim, motion) if feedback else None
    if one is not None and one.feet == 1:
        return FallCause(
            f"the gait stands on one point foot for {one.duration:.3g} s at a time: an "
            "inverted pendulum whose contact force passes through the foot and cannot right "
            f"it, so an error grows as e^(ω₀t), ω₀ = √(g/h) = {one.omega:.3g} /s (centre of "
            f"mass {one.height * 1e3:.0f} mm above the foot), ×{one.growth:.3g} over the stand; "
            "the balance controller (hexaleg.simulation.balance) moves the forces, not where "
            "the feet land (capture-point stepping), so it cannot hold it (point-foot bipeds "
            "walk with stands short against 1/ω₀ and stepping feedback, humanoids on soles "
            "with ankles); a slower gait makes it worse", one)
    if one is not None and one.too_long:
        return FallCause(
            f"the gait stands on two point feet for {one.duration:.3g} s at a time: across the "
            "line between them the body is an inverted pendulum whose contact forces pass "
            "through that line and cannot right it, so an error grows as e^(ω₀t), ω₀ = √(g/h) "
            f"= {one.omega:.3g} /s (centre of mass {one.height * 1e3:.0f} mm above the feet), "
            f"×{one.growth:.3g} over the stand, more than the balance controller "
            "(hexaleg.simulation.balance) holds; a shorter period "
            f"({one.holding_period:.2g} s or less, the stand then {HOLDS:g}/ω₀) would; a "
            "slower gait makes it worse", one)
    if feedback:
        return FallCause(
            "the balance controller (hexaleg.simulation.balance) did not hold the body on this "
            f"gait ({feet} stance feet at the fewest); check the ground ([simulate] stiffness, "
            f"damping, mu) and the servo gains (kp_scale, kd_scale), {_pace(one)}")
    if feet <= 2:
        return FallCause(
            f"the gait stands on {'one foot' if feet == 1 else f'{feet} feet'} at times and is "
            "balanced by its plan alone; the simulated servos follow the joints without "
            "feedback on the body's attitude, so an error grows until it tips (a trot, a bound "
            "or a walk on one foot needs balance feedback: [simulate] feedback = \"auto\" or "
            "\"on\"), or simulate a gait on three or more feet ([gait] pattern = \"crawl\" or "
            "duty_factor ≥ 0.75) — the analysis of this one stands")
    return FallCause("check the ground ([simulate] stiffness, damping) and the servo gains "
                     "(kp_scale, kd_scale) against the robot's weight")
