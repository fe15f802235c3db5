"""Issue #56's 0.8× target, the footholds as decisions: from the widest co-design V (duty factor
≤ 0.9, body height ≤ 1.7 × the default gait's) with its springs, the optimal motion with its
footholds fixed (the warm start's, today's problem) against the footholds chosen by a compass
search (:func:`hexaleg.optimal.footholds.search_footholds`), each judged as the alternation
judges, against V and the default co-design D predicted in the same process (log:
analysis/bench_logs/bench_optimal_footholds.log; not an example study: it needs the optimal
extra and minutes).

Run:  python analysis/bench_optimal_footholds.py --chosen cd.pkl --widest cd0917.pkl
                                                 --results footholds.jsonl
                                                 [--alternate] [--simulate]

Needs the ``optimal`` extra. D and its springs from the pickle ``--chosen``, V and its springs
from ``--widest`` (analysis/bench_codesign_duty_bound.py ``--chosen``: ``--duty-high 0.8``, and
``--duty-high 0.9 --body-high 1.7``). Rows, each one box-FDDP solve (40 knots, 100 iterations,
V's springs in its dynamics):

* fixed footholds: V's gait as the warm start (today's problem; docs/optimal.md's V row);
* the relaxed foothold of the first design tried (a fixed point on where the feet land): the
  foothold cost 1e8 → 1e2 and the swing path's weight × 0.01, to show where the solver puts a
  foot it is free to land anywhere — each touch-down's distance from its foothold and the next
  knot's (the stance contact pulls it back), slip and drift;
* the search: every candidate's offsets (mm), its moved gait's own prediction (the parametric
  gait with those footholds), the optimal cycle's judged figure (hexaleg's prediction of it
  rebuilt in task space, :func:`~hexaleg.design.codesign.alternation.judged`) — the search's
  value —, the solver's J/m, friction use (of μ), slip; each written to ``--results`` as it
  ends, and a candidate already there read back (a killed run resumes);
* the answer: each leg's offset (mm), its figures and ratios to V and D; V's footholds and the
  answer's each moved by 1e-9 m and solved again (how much of a candidate's figure is the
  unconverged solve's path rather than its footholds).

``--alternate`` then alternates (springs redesigned on the rebuilt cycle, the cycle re-solved
with them; up to 6 rounds, no tolerance) from the fixed footholds and from the answer's, and
``--simulate`` simulates V and the best of those under both servos with balance feedback on.
"""

from __future__ import annotations

import argparse
import json
import os
import pickle
import time
from typing import Any

import numpy as np

import hexaleg
from hexaleg.design.codesign.alternation import alternate, judged, predicted_per_metre
from hexaleg.design.codesign.servo import simulated_run
from hexaleg.errors import HexalegError
from hexaleg.optimal.footholds import FootholdSearch, moved_footholds, search_footholds
from hexaleg.optimal.problem import OptimalParams, build_problem
from hexaleg.optimal.solve import solve

SERVOS = ("feedforward", "position")


def out(line: str) -> None:
    print(line, flush=True)


def read(path: str) -> dict[str, dict[str, Any]]:
    """The candidates already in ``path`` by key (a line a killed run left torn is dropped: its
    candidate is solved again)."""
    out: dict[str, dict[str, Any]] = {}
    if os.path.exists(path):
        with open(path, encoding="utf-8") as f:
            for line in f:
                try:
                    record = json.loads(line)
                except json.JSONDecodeError:
                    continue
                out[record["key"]] = record
    return out


def simulated(robot: Any, motion: Any, motor: Any, springs: Any, contact: Any
              ) -> dict[str, float | None]:
    """Simulated J/m under each servo, balance feedback on (None: it did not walk)."""
    return {k: simulated_run(robot, motion, motor, springs, k, contact, "on")[0]
            for k in SERVOS}


def shown(sims: dict[str, float | None]) -> str:
    return ", ".join(f"{k} {'—' if v is None else f'{v:.2f}'}" for k, v in sims.items())


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--chosen", required=True, help="pickle of D (duty ≤ 0.8)")
    parser.add_argument("--widest", required=True, help="pickle of V (duty ≤ 0.9, body ≤ 1.7)")
    parser.add_argument("--results", required=True, help="JSON lines of the candidates")
    parser.add_argument("--alternate", action="store_true", help="alternate fixed and answer")
    parser.add_argument("--simulate", action="store_true", help="simulate V and the best")
    args = parser.parse_args()
    t0, c0 = time.perf_counter(), os.times()
    data = {}
    for key, path in (("D", args.chosen), ("V", args.widest)):
        with open(path, "rb") as f:
            data[key] = pickle.load(f)
    run = hexaleg.Scenario.load("hexaleg")
    robot, motor, contact = run.model, run.actuator, run.contact
    base = {}
    for key in ("V", "D"):
        value, _ = predicted_per_metre(robot, hexaleg.gait(robot, data[key]["chosen"]), motor,
                                       data[key]["springs"], contact)
        assert value is not None
        base[key] = value
        out(f"baseline {key}: {value:.3f} J/m predicted (the co-design's own figure "
            f"{data[key]['per_metre']:.3f})")
    gait, springs = hexaleg.gait(robot, data["V"]["chosen"]), data["V"]["springs"]
    settings = OptimalParams()

    def ratios(value: float | None) -> str:
        return " ".join(f"× {k} {'—' if value is None else f'{value / b:.3f}'}"
                        for k, b in base.items())

    def solved(motion: Any, params: OptimalParams) -> tuple[Any, Any, float | None, float]:
        c = time.process_time()
        built = build_problem(robot, motion, motor, springs, params)
        result = solve(robot, built)
        value, _ = judged(robot, result, motion, motor, springs, contact)
        return built, result, value, time.process_time() - c

    def figures(result: Any, value: float | None, cpu: float) -> str:
        return (f"judged {'—' if value is None else f'{value:.3f}'} ({ratios(value)}), solver "
                f"{result.energy_per_metre:.3f}, stationarity {result.stationarity:.2g}, "
                f"friction use {result.friction_use:.3f}, slip {1e3 * result.slip:.1f} mm/s, "
                f"drift {1e3 * result.drift:.3f} mm, CPU {cpu:.1f} s")

    _, fixed, fixed_value, cpu = solved(gait, settings)
    out(f"fixed footholds (V's): {figures(fixed, fixed_value, cpu)}")

    relaxed = OptimalParams(foothold_weight=1e2, swing_weight=settings.swing_weight * 0.01)
    built, result, value, cpu = solved(gait, relaxed)
    out(f"relaxed foothold (1e2) and swing path (× 0.01): {figures(result, value, cpu)}")
    n = len(built.stance)
    for k, j in ((k, j) for k in range(n) for j in range(len(robot.legs))
                 if built.stance[k, j] and not built.stance[k - 1, j]):
        off = [1e3 * float(np.linalg.norm(result.motion.feet[i % n, j] - built.footholds[i % n, j]))
               for i in (k, k + 1)]
        out(f"  {robot.leg_names[j]} lands at knot {k}: {off[0]:.2f} mm off its foothold, the "
            f"next knot {off[1]:.3f} mm" + ("  (knot 0: the fixed initial state)" if k == 0
                                           else ""))

    kept = read(args.results)

    def value_of(offsets: np.ndarray) -> float | None:
        key = json.dumps(np.round(1e3 * offsets, 6).tolist())
        if key not in kept:
            record: dict[str, Any] = {"key": key}
            try:
                motion = moved_footholds(robot, gait, offsets)
            except HexalegError as err:
                record["why"] = f"{type(err).__name__}: {err}"[:200]
            else:
                record["gait"], _ = predicted_per_metre(robot, motion, motor, springs, contact)
                _, result, value, cpu = solved(motion, settings)
                record.update(judged=value, solver=result.energy_per_metre,
                              stationarity=result.stationarity,
                              friction=result.friction_use, slip=result.slip, cpu=cpu)
            kept[key] = record
            with open(args.results, "a", encoding="utf-8") as f:
                f.write(json.dumps(record) + "\n")
        r = kept[key]
        if "why" in r:
            out(f"    {r['why']}")
        else:
            out(f"    its gait {r['gait']:.3f}, solver {r['solver']:.3f}, friction use "
                f"{r['friction']:.3f}, slip {1e3 * r['slip']:.1f} mm/s, CPU {r['cpu']:.1f} s")
        return r.get("judged")

    search = FootholdSearch()
    out(f"the search: {search}; coordinates (LF/RF, LM/RM, LH/RH) × (fore-aft, outward)")
    answer = search_footholds(robot, value_of, search, say=lambda line: out(f"  {line}"))
    out(f"answer after {answer.polls} polls, {len(answer.tried)} candidates: judged "
        f"{answer.value:.3f} J/m ({ratios(answer.value)}), start {answer.start:.3f}, gain "
        f"{answer.value / answer.start:.3f}× — a local optimum of the "
        f"{1e3 * search.smallest:g} mm lattice")
    for name, (dx, dy) in zip(robot.leg_names, 1e3 * answer.offsets, strict=True):
        out(f"  {name}: {dx:+.0f} mm fore-aft, {dy:+.0f} mm in y")
    moved = moved_footholds(robot, gait, answer.offsets)
    _, best, best_value, cpu = solved(moved, settings)
    out(f"the answer re-solved: {figures(best, best_value, cpu)}")
    out(f"its gait (the parametric gait with the moved footholds): "
        f"{predicted_per_metre(robot, moved, motor, springs, contact)[0]:.3f} J/m predicted")
    for label, offsets in (("V's footholds", np.zeros((6, 2))), ("the answer's", answer.offsets)):
        _, result, value, cpu = solved(moved_footholds(robot, gait, offsets + 1e-9), settings)
        out(f"{label} moved by 1e-9 m (the solve's sensitivity): {figures(result, value, cpu)}")

    answers = []
    if args.alternate:
        for label, motion, first in (("fixed footholds", gait, fixed),
                                     ("the searched footholds", moved, best)):
            c = time.process_time()
            alt = alternate(robot, motion, motor, contact, springs=springs, params=settings,
                            first=first, rounds=6, tolerance=0.0)
            r = alt.best
            out(f"alternation from {label}: " + " → ".join(
                "—" if e is None else f"{e:.3f}" for e in alt.energies)
                + f" J/m predicted rebuilt ({len(alt.rounds)} rounds, the gait kept: "
                f"{alt.kept_gait}; CPU {time.process_time() - c:.0f} s); {ratios(alt.predicted)}; "
                f"friction use {r.friction_use:.3f}, slip {1e3 * r.slip:.1f} mm/s")
            answers.append((label, alt))
    if args.simulate:
        sims_v = simulated(robot, gait, motor, springs, contact)
        out(f"V simulated with balance feedback: {shown(sims_v)}")
        for label, alt in answers:
            sims = simulated(robot, alt.motion, motor, alt.springs, contact)
            worse = [sims[k] for k in SERVOS]
            ratio = ("—" if None in worse or None in sims_v.values() else
                     f"{max(worse) / max(sims_v.values()):.3f}")  # type: ignore[type-var]
            out(f"alternation from {label} simulated with balance feedback: {shown(sims)}; "
                f"worse servo × V {ratio}")
    c1 = os.times()
    out(f"wall {time.perf_counter() - t0:.0f} s, CPU "
        f"{(c1.user - c0.user) + (c1.system - c0.system):.0f} s")


if __name__ == "__main__":
    main()
