"""Issue #56: where the position servo's extra energy goes for the optimal motion with its springs,
against the parametric co-design's gait (log: analysis/bench_logs/bench_optimal_servo.log; a
probe, not an example study: it needs the optimal extra and minutes).

Run:  python analysis/bench_optimal_servo.py --codesign DIR/codesign.json [--cache FILE]
                                             [--rounds 4] [--finalist N]
                                             [--servo-landing W ...] [--landing-knots 1]
                                             [--spread]

Needs the ``optimal`` extra. The co-design's chosen gait G (``gait.parameters`` of a kept
``hexaleg codesign`` run's JSON, the servo-checked gait; ``--finalist N``: the search's N-th
finalist instead) and its inner-program springs S
(:func:`~hexaleg.design.codesign.gait_evaluation.evaluate_gait`, linear, one design a joint
class), then the optimal motion with its springs as ``codesign --motion optimal`` computes it
(:func:`~hexaleg.design.codesign.alternation.alternate` from G and S, up to ``--rounds`` rounds,
40 knots, 100 iterations; kept in ``--cache`` as it ends, so a rerun after a kill skips it).
The same alternation from its start moved by the command's spread
(:data:`~hexaleg.design.codesign.alternation.MOVES`) is simulated too: the position servo's
figure is not a hair's accident. Each motion with its springs is predicted (hexaleg's force
program, objective ``joule``: the feedforward) and simulated open loop (``feedback = "auto"``,
as the command's rows) under each servo (:mod:`hexaleg.simulation.controllers`), and the
evaluated cycles are taken apart:

* electrical energy per metre by joint class and by the joint's leg's planned phase (stance or
  swing), and the Joule part (``c τ²``) of each, planned against simulated: the electrical
  power per sample is the motor model's (:meth:`hexaleg.robot.motor.Motor.electrical_power`,
  the integrand of :func:`hexaleg.dynamics.energy.metrics`);
* the stance feet's normal forces, planned (the force program's) against simulated (MuJoCo's
  contact forces at the recorded states, :func:`hexaleg.simulation.measures.contact_forces`):
  how unevenly the stance feet share the load (coefficient of variation of the normal forces
  over the stance feet at an instant, time-averaged), the RMS difference per foot, and the
  feet's internal tangential force ``Σ|f_t| − |Σ f_t|`` (legs pushing against each other);
* the joints' tracking error in stance and in swing (RMS and mean, by joint class), the body's
  height below the plan;
* the springs' share of the stance joints' torque (mean |τ_spring| / mean |τ_spring + τ_motor|),
  planned and simulated;
* the swing's speed (the plan's largest joint speed and foot speed in swing).

``--servo-landing W ...`` adds, for each weight W (> 0), the optimal motion with its springs
from the same start and with
:attr:`~hexaleg.optimal.problem.OptimalParams.servo_landing_weight` W (the landing leg's
position-servo effort at its last ``--landing-knots`` swing knots), taken apart the same way;
with ``--spread`` each also from its start moved by the command's spread
(:data:`~hexaleg.design.codesign.alternation.MOVES`), simulated.
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import os
import pickle
import time
from typing import Any

import numpy as np

import hexaleg
from hexaleg.design.chain.groups import design_groups
from hexaleg.design.codesign.alternation import MOVES, alternate
from hexaleg.design.codesign.build import default_gait, floor_constraints
from hexaleg.design.codesign.gait_evaluation import evaluate_gait
from hexaleg.dynamics.prepare import prepare
from hexaleg.motion.legged import gait
from hexaleg.optimal.problem import OptimalParams
from hexaleg.simulation.controllers import Servo, reference
from hexaleg.simulation.measures import contact_forces, forward_states, planned_index
from hexaleg.simulation.run import Settings, simulate

KEYS = ("period", "duty_factor", "step_height", "body_height", "foot_radius")
"""The gait's searched parameters read from ``codesign.json``."""
FORCE_ROWS = 400
"""Recorded steps of the evaluated window at which the simulated foot forces are read."""


def power(motor: Any, tau: np.ndarray, qdot: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Electrical and Joule power per sample and joint, W, each (T, nj): the integrands of
    :func:`hexaleg.dynamics.energy.metrics` (``electrical`` takes back power where the motor
    regenerates, else not)."""
    pe = motor.electrical_power(tau, qdot, regeneration=True)
    pe = np.where(motor.regeneration, pe, np.maximum(pe, 0.0))
    return pe, motor.joule_power(tau)


def split(robot: Any, values: np.ndarray, stance: np.ndarray, dt: float,
          distance: float) -> dict[str, float]:
    """``values`` (T, nj) W integrated over the cycles (``Σ x dt``) per metre, J/m, by joint
    class and by the joint's leg's phase (``stance`` (T, n_legs) bool), plus ``total``."""
    legs = {name: i for i, leg in enumerate(robot.legs) for name in leg.joint_names}
    phase = np.stack([stance[:, legs[j]] for j in robot.joint_names], axis=1)
    out = {"total": float(values.sum() * dt / distance)}
    for kind, joints in robot.joint_classes.items():
        cols = [robot.joint_names.index(j) for j in joints]
        for name, mask in (("stance", phase[:, cols]), ("swing", ~phase[:, cols])):
            out[f"{kind} {name}"] = float((values[:, cols] * mask).sum() * dt / distance)
    return out


def sharing(forces: np.ndarray, stance: np.ndarray) -> dict[str, float]:
    """How the stance feet share the load: ``forces`` (T, n_legs, 3) N, ``stance`` (T, n_legs).
    ``cv``: the normal forces' standard deviation over the stance feet at an instant over their
    mean, averaged over instants; ``internal``: ``Σ|f_t| − |Σ f_t|`` over the stance feet, N,
    averaged; ``peak``: the largest normal force of a foot over the weight's mean share."""
    cv, internal, peak = [], [], []
    for f, s in zip(forces, stance, strict=True):
        fz = f[s, 2]
        ft = f[s, :2]
        cv.append(fz.std() / fz.mean())
        internal.append(np.linalg.norm(ft, axis=1).sum() - np.linalg.norm(ft.sum(0)))
        peak.append(fz.max() / fz.mean())
    return {"cv": float(np.mean(cv)), "internal": float(np.mean(internal)),
            "peak": float(np.mean(peak))}


def servo_shared(robot: Any, motion: Any, tau_motor: np.ndarray, springs: Any,
                 motor: Any) -> tuple[np.ndarray, float]:
    """The stance legs' motor torques position servos would give the plan, quasi-statically:
    the servo-shared torques, (T, nj) N·m (swing legs as planned), and the fraction of the
    stance legs' planned servo effort that servos cannot give (RMS over the samples of
    ``‖u − u_s‖ / ‖u‖``).

    Model (this probe's; a linear compliance argument, as for a statically indeterminate
    structure): a position servo at its reference gives ``−D q̇`` (no feedforward), so the plan
    asks each stance joint for the effort ``u = τ_m + D q̇`` it does not get; the body then
    settles by a small displacement ``δb`` (6) with the stance feet held, each stance leg's
    joints move by ``δq_i = −B_i δb`` with ``B_i = J_leg,i⁻¹ J_base,i`` (the foot's
    LOCAL_WORLD_ALIGNED Jacobian, 3 × 3 and 3 × 6), and take the torque ``K_i B_i δb`` from the
    servo (``kp``) and the spring's stiffness ``k_s`` (``K = kp + k_s``, diagonal). The base's
    balance asks ``Σ B_iᵀ (K_i B_i δb − u_i) = 0`` (the feet's forces on the base as planned:
    ``Δf_i = −J_leg,i⁻ᵀ Δτ_i``), so ``δb = (Σ B_iᵀ K_i B_i)⁻¹ Σ B_iᵀ u_i`` and the motor torque is
    ``kp B_i δb − D q̇_i``: ``u`` projected onto the efforts a rigid body's displacement can
    make, in the stiffness' metric. Springs' stiffness by central differences of their torque."""
    import pinocchio as pin

    model, data = robot.model, robot.data
    kp, _, damping, _ = Servo("position").gains(motor, robot.nj)
    h = 1e-6
    qd = motion.v[:, 6:]
    u = tau_motor + damping * qd
    out = tau_motor.copy()
    missed, asked = [], []
    for k in range(motion.n_samples):
        q = motion.q[k]
        plus, minus = np.repeat(q[None], robot.nj, 0), np.repeat(q[None], robot.nj, 0)
        plus[np.arange(robot.nj), 7 + np.arange(robot.nj)] += h
        minus[np.arange(robot.nj), 7 + np.arange(robot.nj)] -= h
        k_s = -np.diag(springs.torques(robot, plus) - springs.torques(robot, minus)) / (2 * h)
        stiff = kp + k_s
        pin.computeJointJacobians(model, data, q)
        pin.updateFramePlacements(model, data)
        legs = [leg for i, leg in enumerate(robot.legs) if motion.stance[k, i]]
        bs = []
        for leg in legs:
            jac = pin.getFrameJacobian(model, data, leg.foot_frame_id,
                                       pin.LOCAL_WORLD_ALIGNED)[:3]
            bs.append(np.linalg.solve(jac[:, leg.v_index], jac[:, :6]))
        a = sum(b.T @ (stiff[leg.columns][:, None] * b) for b, leg in zip(bs, legs, strict=True))
        rhs = sum(b.T @ u[k, leg.columns] for b, leg in zip(bs, legs, strict=True))
        db = np.linalg.lstsq(a, rhs, rcond=None)[0]
        for b, leg in zip(bs, legs, strict=True):
            c = leg.columns
            out[k, c] = kp[c] * (b @ db) - damping[c] * qd[k, c]
            missed.append(np.sum((u[k, c] - stiff[c] * (b @ db)) ** 2))
            asked.append(np.sum(u[k, c] ** 2))
    return out, float(np.sqrt(np.sum(missed) / np.sum(asked)))


def stance_fraction(stance: np.ndarray) -> np.ndarray:
    """How far each leg is into its stance at each sample of a periodic cycle, in [0, 1) (NaN in
    swing): ``stance`` (T, n_legs) bool → (T, n_legs)."""
    n = stance.shape[0]
    out = np.full(stance.shape, np.nan)
    for leg in range(stance.shape[1]):
        on = stance[:, leg]
        if on.all():
            out[:, leg] = np.arange(n) / n
            continue
        first = int(np.flatnonzero(on & ~np.roll(on, 1))[0])  # a touch-down sample
        length = 0
        for i in range(n):
            k = (first + i) % n
            if on[k] and not on[(k - 1) % n]:
                length = next(j for j in range(1, n + 1) if not on[(k + j) % n])
                start = k
            if on[k]:
                out[k, leg] = ((k - start) % n) / length
    return out


BINS = 5
"""Parts of a stance the stance legs' energy is split into (by the fraction elapsed)."""


def by_stance_part(robot: Any, pe: np.ndarray, frac: np.ndarray, dt: float,
                   distance: float) -> list[float]:
    """The stance legs' electrical energy ``pe`` (T, nj) W per metre, J/m, in :data:`BINS` parts
    of the stance by ``frac`` (T, n_legs) (:func:`stance_fraction`)."""
    out = [0.0] * BINS
    for i, leg in enumerate(robot.legs):
        f = frac[:, i]
        on = ~np.isnan(f)
        part = np.minimum((np.nan_to_num(f) * BINS).astype(int), BINS - 1)
        for b in range(BINS):
            out[b] += float(pe[on & (part == b)][:, leg.columns].sum() * dt / distance)
    return out


def offsets(robot: Any, err: np.ndarray, stance: np.ndarray) -> tuple[float, float]:
    """The stance joints' tracking error ``err`` (T, nj) rad split into each stance's mean (a
    leg's offset held through its stance: where it landed) and the rest, both RMS over the
    stance samples, rad; ``stance`` (T, n_legs) bool, the stances cut by the window's ends
    left out."""
    held, rest, count = 0.0, 0.0, 0
    for i, leg in enumerate(robot.legs):
        on = stance[:, i].astype(int)
        edges = np.flatnonzero(np.diff(on)) + 1
        starts = [e for e in edges if on[e]]
        for a in starts:
            b = next((e for e in edges if e > a and not on[e]), None)
            if b is None:
                continue
            e = err[a:b][:, leg.columns]
            m = e.mean(0)
            held += float(np.sum(m**2)) * len(e)
            rest += float(np.sum((e - m) ** 2))
            count += e.size
    return float(np.sqrt(held / count)), float(np.sqrt(rest / count))


def landing_step(k: np.ndarray, on: np.ndarray) -> int:
    """The first step of a run whose planned sample ``k`` (n,) is a touch-down of the leg whose
    planned stance is ``on`` (T,) bool (periodic)."""
    td = np.flatnonzero(on & ~np.roll(on, 1))
    return int(np.flatnonzero(np.isin(k, td))[0])


def at_touchdown(robot: Any, values: np.ndarray, stance: np.ndarray, before: int) -> float:
    """RMS over every touch-down of the landing leg's joints' ``values`` (T, nj), ``before``
    samples before its first stance sample (0: at it); ``stance`` (T, n_legs) bool,
    periodic."""
    out = []
    for i, leg in enumerate(robot.legs):
        on = stance[:, i]
        for k in np.flatnonzero(on & ~np.roll(on, 1)):
            out.append(values[(k - before) % len(values), leg.columns])
    return float(np.sqrt(np.mean(np.square(out)))) if out else 0.0


def examine(robot: Any, motion: Any, motor: Any, springs: Any, contact: Any,
            label: str) -> dict[str, Any]:
    """``motion`` with ``springs`` predicted and simulated under both servos, taken apart
    (module docstring); prints its lines and returns the simulated J/m by controller."""
    print(f"{label}:", flush=True)
    # the plan: the prediction's own samples
    planned_j = prepare(robot, motion, motor=motor, contact=contact).evaluate(springs, "joule")
    qd = motion.v[:, 6:]
    pe, pj = power(motor, planned_j.tau_motor, qd)
    stance = motion.stance.astype(bool)
    plan = split(robot, pe, stance, motion.dt, motion.distance)
    plan_j = split(robot, pj, stance, motion.dt, motion.distance)
    share_plan = sharing(planned_j.forces[:, :, :], stance)
    tau_s = springs.torques(robot, motion.q)
    kinds = robot.joint_classes
    col = {k: [robot.joint_names.index(j) for j in js] for k, js in kinds.items()}
    leg_of = {name: i for i, leg in enumerate(robot.legs) for name in leg.joint_names}
    phase = np.stack([stance[:, leg_of[j]] for j in robot.joint_names], axis=1)

    def spring_share(ts: np.ndarray, tm: np.ndarray, ph: np.ndarray) -> str:
        """Per joint class, mean |τ_spring| over mean |τ_spring + τ_motor| in stance."""
        shares = {k: np.abs(ts[:, c][ph[:, c]]).mean() / np.abs((ts + tm)[:, c][ph[:, c]]).mean()
                  for k, c in col.items()}
        return ", ".join(f"{k} {v:.2f}" for k, v in shares.items())

    speed_swing = np.abs(qd)[~phase].max() if (~phase).any() else 0.0
    foot_v = np.gradient(motion.feet, motion.dt, axis=0)
    foot_swing = np.linalg.norm(foot_v, axis=2)[~stance].max() if (~stance).any() else 0.0
    print(f"  predicted {plan['total']:.3f} J/m (Joule part {plan_j['total']:.3f}); stance feet "
          f"per instant {stance.sum(1).min()} to {stance.sum(1).max()} (mean "
          f"{stance.sum(1).mean():.2f}); swing: largest joint speed {speed_swing:.2f} rad/s, "
          f"foot speed {foot_swing:.3f} m/s", flush=True)
    _, damping_ = Servo("position").gains(motor, robot.nj)[1:3]
    effort = planned_j.tau_motor + damping_ * qd
    print("  the landing leg's planned servo effort τ_m + D q̇ (what a position servo needs as "
          "error × kp), RMS N·m, at its last swing samples and its first stance sample: "
          + ", ".join(f"{b} before {at_touchdown(robot, effort, stance, b):.3f}"
                      for b in (8, 4, 1, 0))
          + f"; its spring torque {at_touchdown(robot, tau_s, stance, 1):.3f}", flush=True)
    print(f"  planned springs' share of the stance torque: "
          f"{spring_share(tau_s, planned_j.tau_motor, phase)}", flush=True)
    shared, missed = servo_shared(robot, motion, planned_j.tau_motor, springs, motor)
    se, sj = power(motor, shared, qd)
    model_e = split(robot, se, stance, motion.dt, motion.distance)
    model_j = split(robot, sj, stance, motion.dt, motion.distance)
    print(f"  servo-shared (quasi-static position servos on the plan): {model_e['total']:.3f} J/m "
          f"(Joule part {model_j['total']:.3f}); the stance effort servos cannot give: "
          f"{missed:.2f} of the planned (RMS)", flush=True)
    frac = stance_fraction(stance)
    parts = {"planned": by_stance_part(robot, pe, frac, motion.dt, motion.distance),
             "servo-shared": by_stance_part(robot, se, frac, motion.dt, motion.distance)}
    sims: dict[str, Any] = {"planned": plan, "planned joule": plan_j, "servo-shared": model_e,
                            "servo-shared joule": model_j}
    for controller in ("feedforward", "position"):
        sim = simulate(robot, motion, motor, springs,
                       Settings(controller=controller, feedback="auto", force_samples=0),
                       contact=contact)
        run = sim.with_springs
        if not run.walks or run.walk is None:
            print(f"  {controller}: {run.verdict}: {run.message}", flush=True)
            continue
        traj, model = run.trajectory, run.sim
        steps = round(motion.period / model.timestep)
        window = slice((sim.settings.cycles - sim.settings.evaluate) * steps,
                       sim.settings.cycles * steps)
        distance = run.walk.distance_per_cycle * sim.settings.evaluate
        tau = traj.tau_motor[window]
        qdot = model.joints.joints_mj(traj.qvel[window], velocity=True)
        q_sim = model.joints.joints_mj(traj.qpos[window])
        t = traj.t[window]
        k = planned_index(motion, t)
        st = motion.stance[k].astype(bool)
        ph = phase[k]
        e_sim, j_sim = power(motor, tau, qdot)
        got = split(robot, e_sim, st, model.timestep, distance)
        got_j = split(robot, j_sim, st, model.timestep, distance)
        sims[controller], sims[controller + " joule"] = got, got_j
        err = q_sim - reference(motion, planned_j.tau_motor, t).q
        parts[controller] = by_stance_part(robot, e_sim, frac[k], model.timestep, distance)
        held, rest = offsets(robot, err, st)
        stance_e = motion.stance.astype(bool)
        kk = k[:steps]  # one cycle's steps; the error at each planned touch-down's step
        td = [i for i in range(1, len(kk)) if (stance_e[kk[i]] & ~stance_e[kk[i - 1]]).any()]
        landing = []
        for i in td:
            for leg_i, leg in enumerate(robot.legs):
                if stance_e[kk[i], leg_i] and not stance_e[kk[i - 1], leg_i]:
                    landing.append(err[i, leg.columns])
        landed = float(np.sqrt(np.mean(np.square(landing)))) if landing else 0.0
        q_pin = np.array([model.joints.to_pinocchio(a, b)[0]
                          for a, b in zip(traj.qpos[window], traj.qvel[window], strict=True)])
        ts_sim = springs.torques(robot, q_pin)
        rows = np.arange(window.start, window.stop)[
            np.linspace(0, steps * sim.settings.evaluate - 1, FORCE_ROWS).astype(int)]
        f_sim = np.array([contact_forces(model, d) for d in forward_states(model, traj, rows)])
        kr = planned_index(motion, traj.t[rows])
        st_r = motion.stance[kr].astype(bool)
        share_sim = sharing(f_sim, st_r)
        f_plan = planned_j.forces[kr]
        per_foot = np.sqrt(np.mean(((f_sim - f_plan)[..., 2])[st_r] ** 2))
        height = float(np.mean(traj.qpos[window][:, 2]) - np.mean(motion.q[k, 2]))
        print(f"  {controller}: simulated {got['total']:.3f} J/m (Joule part "
              f"{got_j['total']:.3f}), {run.walk.distance_per_cycle / motion.distance:.3f} of "
              f"the planned distance, body {1e3 * height:+.2f} mm from the plan", flush=True)
        print("    tracking error, stance (RMS / mean, mrad): " + ", ".join(
            f"{kd} {1e3 * np.sqrt(np.mean(err[:, c][ph[:, c]] ** 2)):.1f} / "
            f"{1e3 * np.mean(err[:, c][ph[:, c]]):+.1f}" for kd, c in col.items())
            + "; swing: " + ", ".join(
            f"{kd} {1e3 * np.sqrt(np.mean(err[:, c][~ph[:, c]] ** 2)):.1f} / "
            f"{1e3 * np.mean(err[:, c][~ph[:, c]]):+.1f}" for kd, c in col.items()),
            flush=True)
        print(f"    springs' share of the stance torque: {spring_share(ts_sim, tau, ph)}",
              flush=True)
        print(f"    the landing leg's tracking error at its planned touch-down "
              f"{1e3 * landed:.1f} mrad RMS", flush=True)
        legs_said = []
        for i, leg in enumerate(robot.legs):
            at = np.abs(err[landing_step(k, stance[:, i])][leg.columns]).max()
            held_leg = err[st[:, i]][:, leg.columns].mean(0)
            legs_said.append(f"{leg.name} {1e3 * at:.1f} ("
                             + " ".join(f"{1e3 * v:+.1f}" for v in held_leg) + ")")
        print("    per leg, its largest joint error at its first planned touch-down of the window "
              "and each joint's mean error over its stances, mrad: " + "; ".join(legs_said),
              flush=True)
        print(f"    stance error held through a stance (its mean: where the foot landed) "
              f"{1e3 * held:.1f} mrad RMS, the rest {1e3 * rest:.1f} mrad; feet slid "
              f"{1e3 * run.walk.slip_mean:.2f} mm a stance on average "
              f"({1e3 * run.walk.slip_max:.2f} mm at most), contact lost "
              f"{run.walk.contact_losses:.3f} of the stance samples", flush=True)
        print(f"    stance normal forces: spread over the feet (CV) planned "
              f"{share_plan['cv']:.3f}, simulated {share_sim['cv']:.3f}; largest foot's over "
              f"the mean share planned {share_plan['peak']:.2f}, simulated "
              f"{share_sim['peak']:.2f}; RMS planned − simulated per foot {per_foot:.3f} N "
              f"(weight {robot.mass * 9.81:.2f} N); internal tangential force planned "
              f"{share_plan['internal']:.3f} N, simulated {share_sim['internal']:.3f} N",
              flush=True)
    keys = [key for key in plan if key != "total"]
    print("  J/m by joint class and phase (planned / feedforward / servo-shared / position; "
          "Joule part in brackets):", flush=True)
    for key in keys:
        cells = [f"{sims[c][key]:6.3f} ({sims[c + ' joule'][key]:5.3f})"
                 for c in ("planned", "feedforward", "servo-shared", "position") if c in sims]
        print(f"    {key:14s} " + "  ".join(cells), flush=True)
    print(f"  stance legs' J/m in {BINS} parts of a stance (touch-down first): " + "; ".join(
        f"{name} " + " ".join(f"{v:.2f}" for v in values) for name, values in parts.items()),
        flush=True)
    return sims


def brief(robot: Any, motion: Any, motor: Any, springs: Any, contact: Any) -> str:
    """``motion`` with ``springs`` simulated under each servo (open loop where the gait allows):
    its J/m, the feet's mean slip a stance and the stance error held through a stance, as
    text."""
    out = []
    for controller in ("feedforward", "position"):
        sim = simulate(robot, motion, motor, springs,
                       Settings(controller=controller, feedback="auto", force_samples=0),
                       contact=contact)
        run = sim.with_springs
        if not run.walks or run.walk is None:
            out.append(f"{controller} {run.verdict}")
            continue
        out.append(f"{controller} {run.metrics['electrical'] / run.walk.distance_per_cycle:.2f} "
                   f"J/m (slip {1e3 * run.walk.slip_mean:.2f} mm)")
    return ", ".join(out)


def solved(robot: Any, motion: Any, motor: Any, contact: Any, springs: Any, groups: Any,
           params: OptimalParams, rounds: int, cache: str | None, tag: str, origin: Any,
           move: float = 0.0) -> Any:
    """The alternation from ``motion`` and ``springs`` with ``params``: read from ``cache`` (a
    pickle of key → result, the key ``tag`` and the gait's parameters ``origin``) when it holds
    it, else computed and written there."""
    key = f"{tag} | {origin!r} | {rounds}"
    kept: dict[str, Any] = {}
    if cache and os.path.exists(cache):
        with open(cache, "rb") as f:
            kept = pickle.load(f)
    if key in kept:
        print(f"{tag}: read from {cache}", flush=True)
        return kept[key]
    alt = alternate(robot, motion, motor, contact, springs=springs, params=params,
                    groups=groups, rounds=rounds, move=move,
                    say=lambda line: print(f"  {tag}: {line}", flush=True))
    if cache:
        kept[key] = alt
        with open(cache + ".part", "wb") as f:
            pickle.dump(kept, f)
        os.replace(cache + ".part", cache)  # whole or not at all
    return alt


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--codesign", required=True, help="a hexaleg codesign run's JSON")
    parser.add_argument("--finalist", type=int, default=0,
                        help="G the search's n-th finalist of the JSON instead of its chosen gait")
    parser.add_argument("--cache", help="pickle keeping the optimal solves (read, written)")
    parser.add_argument("--rounds", type=int, default=4, help="alternation rounds at most")
    parser.add_argument("--servo-landing", type=float, nargs="*", default=[],
                        help="weights of OptimalParams.servo_landing_weight to try")
    parser.add_argument("--spread", action="store_true",
                        help="each --servo-landing weight also from the moved starts")
    parser.add_argument("--landing-knots", type=int, default=1,
                        help="OptimalParams.servo_landing_knots of those solves")
    args = parser.parse_args()
    t0, c0 = time.perf_counter(), os.times()
    run = hexaleg.Scenario.load("hexaleg")
    robot, motor = run.model, run.actuator
    c = floor_constraints(run)
    contact = c.contact()
    groups = design_groups(robot, tuple(robot.joint_classes), "class")
    with open(args.codesign, encoding="utf-8") as f:
        kept = json.load(f)
    found = (kept["finalists"]["rows"][args.finalist - 1]["gait"] if args.finalist
             else kept["gait"]["parameters"])
    g = dataclasses.replace(default_gait(robot, "hexaleg", 0.06, None, 200),
                            **{k: found[k]["value"] for k in KEYS})
    point = evaluate_gait(robot, g, groups=groups, family="linear", constraints=c,
                          min_margin=0.0, motor=motor)
    springs = point.springs
    print(f"G: duty factor {g.duty_factor:.3g}, period {g.period:.6g} s, body height "
          f"{g.body_height:.6g} m: {point.sprung / point.distance:.4f} J/m with S "
          "(the inner program)", flush=True)
    played = gait(robot, g)
    alt = solved(robot, played, motor, contact, springs, groups, OptimalParams(), args.rounds,
                 args.cache, "optimal", g)
    print(f"optimal motion, its springs: {alt.predicted:.4f} J/m predicted rebuilt "
          f"({len(alt.rounds)} rounds, kept gait: {alt.kept_gait})", flush=True)
    print("the same alternation from its start moved by a hair (the command's spread): "
          "predicted J/m, then simulated", flush=True)
    for m in MOVES:
        other = solved(robot, played, motor, contact, springs, groups, OptimalParams(),
                       args.rounds, args.cache, f"moved {m:+.0e} m", g, m)
        print(f"  moved {m:+.0e} m: {other.predicted:.4f}; "
              + brief(robot, other.motion, motor, other.springs, contact), flush=True)
    examine(robot, played, motor, springs, contact, "parametric co-design (G with S)")
    examine(robot, alt.motion, motor, alt.springs, contact, "optimal motion, its springs")
    for w in args.servo_landing:
        tag = f"servo_landing_weight {w:g}, servo_landing_knots {args.landing_knots}"
        other = solved(robot, played, motor, contact, springs, groups,
                       OptimalParams(servo_landing_weight=w,
                                     servo_landing_knots=args.landing_knots),
                       args.rounds, args.cache, tag, g)
        print(f"optimal motion, its springs, {tag}: {other.predicted:.4f} J/m predicted rebuilt "
              f"({len(other.rounds)} rounds, kept gait: {other.kept_gait}); stationarity "
              f"{other.best.stationarity:.2g}", flush=True)
        examine(robot, other.motion, motor, other.springs, contact,
                f"optimal motion, its springs, {tag}")
        if args.spread:
            print(f"  {tag}, from its start moved by a hair: predicted J/m, then simulated",
                  flush=True)
            for m in MOVES:
                moved = solved(robot, played, motor, contact, springs, groups,
                               OptimalParams(servo_landing_weight=w,
                                             servo_landing_knots=args.landing_knots),
                               args.rounds, args.cache, f"{tag}, moved {m:+.0e} m", g, m)
                print(f"  moved {m:+.0e} m: {moved.predicted:.4f}; "
                      + brief(robot, moved.motion, motor, moved.springs, contact), flush=True)
    c1 = os.times()
    print(f"wall {time.perf_counter() - t0:.0f} s, CPU "
          f"{(c1.user - c0.user) + (c1.system - c0.system):.0f} s", flush=True)


if __name__ == "__main__":
    main()
