"""Speed of the optimal motion's solves (issue #56: ``codesign --motion optimal`` in ≤ 10 min on
2 cores), against baselines run in the same process (log:
analysis/bench_logs/bench_optimal_speed.log).

Run:  python analysis/bench_optimal_speed.py [--nodes 40] [--iterations 100]

Needs the ``optimal`` extra (crocoddyl 3.2.1 with pin 4.0). On the default robot's gait with the
linear springs the project's design gives it (electrical metric; analysis/bench_optimal.py's
warm start):

1. one box-FDDP solve as the package ran it before (the baseline: Eigen's products split over
   the OpenMP threads of every core, the springs evaluated joint by joint through each law's
   own methods — :class:`OldSpringActuation` below, the actuation of commit a288eec, kept here
   only) and as it runs now (:mod:`hexaleg.optimal.backend`: one OpenMP thread;
   :class:`hexaleg.optimal.actuation.LawGroup`), with the largest difference of their iterates
   (0 when the new path is the old arithmetic);
2. the contact timing lattice (:func:`hexaleg.design.codesign.timing.search_timing`, five
   solves with those springs) solved in turn on one worker and side by side on the command's
   workers (:func:`hexaleg.design.codesign.alternation.apart`), about the default gait at the
   co-design's duty factor 0.8 (the lattice: 0.8, 0.85, 0.9, the period × 0.85 and × 1.15),
   with the largest difference of their cycles and whether the choice is the same.

Each is timed by wall clock and by CPU seconds (this process's and its reaped workers'); the
ratios are old / new. Wall times depend on the machine's load, printed beside them.
"""

from __future__ import annotations

import argparse
import ctypes
import dataclasses
import os
import time
from collections.abc import Callable
from typing import Any

import numpy as np

import hexaleg
from hexaleg.design.codesign.build import default_gait
from hexaleg.design.codesign.timing import search_timing
from hexaleg.design.search.optimal import optimal_springs
from hexaleg.optimal import backend, problem
from hexaleg.optimal.actuation import SpringActuation, stiffness
from hexaleg.optimal.problem import OptimalParams, build_problem
from hexaleg.optimal.solve import solve
from hexaleg.parallel import workers


class OldSpringActuation(SpringActuation):
    """The spring actuation of commit a288eec: each sprung joint's torque, stiffness and
    damping by its law's own methods on one-element arrays, joint by joint (the baseline)."""

    def spring_torques(self, x: np.ndarray) -> np.ndarray:
        nq = self.state.nq
        out = np.zeros(self._nv - self._base)
        for s in self.sprung:
            q, v = np.array([x[s.iq]]), np.array([x[nq + s.iv]])
            out[s.column] = float(s.spring.torque(q, v)[0])
        return out

    def calcDiff(self, data: Any, x: np.ndarray, u: np.ndarray | None = None) -> None:
        nv, b = self._nv, self._base
        dx = np.zeros((nv, 2 * nv))
        for s in self.sprung:
            q = x[s.iq]
            dx[b + s.column, s.iv] = stiffness(s.spring, q)
            one, zero = np.array([1.0]), np.array([0.0])
            qa = np.array([q])
            dx[b + s.column, nv + s.iv] = float(s.spring.torque(qa, one)[0]
                                                - s.spring.torque(qa, zero)[0])
        data.dtau_dx[...] = np.reshape(dx, np.shape(data.dtau_dx))
        du = np.zeros((nv, nv - b))
        du[b:, :] = np.eye(nv - b)
        data.dtau_du[...] = np.reshape(du, np.shape(data.dtau_du))


def load() -> str:
    """The load averages, for the wall times."""
    return "load " + ", ".join(f"{x:.2f}" for x in os.getloadavg())


def timed(work: Callable[[], Any]) -> tuple[Any, float, float]:
    """``work()``, its wall time and its CPU seconds (this process and its reaped children)."""
    t0, c0 = time.perf_counter(), os.times()
    out = work()
    t1, c1 = time.perf_counter(), os.times()
    cpu = sum(getattr(c1, k) - getattr(c0, k)
              for k in ("user", "system", "children_user", "children_system"))
    return out, t1 - t0, cpu


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--nodes", type=int, default=40, help="knots per cycle")
    parser.add_argument("--iterations", type=int, default=100, help="box-FDDP iterations")
    args = parser.parse_args()
    run = hexaleg.Scenario.load("hexaleg")
    robot, gait = run.model, run.motion()
    springs = optimal_springs(run.prepare(), list(robot.joint_classes), family="linear",
                              metric="electrical").springs
    params = OptimalParams(nodes=args.nodes, iterations=args.iterations)
    cores = workers.default_workers()
    print(f"default robot, its gait with its linear springs; {args.nodes} knots, "
          f"{args.iterations} iterations at most; {cores} cores; {load()}", flush=True)
    openmp = ctypes.CDLL(backend.OPENMP)

    def old() -> Any:
        openmp.omp_set_num_threads(cores)
        try:
            problem.SpringActuation = OldSpringActuation
            built = build_problem(robot, gait, run.actuator, springs, params)
        finally:
            problem.SpringActuation = SpringActuation
        try:
            return solve(robot, built)
        finally:
            openmp.omp_set_num_threads(1)

    def new() -> Any:
        return solve(robot, build_problem(robot, gait, run.actuator, springs, params))

    before, wall0, cpu0 = timed(old)
    print(f"one solve, before: {before.iterations} iterations, {before.energy_per_metre:.6g} "
          f"J/m, wall {wall0:.1f} s, CPU {cpu0:.1f} s ({load()})", flush=True)
    after, wall1, cpu1 = timed(new)
    print(f"one solve, now:    {after.iterations} iterations, {after.energy_per_metre:.6g} J/m, "
          f"wall {wall1:.1f} s, CPU {cpu1:.1f} s ({load()})", flush=True)
    print(f"one solve: before / now {wall0 / wall1:.2f}× wall, {cpu0 / cpu1:.2f}× CPU; iterates "
          f"differ by {np.abs(before.x - after.x).max():.3g} (states), "
          f"{np.abs(before.torques - after.torques).max():.3g} N·m (torques)", flush=True)

    chosen = dataclasses.replace(default_gait(robot, "hexaleg", gait.distance / gait.period,
                                              None, 200), duty_factor=0.8)
    found = {}
    spans = {}
    for n in (1, cores):
        workers.default_workers = lambda n=n: n
        found[n], wall, cpu = timed(lambda: search_timing(
            robot, chosen, run.actuator, springs, run.contact, params))
        spans[n] = (wall, cpu)
        picked = found[n].chosen
        print(f"timing lattice on {n} worker{'s' * (n > 1)}: {len(found[n].candidates)} solves, "
              f"chosen duty {picked.params.duty_factor:.3g}, period {picked.params.period:.4g} "
              f"s, {picked.predicted:.4g} J/m predicted; wall {wall:.1f} s, CPU {cpu:.1f} s "
              f"({load()})", flush=True)
    diff = max(float(np.abs(a.result.x - b.result.x).max())
               for a, b in zip(found[1].candidates, found[cores].candidates, strict=True))
    (w1, c1), (wn, cn) = spans[1], spans[cores]
    print(f"timing lattice: in turn / side by side {w1 / wn:.2f}× wall, {c1 / cn:.2f}× CPU; "
          f"cycles differ by {diff:.3g}, the same choice: {found[1].best == found[cores].best}",
          flush=True)


if __name__ == "__main__":
    main()
