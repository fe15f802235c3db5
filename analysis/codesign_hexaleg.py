"""The gait and its springs designed together on the default robot at 0.06 m/s (issue #31).

Run:  python analysis/codesign_hexaleg.py

:func:`hexaleg.codesign` with the default constraints (the static margin at least the default
gait's), the default search (a compass search on a lattice with restarts,
:mod:`hexaleg.design.codesign.gait_search`: 200 evaluations at most, 100 samples a cycle; the
rows at 200) and the full spring rules of ``hexaleg design`` on the chosen gait (the
default: parsimony, stop tolerance, envelope and hard stop, fatigue, arbor): the four rows, the
sequential design beside them, the chosen gait, the constraints on it, the check that
``hexaleg.gait`` + ``Prepared.evaluate`` of the reported gait and springs reproduce their
energy (the inner program's and the springs to buy), the rules' figures, the springs read back
by ``hexaleg.load_design`` from ``codesign.json``, and the MuJoCo run with the springs to buy.
Rounded so that the log (analysis/logs/codesign_hexaleg.log) is the same on every run.
"""

from __future__ import annotations

import math
import tempfile
from pathlib import Path

import hexaleg
from hexaleg.commands.codesign.write import write_result
from hexaleg.design.codesign.floors import worst
from hexaleg.design.codesign.rules import per_metre
from hexaleg.robot.registry import description
from hexaleg.simulation.run import Settings, simulate


def main() -> None:
    r = hexaleg.codesign("hexaleg", 0.06, curve=False)
    print(f"{r.title} at {r.speed:g} m/s, {r.family} springs on every joint class in the search")
    for row in (*r.rows, r.sequential):
        print(f"  {row.label:48s} {row.per_metre:6.1f} J/m  CoT {row.cost_of_transport:5.2f}")
    e0, e = r.rows[0].per_metre, r.rows[3].per_metre
    print(f"co-design / default gait without springs: {e / e0:.2f} (target <= 0.65)")
    s = r.shares
    print(f"gait share {100 * s['gait']:.0f} %, springs share {100 * s['springs']:.0f} %")
    print("chosen gait: " + ", ".join(f"{p} {getattr(r.chosen, p):.3g}" for p in
                                      ("body_height", "foot_radius", "step_height",
                                       "duty_factor", "period")))
    k = r.chosen_finalist
    pick, top = r.finalists[k], r.finalists[0]
    print(f"servo check: finalist {k + 1} of {len(r.finalists)} chosen under both servos: "
          f"{pick.worst:.1f} J/m simulated under the worse (the search's best "
          f"{top.worst:.1f} J/m), predicted {pick.point.per_metre_springs:.1f} J/m")
    held = all((v >= b) if k == "min" else (v <= b) for v, b, _u, k in r.measures.values())
    print(f"every constraint holds: {held}")
    use, bound = r.measures["friction"][:2]
    print(f"planned friction use {use:.2f} of the cone at mu {r.constraints.mu:g} (at most "
          f"{r.constraints.friction_margin:g}): {use <= bound}")
    robot = hexaleg.load()
    prepared = hexaleg.prepare(robot, hexaleg.gait(robot, r.chosen),
                               contact=r.constraints.contact())

    def energy(springs: hexaleg.SpringSet) -> float:
        return prepared.evaluate(springs, "joule").metrics["total"]["electrical"] / r.chosen.stride

    again = energy(r.springs)
    print(f"reproduced by tripod_gait + evaluate within 1 %: {abs(again / e - 1) < 0.01}")
    d = r.rules
    rec = d.recommended
    bought = per_metre(d, r.chosen.stride)
    print(f"\nsprings to buy (full spring rules on the chosen gait): {rec.label} on "
          f"{', '.join(rec.optimum.groups)}; {bought:.1f} J/m, {bought / e0:.2f} of the default "
          f"gait without springs")
    print(f"  reproduced by tripod_gait + evaluate within 1 %: "
          f"{abs(energy(rec.optimum.springs) / bought - 1) < 0.01}")
    t = d.tolerance
    if t is None:
        print(f"  stops within ±{math.degrees(d.design.stop_tolerance):g}°: "
              f"{rec.family} springs have no stop to mount")
    else:
        print(f"  stops within ±{math.degrees(t.tolerance):g}°: worst electrical saving "
              f"{100 * t.worst['tolerant']:.1f} % tolerant, {100 * t.worst['blind']:.1f} % "
              f"tolerance-blind; built: {t.chosen}")
    bar = 100 * d.design.min_group_saving
    print(f"  parsimony: {len(rec.optimum.groups)} classes fitted, {len(rec.dropped)} left out "
          f"under the {bar:g} point bar")
    for e_, (p, f) in zip(d.envelope, d.fatigue, strict=True):
        stop = "a hard stop" if e_.stop is not None else "no hard stop"
        print(f"  {p.group} {p.side}: {stop} over the whole envelope; fatigue n_f >= 1: "
              f"{f.safety_factor >= 1}; clears its arbor: {e_.clears_arbor}")
    with tempfile.TemporaryDirectory() as out:
        write_result(r, out)
        loaded = hexaleg.load_design(Path(out) / "codesign.json")
    same = set(loaded.springs) == set(rec.optimum.springs) and all(
        type(loaded.springs[j]) is type(rec.optimum.springs[j]) for j in loaded.springs)
    print(f"  codesign.json read back by load_design: the springs to buy {same}, the chosen "
          f"gait {math.isclose(loaded.gait.period, r.chosen.period)}")
    sim = r.simulation
    print(f"MuJoCo with the springs to buy: walked within 3 % of the plan: "
          f"{abs(sim['walked'] / sim['planned'] - 1) < 0.03}, simulated saving within 2 points "
          f"of the predicted: {abs(sim['simulated'] - sim['predicted']) <= 0.02}")
    for row in d.simulation:
        kept = row["simulated"] / row["predicted"]
        print(f"  {row['label']}, mu {r.constraints.mu:g}: keeps {kept:.2f} of the predicted "
              f"saving (at least 0.85: {kept >= 0.85})")
    low = worst(r.floors)
    print("  predicted on other floors: " + ", ".join(
        f"mu {f.mu:g} {100 * f.saving:.1f} %" for f in r.floors if f.saving is not None)
        + f"; worst {100 * low.saving:.1f} % at mu {low.mu:g}")
    motor = description("hexaleg").actuator(robot)
    for controller in ("feedforward", "position"):  # a grippier floor than designed for
        s = simulate(robot, hexaleg.gait(robot, r.chosen), motor, rec.optimum.springs,
                     Settings(force_samples=0, controller=controller),
                     contact=hexaleg.ContactParams(mu=1.0))
        kept = s.simulated()[2] / s.predicted()[2]
        print(f"  {controller}, mu 1: keeps {kept:.2f} of the predicted saving (at least 0.85: "
              f"{kept >= 0.85})")


if __name__ == "__main__":
    main()
