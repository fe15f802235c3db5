"""What a simulated walk is judged by: energy, tracking, distance, drift, slip, contacts, forces.

All measures are taken over the evaluated window — the last whole cycles of a run, after the
settling cycles — from a :class:`~hexaleg.simulation.stepping.Trajectory`, against the plan
(:class:`~hexaleg.motion.trajectory.Motion`) sampled at the same instants. The energy goes through
the analysis' own energy module (:func:`hexaleg.dynamics.energy.metrics`) with the simulated motor
torques and joint speeds: on the simulation's grid the rectangle rule ``Σ x dt`` of a periodic
window is the trapezoidal rule the analysis uses (:mod:`hexaleg.dynamics.energy`).
"""

from __future__ import annotations

import dataclasses
from collections.abc import Iterator
from dataclasses import dataclass
from typing import Any

import numpy as np

from hexaleg.dynamics import energy
from hexaleg.motion.stands import HOLDS, Stand, longest_stand
from hexaleg.motion.trajectory import Motion
from hexaleg.simulation.model import SimModel
from hexaleg.simulation.stepping import Trajectory, tilt

LOSS_GRACE = 0.02
"""Fraction of a stance at its start and end where a foot not yet / no longer pressing is not
counted as a contact loss (the handover of the load takes the contact's time constant)."""


def planned_index(motion: Motion, t: np.ndarray) -> np.ndarray:
    """The motion's sample at or before each time ``t`` (periodic), shape of ``t``."""
    return np.floor(np.asarray(t) / motion.dt + 1e-9).astype(int) % motion.n_samples


@dataclass(frozen=True)
class Walk:
    """The walk over the evaluated window (SI).

    Attributes:
        distance_per_cycle: Base travel along the heading per cycle, m.
        height_drift: Mean base height minus the planned mean, m.
        roll_max: Largest |roll|, rad. pitch_max: Largest |pitch|, rad.
        tracking_rms: RMS joint-angle error, rad. tracking_max: Largest |error|, rad.
        tracking_rms_joint: RMS error per joint, (nj,), rad.
        slip_max: Largest horizontal foot travel within one stance, m.
        slip_mean: Mean over stances of that travel, m.
        contact_losses: Stance samples (inside the grace margins) with the foot above the
            ground, fraction of such samples.
        stances: Stance phases evaluated.
    """

    distance_per_cycle: float
    height_drift: float
    roll_max: float
    pitch_max: float
    tracking_rms: float
    tracking_max: float
    tracking_rms_joint: np.ndarray
    slip_max: float
    slip_mean: float
    contact_losses: float
    stances: int


DISTANCE_TOLERANCE = 0.10
"""A run "walks" only if its distance per cycle is within this fraction of the planned one (the
tolerance #26 asks for: 10 %). Below :data:`STALL` of it the run stalled; in between, or above
the planned distance by more than this, it fell short or overran."""
STALL = 0.5
"""A run that covers less than this fraction of the planned distance per cycle stalled."""
TRACKING_BOUND = 0.1
"""Largest RMS joint-angle tracking error of a run that "walks", rad (5.7°). A joint error e
moves a foot by about ``l e`` for a leg of length l, so 0.1 rad misplaces the feet by about 10 %
of the leg length — the same order as :data:`DISTANCE_TOLERANCE` of a stride. The default
hexapod tracks at 0.4 mrad (feedforward) and 19 mrad (position servo) RMS
(``analysis/logs/simulate_hexaleg.log``); the 546 mrad of #26's small quadruped is far out."""


def verdict(walked: Walk, planned: float) -> tuple[str, str]:
    """Whether a run that ran to the end walked, and if not what happened.

    Args:
        walked: Its walk over the evaluated cycles.
        planned: The planned distance per cycle, m (0 for a gait in place: distance not judged).

    Returns:
        ``(verdict, message)``: ``"walks"`` and ``""`` when the distance per cycle is within
        :data:`DISTANCE_TOLERANCE` of ``planned`` and the RMS tracking error at most
        :data:`TRACKING_BOUND`; else ``"stalled"`` (under :data:`STALL` of the distance),
        ``"short"`` (under the tolerance), ``"overran"`` (over it) or ``"untracked"`` (distance
        within the tolerance, tracking not), with a message giving the numbers and the bounds.
    """
    d, rms = walked.distance_per_cycle, walked.tracking_rms
    got = (f"it covered {d * 1e3:.1f} mm per cycle of the planned {planned * 1e3:.1f} mm "
           f"({d / planned:.0%})" if planned > 0 else "")
    tracking = (f"RMS joint tracking error {rms * 1e3:.0f} mrad (bound "
                f"{TRACKING_BOUND * 1e3:.0f} mrad)")
    if planned > 0 and d < STALL * planned:
        return "stalled", f"{got}, under {STALL:.0%}; {tracking}"
    if planned > 0 and abs(d / planned - 1) > DISTANCE_TOLERANCE:
        kind = "short" if d < planned else "overran"
        return kind, f"{got}, outside ±{DISTANCE_TOLERANCE:.0%}; {tracking}"
    if rms > TRACKING_BOUND:
        return "untracked", (f"the joints did not follow the gait: {tracking}"
                             + (f"; {got}" if got else ""))
    return "walks", ""


def walk(sim: SimModel, motion: Motion, traj: Trajectory, window: slice, cycles: int,
         q_ref: np.ndarray) -> Walk:
    """The walk measures of ``traj`` over ``window`` (``cycles`` whole cycles).

    Args:
        sim: The model (joint map, robot heading).
        motion: The plan.
        traj: The run.
        window: The evaluated steps.
        cycles: Whole cycles in the window, ≥ 1.
        q_ref: Planned joint angles at every step of the run, shape (n, nj), rad.
    """
    qpos, t, dt = traj.qpos[window], traj.t[window], sim.timestep
    heading = sim.robot.heading
    travel = float((qpos[-1, :3] - qpos[0, :3]) @ heading)
    # the window's last row is one step short of a whole number of cycles: add its velocity
    travel += float(traj.qvel[window][-1, :3] @ heading) * dt
    k = planned_index(motion, t)
    roll, pitch = tilt(qpos)
    err = sim.joints.joints_mj(qpos) - q_ref[window]
    # the plan one step before and after the window: a stance running over its edge is cut
    edges = planned_index(motion, np.r_[t[0] - dt, t, t[-1] + dt])
    stance = motion.stance[edges].astype(bool)
    slips, lost, counted = [], 0, 0
    for leg in range(stance.shape[1]):
        on = np.flatnonzero(np.diff(stance[:, leg].astype(int))) + 1
        starts = [i for i in on if stance[i, leg]]
        ends = [i for i in on if not stance[i, leg]]
        for start in starts:
            end = next((e for e in ends if e > start), None)
            if end is None:  # a stance cut by the window's end
                continue
            start, end = start - 1, end - 1  # rows of the window
            feet = traj.feet[window][start:end, leg, :2]
            slips.append(float(np.max(np.linalg.norm(feet - feet[0], axis=1))))
            grace = int(np.ceil(LOSS_GRACE * (end - start)))
            z = traj.feet[window][start + grace:end - grace, leg, 2]
            lost += int(np.sum(z > 0.0))
            counted += len(z)
    return Walk(distance_per_cycle=travel / cycles,
                height_drift=float(qpos[:, 2].mean() - motion.q[k, 2].mean()),
                roll_max=float(np.abs(roll).max()), pitch_max=float(np.abs(pitch).max()),
                tracking_rms=float(np.sqrt(np.mean(err**2))), tracking_max=float(np.abs(err).max()),
                tracking_rms_joint=np.sqrt(np.mean(err**2, axis=0)),
                slip_max=max(slips, default=0.0),
                slip_mean=float(np.mean(slips)) if slips else 0.0,
                contact_losses=lost / counted if counted else 0.0, stances=len(slips))


def cycle_energies(sim: SimModel, traj: Trajectory, window: slice, cycles: int, motor: Any
                   ) -> list[dict[str, Any]]:
    """:func:`hexaleg.dynamics.energy.metrics` of each evaluated cycle, from the simulated motor
    torques and joint speeds.

    Args:
        sim: The model.
        traj: The run.
        window: The evaluated steps (``cycles`` whole cycles).
        cycles: Cycles in the window.
        motor: The motor model of the analysis (a Motor or a per-joint set).
    """
    tau = traj.tau_motor[window]
    qdot = sim.joints.joints_mj(traj.qvel[window], velocity=True)
    steps = len(tau) // cycles
    return [energy.metrics(tau[c * steps:(c + 1) * steps], qdot[c * steps:(c + 1) * steps],
                           sim.timestep, motor, joint_names=sim.robot.joint_names)
            for c in range(cycles)]


def mean_metrics(cycles: list[dict[str, Any]]) -> dict[str, float]:
    """The per-cycle totals averaged over the cycles (energies J per cycle, torques N·m)."""
    keys = cycles[0]["total"]
    return {key: float(np.mean([c["total"][key] for c in cycles])) for key in keys}


def forward_states(sim: SimModel, traj: Trajectory, rows: np.ndarray) -> Iterator[Any]:
    """MuJoCo's data at each recorded step of ``rows`` after ``mj_forward``: the recorded state
    with the controls and non-native spring torques it was stepped with (one ``mujoco.MjData``,
    refilled for each row: use it before the next)."""
    import mujoco

    m = sim.model
    assert isinstance(m, mujoco.MjModel)
    data = mujoco.MjData(m)
    native = sim.springs.native  # no Python force: qfrc_applied stays zero
    for k in rows:
        data.qpos[:], data.qvel[:] = traj.qpos[k], traj.qvel[k]
        data.ctrl[:sim.robot.nj] = traj.controls[k]
        if not native:
            data.qfrc_applied[sim.joints.dof] = sim.springs.python_torque(
                traj.qpos[k, sim.joints.qpos], traj.qvel[k, sim.joints.dof])
        mujoco.mj_forward(m, data)
        yield data


def contact_forces(sim: SimModel, data: Any) -> np.ndarray:
    """The ground's force on each foot at a computed ``mujoco.MjData`` (after ``mj_forward``):
    MuJoCo's contact force (``mj_contactForce``) of each foot sphere (summed over a sole's
    corners), world frame, shape (n_legs, 3), N, legs in the robot's order; zero for a foot
    without an active contact."""
    import mujoco

    leg_of = {int(g): i for i, leg in enumerate(sim.foot_contacts) for g in leg}
    out = np.zeros((len(sim.foot_contacts), 3))
    n = data.ncon
    if not n:
        return out
    con = data.contact  # the contacts' fields as arrays, read once
    geoms, addresses, frames = con.geom[:n].tolist(), con.efc_address[:n], con.frame[:n]
    wrench = np.zeros(6)
    for c, (g1, g2) in enumerate(geoms):
        leg = leg_of.get(g2, leg_of.get(g1, -1))
        if leg < 0 or addresses[c] < 0:
            continue
        mujoco.mj_contactForce(sim.model, data, c, wrench)
        f = frames[c].reshape(3, 3).T @ wrench[:3]  # force on geom 2 (the foot) from geom 1
        out[leg] += f if g2 in leg_of else -f
    return out


def foot_forces(sim: SimModel, motion: Motion, traj: Trajectory, window: slice,
                predicted: np.ndarray, samples: int = 200) -> dict[str, float]:
    """Simulated ground forces on the stance feet against the analysis', at up to ``samples``
    of the window's steps (:func:`contact_forces` at the recorded state).

    Args:
        sim: The model.
        motion: The plan.
        traj: The run.
        window: The evaluated steps.
        predicted: The analysis' forces, shape (T, n_legs, 3), N.
        samples: Steps compared, ≥ 1.

    Returns:
        ``normal_rms`` and ``tangential_rms`` (N): RMS differences over planned stance feet;
        ``weight`` (N): the robot's weight, for scale; ``normal_mean_sim`` and
        ``normal_mean_predicted`` (N): mean normal force of a stance foot.
    """
    rows = np.arange(window.start or 0, window.stop or traj.n)
    rows = rows[np.linspace(0, len(rows) - 1, min(samples, len(rows))).astype(int)]
    sim_f = np.array([contact_forces(sim, data) for data in forward_states(sim, traj, rows)])
    k = planned_index(motion, traj.t[rows])
    stance = motion.stance[k].astype(bool)
    pred = predicted[k]
    diff = (sim_f - pred)[stance]
    gravity = np.asarray(sim.model.opt.gravity)  # type: ignore[attr-defined]
    return {"normal_rms": float(np.sqrt(np.mean(diff[:, 2] ** 2))),
            "tangential_rms": float(np.sqrt(np.mean(np.sum(diff[:, :2] ** 2, axis=1)))),
            "normal_mean_sim": float(sim_f[stance][:, 2].mean()),
            "normal_mean_predicted": float(pred[stance][:, 2].mean()),
            "weight": float(sim.robot.mass * np.linalg.norm(gravity))}


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
                f"the servos were at their stall torque in {share:.0%} of the steps ({name} "
                f"most, {stall:.3g} N·m{need}): the gait needs a stronger actuator ([motor], "
                "or the robot's own), a slower or shorter gait, or a lighter robot")
        first = float(traj.t[int(np.flatnonzero(at_stall.any(axis=1))[0])])
        stalled = (f"the servos were at their stall torque in {share:.0%} of the steps "
                   f"({name} most, {stall:.3g} N·m) from {first:.2f} s, the fall at "
                   f"{float(traj.t[-1]):.2f} s, but its planned peak command is {peak:.3g} "
                   f"N·m, {peak / stall:.0%} of it: they stalled correcting an error that "
                   "grew, not for the gait's demand, so a stronger actuator is not the fix; ")
    cause = _unbalanced(sim, motion, feedback)
    return dataclasses.replace(cause, message=stalled + cause.message)


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
