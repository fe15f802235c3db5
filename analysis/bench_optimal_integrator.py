"""Issue #56, is the solver's Euler step what the optimal motion loses at the rebuild? The optimal
cycle with the co-design's springs solved from the command's own start (``hexaleg codesign
--motion optimal``: the co-design's chosen gait, its inner-program springs, every solver setting
the default: 40 knots, 100 iterations, the gap closed) with each knot integrated by Crocoddyl's
semi-implicit Euler (the command's) and by its explicit Runge–Kutta of order 2 and 4
(:attr:`~hexaleg.optimal.problem.OptimalParams.integrator`), each judged as the alternation
judges a solve (:func:`~hexaleg.design.codesign.alternation.judged`: hexaleg's prediction of the
cycle rebuilt in task space) beside the solver's own J/m at its knots (log:
analysis/bench_logs/bench_optimal_integrator.log; not an example study: it needs the optimal
extra and minutes).

Run:  python analysis/bench_optimal_integrator.py --codesign DIR/codesign.json --work DIR
                                                  [--alternate [--simulate]]

Needs the ``optimal`` extra. The start from ``--codesign``, a kept ``hexaleg codesign --motion
optimal`` run's ``codesign.json``: ``gait.parameters`` (the chosen gait) and ``inner_springs``
(the springs the command's alternation starts from; none when their family is not one DDP can
differentiate, as the command does). The contact gains of each integrator are its dead-beat ones
(:func:`~hexaleg.optimal.problem.contact_gains`: Euler ``k_p = 1/dt², k_d = 1/dt``; RK2
``2/dt², 2/dt``; RK4 ``3.781/dt², 3.459/dt``, the step's stability function zero on the error's
eigenvalues, so a stance foot off its foothold is back on it at the next knot under each).

The rows (:data:`ROWS`), each one box-FDDP solve (:func:`~hexaleg.optimal.solve.solve`, 100
iterations and the gap closed): each integrator from the command's start (the gait's states and
their quasi-static controls), and from the Euler row's optimum (its knots stepped by another
integrator miss by metres per second, a gap the feasibility-driven solve closes), beside Euler
given the same 100 iterations more from its optimum (the fair reference of those). Each row: the
judged J/m, the solver's J/m at its knots (the exact power at each knot's torque and speed, left
Riemann sum, as :func:`~hexaleg.optimal.solve.solve` books it) and by the knot's own quadrature
(the exact power at each stage's state, weighted as the integrator weighs its cost: Crocoddyl's
RK2 is the midpoint rule; the same figure for Euler), the judged J/m over the solver's, the
Newton–Euler residual as the project computes it (:mod:`~hexaleg.optimal.residual`: ``a_k =
(v_{k+1} − v_k)/dt``, a check of Euler knots; of Runge–Kutta knots it measures how much the
acceleration changes inside the knot, not an error) and at the knots (RNEA at each knot's state
with its first stage's acceleration and contact forces against its torques: what a Runge–Kutta
knot's dynamics must satisfy), the largest defect of the row's knots stepped by each integrator
(how far the optimum of one step is from a trajectory of another), stationarity, iterations,
dynamics gap, friction use, slip, drift, periodicity and the solve's CPU seconds (this
process's, one OpenMP thread).

``--alternate`` then runs the command's alternation (springs by class, 4 rounds, tolerance
0.01) from the Euler row and from the first RK4 row that solved, its rounds solved with that
integrator; ``--simulate`` simulates each alternation's answer with its springs under both servos
(balance feedback ``auto``, as the command's rows). Each solve is kept in ``--work`` as it ends
(:class:`~hexaleg.design.codesign.optimal_stage.KeptSolves`, keyed by the codesign.json's
digest): a run killed and started again with the same arguments reads them back (a row read
back shows the CPU it took when it ran).
"""

from __future__ import annotations

import argparse
import hashlib
import json
import os
import time
from typing import Any

import numpy as np
import pinocchio as pin

import hexaleg
from hexaleg.design.chain.checkpoint import StageFiles
from hexaleg.design.chain.design_file import design_gait
from hexaleg.design.chain.groups import design_groups
from hexaleg.design.codesign.alternation import SMOOTH_FAMILIES, alternate, judged
from hexaleg.design.codesign.build import floor_constraints
from hexaleg.design.codesign.optimal_stage import KeptSolves
from hexaleg.design.codesign.servo import simulated_run
from hexaleg.design.springs.law_json import spring_from_entry
from hexaleg.errors import HexalegError
from hexaleg.optimal.problem import (
    OptimalParams,
    OptimalProblem,
    build_problem,
    contact_gains,
)
from hexaleg.optimal.solve import OptimalResult, knot_defect, solve

WEIGHTS = {"euler": (1.0,), "rk2": (0.0, 1.0), "rk4": (1 / 6, 1 / 3, 1 / 3, 1 / 6)}
"""The stages' weights ``b_i`` of each integrator as Crocoddyl's knots take them (Butcher,
*Numerical Methods for ODEs*, §23: RK2 the midpoint rule, RK4 the classical)."""


def out(line: str) -> None:
    print(line, flush=True)


def start(path: str) -> tuple[Any, hexaleg.GaitParams, hexaleg.SpringSet, str]:
    """The scenario, chosen gait, starting springs and their family of the codesign.json at
    ``path`` (no springs and ``linear`` where the family is not smooth, as the command)."""
    with open(path, encoding="utf-8") as f:
        data = json.load(f)
    name = data["robot"]["name"]
    gait = design_gait(data, name, path)
    assert gait is not None
    family = data["settings"]["family"]
    springs = (hexaleg.SpringSet({e["joint"]: spring_from_entry(e, path)
                                  for e in data["inner_springs"]})
               if family in SMOOTH_FAMILIES else hexaleg.SpringSet())
    return (hexaleg.Scenario.load(name), gait, springs,
            family if family in SMOOTH_FAMILIES else "linear")


def knot_energy(built: OptimalProblem, result: OptimalResult, nq: int) -> float:
    """The cycle's electrical energy by each knot's own quadrature, J (module docstring): the
    exact power at the torque ``u_k`` and each stage's joint speeds, weighted by
    :data:`WEIGHTS`."""
    weights = WEIGHTS[built.params.integrator]
    total = 0.0
    for k, (u, data) in enumerate(zip(result.torques, built.problem.runningDatas, strict=True)):
        stages = [result.x[k]] if built.params.integrator == "euler" else list(data.y)
        total += sum(b * float(built.power.exact(u, np.asarray(y)[nq + 6:]).sum())
                     for b, y in zip(weights, stages, strict=True))
    return total * built.dt


def knot_residual(robot: Any, built: OptimalProblem, result: OptimalResult) -> float:
    """Largest RNEA residual at the knots, N·m: each knot's state with its first stage's
    acceleration and contact forces (the dynamics a knot's integrator samples there) against
    ``u_k + τ_s``."""
    model, data = robot.model, robot.data
    nq = model.nq
    worst = 0.0
    for k, d in enumerate(built.problem.runningDatas):
        stage = d.differential if built.params.integrator == "euler" else d.differential[0]
        q, v = result.x[k, :nq], result.x[k, nq:]
        pin.framesForwardKinematics(model, data, q)
        fext = [pin.Force.Zero() for _ in range(model.njoints)]
        for j, leg in enumerate(robot.legs):
            frame = model.frames[leg.foot_frame_id]
            p = data.oMf[leg.foot_frame_id].translation
            f = result.forces[k, j]
            fext[frame.parentJoint] += data.oMi[frame.parentJoint].actInv(
                pin.Force(f, np.cross(p, f)))
        tau = pin.rnea(model, data, q, v, np.asarray(stage.xout), fext)
        joints = result.torques[k] + result.spring_torques[k]
        worst = max(worst, float(np.abs(tau - np.concatenate([np.zeros(6), joints])).max()))
    return worst


Row = tuple[str, str, str, str]
"""``(label, integrator, start, name)``: one solve of the table; ``start`` ``"gait"`` (the
command's: the gait's states and their quasi-static controls) or the ``name`` of an earlier
row whose optimum starts it; ``name`` the one this row's optimum takes when it is the first of
that name to solve ("": none)."""

ROWS: tuple[Row, ...] = (
    ("euler (the command's solve)", "euler", "gait", "euler"),
    ("euler again from its optimum", "euler", "euler", ""),
    ("rk2 from the gait", "rk2", "gait", ""),
    ("rk2 from euler's optimum", "rk2", "euler", "rk2"),
    ("rk4 from the gait", "rk4", "gait", "rk4"),
    ("rk4 from euler's optimum", "rk4", "euler", "rk4"),
    ("rk4 from rk2's optimum", "rk4", "rk2", "rk4"),
)
"""The rows: each integrator from the command's start, and from the Euler optimum (its defect
closed by the feasibility-driven solve), Euler itself given the same 100 iterations more as the
fair reference of those; RK4 also from the RK2 optimum started from Euler's (a step between:
box-FDDP's line search from Euler's optimum under RK4 can try a step whose rollout leaves the
finite numbers, and the springs' actuation raises there instead of the step being refused)."""


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--codesign", required=True, help="codesign.json of the start")
    parser.add_argument("--work", required=True,
                        help="folder of the kept solves (a rerun reads them back)")
    parser.add_argument("--alternate", action="store_true",
                        help="the command's alternation from the euler and rk4 rows")
    parser.add_argument("--simulate", action="store_true",
                        help="each alternation's answer simulated under both servos")
    args = parser.parse_args()
    t0, c0 = time.perf_counter(), os.times()
    run, chosen, springs, family = start(args.codesign)
    robot, motor = run.model, run.actuator
    contact = floor_constraints(run).contact()
    motion = hexaleg.gait(robot, chosen)
    nq = robot.model.nq
    with open(args.codesign, "rb") as f:
        key = hashlib.sha256(f.read()).hexdigest()[:16]
    keep = KeptSolves(StageFiles(args.work, key), robot, lambda line: out(f"  {line}"))
    timing = (f"pattern {chosen.pattern}" if chosen.pattern else
              "groups " + " / ".join(",".join(g) for g in chosen.groups or ()))
    out(f"start: {args.codesign} (sha256 {key}): {robot.name}, {timing}, duty "
        f"factor {chosen.duty_factor:.4g}, period {chosen.period:.4g} s, body "
        f"{chosen.body_height:.4g} m, springs {len(springs)} ({', '.join(springs) or 'none'}); "
        f"knot dt {1e3 * chosen.period / OptimalParams().nodes:.1f} ms; contact gains "
        + ", ".join(f"{n} k_p {g[0]:.4g} 1/s², k_d {g[1]:.4g} 1/s" for n in WEIGHTS
                    for g in [contact_gains(chosen.period / OptimalParams().nodes, n)]))
    built_of = {name: build_problem(robot, motion, motor, springs,
                                    OptimalParams(integrator=name))
                for name in WEIGHTS}
    solved: dict[str, OptimalResult] = {}
    source: dict[str, str] = {}
    lines = []
    for label, name, origin, saved in ROWS:
        built = built_of[name]
        if origin != "gait" and origin not in solved:
            lines.append(f"{label:30s} not run: no {origin} optimum to start from")
            out(lines[-1])
            continue
        warm = None if origin == "gait" else (solved[origin].x, solved[origin].torques)

        def compute(built: OptimalProblem = built, warm: Any = warm
                    ) -> tuple[OptimalResult | None, float, str]:
            c = time.process_time()
            try:
                return solve(robot, built, warm=warm), time.process_time() - c, ""
            except HexalegError as err:  # a stage's state gone non-finite in a line search
                return None, time.process_time() - c, f"{type(err).__name__}: {err}"
        result, cpu, failed = keep((label, name, origin, key), compute)
        if result is None:
            lines.append(f"{label:30s} failed after {cpu:.1f} s CPU: {failed}")
            out(lines[-1])
            continue
        if saved and saved not in solved:
            solved[saved], source[saved] = result, label
        x, u = result.x, result.torques
        defects = {n: knot_defect(b, x, u) for n, b in built_of.items()}
        built.problem.calc(list(x), list(u))  # the row's own datas for the knots' figures
        value, why = judged(robot, result, motion, motor, springs, contact)
        ratio = "—" if value is None else f"{value / result.energy_per_metre:6.3f}"
        lines.append(
            f"{label:30s} {'—' if value is None else f'{value:7.3f}'} "
            f"{result.energy_per_metre:7.3f} {ratio:>6s} "
            f"{knot_energy(built, result, nq) / built.distance:7.3f} "
            f"{result.residual:9.2g} {knot_residual(robot, built, result):9.2g} "
            + "".join(f"{defects[n]:9.2g}" for n in built_of)
            + f" {result.stationarity:12.2g} {result.iterations:4d} {result.dynamic_gap:8.1g} "
            f"{result.friction_use:8.3f} {1e3 * result.slip:6.1f} {1e3 * result.drift:6.3f} "
            f"{result.periodicity:8.2g} {cpu:6.1f}" + (f"  ({why})" if why else ""))
        out(lines[-1])
    out(f"{'row':30s} {'judged':>7s} {'solver':>7s} {'ratio':>6s} {'stages':>7s} "
        f"{'residual':>9s} {'at knots':>9s} "
        + "".join(f"{'→ ' + n:>9s}" for n in built_of)
        + f" {'stationarity':>12s} {'its':>4s} {'gap':>8s} {'friction':>8s} {'slip':>6s} "
        f"{'drift':>6s} {'period.':>8s} {'CPU s':>6s}")
    for line in lines:
        out(line)
    out("columns: judged = hexaleg's prediction of the rebuilt cycle, J/m (the alternation's "
        "judge); solver = its J/m at the knots (left Riemann); ratio = judged / solver; stages = "
        "the solver's J/m by its knot's own quadrature; residual = Newton–Euler by "
        "(v_{k+1} − v_k)/dt (Euler's check), at knots = RNEA at each knot's own acceleration, "
        "N·m; → X = the knots' largest defect stepped by X (‖x_{k+1} ⊖ f(x_k, u_k)‖∞); "
        "its = box-FDDP iterations of the row (after those of the row it starts from); slip "
        "mm/s, drift mm, period. = periodicity gap")
    if args.alternate:
        groups = design_groups(robot, tuple(robot.joint_classes), "class")
        for name in ("euler", "rk4"):
            if name not in solved:
                continue
            first = solved[name]
            c = time.process_time()
            alt = alternate(robot, motion, motor, contact, springs=springs,
                            params=OptimalParams(integrator=name), family=family, groups=groups,
                            first=first,
                            keep=keep, say=lambda line: None)
            r = alt.best
            out(f"alternation from the row {source[name]} (the command's: 4 rounds, tolerance "
                "0.01, springs by class): "
                + " → ".join("—" if e is None else f"{e:.3f}" for e in alt.energies)
                + f" J/m judged (first: the gait; {len(alt.rounds)} rounds, the gait kept: "
                f"{alt.kept_gait}); its solver's {r.energy_per_metre:.3f} J/m at the knots, "
                f"stationarity {r.stationarity:.2g}, friction use {r.friction_use:.3f}, slip "
                f"{1e3 * r.slip:.1f} mm/s; CPU {time.process_time() - c:.0f} s")
            if args.simulate:
                sims = []
                for servo in ("feedforward", "position"):
                    value, why, closed = simulated_run(robot, alt.motion, motor, alt.springs,
                                                       servo, contact, "auto")
                    loop = "closed loop" if closed else "open loop"
                    sims.append(f"{servo} " + (f"{value:.2f} ({loop})" if value is not None
                                               else f"— ({why})"))
                out(f"  its answer simulated (balance feedback auto): {', '.join(sims)} J/m")
    c1 = os.times()
    cpu_all = (c1.user - c0.user) + (c1.system - c0.system)
    out(f"wall {time.perf_counter() - t0:.0f} s, CPU {cpu_all:.0f} s (this process)")


if __name__ == "__main__":
    main()
