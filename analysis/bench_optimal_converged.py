"""Convergence levers of the optimal motion now that a solve is fast (issue #56's 0.8× target):
from the co-design's gait G and springs S at duty factor 0.85 with the best start of the starts
lattice (body height × 1.05), the solve run longer (iterations), on finer knots, from combined
start moves, from taller bodies, and from the widened co-designs' gaits; the alternation with
more rounds. Each judged by hexaleg's prediction of its cycle rebuilt in task space (the
alternation's judge), against three parametric co-designs predicted the same way; the
alternation's answers simulated with balance feedback under both servos (log:
analysis/bench_logs/bench_optimal_converged.log; not an example study: it needs the optimal
extra and minutes).

Run:  python analysis/bench_optimal_converged.py --chosen cd.pkl --widened cd0915.pkl
                                                 --widest cd0917.pkl
                                                 [--duty 0.85] [--rounds 6] [--work DIR]

Needs the ``optimal`` extra. G and S from the pickle ``--chosen`` (the co-design searched to duty
factor 0.8: analysis/bench_optimal_rows.py ``--chosen`` or
analysis/bench_codesign_duty_bound.py ``--duty-high 0.8 --chosen``); the widened baseline from
``--widened`` (``bench_codesign_duty_bound.py --duty-high 0.9 --body-high 1.5 --chosen``) and
the widest from ``--widest`` (the same with ``--body-high 1.7``).
The three baselines are predicted and simulated here, in the same process. Each row: one box-FDDP
solve with S in its dynamics (:class:`~hexaleg.optimal.problem.OptimalParams` as the row says,
every other setting the default), its rebuilt cycle's prediction with S
(:func:`~hexaleg.design.codesign.alternation.judged`), the solver's own J/m at its knots, its
stationarity (threshold 1e-8), largest friction use of the cone, largest stance slip at a knot,
and the solve's CPU seconds (this process's, one OpenMP thread; a solve read back shows the CPU
it took when it ran). The row with the least prediction from G on 40 knots, the one on 80, and
the one from each widened gait are then each alternated (springs designed on its rebuilt cycle,
the cycle re-solved with them) for up to ``--rounds`` rounds with no tolerance (it stops at the
first round that does not gain), and each answer simulated under both servos with balance
feedback on. Each solve is kept in ``--work`` as it ends
(:class:`~hexaleg.design.codesign.optimal_stage.KeptSolves`): a run killed and started again
with the same arguments reads them back.
"""

from __future__ import annotations

import argparse
import dataclasses
import os
import pickle
import time
from typing import Any

import hexaleg
from hexaleg.design.chain.checkpoint import StageFiles
from hexaleg.design.codesign.alternation import alternate, judged, predicted_per_metre
from hexaleg.design.codesign.gait_evaluation import Constraints
from hexaleg.design.codesign.optimal_stage import KeptSolves
from hexaleg.design.codesign.servo import simulated_run
from hexaleg.errors import HexalegError
from hexaleg.optimal.problem import OptimalParams

BODY = 1.05
"""The starts lattice's best start (docs/optimal.md, "Starts of the optimal motion")."""

SERVOS = ("feedforward", "position")


Row = tuple[str, hexaleg.GaitParams, hexaleg.SpringSet, OptimalParams]
"""``(label, gait, springs, settings)``: one solve of the table."""


def rows(timed: hexaleg.GaitParams, springs: hexaleg.SpringSet,
         wider: dict[str, dict[str, Any]]) -> list[Row]:
    """The levers: the best start at the command's settings first (the reference), each lever
    moved alone from it, the body height's trend on 40 and 80 knots, then each widened
    co-design's gait (``wider``: name → its pickle) with its springs as the start (the optimal
    control's own gain over the parametric family searched as widely)."""
    assert timed.body_height is not None

    def body(f: float) -> hexaleg.GaitParams:
        return dataclasses.replace(timed, body_height=timed.body_height * f)

    d = OptimalParams()
    k80 = dataclasses.replace(d, nodes=80)
    return [
        ("body × 1.05, 40 knots, 100 iterations", body(BODY), springs, d),
        ("body × 1.05, 40 knots, 300 iterations", body(BODY), springs,
         dataclasses.replace(d, iterations=300)),
        ("body × 1.05, 40 knots, 1000 iterations", body(BODY), springs,
         dataclasses.replace(d, iterations=1000)),
        ("body × 1.05, 80 knots, 100 iterations", body(BODY), springs, k80),
        ("body × 1.05, 120 knots, 100 iterations", body(BODY), springs,
         dataclasses.replace(d, nodes=120)),
        ("body × 1.05, 80 knots, 300 iterations", body(BODY), springs,
         dataclasses.replace(d, nodes=80, iterations=300)),
        ("body × 1.05 + swing weight × 0.01", body(BODY), springs,
         dataclasses.replace(d, swing_weight=d.swing_weight * 0.01)),
        ("body × 1.10, 40 knots, 100 iterations", body(1.10), springs, d),
        ("body × 1.10, 80 knots, 100 iterations", body(1.10), springs, k80),
        ("body × 1.15, 40 knots, 100 iterations", body(1.15), springs, d),
        ("body × 1.15, 80 knots, 100 iterations", body(1.15), springs, k80),
        ("body × 1.20, 40 knots, 100 iterations", body(1.20), springs, d),
        ("body × 1.20, 80 knots, 100 iterations", body(1.20), springs, k80),
        ("body × 1.25, 40 knots, 100 iterations", body(1.25), springs, d),
        ("body × 1.30, 40 knots, 100 iterations", body(1.30), springs, d),
    ] + [(f"{name} gait, its springs, {k.nodes} knots", w["chosen"], w["springs"], k)
         for name, w in wider.items() for k in (d, k80)]


def simulated(robot: Any, motion: Any, motor: Any, springs: Any, contact: Any
              ) -> dict[str, float | None]:
    """Simulated J/m under each servo, balance feedback on (None: it did not walk)."""
    return {k: simulated_run(robot, motion, motor, springs, k, contact, "on")[0]
            for k in SERVOS}


def worse(sims: dict[str, float | None]) -> float:
    """The worse servo's J/m (nan where one did not walk)."""
    values = list(sims.values())
    return float("nan") if any(v is None for v in values) else max(values)  # type: ignore


def shown(sims: dict[str, float | None]) -> str:
    return ", ".join(f"{k} {'—' if v is None else f'{v:.2f}'}" for k, v in sims.items())


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--chosen", required=True, help="pickle of G and S (duty ≤ 0.8)")
    parser.add_argument("--widest", required=True,
                        help="pickle of the co-design with duty ≤ 0.9, body ≤ 1.7 × default")
    parser.add_argument("--widened", required=True,
                        help="pickle of the co-design with duty ≤ 0.9, body ≤ 1.5 × default")
    parser.add_argument("--duty", type=float, default=0.85, help="the timing's duty factor")
    parser.add_argument("--rounds", type=int, default=6, help="alternation rounds at most")
    parser.add_argument("--work", default="bench_optimal_converged.work",
                        help="folder of the kept solves (a rerun reads them back)")
    args = parser.parse_args()
    t0, c0 = time.perf_counter(), os.times()
    with open(args.chosen, "rb") as f:
        saved = pickle.load(f)
    wider = {}
    for name, path in (("widened", args.widened), ("widest", args.widest)):
        with open(path, "rb") as f:
            wider[name] = pickle.load(f)
    run = hexaleg.Scenario.load("hexaleg")
    robot, motor, contact = run.model, run.actuator, run.contact
    g, s = saved["chosen"], saved["springs"]
    stages = StageFiles(args.work, f"{args.chosen} {args.widened} {args.widest} {args.duty!r}")
    keep = KeptSolves(stages, robot, lambda line: print(f"  {line}", flush=True))

    def out(line: str) -> None:
        print(line, flush=True)

    base: dict[str, tuple[float, dict[str, float | None]]] = {}
    for name, data in (("default", saved), *wider.items()):
        motion = hexaleg.gait(robot, data["chosen"])
        value, _ = predicted_per_metre(robot, motion, motor, data["springs"], contact)
        assert value is not None
        base[name] = (value, simulated(robot, motion, motor, data["springs"], contact))
        p = data["chosen"]
        out(f"baseline {name}: duty {p.duty_factor:.4g}, period {p.period:.4g} s, body "
            f"{p.body_height:.4g} m: {value:.3f} J/m predicted (the co-design's own figure "
            f"{data['per_metre']:.3f}), simulated with balance feedback "
            f"{shown(base[name][1])}")

    timed = dataclasses.replace(g, duty_factor=args.duty)
    out(f"G at duty factor {args.duty} with S: "
        f"{predicted_per_metre(robot, hexaleg.gait(robot, timed), motor, s, contact)[0]:.3f} "
        "J/m predicted")
    from hexaleg.optimal.problem import build_problem  # needs Crocoddyl
    from hexaleg.optimal.solve import solve

    out(f"{'row (G at duty ' + str(args.duty) + ', with S)':42s} {'rebuilt':>8s} "
        + "".join(f"{'× ' + n:>10s}" for n in base)
        + f" {'solver':>7s} {'stationarity':>12s} {'its':>5s} {'friction':>8s} "
        f"{'slip mm/s':>9s} {'CPU s':>6s}")
    found: list[tuple[Row, Any, float]] = []
    for row in rows(timed, s, wider):
        label, gp, springs, settings = row
        try:
            motion = hexaleg.gait(robot, gp)
        except HexalegError as err:  # a body height the legs cannot reach
            out(f"{label:42s} no gait ({type(err).__name__}: {err})")
            continue

        def compute(motion: Any = motion, springs: Any = springs, settings: Any = settings
                    ) -> tuple[Any, float]:
            c = time.process_time()
            built = build_problem(robot, motion, motor, springs, settings)
            return solve(robot, built), time.process_time() - c
        result, cpu = keep(("row", gp, springs, settings), compute)
        said = judged(robot, result, motion, motor, springs, contact,
                      Constraints.friction_margin)
        value, why = said.judged, said.why
        if value is not None:
            found.append((row, result, value))
        ratio = "".join(f"{'—' if value is None else f'{value / b:.3f}':>10s}"
                        for b, _ in base.values())
        out(f"{label:42s} {'—' if value is None else f'{value:8.3f}'}{ratio} "
            f"{result.energy_per_metre:7.3f} {result.stationarity:12.2g} "
            f"{result.iterations:5d} {result.friction_use:8.3f} {1e3 * result.slip:9.1f} "
            f"{cpu:6.1f}" + (f"  ({why})" if why else ""))
    groups = [("from G, 40 knots", "body", 40), ("from G, 80 knots", "body", 80),
              *((f"from the {n} gait", n, 0) for n in wider)]  # 0: any knots
    for name, first, nodes in groups:
        (label, gp, springs, settings), result, _ = min(
            (f for f in found if f[0][0].startswith(first) and nodes in (0, f[0][3].nodes)),
            key=lambda f: f[2])
        out(f"alternation from the best row {name}: {label}")
        c = time.process_time()

        def told(line: str) -> None:
            if not line.startswith("iteration"):  # the rounds' lines, not each solve's progress
                out(f"  alternation: {line}")

        alt = alternate(robot, hexaleg.gait(robot, gp), motor, contact, springs=springs,
                        params=settings, first=result, rounds=args.rounds, tolerance=0.0,
                        keep=keep, say=told)
        out("alternation: " + " → ".join("—" if e is None else f"{e:.3f}" for e in alt.energies)
            + f" J/m predicted rebuilt ({len(alt.rounds)} rounds, last gain {alt.gap:.2g}, the "
            f"gait kept: {alt.kept_gait}; CPU {time.process_time() - c:.0f} s)")
        r = alt.best
        out(f"its solve: stationarity {r.stationarity:.2g} after {r.iterations} iterations, "
            f"residual {r.residual:.1g} N·m, friction use {r.friction_use:.3f}, slip "
            f"{1e3 * r.slip:.1f} mm/s, drift {1e3 * r.drift:.3f} mm, periodicity "
            f"{r.periodicity:.2g}")
        sims = simulated(robot, alt.motion, motor, alt.springs, contact)
        value = alt.predicted
        assert value is not None
        out(f"the answer simulated with balance feedback: {shown(sims)}")
        for n, (b, sb) in base.items():
            out(f"against the {n} co-design ({b:.3f} predicted, worse servo {worse(sb):.2f}): "
                f"predicted {value / b:.3f}×, worse servo {worse(sims) / worse(sb):.3f}×"
                + (" (targets ≤ 0.8 and ≤ 0.85)" if n == "default" else ""))
    c1 = os.times()
    cpu = (c1.user - c0.user) + (c1.system - c0.system)
    out(f"wall {time.perf_counter() - t0:.0f} s, CPU {cpu:.0f} s")


if __name__ == "__main__":
    main()
