"""Issue #56's 0.8× target, second round: the optimal motion's starts and solver settings probed
one lever at a time, each against the parametric co-design as ``hexaleg codesign`` searches it
by default (duty factor ≤ 0.8, body height ≤ 1.3 × the default gait's), widened (duty factor ≤
0.9, body height ≤ 1.5 ×) and, with ``--widest``, widened to a taller body still, all in the
same process (log: analysis/bench_logs/bench_optimal_target2.log; not an example study: it needs
the optimal extra and many minutes).

Run:  python analysis/bench_optimal_target2.py --chosen cd.pkl --widened cd0915.pkl
                                              [--widest cd0917.pkl] --results probes.jsonl
                                              [--nodes 40] [--iterations 100] [--probe LABEL ...]
                                              [--simulate] [--alternate LABEL ...]

Needs the ``optimal`` extra. G and S, the default co-design's gait and springs, from the
pickle ``--chosen``; W and its springs, the widened co-design's, from ``--widened`` (both
written by analysis/bench_codesign_duty_bound.py ``--chosen``: ``--duty-high 0.8`` and
``--duty-high 0.9 --body-high 1.5``); V, a co-design searched with a taller body box still,
from ``--widest`` when given. Each probe of :data:`PROBES` (or those ``--probe`` names) is one
solve of box-FDDP (:func:`hexaleg.optimal.solve.solve`) from a gait with the co-design's springs
in its dynamics, judged as the alternation judges
(:func:`hexaleg.design.codesign.alternation.judged`: hexaleg's prediction of its cycle rebuilt in
task space) beside its start gait's own prediction with those springs (what the parametric
family gives there: the optimal control's own gain is the difference), with the solver's own
J/m, its friction use (of μ), stationarity, stance slip and drift. Each probe's line is appended
to ``--results`` as it ends, and a probe already there (the same label, knots and iterations) is
read back instead of solved again: a killed run resumes. ``--simulate`` also simulates, under
both servos with balance feedback on, the baselines and every probe whose prediction is below
0.85× either baseline's. ``--alternate LABEL ...`` then runs the alternation
(:func:`hexaleg.design.codesign.alternation.alternate`: the springs redesigned on the rebuilt
cycle, the motion re-optimised, kept while the prediction falls) from each probe's start and
simulates its answer the same way.
"""

from __future__ import annotations

import argparse
import dataclasses
import json
import os
import pickle
import time
from typing import Any

import hexaleg
from hexaleg.design.codesign.alternation import alternate, judged, predicted_per_metre
from hexaleg.design.codesign.servo import simulated_run
from hexaleg.errors import HexalegError
from hexaleg.optimal.problem import OptimalParams, build_problem
from hexaleg.optimal.solve import solve

PROBES: dict[str, tuple[str, dict[str, float], dict[str, float]]] = {
    "G at duty 0.85": ("G", {"duty_factor": 0.85}, {}),
    "G at duty 0.85, body × 1.05": ("G", {"duty_factor": 0.85, "body": 1.05}, {}),
    "G at duty 0.85, body × 1.05, swing weight × 0.01":
        ("G", {"duty_factor": 0.85, "body": 1.05}, {"swing": 0.01}),
    "G at duty 0.85, body × 1.10": ("G", {"duty_factor": 0.85, "body": 1.10}, {}),
    "G at duty 0.85, body × 1.10, swing weight × 0.01":
        ("G", {"duty_factor": 0.85, "body": 1.10}, {"swing": 0.01}),
    "G at duty 0.85, foot radius × 0.9": ("G", {"duty_factor": 0.85, "radius": 0.9}, {}),
    "G at duty 0.85, body × 1.05, foot radius × 0.9":
        ("G", {"duty_factor": 0.85, "body": 1.05, "radius": 0.9}, {}),
    "G at duty 0.85, body × 1.05, foot radius × 1.1":
        ("G", {"duty_factor": 0.85, "body": 1.05, "radius": 1.1}, {}),
    "W": ("W", {}, {}),
    "W, swing weight × 0.01": ("W", {}, {"swing": 0.01}),
    "W, state weight × 0.1": ("W", {}, {"state": 0.1}),
    "W, body × 1.05": ("W", {"body": 1.05}, {}),
    "W, foot radius × 0.9": ("W", {"radius": 0.9}, {}),
    "W, foot radius × 0.8": ("W", {"radius": 0.8}, {}),
    "W, body × 1.05, foot radius × 0.9": ("W", {"body": 1.05, "radius": 0.9}, {}),
    "V": ("V", {}, {}),
    "V, swing weight × 0.01": ("V", {}, {"swing": 0.01}),
    "V, body × 1.05": ("V", {"body": 1.05}, {}),
    "V, foot radius × 0.95": ("V", {"radius": 0.95}, {}),
    "V, foot radius × 0.9": ("V", {"radius": 0.9}, {}),
    "V at duty 0.85": ("V", {"duty_factor": 0.85}, {}),
    "V at duty 0.875": ("V", {"duty_factor": 0.875}, {}),
}
"""Each probe: (the gait it starts from — ``G`` the default co-design's, ``W`` the widened
one's, ``V`` the widest one's (``--widest``) —, its changes: ``duty_factor`` set, ``body`` and
``radius`` × the gait's body height and foot radius; the solver's changes: ``swing`` × its
swing weight, ``state`` × its state weight, the pull of every knot towards the start)."""


def probe_gait(base: hexaleg.GaitParams, change: dict[str, float]) -> hexaleg.GaitParams:
    """``base`` with a probe's changes (:data:`PROBES`)."""
    assert base.body_height is not None and base.foot_radius is not None
    return dataclasses.replace(
        base, duty_factor=change.get("duty_factor", base.duty_factor),
        body_height=base.body_height * change.get("body", 1.0),
        foot_radius=base.foot_radius * change.get("radius", 1.0))


def simulated(robot: Any, motion: Any, motor: Any, springs: Any, contact: Any
              ) -> dict[str, float | None]:
    """Simulated J/m under each servo, balance feedback on (None: it did not walk)."""
    out: dict[str, float | None] = {}
    for k in ("feedforward", "position"):
        out[k], _, _ = simulated_run(robot, motion, motor, springs, k, contact, "on")
    return out


def done(path: str) -> dict[str, dict[str, Any]]:
    """The probes already in the results file, by key."""
    if not os.path.exists(path):
        return {}
    with open(path) as f:
        return {r["key"]: r for r in map(json.loads, f) if r}


def append(path: str, record: dict[str, Any]) -> None:
    """One probe's record appended to the results file, flushed to disk."""
    with open(path, "a") as f:
        f.write(json.dumps(record) + "\n")
        f.flush()
        os.fsync(f.fileno())


def ratios(value: float | None, baselines: dict[str, float]) -> str:
    """``value`` against each baseline."""
    if value is None:
        return "—"
    return ", ".join(f"{value / b:.3f}× {name}" for name, b in baselines.items())


def said(sims: dict[str, float | None], worse: dict[str, float]) -> None:
    """Print a motion's simulated J/m under each servo and, when it walked under both, its
    figure under the worse servo against each baseline's under its worse servo."""
    walked = [v for v in sims.values() if v is not None]
    tail = ""
    if worse and len(walked) == len(sims):
        tail = "; under the worse servo " + ratios(max(walked), worse)
    print("    simulated with balance feedback: " + ", ".join(
        f"{k} {v:.2f}" if v is not None else f"{k} —" for k, v in sims.items()) + tail,
        flush=True)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--chosen", required=True, help="pickle of G and S (duty ≤ 0.8)")
    parser.add_argument("--widened", required=True, help="pickle of W (duty ≤ 0.9, body ≤ 1.5×)")
    parser.add_argument("--widest", help="pickle of V (duty ≤ 0.9, a taller body box)")
    parser.add_argument("--results", required=True, help="JSON lines of the probes (resumed)")
    parser.add_argument("--nodes", type=int, default=40, help="knots a cycle")
    parser.add_argument("--iterations", type=int, default=100, help="box-FDDP iterations")
    parser.add_argument("--probe", nargs="*", help="the probes to run (default: all)")
    parser.add_argument("--alternate", nargs="*", default=[],
                        help="probes' labels: the alternation run from each")
    parser.add_argument("--simulate", action="store_true",
                        help="simulate the baselines and every probe below 0.85× either")
    args = parser.parse_args()
    t0 = time.perf_counter()
    bases, springs = {}, {}
    paths = {"G": args.chosen, "W": args.widened, "V": args.widest}
    for key, path in paths.items():
        if path is None:
            continue
        with open(path, "rb") as f:
            saved = pickle.load(f)
        bases[key], springs[key] = saved["chosen"], saved["springs"]
    run = hexaleg.Scenario.load("hexaleg")
    robot, motor, contact = run.model, run.actuator, run.contact
    names = {"G": "the default co-design", "W": "the widened co-design",
             "V": "the widest co-design"}
    predicted = {}
    for key in bases:
        g = bases[key]
        value, _ = predicted_per_metre(robot, hexaleg.gait(robot, g), motor, springs[key],
                                       contact)
        assert value is not None
        predicted[names[key]] = value
        print(f"{names[key]} ({key}: duty factor {g.duty_factor:.4g}, period {g.period:.4g} s, "
              f"body height {g.body_height:.4g} m, foot radius {g.foot_radius:.4g} m, step "
              f"height {g.step_height:.4g} m): {value:.3f} J/m predicted", flush=True)
    worse: dict[str, float] = {}  # each baseline's J/m simulated under the worse servo
    if args.simulate:
        for key in bases:
            sims = simulated(robot, hexaleg.gait(robot, bases[key]), motor, springs[key], contact)
            print(f"{names[key]} simulated with balance feedback: " + ", ".join(
                f"{k} {v:.2f}" if v is not None else f"{k} —" for k, v in sims.items()),
                flush=True)
            walked = [v for v in sims.values() if v is not None]
            if len(walked) == len(sims):
                worse[names[key]] = max(walked)
    params = OptimalParams(nodes=args.nodes, iterations=args.iterations)
    print(f"probes: {args.nodes} knots, {args.iterations} iterations, each with its gait's "
          f"co-design springs; ratios of the predicted rebuilt J/m", flush=True)
    kept = done(args.results)
    records = []
    for label in args.probe or list(PROBES):
        key, change, solver = PROBES[label]
        record_key = f"{label} | {args.nodes} knots | {args.iterations} iterations"
        if record_key in kept:
            record = kept[record_key]
        else:
            g = probe_gait(bases[key], change)
            settings = dataclasses.replace(
                params, swing_weight=params.swing_weight * solver.get("swing", 1.0),
                state_weight=params.state_weight * solver.get("state", 1.0))
            try:
                motion = hexaleg.gait(robot, g)
            except HexalegError as err:  # a body the legs cannot reach
                print(f"  {label}: no gait ({type(err).__name__}: {err})", flush=True)
                continue
            start = os.times()
            result = solve(robot, build_problem(robot, motion, motor, springs[key], settings))
            cpu = sum(os.times()[:2]) - sum(start[:2])
            value, why = judged(robot, result, motion, motor, springs[key], contact)
            record = {"key": record_key, "label": label, "base": key, "predicted": value,
                      "why": why, "solver": result.energy_per_metre,
                      "friction_use": result.friction_use,
                      "stationarity": result.stationarity, "residual": result.residual,
                      "slip": result.slip, "drift": result.drift,
                      "periodicity": result.periodicity, "cpu": cpu,
                      "wall": result.seconds}
            if args.simulate and value is not None and any(
                    value < 0.85 * b for b in predicted.values()):
                record["simulated"] = simulated(robot, result.task_space, motor, springs[key],
                                                contact)
            append(args.results, record)
        records.append(record)
        value = record["predicted"]
        start_gait, _ = predicted_per_metre(robot, hexaleg.gait(robot, probe_gait(
            bases[key], change)), motor, springs[key], contact)
        print(f"  {label}: its start gait {start_gait:.3f} J/m predicted; the optimal cycle "
              "predicted rebuilt "
              + ("—" if value is None else f"{value:.3f} J/m") + f" ({ratios(value, predicted)});"
              f" the solver's {record['solver']:.3f} J/m; friction use {record['friction_use']:.3f}"
              f" of μ; stationarity {record['stationarity']:.2g}; residual "
              f"{record['residual']:.1g} N·m; slip {1e3 * record['slip']:.1f} mm/s, drift "
              f"{1e3 * record['drift']:.3f} mm; periodicity gap {record['periodicity']:.2g}; "
              f"solve {record['cpu']:.0f} s of CPU" + (f"; {record['why']}" if record["why"]
                                                       else ""), flush=True)
        if "simulated" in record:
            said(record["simulated"], worse)
    for label in args.alternate:
        key, change, solver = PROBES[label]
        g = probe_gait(bases[key], change)
        settings = dataclasses.replace(
            params, swing_weight=params.swing_weight * solver.get("swing", 1.0),
            state_weight=params.state_weight * solver.get("state", 1.0))
        alt = alternate(robot, hexaleg.gait(robot, g), motor, contact, springs=springs[key],
                        params=settings,
                        say=lambda line: print(f"  alternation: {line}", flush=True))
        value, r = alt.predicted, alt.best
        print(f"the alternation from {label}: "
              + " → ".join("—" if e is None else f"{e:.3f}" for e in alt.energies)
              + f" J/m predicted (the gait kept: {alt.kept_gait}); "
              + ratios(value, predicted) + f"; its solve: friction use {r.friction_use:.3f} of "
              f"μ, stationarity {r.stationarity:.2g}, residual {r.residual:.1g} N·m, slip "
              f"{1e3 * r.slip:.1f} mm/s, drift {1e3 * r.drift:.3f} mm", flush=True)
        said(simulated(robot, alt.motion, motor, alt.springs, contact), worse)
    times = os.times()
    print(f"wall {time.perf_counter() - t0:.0f} s, CPU {times.user + times.system:.0f} s",
          flush=True)


if __name__ == "__main__":
    main()
