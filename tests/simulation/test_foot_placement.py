"""Raibert's foot placement of the balance controller's swing feet
(:mod:`hexaleg.simulation.foot_placement`): the runs of a mask, the lead and its deadbeat bound, the
blend into the swing and the release over the stance, and the trot it was changed for."""

from __future__ import annotations

import numpy as np
import pytest

from hexaleg.motion.stands import longest_stand
from hexaleg.scenario.scenario import Scenario
from hexaleg.simulation import balance, foot_placement

from .test_balance import _model, trot  # noqa: F401  # Solo-12's trot, its model


def test_the_runs_of_a_periodic_mask_wrap_around_the_cycle():
    """:func:`foot_placement.runs`: the run that ends the cycle continues into its start."""
    mask = np.array([[1, 1, 1], [1, 0, 1], [0, 0, 1], [0, 1, 1], [1, 1, 1]], dtype=bool)
    at, of = foot_placement.runs(mask)
    assert at[:, 0].tolist() == [1, 2, 0, 0, 0] and of[:, 0].tolist() == [3, 3, 1, 1, 3]
    assert at[:, 1].tolist() == [2, 0, 0, 0, 1] and of[:, 1].tolist() == [3, 1, 1, 3, 3]
    assert at[:, 2].tolist() == [0, 1, 2, 3, 4] and (of[:, 2] == 5).all()


def test_a_fast_body_sets_its_swing_foot_down_ahead_and_holds_it_at_touchdown(trot):  # noqa: F811
    """Raibert's foot placement (:mod:`hexaleg.simulation.foot_placement`): a body faster than
    planned by δv moves a swinging foot, in the base frame, by b(φ) (T_stance/2) δv
    horizontally — none at lift-off, all of it at touchdown, T_stance/2 = 0.1 s on Solo-12's
    trot at duty 0.5 (ω₀ T_stance = 1.4: short of the deadbeat step's 0.158 s) — and the
    stance leg keeps that correction at touchdown and has released it after HOLD of its
    stance (a wrong sign or a missing lead fails it)."""
    prepared, analysis = trot
    sim = _model(prepared, "feedforward")
    motion = prepared.motion
    b = balance.Balance(sim, motion, analysis.forces, analysis.tau_motor)
    pl = b.placement
    leg = 0
    swinging = np.flatnonzero(pl.swing_of[:, leg] > 1)
    n = motion.n_samples
    last = int(swinging[np.argmax(pl.swing_at[swinging, leg])])
    touchdown = (last + 1) % n
    rows = b.leg_rows[leg]
    fast = np.array([0.1, 0.05, 0.0])

    def correction(k: int, faster: np.ndarray) -> np.ndarray:
        q = motion.q[k].copy()
        q[:3] += b.offset
        qpos, qvel = sim.joints.to_mujoco(q, motion.v[k])
        qvel[:3] += faster
        return b.correction(motion.t[k] + motion.period, qpos, qvel, motion.feet[k] + b.offset)

    lift = int(swinging[np.argmin(pl.swing_at[swinging, leg])])
    assert np.abs(correction(lift, fast)[rows]).max() < 1e-12
    step = correction(last, fast)[rows]
    jac = np.linalg.pinv(b.swing_map[last][rows][:, leg])
    rot = balance.rotation_from_quaternion(motion.q[last:last + 1, 3:7])[0]
    phase = pl.swing_at[last, leg] / pl.swing_of[last, leg]
    stand = longest_stand(prepared.robot, motion)
    assert 1 / (stand.omega * np.tanh(stand.omega * 0.2)) == pytest.approx(0.158, abs=0.001)
    assert pl.lead[last, leg] == pytest.approx(0.1, abs=2 * motion.dt)
    expected = 3 * phase**2 - 2 * phase**3
    assert phase > 0.9 and jac @ step == pytest.approx(
        expected * pl.lead[last, leg] * (rot.T @ fast), abs=1e-9)
    assert correction(touchdown, 0 * fast)[rows] == pytest.approx(step, abs=1e-12)
    later = (touchdown + int(np.ceil(foot_placement.HOLD * pl.stance_of[touchdown, leg]))) % n
    assert np.abs(correction(later, 0 * fast)[rows]).max() < 1e-9


def test_the_lead_is_raiberts_up_to_the_pendulums_deadbeat_step():
    """:func:`foot_placement.lead`: on a linear inverted pendulum ``ẍ = ω₀² x`` (integrated
    numerically, not by the closed form) a velocity error e with the foot set down ``L e``
    further ahead leaves a long stance (Solo-12's co-designed trot, ω₀ T = 4.0) at zero with
    the lead, where Raibert's ``T/2`` sends it back at −28 e; on a short stance (its registered
    trot, ω₀ T = 1.4) the lead is ``T/2``, which leaves 0.81 e (the deadbeat step there,
    0.158 s, would ask 58 % more); they meet at ω₀ T = 2.07."""
    from scipy.integrate import solve_ivp

    def error_after(omega: float, stance: float, lead: float) -> float:
        end = solve_ivp(lambda _, y: [y[1], omega**2 * y[0]], (0, stance), [-lead, 1.0],
                        rtol=1e-11, atol=1e-12).y[:, -1]
        return float(end[1])

    omega, stance = 6.25, 0.644
    lead = float(foot_placement.lead(np.array(stance), omega))
    assert lead < stance / 2 and error_after(omega, stance, lead) == pytest.approx(0, abs=1e-6)
    assert error_after(omega, stance, stance / 2) == pytest.approx(-28.4, rel=0.01)
    omega, stance = 7.12, 0.2
    assert float(foot_placement.lead(np.array(stance), omega)) == stance / 2
    assert error_after(omega, stance, stance / 2) == pytest.approx(0.81, abs=0.01)
    meet = 2.0653 / omega
    assert foot_placement.lead(np.array([meet * 0.999, meet * 1.001]), omega) == pytest.approx(
        [meet * 0.999 / 2, meet * 1.001 / 2], rel=3e-3)  # continuous where they meet
    assert foot_placement.lead(np.array([0.0, 100.0]), omega) == pytest.approx([0.0, 1 / omega])
    assert foot_placement.lead(np.array([0.2]), 0.0) == pytest.approx([0.1])


CODESIGNED = ('[gait]\nduty_factor = 0.7\nperiod = 0.9219\nspeed = 0.3\nstep_height = 0.015\n'
              'body_height = 0.2807\n')
"""Solo-12's co-designed trot (``analysis/bench_logs/bench_optimal_rows_solo12_placement.log``):
fast, low, its stances 0.64 s long (ω₀ T = 4.0)."""


@pytest.mark.slow
@pytest.mark.parametrize("controller", ["feedforward", "position"])
def test_a_long_stance_of_a_low_body_walks_near_its_plan(controller, tmp_path):
    """Solo-12's co-designed trot walks under both servos with and without springs, the
    springs' run within 20 % of the plan's energy: with Raibert's ``T_stance/2`` lead (twice
    the deadbeat step, :func:`foot_placement.lead`) it spent 14.51 J a cycle against the plan's
    8.42 under feedforward + PD, and with the co-design's springs ran short under both."""
    from hexaleg.commands.simulate.study import load_study

    config = tmp_path / "run.toml"
    config.write_text(CODESIGNED + f'[simulate]\ncontroller = "{controller}"\n')
    s = load_study(Scenario.load("solo12", config)).run()
    for run in (s.with_springs, s.baseline):
        assert run.feedback and run.verdict == "walks", (run.name, run.verdict, run.message)
    assert s.simulated()[0] < 1.2 * s.predicted()[0]
