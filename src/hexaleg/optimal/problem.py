"""The whole-body optimal-control problem of one gait cycle with the springs in the dynamics.

One cycle of a gait, cut into ``N`` knots of ``dt = period / N`` (the contact timing is the gait
pattern's, fixed), each an Euler-integrated contact dynamics of the whole robot on its floating
base (Crocoddyl's ``DifferentialActionModelContactFwdDynamics``: ``M a + h = τ + Jᶜᵀ λ`` with the
stance feet's 3-D contact accelerations held at zero, Featherstone, *Rigid Body Dynamics
Algorithms*, §11; Mastalli et al., ICRA 2020, eq. 9), as Crocoddyl's quadrupedal examples build
their gaits (``SimpleQuadrupedalGaitProblem``: one contact set per knot, swing feet by frame
costs), here with

* the actuation ``τ = [0₆; u + τ_s(q, q̇)]`` (:mod:`~hexaleg.optimal.actuation`): ``u`` is the
  motor's torque, its box ``|u| ≤`` stall torque is box-FDDP's control bound;
* the running cost the motor's smoothed electrical power (:mod:`~hexaleg.optimal.energy`), plus
  small regularisation towards the warm start and the swing feet's path (weights in
  :class:`OptimalParams`; what they cost is reported apart from the energy);
* friction cones (a 4-facet pyramid inside the cone of friction ``μ · friction_use``,
  :mod:`~hexaleg.optimal.friction`) and the joints' position and speed limits (URDF
  limits, the motor's no-load speed) as quadratic barriers, which are zero inside the bounds;
* each stance foot held at its foothold, the point where the warm start's foot lands (the
  contact's Baumgarte stabilisation ``a_c = −k_p (p − p*) − k_d v_c`` with the dead-beat gains
  ``k_p = 1/dt², k_d = 1/dt`` of the semi-implicit Euler step, :func:`contact_gains`; a
  Runge–Kutta knot (``OptimalParams.integrator``) takes its own dead-beat gains), landing
  there (a cost on the foot's distance to its foothold at its touch-down knot) at rest (a cost
  on its linear velocity there; no impact model);
* each leg kept ``reach_margin`` short of full stretch at every knot (its knee, the last joint
  that can stretch it, held off its stretched angle by a barrier on the side the warm start
  bends it, :func:`~hexaleg.optimal.bounds.knee_bounds`), so the cycle rebuilt in task space
  between knots stays in reach;
* each swing foot above the ground at every knot (a barrier on the foot frame's height, as
  Crocoddyl's own bounds on a residual are written: ``ActivationModelQuadraticBarrier`` on a
  ``ResidualModelFrameTranslation``, zero above the ground's height,
  :func:`~hexaleg.optimal.bounds.ground_heights`);
* the terminal periodicity cost (:mod:`~hexaleg.optimal.periodic`).
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import pinocchio as pin

from hexaleg.checks import integer, one_of, positive, real
from hexaleg.errors import InvalidParameterError
from hexaleg.motion.trajectory import Motion
from hexaleg.optimal.actuation import SpringActuation, sprung_joints
from hexaleg.optimal.backend import crocoddyl_module
from hexaleg.optimal.bounds import ground_heights, knee_bounds
from hexaleg.optimal.energy import EnergyCost, JointPower
from hexaleg.optimal.friction import FrictionPyramid
from hexaleg.optimal.periodic import cycle_displacement, shifted_state
from hexaleg.optimal.servo_effort import ServoEffortCost, back_emf_damping
from hexaleg.robot.model import Robot
from hexaleg.robot.springs import SpringSet

crocoddyl = crocoddyl_module()


@dataclass(frozen=True)
class OptimalParams:
    """How the cycle is cut and weighed.

    Attributes:
        nodes: Knots per cycle ``N`` (≥ 8).
        smoothing: ε of the energy's softplus, W (:mod:`~hexaleg.optimal.energy`).
        mu: Friction coefficient of the cones.
        friction_use: Fraction of ``μ`` the feet may use (the cone's ``μ · friction_use``), in
            (0, 1].
        state_weight: Weight of ``‖x ⊖ x_warm‖²`` at every knot (J·s per unit²).
        swing_weight: Weight of the swing feet's distance to the warm start's path, per m².
        landing_weight: Weight of a foot's squared velocity at its touch-down knot.
        foothold_weight: Weight of a foot's squared distance to its foothold at its touch-down
            knot, per m² (a foot that lands off it is pulled onto it in one knot: it slides).
        clearance_weight: Weight of a swing foot's squared depth below the ground at a knot,
            per m² (:func:`ground_heights`; a barrier, zero above it). 1e7 holds Solo-12's
            optimal trot's swing feet within 0.02 mm of the ground (1.5 mm below it without);
            1e8 holds them within 0.002 mm but its Hessian, which switches on where a foot
            leaves the ground, kept a 40-iteration solve of Solo-12's trot on 16 knots from
            closing its dynamics gap (1.6e-4).
        limit_weight: Weight of the position, speed, reach and friction barriers.
        reach_margin: How far short of its full stretch each leg's knee holds the foot at every
            knot, m (:func:`knee_bounds`): the solver bounds the legs only at its knots, and
            the cycle rebuilt between them (its base moving on while a foot holds its foothold
            or leaves it) must stay in reach. 3 mm: without it Solo-12's optimal trot at 0.3 m/s
            (0.875 s, duty factor 0.644, 7.6 mm of base travel a knot) held leg RH 0.5 mm short
            of its reach at its lift-off knot and the rebuild asked 1.1 mm beyond it 2.6 ms
            later (1.6 mm between knots); 3 mm keeps Solo-12's knees 0.28 rad off straight
            at the knots, and that cycle's rebuild then bent leg RH's knee to 0.17 rad
            between them (1.2 mm short of its reach: the margin is used, 2 mm would be
            marginal).
        periodic_weight: Weight of the terminal periodicity cost.
        iterations: Box-FDDP iterations; the solve ends after them once its dynamics gap is
            closed (``gap``).
        gap: The dynamics gap (Crocoddyl's ``ffeas``: the largest defect between a knot's
            integrated state and the next) the solve closes before it ends: past
            ``iterations`` it goes on while its gap is larger, ``closing`` iterations at most
            (:func:`~hexaleg.optimal.solve.solve`). 1e-8: Solo-12's bare trot at 0.3 m/s left
            a gap of 8.1e-06 after 100 iterations and a Newton–Euler residual of 4.5e-06 N·m,
            over issue #56's 1e-6; box-FDDP's partial steps shrink the gap about 3 % an
            iteration there, and 1e-8 took it 220 more (its residual then 2.7e-09 N·m).
        closing: Iterations the solve may take past ``iterations`` to close its gap (≥ 0).
        stop: Box-FDDP's stopping threshold ``th_stop`` (:mod:`~hexaleg.optimal.solve`); the
            energy of a cycle of this small robot is about a joule, so Crocoddyl's default 5e-5
            stops it early.
        servo_landing_weight: Weight of a landing leg's position-servo effort
            ``½ Σ (u + D q̇)²`` at its last swing knots, W/(N·m)²
            (:class:`~hexaleg.optimal.servo_effort.ServoEffortCost`: the lag a position servo
            lands with); 0 (default): off, the problem unchanged.
        servo_landing_knots: The last swing knots of each leg that cost is on (≥ 1).
        integrator: How a knot integrates its dynamics and cost, one of :data:`INTEGRATORS`:
            ``"euler"`` Crocoddyl's semi-implicit Euler (``IntegratedActionModelEuler``), or
            ``"rk2"``, ``"rk3"``, ``"rk4"`` its explicit Runge–Kutta of that order
            (``IntegratedActionModelRK``, the control held over the knot), solved from a fresh
            start by continuation through Euler's and RK2's knots
            (:func:`~hexaleg.optimal.solve.solve`) and checked at each knot's own acceleration
            with the knots' defect (:mod:`~hexaleg.optimal.residual`; issue #56's probe:
            analysis/bench_optimal_integrator.py).
    """

    nodes: int = 40
    smoothing: float = 1e-3
    mu: float = 0.6
    friction_use: float = 0.7
    state_weight: float = 1e-3
    swing_weight: float = 1e2
    landing_weight: float = 1e3
    foothold_weight: float = 1e8
    clearance_weight: float = 1e7
    limit_weight: float = 1e3
    reach_margin: float = 3e-3
    periodic_weight: float = 1e4
    iterations: int = 100
    gap: float = 1e-8
    closing: int = 400
    stop: float = 1e-8
    servo_landing_weight: float = 0.0
    servo_landing_knots: int = 1
    integrator: str = "euler"

    def __post_init__(self) -> None:
        one_of("OptimalParams.integrator", self.integrator, INTEGRATORS)
        integer("OptimalParams.nodes", self.nodes, low=8)
        integer("OptimalParams.servo_landing_knots", self.servo_landing_knots, low=1)
        real("OptimalParams.servo_landing_weight", self.servo_landing_weight, low=0.0)
        integer("OptimalParams.iterations", self.iterations, low=1)
        integer("OptimalParams.closing", self.closing, low=0)
        real("OptimalParams.friction_use", self.friction_use, low=0.0, high=1.0,
             low_open=True)
        for key in ("stop", "gap", "smoothing", "mu", "state_weight", "swing_weight",
                    "landing_weight", "foothold_weight", "clearance_weight", "limit_weight",
                    "periodic_weight"):
            positive(f"OptimalParams.{key}", getattr(self, key))
        real("OptimalParams.reach_margin", self.reach_margin, low=0.0)


@dataclass
class OptimalProblem:
    """The built problem and what solving and reading it need.

    Attributes:
        problem: Crocoddyl's shooting problem (N running knots, one terminal).
        state: Crocoddyl's multibody state.
        actuation: The spring actuation (shared by every knot).
        x_warm: The warm start's states at the knots, (N + 1, nq + nv).
        stance: Which legs touch the ground at each knot, (N, n_legs) bool.
        dt: Knot spacing, s.
        period: Cycle duration, s.
        distance: Distance per cycle, m.
        displacement: The cycle's rigid displacement (4, 4).
        power: The joints' motor constants (the energy cost's).
        params: The parameters it was built with.
        footholds: Each stance foot's foothold at each knot, (N, n_legs, 3), m (zero in swing).
        contact_names: The legs in contact at each knot and the terminal one.
        inputs: What it was built from beside ``params``: the robot, the motion, the motors
            and the springs (:meth:`on_knots` builds it again on other knots).
    """

    problem: Any
    state: Any
    actuation: SpringActuation
    x_warm: np.ndarray
    stance: np.ndarray
    dt: float
    period: float
    distance: float
    displacement: np.ndarray
    power: JointPower
    params: OptimalParams
    footholds: np.ndarray
    contact_names: list[list[str]] = field(default_factory=list)
    inputs: tuple[Robot, Motion, Any, SpringSet] | None = None

    def on_knots(self, integrator: str) -> OptimalProblem:
        """The same problem with each knot integrated by ``integrator`` (one of
        :data:`INTEGRATORS`; :attr:`OptimalParams.integrator`), every other parameter the same:
        the rungs of a solve's continuation in the knots' order (:mod:`hexaleg.optimal.solve`).

        Raises:
            InvalidParameterError: a problem not built by :func:`build_problem`.
        """
        if self.inputs is None:
            raise InvalidParameterError("OptimalProblem.inputs", None,
                                        "a problem built by build_problem")
        return build_problem(*self.inputs, dataclasses.replace(self.params,
                                                               integrator=integrator))


INTEGRATORS = ("euler", "rk2", "rk3", "rk4")
"""The knots' integrators (:attr:`OptimalParams.integrator`)."""


RK_GAINS = {"rk2": (2.0, 2.0), "rk3": (3.759229759624812, 1.4039283620166814),
            "rk4": (3.781252789774624, 3.4588884621354117)}
"""``(k_p dt², k_d dt)`` of the dead-beat contact gains of each Runge–Kutta knot
(:func:`contact_gains`)."""


RK_ORDER = {"rk2": "two", "rk3": "three", "rk4": "four"}
"""Crocoddyl's ``RKType`` of each Runge–Kutta integrator."""


LINEAR = np.array([1.0, 1.0, 1.0, 0.0, 0.0, 0.0])
"""Weights of a frame velocity's (linear, angular) parts in the landing cost: a round foot may
roll as it lands, it must not slide."""


def _knot_samples(motion: Motion, nodes: int) -> np.ndarray:
    """The motion's sample index at each knot time ``k · period / N``, k = 0 … N − 1."""
    t = np.arange(nodes) * motion.period / nodes
    return np.clip(np.rint((t - motion.t[0]) / (motion.t[1] - motion.t[0])).astype(int), 0,
                   len(motion.t) - 1)


def _foot_positions(robot: Robot, q: np.ndarray) -> np.ndarray:
    """World position of every foot frame at configuration ``q``, (n_legs, 3)."""
    pin.framesForwardKinematics(robot.model, robot.data, q)
    return np.array([robot.data.oMf[leg.foot_frame_id].translation for leg in robot.legs])


def _references(robot: Robot, qs: np.ndarray, stance: np.ndarray,
                displacement: np.ndarray) -> np.ndarray:
    """Each stance foot's contact point at each knot, (N, n_legs, 3): the foot's position at
    the knot its stance phase begins (cyclically); a phase that began in the previous cycle has
    that point moved back by the cycle's displacement."""
    n, legs = stance.shape
    feet = np.array([_foot_positions(robot, q) for q in qs])
    back = np.linalg.inv(displacement)
    out = np.zeros((n, legs, 3))
    for j in range(legs):
        if stance[:, j].all():
            out[:, j] = feet[0, j]
            continue
        for k in range(n):
            if not stance[k, j]:
                continue
            s = k
            while stance[(s - 1) % n, j]:
                s -= 1
            p = feet[s % n, j]
            out[k, j] = p if s >= 0 else back[:3, :3] @ p + back[:3, 3]
    return out


def contact_gains(dt: float, integrator: str = "euler") -> np.ndarray:
    """Baumgarte gains ``(k_p, k_d)`` that hold a contact point on its reference ``p*`` across
    one semi-implicit Euler knot of ``dt`` (Baumgarte, *Comput. Methods Appl. Mech. Eng.* 1,
    1972; the step as Crocoddyl's ``IntegratedActionModelEuler`` takes it): with the contact
    acceleration ``a_c = −k_p e − k_d v_c`` (``e = p − p*``), ``v' = v_c + dt a_c`` and
    ``e' = e + dt v'``, so ``e' = (1 − k_p dt²) e + dt (1 − k_d dt) v_c``; ``k_p = 1/dt²``,
    ``k_d = 1/dt`` make it zero — the foot is back on its point at the next knot, to second
    order in the knot's change of the contact Jacobian. With ``k_p = 0`` (damping alone) the
    position is not held: the ``J̇ v dt²`` each knot leaves accumulates over the stance.

    A Runge–Kutta knot of order ``p ≤ 4`` (``integrator`` ``"rk2"`` … ``"rk4"``) steps the
    error's ODE ``ë = −k_p e − k_d ė`` (the contact acceleration is held to it at every
    stage) by its stability function ``R(z) = Σ_{i ≤ p} zⁱ/i!`` at the eigenvalues ``z`` of
    ``dt [[0, 1], [−k_p, −k_d]]`` (Hairer & Wanner, *Solving ODEs II*, §IV.2), the roots of
    ``z² + k_d dt z + k_p dt² = 0``; gains that put those on a complex pair of ``R``'s roots
    make the step dead-beat too (:data:`RK_GAINS`; RK4's better-damped pair
    ``−1.729 ± 0.889 i``, damping ratio 0.89, not ``−0.271 ± 2.505 i``, 0.11, which rings
    between the stages)."""
    dt = positive("dt", dt)
    one_of("integrator", integrator, INTEGRATORS)
    if integrator == "euler":
        return np.array([1.0 / dt**2, 1.0 / dt])
    kp, kd = RK_GAINS[integrator]
    return np.array([kp / dt**2, kd / dt])


def _landing_knots(stance: np.ndarray, knots: int) -> np.ndarray:
    """Whether each leg is at one of its last ``knots`` swing knots before a touch-down at each
    knot of the cycle (cyclically), (N, n_legs) bool, from ``stance`` (N, n_legs) bool."""
    n = stance.shape[0]
    out = np.zeros(stance.shape, dtype=bool)
    for k in range(n):
        for j in range(stance.shape[1]):
            if stance[k, j]:
                continue
            ahead = next((i for i in range(1, n + 1) if stance[(k + i) % n, j]), n + 1)
            out[k, j] = ahead <= knots
    return out


def _barrier(residual: Any, lower: np.ndarray, upper: np.ndarray) -> Any:
    """``residual`` under a quadratic barrier that is zero inside ``[lower, upper]``."""
    bounds = crocoddyl.ActivationBounds(np.asarray(lower, float), np.asarray(upper, float))
    return crocoddyl.CostModelResidual(residual.state,
                                       crocoddyl.ActivationModelQuadraticBarrier(bounds), residual)


def build_problem(robot: Robot, motion: Motion, actuator: Any, springs: SpringSet,
                  params: OptimalParams | None = None) -> OptimalProblem:
    """The optimal-control problem of one cycle of ``motion``'s gait (module docstring).

    Args:
        robot: The robot (free flyer).
        motion: The gait whose contact timing, cycle displacement and path the problem takes,
            and which warm-starts it; periodic, on the floating base.
        actuator: The motors: a :class:`~hexaleg.robot.motor.Motor` or a
            :class:`~hexaleg.robot.motor_set.MotorSet`.
        springs: The springs in the dynamics (empty: none).
        params: The parameters; defaults when None.

    Raises:
        InvalidParameterError: a fixed-base motion, or a knot with no foot on the ground.
    """
    params = params or OptimalParams()
    if motion.fixed_base:
        raise InvalidParameterError("motion.fixed_base", True, "a motion on the floating base")
    displacement = cycle_displacement(motion)
    n = params.nodes
    samples = _knot_samples(motion, n)
    stance = np.asarray(motion.stance[samples], dtype=bool)
    if not stance.any(axis=1).all():
        k = int(np.flatnonzero(~stance.any(axis=1))[0])
        raise InvalidParameterError("stance", f"no foot down at knot {k}",
                                    "a gait with a foot on the ground at every knot")
    nq = robot.model.nq
    xs = np.hstack([motion.q[samples], motion.v[samples]])
    x_warm = np.vstack([xs, shifted_state(xs[0], displacement)])
    refs = _references(robot, motion.q[samples], stance, displacement)
    ground = ground_heights(stance, refs, displacement)
    state = crocoddyl.StateMultibody(robot.model)
    actuation = SpringActuation(state, sprung_joints(robot, springs))
    nu = actuation.nu
    power = JointPower.of(actuator, nu, params.smoothing)
    limit = np.broadcast_to(np.asarray(actuator.stall_torque, float), (nu,))
    speed = np.broadcast_to(np.asarray(actuator.no_load_speed, float), (nu,))
    dt = motion.period / n
    gains = contact_gains(dt, params.integrator)
    bent_lo, bent_hi = knee_bounds(robot, motion.q[samples], params.reach_margin)
    lo = np.hstack([np.full((n, 6), -1e6), bent_lo[:, 7:], np.full((n, 6), -1e6),
                    np.tile(-speed, (n, 1))])
    hi = np.hstack([np.full((n, 6), 1e6), bent_hi[:, 7:], np.full((n, 6), 1e6),
                    np.tile(speed, (n, 1))])
    zero_x = np.concatenate([pin.neutral(robot.model), np.zeros(robot.model.nv)])
    landing = _landing_knots(stance, params.servo_landing_knots)
    damping = back_emf_damping(actuator, nu) if params.servo_landing_weight > 0 else None
    models, names = [], []
    for k in range(n + 1):
        terminal = k == n
        kk = 0 if terminal else k
        contacts = crocoddyl.ContactModelMultiple(state, nu)
        costs = crocoddyl.CostModelSum(state, nu)
        down = []
        for j, leg in enumerate(robot.legs):
            if stance[kk, j]:
                ref = refs[kk, j]
                if terminal:
                    ref = displacement[:3, :3] @ ref + displacement[:3, 3]
                contacts.addContact(leg.name, crocoddyl.ContactModel3D(
                    state, leg.foot_frame_id, ref, pin.LOCAL_WORLD_ALIGNED, nu, gains))
                down.append(leg.name)
                if not terminal and not stance[k - 1, j]:  # touch-down: on its foothold, at rest
                    rest = crocoddyl.ResidualModelFrameVelocity(
                        state, leg.foot_frame_id, pin.Motion.Zero(), pin.LOCAL_WORLD_ALIGNED, nu)
                    costs.addCost(f"{leg.name}_landing", crocoddyl.CostModelResidual(
                        state, crocoddyl.ActivationModelWeightedQuad(LINEAR), rest),
                        params.landing_weight)
                    costs.addCost(f"{leg.name}_foothold", crocoddyl.CostModelResidual(
                        state, crocoddyl.ResidualModelFrameTranslation(
                            state, leg.foot_frame_id, ref, nu)), params.foothold_weight)
                if not terminal:
                    force = crocoddyl.ResidualModelContactForce(
                        state, leg.foot_frame_id, pin.Force.Zero(), 3, nu, True)
                    costs.addCost(f"{leg.name}_cone", crocoddyl.CostModelResidual(
                        state, FrictionPyramid(params.mu * params.friction_use), force),
                        params.limit_weight)
            elif not terminal:
                path = crocoddyl.ResidualModelFrameTranslation(
                    state, leg.foot_frame_id, _foot_positions(robot, x_warm[k, :nq])[j], nu)
                costs.addCost(f"{leg.name}_swing", crocoddyl.CostModelResidual(state, path),
                              params.swing_weight)
                if np.isfinite(ground[k, j]):  # above the ground: a barrier on the foot's height
                    height = crocoddyl.ResidualModelFrameTranslation(
                        state, leg.foot_frame_id, np.zeros(3), nu)
                    costs.addCost(f"{leg.name}_clearance", _barrier(
                        height, np.array([-1e6, -1e6, ground[k, j]]), np.full(3, 1e6)),
                        params.clearance_weight)
                if damping is not None and landing[k, j]:
                    costs.addCost(f"{leg.name}_servo_landing",
                                  ServoEffortCost(state, leg.columns, damping),
                                  params.servo_landing_weight)
        names.append(down)
        if terminal:
            costs.addCost("periodic", crocoddyl.CostModelResidual(
                state, crocoddyl.ResidualModelState(state, x_warm[n], nu)),
                params.periodic_weight)
        else:
            costs.addCost("energy", EnergyCost(state, power), 1.0)
            costs.addCost("regularisation", crocoddyl.CostModelResidual(
                state, crocoddyl.ResidualModelState(state, x_warm[k], nu)), params.state_weight)
            costs.addCost("limits", _barrier(crocoddyl.ResidualModelState(state, zero_x, nu),
                                             lo[k], hi[k]), params.limit_weight)
        dam = crocoddyl.DifferentialActionModelContactFwdDynamics(state, actuation, contacts,
                                                                  costs, 0.0, True)
        dam.u_lb, dam.u_ub = -limit.copy(), limit.copy()
        if terminal or params.integrator == "euler":
            models.append(crocoddyl.IntegratedActionModelEuler(dam, 0.0 if terminal else dt))
        else:
            models.append(crocoddyl.IntegratedActionModelRK(
                dam, getattr(crocoddyl.RKType, RK_ORDER[params.integrator]), dt))
    problem = crocoddyl.ShootingProblem(x_warm[0].copy(), models[:-1], models[-1])
    return OptimalProblem(problem, state, actuation, x_warm, stance, dt, motion.period,
                          motion.distance, displacement, power, params, refs, names,
                          (robot, motion, actuator, springs))
