"""Balance feedback in the simulated robot: the body's measured pose and velocity fed back into the
stance feet's forces and the swing feet's placement, through the robot's own servos.

The controller of the field's whole-body controllers, reduced to the change from the plan (the
plan's inverse dynamics are already the feedforward):

1. **Body wrench** (Di Carlo et al., "Dynamic locomotion in the MIT Cheetah 3 through convex
   model-predictive control", IROS 2018, eq. 4–5, the PD on the body of its balance
   controller; Kim et al., "Highly dynamic quadruped locomotion via whole-body impulse control
   and model predictive control", arXiv:1909.06586, 2019, §III-C, the body task of WBIC):

       ΔF = m (k_p e_p + k_d e_v),    ΔM = I_w (k_p e_R + k_d e_ω),
       e_p = p* − p,  e_v = ṗ* − ṗ,   e_R = log(R* Rᵀ),  e_ω = ω* − ω     (world frame)

   with ``p`` the base origin, ``R`` its orientation, ``*`` the plan at the same instant, m the
   robot's mass and ``I_w = R I_b Rᵀ`` its centroidal rotational inertia (``pin.ccrba`` at the
   plan's first sample, in the base frame: constant, as the MIT controllers take it). The
   desired wrench is the plan's (its inverse dynamics' contact wrench) plus ``ΔW = (ΔF, ΔM)``.
2. **Force distribution** (:mod:`hexaleg.simulation.distribution`): the change ``Δf`` of the
   planned stance feet's forces that makes ``ΔW`` within the friction cones and the servos'
   torque limits (a QP).
3. **Joint torques** (Del Prete, Nori, Metta & Natale, "Prioritized motion–force control of
   constrained fully-actuated robots: Task Space Inverse Dynamics", Robotics and Autonomous
   Systems 63, 2015 — TSID's ``Mv̇ + h = Sᵀτ + J_cᵀ f``: at the plan's accelerations, a change of the
   contact forces is a change ``Δτ = −J_cᵀ Δf`` of the joint torques, ``J_c`` the stance feet's
   Jacobians' joint columns — MIT's ``τ = Jᵀ Rᵀ f`` with the sign of the ground's force on the
   foot), at the plan's joint angles.
4. **Swing feet: foot placement** (a gait on two point feet at times and never on one: a trot, a
   pace, a bound; "Footholds" below): Raibert's foot placement, its lead bounded by the linear
   inverted pendulum's deadbeat step, blended into the swing and released over the next stance
   (:mod:`hexaleg.simulation.foot_placement`).

**Soles** (:mod:`hexaleg.robot.soles`). A foot with a sole enters the force program as its four
corners, each with its own force in its own friction cone — the exact contact wrench of a
rectangle (Caron, Pham & Nakamura, ICRA 2015) — so the correction moves the sole's centre of
pressure within it (an ankle torque) and never past its edge; the plan's force at the sole's
centre is the corners' four equal shares. A corner's Jacobian is the foot's ``J_v − [R_f c]×
J_ω`` (its lever ``R_f c`` from the foot frame). A swinging sole turns to its planned
orientation in the world too (``J_ω Δq = log(Rᵀ R*)``, the 6-row inverse of its leg's Jacobian),
so it lands flat.

**Footholds.** Where a gait does not step for balance the swing feet keep the plan's
footholds: each aims at its planned world pose from the measured body, :data:`FOOTHOLD` of its
error per update (``Δq = J_b⁺ (Rᵀ (x* − p) − R*ᵀ (x* − p*))``, a sole's orientation as above),
so a body that lags or leans still sets its feet down near where the plan does. That is a sole
(a walk on soles balances by its centre of pressure within the sole about the ZMP plan's
footholds — the ankle torque above — not by where it steps), every foot of a gait always on
:data:`FEWEST_STATIC` feet or more (its support polygon holds the body: the default tripod,
the crawls), and a point foot of a gait on one foot at times (a point-foot biped, an inverted
pendulum every way, which the neutral point alone does not catch: the test humanoid's walk,
placed so, saturated its knees and fell at 0.87 s, its diagnosis then "a stronger actuator"
where it falls as the pendulum it is; ``docs/simulate.md``, "Bipeds on point feet").
Raibert's placement (4.) was measured on trots of point feet only; these keep this law and
their results (``analysis/bench_logs/position_soles.log``, ``simulate_talos.log``, the
tripod's closed loop in ``docs/simulate.md``).

**Through the servos.** The controller's output becomes the servo's reference
(:mod:`hexaleg.simulation.controllers`): the control moves by ``Δτ/kp + Δq``. For the
feedforward + PD servo that is the feedforward torque ``τ_ff + Δτ`` and the position reference
``q* + Δq``; for the position-only servo (no torque input) the reference
``q* + Δq + (τ* + Δτ)/kp``, whose P gain turns the offset into the controller's whole torque,
the plan's and the correction ("Deflection", below; the plan's ``q* + τ*/kp`` at every
simulation step, :func:`~hexaleg.simulation.controllers.controls` with ``torques``, the
correction ``Δq + Δτ/kp`` held over each update) — the robot with a position servo is
simulated as it is built (a host computes the torques and sends positions), and the feedback's
own torques are the servos' and count in the energy.

**Deflection** (a position servo). A P servo delivers a torque only by deflecting:
without a torque input it gives the plan's own torque τ* once its joint has sagged by τ*/kp,
and that sag is a motion of the body — the stance hip roll's is a roll of the whole body about
the stance hip toward the swing side, which the body PD above, a correction at the gait's
frequency, neither asks back nor can hold. On a sole that motion tips the robot: the torque the
stance leg lacks while it sags turns the body, the ground must supply that moment, and a sole
holds at most ``m g a`` (a its half-width) before its centre of pressure reaches the edge. At
lift-off Talos' stance hip roll is asked for 70 N·m and gives −5 N·m (its sole holds 49 N·m,
the feedback's own change there reached 18 N·m): its body rolled 67 mrad over the stance,
carried it into the next one as an outward lean and fell; the test biped's gives 0.4 of
11.2 N·m (its sole holds 7.2 N·m), then rings ±7 N·m about the plan, and its sole's centre of
pressure swings from edge to edge. A stiffer servo does not help: it sags less but its loop on
the body rings faster and less damped (``ζ = D / (2 √(kp I))``), its torque error as large
(4 × kp still tips). So the controller also asks a position servo for the plan's
torque through its reference — the static compensation of a compliant joint (Tomei, "A simple
PD controller for robots with elastic joints", IEEE Trans. Automatic Control 36(10), 1991: the
motor's set point ``q* + K⁻¹ g(q*)`` for a joint of stiffness K holding the load g; here
``K = kp`` and the load the plan's whole torque) — the reference ``q* + Δq + (τ* + Δτ)/kp``,
τ* the plan's motor torque at every simulation step, as the plan's angles q* are: both are the
plan's, known ahead, and a host streams them together. Held over each 10-ms update instead
(its value at the hold's midpoint), τ* missed the stance handovers, where the plan's torque
changes by up to 63 N·m within one 0.9-ms sample (Unitree B1's knee, its sized trot): up to
73 mrad of reference for about 5 ms at each of the four handovers a cycle, and B1 (56 kg)
covered 59 % and 76 % of its stride (springs, baseline) with its body rolling to 0.73 rad, and
Laikago (25 kg) fell with its springs; asked for τ* at every step both walk
(``analysis/bench_logs/newcomers_simulate.log``). The servo then gives τ* at the plan's angle;
its velocity lag ``D q̇/kp`` (the back-EMF, which no torque input cancels) stays, the position
servo's own tracking error. On point feet the sag costs the stride instead: a stance leg's
sag lowers and tilts the body over the feet, and a quadruped new to hexaleg (Unitree Go1 from
example-robot-data, 13 kg, its sized trot) covered only 73 % and 80 % of its stride (springs,
baseline) at 68–73 mrad RMS tracking error without the plan's torque, against the whole stride
with it; the registered quadrupeds' trots, which walked without it, now spend what the plan
predicts (``docs/simulate.md``, "Balance feedback"). Measured on soles in
``analysis/bench_logs/position_soles.log`` (``docs/simulate.md``, "Position servos on soles:
the sag").

**What is measured.** The base's pose and velocity and the feet's positions are MuJoCo's ground
truth (``qpos``, ``qvel``, the foot sites): a perfect state estimator, stated in
``docs/simulate.md``. The controller runs at the rate :mod:`hexaleg.simulation.control_rate` sets
(100 Hz, or faster where its sampled loop needs it), holding its correction in between; the
servos' own loop and the plan's references run every simulation step.

**Gains** (:func:`size_gains`): ``k_p = ω²``, ``k_d = 2 ζ ω`` with ζ = 1 (critically damped) and
``ω = BANDWIDTH · 2π / period``: the body's closed loop at the gait's frequency, so an error
decays within a cycle, and below the servos' own loops (5.4–20× the gait's frequency on every
registered robot, ``docs/simulate.md``) so the inner loop stays the faster; the swing feet place
their feet as 4. says. BANDWIDTH was chosen by measurement on the registered quadrupeds' trots
under position servos (``docs/simulate.md``, "Balance feedback"), not derived: twice the
bandwidth asked the servos for more torque than they have. Before 4. every swing foot kept its
foothold ("Footholds"), as a tripod's and a sole still do: Laikago (25 kg) and B1 (56 kg) fell
within 8 cycles of their sized trots with it, and Go2's trot rolled ten times as far without it
(``analysis/bench_logs/newcomers_simulate.log``)."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import pinocchio as pin

from hexaleg.checks import positive
from hexaleg.errors import InvalidParameterError
from hexaleg.motion.recorded.base import rotation_from_quaternion
from hexaleg.motion.trajectory import SEMI_IMPLICIT, Motion
from hexaleg.robot.model import Robot
from hexaleg.simulation import foot_placement
from hexaleg.simulation.control_rate import CONTROL_PERIOD, control_period
from hexaleg.simulation.distribution import TorqueBounds, distribute, wrench_map
from hexaleg.simulation.model import SimModel

BANDWIDTH = 1.0
"""The body's closed-loop natural frequency in multiples of the gait's frequency (module
docstring, "Gains")."""
FOOTHOLD = 0.3
"""The fraction of a swing foot's task-space error to its planned world pose corrected per
update where the foot is not placed for balance: a sole, or any foot of a gait always on
:data:`FEWEST_STATIC` feet or more (module docstring, "Footholds")."""
MODES: tuple[str, ...] = ("auto", "on", "off")
"""``[simulate] feedback``: ``"auto"`` (default) runs the controller where the gait needs it
(fewer than three stance feet at some instant, or an open-loop run that fell); ``"on"``,
``"off"`` always or never."""
TURN = 1e-3
"""rad: a plan whose base ends a cycle rotated by more than this from where it began turns (its
later cycles are not translations of the first); the one-sample extrapolation that closes the
cycle is exact to about ½ |ω̇| dt² (5e-6 rad at 10 rad/s² and 1 ms)."""
FEWEST_STATIC = 3
"""A gait always on at least this many feet can stand without balance feedback."""


@dataclass(frozen=True)
class Gains:
    """The balance controller's gains (module docstring).

    Attributes:
        omega: ω, the body's closed-loop natural frequency, rad/s, > 0.
        zeta: ζ, its damping ratio, > 0.
        capture: k, s, ≥ 0: the landing point's lead per m/s of the body's velocity error
            beyond :func:`hexaleg.simulation.foot_placement.lead` (0 by default).
        period: The controller's period, s, > 0
            (:func:`~hexaleg.simulation.control_rate.control_period`).
    """

    omega: float
    zeta: float = 1.0
    capture: float = 0.0
    period: float = CONTROL_PERIOD

    def __post_init__(self) -> None:
        positive("balance omega (rad/s)", self.omega)
        positive("balance zeta", self.zeta)
        positive("balance period (s)", self.period)
        if not self.capture >= 0:
            raise InvalidParameterError("balance capture (s)", self.capture, "≥ 0")

    @property
    def kp(self) -> float:
        """ω², 1/s²."""
        return self.omega**2

    @property
    def kd(self) -> float:
        """2 ζ ω, 1/s."""
        return 2 * self.zeta * self.omega


def size_gains(robot: Robot, motion: Motion) -> Gains:
    """The default gains of ``robot`` for ``motion``: ω = :data:`BANDWIDTH` × 2π / period, ζ = 1
    and the period :func:`control_period` (module docstring)."""
    omega = BANDWIDTH * 2 * math.pi / motion.period
    return Gains(omega=omega, period=control_period(robot, motion, omega))


def needed(motion: Motion) -> bool:
    """Whether the gait needs balance feedback in any case: fewer than :data:`FEWEST_STATIC`
    planned stance feet at some sample (a trot, a pace, a bound; a biped)."""
    return int(np.asarray(motion.stance).sum(axis=1).min()) < FEWEST_STATIC


def _skew(r: np.ndarray) -> np.ndarray:
    """The cross-product matrix [r]× of r (3,), shape (3, 3)."""
    return np.array([[0.0, -r[2], r[1]], [r[2], 0.0, -r[0]], [-r[1], r[0], 0.0]])


def _skew_log(r: np.ndarray) -> np.ndarray:
    """log(R) as a rotation vector (rad), R (3, 3) a rotation (Pinocchio's ``log3``)."""
    return np.asarray(pin.log3(r))


def cycle_end(model: pin.Model, motion: Motion) -> tuple[np.ndarray, np.ndarray]:
    """The base's rotation (world, 3 × 3) and position (world, m) one sample after the plan's
    last, where its next cycle begins: one explicit step of the last sample, its rotation by
    ``exp(ω dt)`` and its position by ``R v dt`` (exact to about ½ |v̇| dt², :data:`TURN`); for
    a plan made of the knots of a semi-implicit Euler integration (``info["integrator"]``
    :data:`~hexaleg.motion.trajectory.SEMI_IMPLICIT`, an optimal motion at tens of milliseconds
    a knot, where that error exceeds :data:`TURN`) its own step ``q ⊕ (v + a dt) dt``, which is
    exactly its next knot (Pinocchio's ``integrate``, as Crocoddyl's state integrates)."""
    q, v, dt = motion.q[-1], motion.v[-1], motion.dt
    rot = rotation_from_quaternion(q[None, 3:7])[0]
    if motion.info.get("integrator") != SEMI_IMPLICIT:
        return rot @ pin.exp3(v[3:6] * dt), q[:3] + rot @ v[:3] * dt
    nxt = pin.integrate(model, q, (v + motion.a[-1] * dt) * dt)
    return rotation_from_quaternion(nxt[None, 3:7])[0], np.array(nxt[:3])


Sample = tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray]
"""What a plan sample fixes for the balance controller's update (:meth:`Balance._sample`)."""


class Balance:
    """The controller for one model and plan (module docstring); :meth:`correction` at a state.

    Args:
        sim: The model (robot, joint map, servo gains, ground μ).
        motion: The plan (a periodic gait).
        forces: The plan's foot forces, shape (T, n_legs, 3), N, world
            (:attr:`hexaleg.dynamics.prepare.Analysis.forces`).
        tau: The plan's motor torques, shape (T, nj), N·m
            (:attr:`hexaleg.dynamics.prepare.Analysis.tau_motor`): the torque bounds of the
            force program are the servos' stall torques less these.
        gains: The gains (default :func:`size_gains`).

    Raises:
        InvalidParameterError: a gait whose base does not return to its heading each cycle (a
            turning gait: its plan in later cycles is not a translation of the first), or forces
            of another shape.
    """

    def __init__(self, sim: SimModel, motion: Motion, forces: np.ndarray, tau: np.ndarray,
                 gains: Gains | None = None) -> None:
        import mujoco  # where a model is built: importing this package stays light

        self._quat2mat = mujoco.mju_quat2Mat
        robot = sim.robot
        model = robot.model
        data = model.createData()
        n = motion.n_samples
        forces = np.asarray(forces, dtype=float)
        if forces.shape != (n, len(robot.legs), 3):
            raise InvalidParameterError("balance forces", forces.shape,
                                        f"({n}, {len(robot.legs)}, 3): the plan's foot forces")
        self.sim, self.motion = sim, motion
        self.gains = gains or size_gains(robot, motion)
        self.dt, self.n = motion.dt, n
        q, v = motion.q, motion.v
        rot = rotation_from_quaternion(q[:, 3:7])
        end, position = cycle_end(model, motion)
        if np.linalg.norm(_skew_log(rot[0].T @ end)) > TURN:
            raise InvalidParameterError("[simulate] feedback", "on",
                                        "a gait whose base returns to its heading each cycle "
                                        "(yaw_rate = 0), or feedback = \"off\"")
        self.offset = position - q[0, :3]
        """Base travel per cycle (world), m."""
        self.rotation = np.concatenate([rot, rot[:1]])
        track = np.hstack([q[:, :3], np.einsum("kij,kj->ki", rot, v[:, :3]),
                           np.einsum("kij,kj->ki", rot, v[:, 3:6])])
        self.track = np.vstack([track, track[:1]])
        self.track[-1, :3] += self.offset
        """Per sample, the first repeated a cycle on: base position, velocity and angular
        velocity (world), (T + 1, 9)."""
        load = np.hstack([forces.reshape(n, -1), np.asarray(tau, dtype=float)])
        self.load = np.vstack([load, load[:1]])
        """Per sample, extended: the feet's forces (n_legs × 3) and the motor torques, N, N·m."""
        self.n_force = forces[0].size
        stance = np.asarray(motion.stance).astype(bool)
        self.stance = np.vstack([stance, stance[:1]])
        self.feet = np.asarray(motion.feet, dtype=float)
        self._samples: dict[int, Sample] = {}
        self.mass = robot.mass
        self.nj, self.mu = robot.nj, sim.ground.mu
        self.com = np.zeros((n, 3))
        nj, n_legs = robot.nj, len(robot.legs)
        corners = [robot.soles[leg.name].corners() if leg.name in robot.soles
                   else np.zeros((1, 3)) for leg in robot.legs]
        self.point_leg = np.concatenate([np.full(len(c), i) for i, c in enumerate(corners)])
        """The leg of each contact point (a point foot's one, a sole's four corners),
        (n_points,)."""
        self.point_share = np.concatenate([np.full(len(c), 1.0 / len(c)) for c in corners])
        """The share of its leg's planned force each contact point carries, (n_points,): the
        plan's force at a sole's centre is its four corners' equal forces."""
        n_points = len(self.point_leg)
        jac = [np.zeros((n, 3, len(leg.columns))) for leg in robot.legs]
        points = [np.zeros((n, len(c), 3, len(leg.columns)))
                  for c, leg in zip(corners, robot.legs, strict=True)]
        turn = {i: np.zeros((n, 3, len(leg.columns))) for i, leg in enumerate(robot.legs)
                if leg.name in robot.soles}
        fewest = int(stance.sum(axis=1).min())
        self.placed = (np.array([i not in turn for i in range(n_legs)])
                       & (foot_placement.FEWEST_PLACED <= fewest < FEWEST_STATIC))
        """Whether each leg's foot is placed for balance (Raibert's placement, module docstring
        4.: a point foot of a gait on two feet at times, never on one), or aims at its planned
        world pose ("Footholds"), (n_legs,)."""
        self.soles = bool(turn)
        """Whether a foot has a sole."""
        for k in range(n):
            qk = q[k].copy()
            qk[:7] = [0, 0, 0, 0, 0, 0, 1]  # the base at the origin: base-frame Jacobians
            pin.computeJointJacobians(model, data, qk)
            pin.updateFramePlacements(model, data)
            self.com[k] = pin.centerOfMass(model, data, qk)
            for i, leg in enumerate(robot.legs):
                full = pin.getFrameJacobian(model, data, leg.foot_frame_id,
                                            pin.ReferenceFrame.LOCAL_WORLD_ALIGNED)
                jac[i][k] = full[:3, 6 + np.asarray(leg.columns)]
                points[i][k] = jac[i][k]
                if i in turn:  # a corner c of the sole moves with v + ω × (R_f c)
                    turn[i][k] = full[3:, 6 + np.asarray(leg.columns)]
                    arm = corners[i] @ data.oMf[leg.foot_frame_id].rotation.T
                    points[i][k] = jac[i][k] + np.einsum(
                        "cxy,yj->cxj", np.array([-_skew(r) for r in arm]), turn[i][k])
        self.stance_map = np.zeros((n, nj, n_points, 3))
        """−J_bᵀ of each contact point in its leg's joints' rows, (T, nj, n_points, 3):
        Δτ = Σ_i (−J_b,iᵀ) Rᵀ Δf_i."""
        self.swing_map = np.zeros((n, nj, n_legs, 3))
        """J_b⁺ of each leg in its joints' rows, (T, nj, n_legs, 3): the swing IK step (a
        sole's: the position columns of the pseudo-inverse of its 6-row Jacobian)."""
        self.swing_turn = np.zeros((n, nj, n_legs, 3))
        """A sole's swing step for its foot's orientation: the orientation columns of that
        pseudo-inverse, (T, nj, n_legs, 3) (zero for point feet)."""
        self.leg_rows = np.zeros((n_legs, nj), dtype=bool)
        for i, leg in enumerate(robot.legs):
            cols = np.asarray(leg.columns)
            self.leg_rows[i, cols] = True
            at = np.flatnonzero(self.point_leg == i)
            self.stance_map[:, cols[:, None], at, :] = -np.swapaxes(points[i], 2, 3).transpose(
                0, 2, 1, 3)
            if i in turn:
                inverse = np.linalg.pinv(np.concatenate([jac[i], turn[i]], axis=1), rcond=1e-3)
                self.swing_map[:, cols, i, :] = inverse[..., :3]
                self.swing_turn[:, cols, i, :] = inverse[..., 3:]
            else:
                self.swing_map[:, cols, i, :] = np.linalg.pinv(jac[i], rcond=1e-3)
        self.placement = foot_placement.Placement(robot, motion, self.placed, self.leg_rows,
                                             self.gains.capture)
        """The swing feet's placement (:mod:`hexaleg.simulation.foot_placement`)."""
        pin.ccrba(model, data, q[0], np.zeros(model.nv))
        inertia = np.asarray(data.Ig.inertia)  # world-aligned at the plan's first sample
        self.inertia = rot[0].T @ inertia @ rot[0]
        """Centroidal rotational inertia, base frame, kg·m²."""
        planted = self.feet[stance]
        centre = planted.mean(axis=0) if len(planted) else np.zeros(3)
        self.spread = max(float(np.max(np.linalg.norm((planted - centre)[:, :2], axis=1)))
                          if len(planted) else 0.0, 1e-3)
        """L, m: the stance feet's horizontal spread about their centre (the moment scale)."""
        self.constrained = 0
        """Updates at which a friction cone bound the force correction."""
        self.updates = 0

    def plan(self, t: float) -> tuple[int, float, np.ndarray]:
        """The plan's samples around ``t``: ``(k, s, travel)``: t lies between samples k and
        k + 1 of the extended arrays (the first sample repeated after the last, a cycle on),
        s the linear weight of k + 1, travel the base's travel over the cycles before (world,
        m)."""
        x = t / self.dt
        k = math.floor(x + 1e-9)
        return k % self.n, min(max(x - k, 0.0), 1.0), (k // self.n) * self.offset

    def _sample(self, k: int) -> Sample:
        """What the plan's sample k fixes for an update between samples k and k + 1, worked
        out at its first update: ``(stance legs' contact points, their joints' rows (bool),
        swing legs, the stance map's block −J_bᵀ (rows, stance points, 3), the rows' stall
        torques and kp, the swing map's block J_b⁺ (nj, 3 × swing legs))`` — the feet on the
        ground at both samples stand, the others swing."""
        if k not in self._samples:
            stance = self.stance[k] & self.stance[k + 1]
            legs, swing = np.flatnonzero(stance), np.flatnonzero(~stance)
            points = np.flatnonzero(stance[self.point_leg])
            rows = np.asarray(self.leg_rows[legs].any(axis=0), dtype=bool)
            sm = self.swing_map[k][:, swing]
            self._samples[k] = (points, rows, swing, self.stance_map[k][rows][:, points],
                                self.sim.stall[rows], self.sim.kp[rows],
                                sm.reshape(len(sm), -1))
        return self._samples[k]

    def correction(self, t: float, qpos: np.ndarray, qvel: np.ndarray, feet: np.ndarray
                   ) -> np.ndarray:
        """The servo controls' change at a measured state (module docstring), shape (nj,).

        Args:
            t: Time, s.
            qpos: MuJoCo configuration (base position, quaternion w x y z, joints).
            qvel: MuJoCo velocity (base linear in the world frame, angular in the base frame).
            feet: Contact point positions (world), shape (n_points, 3), m: each point foot's,
                each sole's four corners (legs in robot order,
                :func:`~hexaleg.simulation.mjcf.contact_sites`).
        """
        g = self.gains
        kp, kd = g.kp, g.kd
        k, s, travel = self.plan(t)
        track = self.track[k] + s * (self.track[k + 1] - self.track[k])
        p_plan, r_plan = track[:3] + travel, self.rotation[k]
        p = qpos[:3]
        flat = np.empty(9)
        quat = qpos[3:7]
        self._quat2mat(flat, quat / math.sqrt(quat.dot(quat)))  # np.linalg.norm's arithmetic
        rot = flat.reshape(3, 3)
        dw = np.empty(6)
        dw[:3] = self.mass * (kp * (p_plan - p) + kd * (track[3:6] - qvel[:3]))
        dw[3:] = rot @ (self.inertia @ (rot.T @ (kp * _skew_log(r_plan @ rot.T)
                                                + kd * (track[6:] - rot @ qvel[3:6]))))
        out = np.zeros(self.nj)
        points, cols, swing, stance_map, stall, gain, swing_map = self._sample(k)
        self.updates += 1
        if len(points):  # the stance feet's contact points
            load = self.load[k] + s * (self.load[k + 1] - self.load[k])
            f0 = (load[:self.n_force].reshape(-1, 3)[self.point_leg[points]]
                  * self.point_share[points, None])
            t_map = (stance_map @ rot.T).reshape(-1, 3 * len(points))
            tau0 = load[self.n_force:][cols]
            bounds = TorqueBounds(t_map, np.minimum(-stall - tau0, 0.0),
                                  np.maximum(stall - tau0, 0.0))
            df, bound = distribute(wrench_map(feet[points], p + rot @ self.com[k]), dw, f0,
                                   self.mu, self.spread, bounds)
            self.constrained += bound
            out[cols] += (t_map @ df.ravel()) / gain
        if len(swing):
            x = self.feet[k, swing] + travel
            placed = self.placed[swing]
            if not placed.all():  # its planned world pose (module docstring, "Footholds")
                target = (x - p) @ rot - (x - p_plan) @ r_plan  # Rᵀ (x − p) − R*ᵀ (x − p*)
                target[placed] = 0.0
                out += FOOTHOLD * (swing_map @ target.ravel())
                if self.soles:  # a sole turns by Rᵀ R*: flat on the ground as planned
                    st = self.swing_turn[k][:, swing]
                    out += FOOTHOLD * (st.reshape(len(st), -1)
                                       @ np.tile(_skew_log(rot.T @ r_plan), len(swing)))
            if placed.any():  # Raibert's foot placement, blended into the swing (4.)
                out += self.placement.step(k, s, swing, x, p, rot, p_plan, r_plan,
                                           qvel[:3] - track[3:6], swing_map)
        out += self.placement.release(k, s, self.stance[k] & self.stance[k + 1])
        return out
