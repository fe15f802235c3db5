"""The paper's Adams experiment rerun in MuJoCo, beside the analytic reproduction.

Run:  python analysis/simulate_paper.py      (expected output: analysis/logs/simulate_paper.log)

The lever of Table 6 driven along θ = 0.3 sin 2t (eq. 25; the motion driver: the lever is
kinematic, the required torque measured), the main torsion springs as their own bodies (Table 4
stiffness and damping, κ = k α, resting on stops at ±θ_k), the lever–spring contact of Table 3
(Adams IMPACT: K δ^2.2 + STEP damping, 0.1 mm), the secondary spring of Table 5 and the joint
friction of Table 2 (``hexaleg.studies.simulate.paper_joint``), all numbers in the paper's unit
system (kg, mm, s, rad: the one in which eq. 19 gives 713.5; 1 stiffness unit = 1e-6 N·m/rad,
docs/paper.md). No gravity (the paper's k_M and k_E analysis leaves it out). For the required
torque (Figs 5–8), the mean torque vs k (Figs 9–10) and the energy ratio ε vs k (Figs 12–13):
the analytic model (``hexaleg.studies.paper``), the forward simulation without friction, and with
Table 2's friction; the simulated optimum against the analytic one and the paper's readings
(740 for the mean torque, 800 for ε). Then the invariant of the simulation on this joint: the
analysis' torque applied open loop follows the plan within the derived bound, at second order.
Assumed (the paper does not give them): the contact radius 10 mm and each spring arm's inertia,
1 % of the lever's.
"""

from __future__ import annotations

import numpy as np

from hexaleg.dynamics.energy import saving
from hexaleg.studies.paper.joint import PaperJoint
from hexaleg.studies.paper.metrics import energy_ratio, metric
from hexaleg.studies.paper.readings import PAPER_K_E, PAPER_K_M, paper_number_to_si
from hexaleg.studies.simulate.paper_joint import AdamsJoint, adams, open_loop, open_loop_bound

JOINT = PaperJoint()
K_GRID = np.arange(100.0, 1700.0, 100.0)  # paper units (the paper swept 100…1200)
PAPER_MEAN_MIN, PAPER_EPS_MIN = 740.0, 800.0  # Figs 10 and 13, read off
TOTALS = {"mean_abs": "mean_abs_torque", "peak": "peak_torque", "rms": "rms_torque"}
"""hexaleg.studies.paper.metrics names → keys of hexaleg.dynamics.energy.metrics."""


def analytic(name: str, k: float) -> float:
    si = float(paper_number_to_si(k))
    if name == "epsilon":
        return float(energy_ratio(JOINT, si, gravity=False))
    return float(metric(JOINT, name, si, gravity=False))


def simulated(runs: dict, name: str, k: float) -> float:
    r = runs[k]
    if name == "epsilon":
        return r.epsilon(JOINT)
    return float(r.metrics()[TOTALS[name]])


def vertex(ks: np.ndarray, values: np.ndarray) -> float:
    """The minimum of the parabola through the grid minimum and its neighbours."""
    i = int(np.clip(np.argmin(values), 1, len(ks) - 2))
    a, b, _ = np.polyfit(ks[i - 1:i + 2], values[i - 1:i + 2], 2)
    return float(-b / (2 * a))


def main() -> None:
    frictionless, table2 = AdamsJoint(friction=False), AdamsJoint()
    K, c, d = table2.contact_si()
    print("Adams single joint in MuJoCo, the paper's units (kg, mm, s, rad): no gravity, dt "
          f"{table2.timestep:g} s")
    print(f"Table 3 contact K = 1e5 mN/mm^2.2 = {K:.4g} N/m^2.2, damping 10 mN·s/mm = "
          f"{c:g} N·s/m over {d * 1e3:g} mm; Table 4 damping 1 = "
          f"{table2.stiffness_si(1.0) * JOINT.transmission:.3g} N·m·s/rad (κ = kα); Table 5 "
          f"k2 = {table2.stiffness_si(0.01):.3g} N·m/rad")
    print(f"Table 2 friction: μ_s 0.5, μ_d 0.8, pin radius 10 mm, v_s 0.1 mm/s; assumed contact "
          f"radius {table2.contact_radius * 1e3:g} mm, arm inertia {table2.arm_inertia:.3g} kg·m²")
    ks = sorted({0.0, 400.0, PAPER_K_M, PAPER_MEAN_MIN, *K_GRID})
    runs = {k: adams(frictionless, k, periods=1) for k in ks}
    fric = {k: adams(table2, k, periods=1) for k in ks}
    check = adams(table2, PAPER_K_M, periods=2)
    print(f"one period vs two (k_M, friction): mean |M| differs by "
          f"{abs(check.mean_abs() / fric[PAPER_K_M].mean_abs() - 1):.1e} (relative)")
    print("\nrequired torque (Figs 5, 6, 8), N·m: analytic | simulated | with friction")
    for k, label in ((0.0, "rigid"), (400.0, "Table 4, 400"), (PAPER_K_M, "k_M 713.5"),
                     (PAPER_MEAN_MIN, "740")):
        cells = []
        for name in ("peak", "mean_abs", "rms"):
            a = analytic(name, k)
            cells.append(f"{name} {a:.4e} | {simulated(runs, name, k):.4e} | "
                         f"{simulated(fric, name, k):.4e}")
        print(f"  {label:<13} " + "; ".join(cells))
    for name, figs, paper_min in (("mean_abs", "Figs 9–10", PAPER_MEAN_MIN),
                                  ("epsilon", "Figs 12–13", PAPER_EPS_MIN)):
        unit = "N·m" if name == "mean_abs" else "1/s²"
        print(f"\n{name} vs k ({figs}), {unit}: k (paper units) analytic | simulated | with "
              "friction")
        rows = {k: (analytic(name, k), simulated(runs, name, k), simulated(fric, name, k))
                for k in K_GRID}
        for k, (a, s, f) in rows.items():
            print(f"  {k:6.0f}  {a:.4e} | {s:.4e} | {f:.4e}")
        columns = np.array(list(rows.values()))
        closed = (JOINT.closed_form_mean_abs() if name == "mean_abs"
                  else JOINT.closed_form_work()) * 1e6
        sim_min, fric_min = vertex(K_GRID, columns[:, 1]), vertex(K_GRID, columns[:, 2])
        print(f"  optimum k: analytic closed form {closed:.1f}; simulated {sim_min:.0f}; with "
              f"friction {fric_min:.0f}; the paper's Adams reading {paper_min:.0f} (k_M "
              f"{PAPER_K_M}, k_E {PAPER_K_E})")
        base = (analytic(name, 0.0), simulated(runs, name, 0.0), simulated(fric, name, 0.0))
        best = columns.min(axis=0)
        print("  saving at the grid's best k: " + ", ".join(
            f"{what} {100 * saving(b, z):.1f} %" for what, b, z in
            zip(("analytic", "simulated", "with friction"), best, base, strict=True)))
    print("\nopen loop (the analysis' torque, no feedback, native dead-zone spring at k_M): "
          "max |θ − θ_plan| over a period")
    k_m = JOINT.k_M()
    errors = []
    for dt in (1e-3, 5e-4, 2.5e-4):
        t, err = open_loop(PaperJoint(gravity=0.0), k_m, dt)
        bound = open_loop_bound(JOINT, dt, t)
        errors.append(np.abs(err).max())
        print(f"  dt {dt:g} s: {errors[-1]:.3e} rad (bound {bound.max():.3e}, within: "
              f"{bool(np.all(np.abs(err) <= bound))})")
    print(f"  order: {np.log2(errors[0] / errors[1]):.2f}, {np.log2(errors[1] / errors[2]):.2f}")


if __name__ == "__main__":
    main()
