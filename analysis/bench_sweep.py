"""Benchmark of stiffness sweeps and the spring-placement study on the default tripod gait.

Run:  python analysis/bench_sweep.py [--samples 1000] [--workers N] [--mu 0.3] [--out DIR]

Both run with friction ``--mu`` (default 0.3, the paper's Table 3 static friction: many samples
put a foot on its friction cone's surface, issue #15).

1. A 100-value stiffness sweep of one joint class (femur, centred dead zone with the paper's
   θ_k/A, k log-spaced): serial and on the local process pool, each including the one-off gait
   and ``prepare``; the baseline is the same designs through fresh ``analyze()`` calls (gait
   prepared anew per design, measured on 10 designs and scaled to 100). Both runs start from
   the same state: libraries imported, no robot or gait cached. Target ≤ 1 s.
2. The placement study: coxa, femur and tibia × 50 k × 10 dead-zone widths (1500 points, one
   class sprung at a time) on the process pool, then each class's optimum refined from the grid's
   best point by Nelder–Mead, every combination of classes, and the robustness of the best set to
   ±20 % period and stride; then the global optimum of the preloaded family on every set of classes
   (hexaleg.design.studies.placement.placement, Joule energy), beside the old search's saving.
   Target ≤ 20 s on 2 cores for the grid at μ = 0.3 (issue #15). The same grid is then run serially
   in this process for the pool's speed-up (and must give the same table).
"""

from __future__ import annotations

import argparse
import dataclasses
import itertools
import shutil
import tempfile
import time
from pathlib import Path

import numpy as np

import hexaleg
import hexaleg.design.studies.placement
import hexaleg.dynamics.prepare
from hexaleg.design.evaluator import clear_cache, evaluator
from hexaleg.design.robust.conditions import robustness
from hexaleg.design.rules import PAPER_DEAD_ZONE_RATIO
from hexaleg.design.studies.optimise import optimise
from hexaleg.design.studies.placement import placement
from hexaleg.dynamics.contact import ContactParams
from hexaleg.motion.params import GaitParams
from hexaleg.scenario.scenario import Scenario
from hexaleg.sweep.executors import default_workers
from hexaleg.sweep.runner import run_sweep
from hexaleg.sweep.spec import SweepSpec

CLASSES = ("coxa", "femur", "tibia")


def _timed(fn):
    t0 = time.perf_counter()
    out = fn()
    return out, time.perf_counter() - t0


def single_class(out: Path, samples: int, workers: int, run: Scenario) -> None:
    ks = tuple(float(k) for k in np.geomspace(0.01, 2.0, 100))
    spec = SweepSpec(run=run, gait={"samples": samples},
                     springs={"femur": {"k": ks, "dead_zone": PAPER_DEAD_ZONE_RATIO}},
                     chunk_size=25)
    # Same start for both: libraries imported (a one-point sweep), no robot or gait cached.
    run_sweep(SweepSpec(run=run, gait={"samples": 20},
                        springs={"femur": {"k": 0.1, "dead_zone": 0.5}}),
              out / "warm-up", executor="serial")
    clear_cache()
    res_pool, t_pool = _timed(lambda: run_sweep(spec, out / "single-pool", workers=workers))
    clear_cache()
    res_serial, t_serial = _timed(lambda: run_sweep(spec, out / "single-serial",
                                                    executor="serial"))
    assert res_pool.table.equals(res_serial.table)
    robot = hexaleg.load()
    gait = GaitParams(samples=samples)
    ev = evaluator(run.with_gait({"samples": samples}))

    def fresh(k: float) -> float:
        motion = hexaleg.gait(robot, gait)
        springs = ev.springs({"femur": robot.joints("femur")},
                             {"femur": {"k": k, "dead_zone": PAPER_DEAD_ZONE_RATIO}})
        return hexaleg.dynamics.prepare.analyze(robot, motion, springs,
                               contact=run.contact).metrics["total"]["electrical"]

    _, t_fresh10 = _timed(lambda: [fresh(k) for k in ks[::10]])
    t_fresh = t_fresh10 * 10
    best = res_serial.table.loc[res_serial.table["electrical"].idxmin()]
    print(f"1. femur stiffness sweep, 100 values, default gait ({samples} samples/cycle)")
    print(f"   process pool ({workers} workers): {t_pool:.2f} s   serial: {t_serial:.2f} s   "
          f"(target ≤ 1 s; both include the gait and prepare)")
    print(f"   100 fresh analyze() calls: {t_fresh:.2f} s (10 measured ×10) → sweep is "
          f"{t_fresh / t_serial:.1f}× (serial) and {t_fresh / t_pool:.1f}× (pool) faster; "
          f"pool/serial = {t_pool / t_serial:.2f}")
    print(f"   best: k = {best['femur.k']:.4g} N·m/rad, electrical saving "
          f"{100 * best['saving.electrical']:+.2f} %")


def placement_study(out: Path, samples: int, workers: int, run: Scenario) -> None:
    ks = {"start": 0.01, "stop": 2.0, "num": 50, "scale": "log"}
    zones = {"start": 0.05, "stop": 0.9, "num": 10}
    data = {"sweep": {"layout": "each", "chunk_size": 50}, "gait": {"samples": samples},
            "springs": {c: {"k": ks, "dead_zone": zones} for c in CLASSES}}
    spec = dataclasses.replace(SweepSpec.from_mapping(data), run=run)
    result, t_grid = _timed(lambda: run_sweep(spec, out / "placement", workers=workers))
    table = result.table
    serial, t_serial = _timed(lambda: run_sweep(spec, out / "placement-serial",
                                                executor="serial"))
    assert serial.table.equals(table)

    ev = evaluator(run.with_gait({"samples": samples}))
    groups = {c: ev.robot.joints(c) for c in CLASSES}
    starts = {}
    for c in CLASSES:
        rows = table[(table["springs"] == c) & (table["status"] == "ok")]
        best = rows.loc[rows["electrical"].idxmin()]
        half = max(ev.half_range[j] for j in groups[c])
        starts[c] = (float(best[f"{c}.k"]), float(best[f"{c}.dead_zone"]) * half)
    optima, t_opt = _timed(lambda: {c: optimise(ev, c, groups[c], start=starts[c],
                                                k_bounds=(0.01, 2.0)) for c in CLASSES})
    combos = sorted((ev.value({c: groups[c] for c in combo},
                               {c: optima[c].design() for c in combo}), combo)
                     for r in range(1, len(CLASSES) + 1)
                     for combo in itertools.combinations(CLASSES, r))
    top = combos[0][1]
    robust, t_rob = _timed(lambda: robustness(run.replace(gait=GaitParams(samples=samples)),
                                              groups, {c: optima[c].design() for c in top},
                                              factors=(0.8, 1.0, 1.2)))
    failed = int((table["status"] != "ok").sum())
    print(f"2. placement study: {len(CLASSES)} classes × 50 k × 10 dead zones = "
          f"{spec.n_points} points ({failed} without admissible forces/torques)")
    print(f"   grid on the process pool ({workers} workers): {t_grid:.1f} s (target ≤ 20 s); "
          f"serial {t_serial:.1f} s → pool speed-up "
          f"{t_serial / t_grid:.2f}×")
    print(f"   Nelder–Mead refinement per class: {t_opt:.1f} s; robustness ±20 %: {t_rob:.1f} s")
    for c, o in optima.items():
        print(f"   {c:6s} optimum k = {o.k:.4g} N·m/rad, θ_k = {o.theta_k:.4g} rad: "
              f"electrical {o.value:.5g} J vs {o.baseline:.5g} J, saving "
              f"{100 * o.saving:+.2f} %")
    base = ev.baseline["total"]["electrical"]
    print("   sets of sprung classes (each at its own optimum), best first:")
    for value, combo in combos:
        print(f"     {'+'.join(combo):18s} saving {100 * (base - value) / base:+.2f} %")
    print(f"   robustness of {'+'.join(top)} (design frozen on the nominal gait):")
    for _, row in robust.iterrows():
        print(f"     {row['parameter']:13s} ×{row['factor']:.1f}: saving "
              f"{100 * row['saving']:+.2f} % ({row['status']})")
    best, t_best = _timed(lambda: placement(ev.prepared, list(CLASSES), "preloaded"))
    print(f"   global optimum, preloaded family, every set of classes designed together (Joule; "
          f"with the old search per class for the gap): {t_best:.1f} s")
    for _, row in best.table.iterrows():
        print(f"     {row['springs']:18s} saving {100 * row['saving']:+.2f} % (old search "
              f"{100 * row['old_saving']:+.2f} %)")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--samples", type=int, default=1000)
    parser.add_argument("--workers", type=int, default=default_workers())
    parser.add_argument("--mu", type=float, default=0.3, help="friction coefficient (0.3)")
    parser.add_argument("--out", help="keep the sweep directories here (default: a temp dir)")
    args = parser.parse_args()
    run = Scenario.load().replace(contact=ContactParams(mu=args.mu))
    print(f"friction μ = {args.mu}")
    out = Path(args.out) if args.out else Path(tempfile.mkdtemp(prefix="bench-sweep-"))
    try:
        single_class(out, args.samples, args.workers, run)
        placement_study(out, args.samples, args.workers, run)
    finally:
        if not args.out:
            shutil.rmtree(out, ignore_errors=True)


if __name__ == "__main__":
    main()
