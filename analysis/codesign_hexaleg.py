"""The gait and its springs designed together on the default robot at 0.06 m/s (issue #31).

Run:  python analysis/codesign_hexaleg.py

:func:`hexaleg.codesign` with the default constraints (the static margin at least the default
gait's) and the default search (restarted Nelder–Mead, 100 evaluations a search, 100 samples a
cycle; the rows at 200): the four rows, the sequential design beside them, the chosen gait, the
constraints on it, the check that ``hexaleg.tripod_gait`` + ``Prepared.evaluate`` of the reported
gait and springs reproduce its energy, and the MuJoCo run. Rounded so that the log
(analysis/logs/codesign_hexaleg.log) is the same on every run. The full spring rules of
``hexaleg design`` are not applied here (``hexaleg codesign --rules``).
"""

from __future__ import annotations

import hexaleg


def main() -> None:
    r = hexaleg.codesign("hexaleg", 0.06, curve=False)
    print(f"{r.title} at {r.speed:g} m/s, {r.family} springs on every joint class")
    for row in (*r.rows, r.sequential):
        print(f"  {row.label:48s} {row.per_metre:6.1f} J/m  CoT {row.cost_of_transport:5.2f}")
    e0, e = r.rows[0].per_metre, r.rows[3].per_metre
    print(f"co-design / default gait without springs: {e / e0:.2f} (target <= 0.65)")
    s = r.shares
    print(f"gait share {100 * s['gait']:.0f} %, springs share {100 * s['springs']:.0f} %")
    print("chosen gait: " + ", ".join(f"{p} {getattr(r.chosen, p):.3g}" for p in
                                      ("body_height", "foot_radius", "step_height",
                                       "duty_factor", "period")))
    held = all((v >= b) if k == "min" else (v <= b) for v, b, _u, k in r.measures.values())
    print(f"every constraint holds: {held}")
    robot = hexaleg.load_robot()
    prepared = hexaleg.prepare(robot, hexaleg.tripod_gait(robot, r.chosen),
                               contact=r.constraints.contact())
    again = prepared.evaluate(r.springs, "joule").metrics["total"]["electrical"] / r.chosen.stride
    print(f"reproduced by tripod_gait + evaluate within 1 %: {abs(again / e - 1) < 0.01}")
    sim = r.simulation
    print(f"MuJoCo: walked within 3 % of the plan: "
          f"{abs(sim['walked'] / sim['planned'] - 1) < 0.03}, simulated saving within 2 points "
          f"of the predicted: {abs(sim['simulated'] - sim['predicted']) <= 0.02}")


if __name__ == "__main__":
    main()
