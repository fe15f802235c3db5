"""Issue #56's 0.8× target, the footholds as decisions: from the widest co-design V (duty factor
≤ 0.9, body height ≤ 1.7 × the default gait's) with its springs, the optimal motion with its
footholds fixed (the warm start's, today's problem) against the footholds chosen by a compass
search (:func:`hexaleg.optimal.footholds.search_footholds`), each judged as the alternation
judges, against V and the default co-design D predicted in the same process (log:
analysis/bench_logs/bench_optimal_footholds.log; not an example study: it needs the optimal
extra and minutes).

Run:  python analysis/bench_optimal_footholds.py --chosen cd.pkl --widest cd0917.pkl
                                                 --results footholds.jsonl [--by-solver]
                                                 [--alternate [--again]] [--simulate]

Needs the ``optimal`` extra. D and its springs from the pickle ``--chosen``, V and its springs
from ``--widest`` (analysis/bench_codesign_duty_bound.py ``--chosen``: ``--duty-high 0.8``, and
``--duty-high 0.9 --body-high 1.7``). Rows, each one box-FDDP solve (40 knots, 100 iterations,
V's springs in its dynamics unless said):

* fixed footholds: V's gait as the warm start (today's problem; docs/optimal.md's V row), and
  the same with every foothold moved by 1e-9 m (how much of a figure is the unconverged solve's
  path rather than its footholds);
* the relaxed foothold of the first design tried (a fixed point on where the feet land): the
  foothold cost 1e8 → 1e2 and the swing path's weight × 0.01, to show where the solver puts a
  foot it is free to land anywhere — each touch-down's distance from its foothold and the next
  knot's (the stance contact pulls it back), slip and drift;
* the search valued by the judged figure (hexaleg's prediction of the optimal cycle rebuilt in
  task space, :func:`~hexaleg.design.codesign.alternation.judged`, the alternation's judge),
  and with ``--by-solver`` another valued by the solver's own J/m: every candidate's offsets
  (mm), its moved gait's own prediction (the parametric gait with those footholds), its judged
  and solver's figures, friction use (of μ), slip; each written to ``--results`` as it ends,
  and a candidate already there read back (a killed run resumes; its CPU is the run's that
  solved it);
* each answer: each leg's offset (mm), its figures and ratios to V and D, and its footholds
  moved by 1e-9 m and solved again.

``--alternate`` then alternates (springs redesigned on the rebuilt cycle, the cycle re-solved
with them; up to 6 rounds, no tolerance) from the fixed footholds and from each answer's;
``--again`` searches once more from the judged answer with the springs of the alternation from
it, and alternates from there; ``--simulate`` simulates D, V and every alternation's answer
under both servos with balance feedback on.
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
from hexaleg.design.codesign.gait_evaluation import Constraints
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
    parser.add_argument("--by-solver", action="store_true",
                        help="also search valued by the solver's own J/m")
    parser.add_argument("--again", action="store_true",
                        help="search again with the alternation's springs (needs --alternate)")
    parser.add_argument("--simulate", action="store_true",
                        help="simulate D, V and each alternation's answer")
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

    def solved(motion: Any, params: OptimalParams, sprung: Any = springs
               ) -> tuple[Any, Any, float | None, float]:
        c = time.process_time()
        built = build_problem(robot, motion, motor, sprung, params)
        result = solve(robot, built)
        value = judged(robot, result, motion, motor, sprung, contact,
                       Constraints.friction_margin).judged
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

    def record_of(offsets: np.ndarray, sprung: Any, name: str) -> dict[str, Any]:
        """The candidate's record with the springs ``sprung`` (called ``name`` in its key;
        V's springs: no name), solved and written when not kept."""
        key = name + json.dumps(np.round(1e3 * offsets, 6).tolist())
        if key not in kept:
            record: dict[str, Any] = {"key": key}
            try:
                motion = moved_footholds(robot, gait, offsets)
            except HexalegError as err:
                record["why"] = f"{type(err).__name__}: {err}"[:200]
            else:
                record["gait"], _ = predicted_per_metre(robot, motion, motor, sprung, contact)
                _, result, value, cpu = solved(motion, settings, sprung)
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
            judge = "—" if r["judged"] is None else f"{r['judged']:.3f}"
            out(f"    its gait {r['gait']:.3f}, judged {judge}, solver "
                f"{r['solver']:.3f}, friction use {r['friction']:.3f}, slip "
                f"{1e3 * r['slip']:.1f} mm/s, CPU {r['cpu']:.1f} s")
        return r

    search = FootholdSearch()
    out(f"the search: {search}; coordinates (LF/RF, LM/RM, LH/RH) × (fore-aft, outward)")

    def searched(label: str, by: str, sprung: Any, name: str = "",
                 start: tuple[int, ...] | None = None) -> tuple[Any, Any, Any]:
        """The search valued by the record's ``by`` (judged or solver) with ``sprung``; its
        answer re-solved: (answer, moved gait, its solve)."""
        out(f"search {label}, valued by the {by} J/m:")
        answer = search_footholds(robot, lambda o: record_of(o, sprung, name).get(by), search,
                                  say=lambda line: out(f"  {line}"), start=start)
        out(f"answer after {answer.polls} polls, {len(answer.tried)} candidates: {by} "
            f"{answer.value:.3f} J/m, start {answer.start:.3f}, "
            f"{answer.value / answer.start:.3f}× — a local optimum of the "
            f"{1e3 * search.smallest:g} mm lattice")
        for leg, (dx, dy) in zip(robot.leg_names, 1e3 * answer.offsets, strict=True):
            out(f"  {leg}: {dx:+.0f} mm fore-aft, {dy:+.0f} mm in y")
        moved = moved_footholds(robot, gait, answer.offsets)
        _, best, best_value, cpu = solved(moved, settings, sprung)
        out(f"the answer re-solved: {figures(best, best_value, cpu)}")
        out(f"its gait (the parametric gait with the moved footholds): "
            f"{predicted_per_metre(robot, moved, motor, sprung, contact)[0]:.3f} J/m predicted")
        _, result, value, cpu = solved(moved_footholds(robot, gait, answer.offsets + 1e-9),
                                       settings, sprung)
        out(f"the answer's footholds moved by 1e-9 m (the solve's sensitivity): "
            f"{figures(result, value, cpu)}")
        return answer, moved, best

    _, result, value, cpu = solved(moved_footholds(robot, gait, np.full((6, 2), 1e-9)),
                                   settings, springs)
    out(f"V's footholds moved by 1e-9 m (the solve's sensitivity): {figures(result, value, cpu)}")
    answer, moved, best = searched("from V's footholds with V's springs", "judged", springs)
    starts = [("fixed footholds", gait, fixed),
              ("the footholds searched by the judged figure", moved, best)]
    if args.by_solver:
        _, by_solver, its = searched("from V's footholds with V's springs", "solver", springs)
        starts.append(("the footholds searched by the solver's figure", by_solver, its))

    answers = []

    def alternated(label: str, motion: Any, first: Any, sprung: Any) -> Any:
        c = time.process_time()
        alt = alternate(robot, motion, motor, contact, springs=sprung, params=settings,
                        first=first, rounds=6, tolerance=0.0)
        r = alt.best
        out(f"alternation from {label}: " + " → ".join(
            "—" if e is None else f"{e:.3f}" for e in alt.energies)
            + f" J/m predicted rebuilt ({len(alt.rounds)} rounds, the gait kept: "
            f"{alt.kept_gait}; CPU {time.process_time() - c:.0f} s); {ratios(alt.predicted)}; "
            f"the solver's {r.energy_per_metre:.3f}; friction use {r.friction_use:.3f}, slip "
            f"{1e3 * r.slip:.1f} mm/s")
        answers.append((label, alt))
        return alt

    if args.alternate:
        for label, motion, first in starts:
            alternated(label, motion, first, springs)
    if args.again:
        alt = dict(answers)["the footholds searched by the judged figure"]
        _, moved2, best2 = searched(
            "again, from its answer with the springs of the alternation from it", "judged",
            alt.springs, "alternated:", answer.point)
        alternated("the footholds searched again", moved2, best2, alt.springs)
    if args.simulate:
        sims: dict[str, dict[str, float | None]] = {}
        for key in ("D", "V"):
            sims[key] = simulated(robot, hexaleg.gait(robot, data[key]["chosen"]), motor,
                                  data[key]["springs"], contact)
            out(f"{key} simulated with balance feedback: {shown(sims[key])}")
        for label, alt in answers:
            got = simulated(robot, alt.motion, motor, alt.springs, contact)
            ratio = " ".join(
                f"× {k} " + ("—" if None in got.values() or None in sims[k].values() else
                             f"{max(got.values()) / max(sims[k].values()):.3f}")  # type: ignore
                for k in ("V", "D"))
            out(f"alternation from {label} simulated with balance feedback: {shown(got)}; "
                f"worse servo {ratio}")
    c1 = os.times()
    out(f"wall {time.perf_counter() - t0:.0f} s, CPU "
        f"{(c1.user - c0.user) + (c1.system - c0.system):.0f} s")


if __name__ == "__main__":
    main()
