"""Energy per cycle of hexaleg's default tripod gait, per joint class, without springs and with
the paper's springs on the femurs.

Run:  python analysis/energy_hexaleg.py      (expected output: analysis/logs/energy_hexaleg.log)

The default gait (``hexaleg.gait``: period 1 s, duty factor 0.5, stride 0.06 m, 1000
samples) on the built-in robot with AX-18A servos; foot forces from the minimum-Joule program
(``objective="joule"``). Per joint class, summed over the six legs, J per cycle:

* positive work ∫ max(0, τ q̇) dt and Joule loss ∫ c τ² dt, c = R / k_t² (the servo model,
  docs/energy.md); electrical = Joule loss + mechanical work through the gearbox, no
  regeneration (what the battery pays: the paper's energy criterion, eq. 20–24, with a motor);
* the springs are the paper's design carried over (``hexaleg.design.rules.paper_style_springs``):
  dead zone centred on each femur's range of motion with θ_k/A = 7.32°/0.3 rad (Section 4.2,
  eq. 25), α = 1.05, stiffness k_M = ω² J / α (eq. 19, J the femur's apparent inertia) in the
  paper's eq. 14 convention.

saving = (without − with) / without; negative = the springs cost energy (README, "What the
numbers say": gravity loads the femurs one way through stance; a centred dead zone cannot help).
"""

from __future__ import annotations

import hexaleg
from hexaleg.design.rules import paper_style_springs
from hexaleg.robot.catalogue import DEFAULT_MOTOR

METRICS = ("positive_work", "joule", "electrical")


def class_totals(metrics: dict, robot: hexaleg.Robot) -> dict[str, dict[str, float]]:
    """Metric → joint class → sum over the class's joints, plus "all"."""
    names = list(metrics["joint_names"])
    out: dict[str, dict[str, float]] = {}
    for m in METRICS:
        per_joint = metrics["joint"][m]
        out[m] = {c: float(sum(per_joint[names.index(j)] for j in robot.joints(c)))
                  for c in ("coxa", "femur", "tibia")}
        out[m]["all"] = float(metrics["total"][m])
    return out


def main() -> None:
    robot = hexaleg.load()
    motion = hexaleg.gait(robot)
    prepared = hexaleg.prepare(robot, motion)
    springs = paper_style_springs(robot, motion, "femur")
    without = class_totals(prepared.evaluate().metrics, robot)
    with_ = class_totals(prepared.evaluate(springs).metrics, robot)
    print(f"robot {robot.name}: {robot.nj} joints, {robot.mass:.4g} kg; gait: period "
          f"{motion.period:.4g} s, {motion.n_samples} samples; motor {DEFAULT_MOTOR}")
    lf = springs["LF_femur"]
    print(f"paper-style springs on the {len(springs)} femurs; LF_femur: k_M = {lf.stiffness:.4g} "
          f"N·m/rad, θ_k = {lf.theta_k:.4g} rad about {lf.neutral:.4g} rad")
    for m in METRICS:
        print(f"\n{m} per cycle [J]")
        print(f"  {'class':6s} {'without':>9s} {'with':>9s} {'saving':>9s}")
        for c, w0 in without[m].items():
            w1 = with_[m][c]
            saving = f"{100 * (w0 - w1) / w0:+.2f} %" if w0 else "—"
            print(f"  {c:6s} {w0:9.4g} {w1:9.4g} {saving:>9s}")
    share = without["joule"]["all"] / without["electrical"]["all"]
    print(f"\nJoule loss / electrical energy without springs: {100 * share:.3g} %")


if __name__ == "__main__":
    main()
