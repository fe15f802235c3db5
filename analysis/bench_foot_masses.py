"""The mass each foot's ground contact moves, and the automatic timestep it allows (issue #54).

For each robot and gait given (``ROBOT`` or ``ROBOT:CONFIG.toml``, as ``hexaleg simulate``
takes them): the sized ground (K, B), then per foot at the gait's first sample the mass MuJoCo's
``body_invweight0`` gives the foot's body (what sized the contact's stability limit before), the
foot point's mass free to slide ``1/(J_z M⁻¹ J_zᵀ)`` and held by its friction ``Λ_zz``
(:mod:`hexaleg.simulation.foot_mass`), and the least held mass over 40 samples of the gait;
then the automatic timestep sized at the body's mass (before) and at the held foot point's
(now: :func:`hexaleg.simulation.timestep.automatic_timestep`), each rounded to divide the
period, and what sets it.

    cd analysis && python bench_foot_masses.py hexaleg solo12 a1:trot_a1.toml ...
"""

from __future__ import annotations

import dataclasses
import sys

import numpy as np

from hexaleg.commands.simulate.study import load_study
from hexaleg.scenario.scenario import Scenario
from hexaleg.simulation.foot_mass import held_masses, sliding_masses
from hexaleg.simulation.ground import Ground
from hexaleg.simulation.model import TIMESTEP, _dt_limit, _inverse_weight, build_model
from hexaleg.simulation.model import timestep_limit as limit_of
from hexaleg.simulation.timestep import automatic_timestep, cycle_timestep


def main(cases: list[str]) -> None:
    for case in cases:
        name, _, config = case.partition(":")
        study = load_study(Scenario.load(name, config or None))
        p = study.prepared
        robot, motion = p.robot, p.motion
        settings = study.settings.sized(robot.mass)
        servo, ground = settings.servo(), settings.ground(p.contact.mu)
        probe = build_model(robot, motion, p.motor, servo=servo, ground=ground, check=False)
        now = cycle_timestep(automatic_timestep(robot, motion, p.motor, servo, ground, probe),
                             motion.period)
        _, what = limit_of(probe, motion)
        servos, _ = limit_of(dataclasses.replace(probe, ground=Ground(1e-12, 0.0)), motion)
        body = np.array([1 / _inverse_weight(probe.model, int(g)) for g in probe.foot_geoms])
        bounds = [_dt_limit(ground.damping / m, ground.stiffness / m) for m in body]
        before = cycle_timestep(min(TIMESTEP, motion.dt / 2, 0.8 * min(servos, *bounds)),
                                motion.period)
        samples = np.linspace(0, motion.n_samples - 1, 40).astype(int)
        least = np.min([held_masses(robot, motion.q[i]) for i in samples], axis=0)
        held, sliding = held_masses(robot, motion.q[0]), sliding_masses(robot, motion.q[0])
        print(f"{case}: {robot.mass:.1f} kg, period {motion.period:.3f} s, ground K "
              f"{ground.stiffness:.3g} N/m, B {ground.damping:.3g} N·s/m; automatic timestep "
              f"{before * 1e3:.4f} ms before, {now * 1e3:.4f} ms now ({before / now:.2f}x; "
              f"gait dt/2 {motion.dt / 2e-3:.4g} ms; the stability limit set by {what})")
        for i, leg in enumerate(robot.legs):
            print(f"  {leg.name:>10s}  body {body[i]:.3g} kg  foot point sliding "
                  f"{sliding[i]:.3g} kg  held {held[i]:.3g} kg  (held over the gait >= "
                  f"{least[i]:.3g} kg)")


if __name__ == "__main__":
    main(sys.argv[1:] or ["hexaleg"])
