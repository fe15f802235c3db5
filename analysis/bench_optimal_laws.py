"""Speed of one optimal solve with the spring laws' own formulas in the actuation, against the
actuation that wrote them a second time, run in the same process (log:
analysis/bench_logs/bench_optimal_laws.log).

Run:  python analysis/bench_optimal_laws.py [--nodes 40] [--iterations 100] [--repeats 3]

Needs the ``optimal`` extra (crocoddyl 3.2.1 with pin 4.0). :class:`hexaleg.optimal.actuation.
LawGroup` evaluates a group of sprung joints' laws at once; it used to copy the laws' torque
formulas vectorised (each term kind's φ and the dead zone's torque: :class:`CopiedLawGroup`
below, the class of commit 3ec0662, kept here only), and now calls the laws' own
(:func:`hexaleg.robot.springs.terms.basis_torque`, :func:`hexaleg.robot.springs.dead_zone.
zone_basis` and ``zone_torque``) with the group's parameters as arrays. On the default robot's
gait, one box-FDDP solve with each of two spring sets — the linear springs the project's design
gives it (electrical metric; the term laws' path) and a dead-zone spring on every femur
(:data:`ZONE_STIFFNESS`) with the linear springs elsewhere (the dead zone's path) — is timed
with the copied formulas and with the laws' own, alternately ``repeats`` times; the least CPU
seconds of each are compared (ratio copied / own: 1 is the same speed), and the iterates must
not differ.
"""

from __future__ import annotations

import argparse
import os
import time
from collections.abc import Callable
from typing import Any

import numpy as np

import hexaleg
from hexaleg.design.search.optimal import optimal_springs
from hexaleg.optimal import actuation
from hexaleg.optimal.problem import OptimalParams, build_problem
from hexaleg.optimal.solve import solve
from hexaleg.robot.springs import DeadZoneSpring


class CopiedLawGroup(actuation.LawGroup):
    """:class:`~hexaleg.optimal.actuation.LawGroup` as commit 3ec0662 had it: the laws' torque
    formulas copied, vectorised (the baseline)."""

    def torques(self, q: np.ndarray, v: np.ndarray) -> np.ndarray:
        if self.zone:  # DeadZoneSpring.torque and its torque_basis, term by term
            d = q - self.neutral
            a = self.transmission
            plus = -a * np.maximum(d - self.plus, 0.0)
            minus = -a * np.minimum(d - self.minus, 0.0)
            engaged = (d > self.plus) | (d < self.minus)
            damp = np.where(engaged, -a * v, 0.0)
            return (self.k_plus * plus + self.k_minus * minus + self.k2 * -d
                    + self.damping * damp)
        d = q[:, None] - self.angles  # Term.torque of every term, then basis @ magnitudes
        phi = np.ones_like(d)
        for kind, where in self.kinds.items():
            phi[where] = _PHI[kind](d[where])
        return np.matmul(phi[:, None, :], self.magnitudes[:, :, None])[:, 0, 0]


_PHI: dict[str, Callable[[np.ndarray], np.ndarray]] = {
    "above": lambda d: -np.maximum(d, 0.0), "below": lambda d: np.maximum(-d, 0.0),
    "step_above": lambda d: -(d > 0).astype(float), "step_below": lambda d: (d < 0).astype(float),
    "linear": lambda d: -d, "constant": np.ones_like}
"""The copy of each term kind's φ that :class:`CopiedLawGroup` used."""


ZONE_STIFFNESS = 20.0
"""The femurs' dead-zone stiffness, N·mm/deg: the paper's contact angle (7.32°), α (1.05) and
damping (1 N·mm·s/deg, Table 4) with a softer spring than its 400, at which this gait's solve
stops after 22 of its iterations (100 and 400 alike): at 20 it runs all of them."""


def load() -> str:
    """The load averages, for the wall times."""
    return "load " + ", ".join(f"{x:.2f}" for x in os.getloadavg())


def timed(work: Callable[[], Any]) -> tuple[Any, float, float]:
    """``work()``, its wall time and its CPU seconds (this process)."""
    t0, c0 = time.perf_counter(), time.process_time()
    out = work()
    return out, time.perf_counter() - t0, time.process_time() - c0


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--nodes", type=int, default=40, help="knots per cycle")
    parser.add_argument("--iterations", type=int, default=100, help="box-FDDP iterations")
    parser.add_argument("--repeats", type=int, default=3, help="solves of each, alternately")
    args = parser.parse_args()
    run = hexaleg.Scenario.load("hexaleg")
    robot, gait = run.model, run.motion()
    linear = optimal_springs(run.prepare(), list(robot.joint_classes), family="linear",
                             metric="electrical").springs
    paper = DeadZoneSpring.from_paper(ZONE_STIFFNESS, 7.32, 1.05, damping_nmms_per_deg=1.0)
    zones = hexaleg.SpringSet({**dict(linear.items()), **{
        name: paper for name in robot.joint_names if name.endswith("femur")}})
    params = OptimalParams(nodes=args.nodes, iterations=args.iterations)
    print(f"default robot, its gait; {args.nodes} knots, {args.iterations} iterations at most; "
          f"{args.repeats} solves of each, alternately; {load()}", flush=True)
    own = actuation.LawGroup

    def one(group: type, springs: hexaleg.SpringSet) -> Any:
        built = build_problem(robot, gait, run.actuator, springs, params)
        assert all(type(g) is group for g in built.actuation.groups)
        return solve(robot, built)

    for label, springs in (("linear springs", linear), ("femur dead zones", zones)):
        spans: dict[str, list[tuple[float, float]]] = {"copied": [], "own": []}
        results: dict[str, Any] = {}
        for _ in range(args.repeats):
            for name, group in (("copied", CopiedLawGroup), ("own", own)):
                actuation.LawGroup = group
                try:
                    results[name], wall, cpu = timed(
                        lambda group=group, springs=springs: one(group, springs))
                finally:
                    actuation.LawGroup = own
                spans[name].append((wall, cpu))
        (w0, c0), (w1, c1) = (min(spans[n], key=lambda s: s[1]) for n in ("copied", "own"))
        a, b = results["copied"], results["own"]
        print(f"{label}: {b.iterations} iterations, {b.energy_per_metre:.6g} J/m; least CPU of "
              f"{args.repeats}: copied {c0:.2f} s, own {c1:.2f} s, copied / own {c0 / c1:.3f}× "
              f"(wall {w0:.2f} / {w1:.2f} s); iterates differ by "
              f"{np.abs(a.x - b.x).max():.3g} (states), "
              f"{np.abs(a.torques - b.torques).max():.3g} N·m (torques) ({load()})", flush=True)


if __name__ == "__main__":
    main()
