"""The paper's Adams experiment rerun in MuJoCo, beside the analytic reproduction.

Run:  python analysis/simulate_paper.py      (expected output: analysis/logs/simulate_paper.log)

The lever of Table 6 driven along θ = 0.3 sin 2t (eq. 25; the motion driver: the lever is
kinematic, the required torque measured), the main torsion springs as their own bodies (Table 4
stiffness and damping, κ = k α, resting on stops at ±θ_k), the lever–spring contact of Table 3
(Adams IMPACT: K δ^2.2 + STEP damping, 0.1 mm), the secondary spring of Table 5 and the joint
friction of Table 2 (``hexaleg.paper.simulated_joint``), all numbers in the paper's unit
system (kg, mm, s, rad: the one in which eq. 19 gives 713.5; 1 stiffness unit = 1e-6 N·m/rad,
docs/paper.md). No gravity (the paper's k_M and k_E analysis leaves it out). For the required
torque (Figs 5–8), the mean torque vs k (Figs 9–10) and the energy ratio ε vs k (Figs 12–13):
the analytic model (``hexaleg.paper``), the forward simulation without friction, and with
Table 2's friction; the simulated optimum against the analytic one and the paper's readings
(740 for the mean torque, 800 for ε). Then the invariant of the simulation on this joint: the
analysis' torque applied open loop follows the plan within the derived bound, at second order.
The study itself is ``hexaleg.paper.forward`` (``hexaleg paper`` writes the same as the
``simulation`` section of paper.json); this script prints it.
Assumed (the paper does not give them): the contact radius 10 mm and each spring arm's inertia,
1 % of the lever's.
"""

from __future__ import annotations

import numpy as np

from hexaleg.paper.forward import CURVES, forward_study
from hexaleg.paper.joint import PaperJoint
from hexaleg.paper.readings import PAPER_K_E, PAPER_K_M
from hexaleg.paper.simulated_joint import open_loop, open_loop_bound

JOINT = PaperJoint()
UNITS = {"mean_abs": "N·m", "epsilon": "1/s²"}


def main() -> None:
    study = forward_study(JOINT)
    table2 = study.model
    K, c, d = table2.contact_si()
    print("Adams single joint in MuJoCo, the paper's units (kg, mm, s, rad): no gravity, dt "
          f"{table2.timestep:g} s")
    print(f"Table 3 contact K = 1e5 mN/mm^2.2 = {K:.4g} N/m^2.2, damping 10 mN·s/mm = "
          f"{c:g} N·s/m over {d * 1e3:g} mm; Table 4 damping 1 = "
          f"{table2.stiffness_si(1.0) * JOINT.transmission:.3g} N·m·s/rad (κ = kα); Table 5 "
          f"k2 = {table2.stiffness_si(0.01):.3g} N·m/rad")
    print(f"Table 2 friction: μ_s 0.5, μ_d 0.8, pin radius 10 mm, v_s 0.1 mm/s; assumed contact "
          f"radius {table2.contact_radius * 1e3:g} mm, arm inertia {table2.arm_inertia:.3g} kg·m²")
    print(f"one period vs two (k_M, friction): mean |M| differs by {study.period_check:.1e} "
          "(relative)")
    print("\nrequired torque (Figs 5, 6, 8), N·m: analytic | simulated | with friction")
    for r in study.torques:
        print(f"  {r.label:<13} " + "; ".join(
            f"{name} {a:.4e} | {s:.4e} | {f:.4e}" for name, (a, s, f) in r.metrics.items()))
    for name, (figs, _, _) in CURVES.items():
        print(f"\n{name} vs k ({figs}), {UNITS[name]}: k (paper units) analytic | simulated | "
              "with friction")
        for k, (a, s, f) in zip(study.grid, study.curves[name].T, strict=True):
            print(f"  {k:6.0f}  {a:.4e} | {s:.4e} | {f:.4e}")
        o = study.optima[name]
        print(f"  optimum k: analytic closed form {o.closed_form:.1f}; simulated "
              f"{o.simulated:.0f}; with friction {o.friction:.0f}; the paper's Adams reading "
              f"{o.paper:.0f} (k_M {PAPER_K_M}, k_E {PAPER_K_E})")
        print("  saving at the grid's best k: " + ", ".join(
            f"{what} {100 * x:.1f} %" for what, x in
            zip(("analytic", "simulated", "with friction"), o.saving, strict=True)))
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
