"""Simulated walks: the robot walks, the saving survives, a fall is a verdict, a gait that is not
a periodic one or a run too long for memory is refused before anything is built (the settings'
own checks: test_settings)."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

import hexaleg
from hexaleg.errors import InvalidParameterError, SimulationError
from hexaleg.robot.springs import DeadZoneSpring, SpringSet
from hexaleg.simulation import run as run_module
from hexaleg.simulation.run import Settings, simulate

QUICK = Settings(cycles=2, evaluate=1, force_samples=0)


def test_feedforward_walks_and_keeps_the_predicted_saving(feedforward):
    """Feedforward + PD on firm ground, as docs/simulate.md states it: distance within 0.25 % of
    the plan, no contact lost, feet slipping under 0.17 mm, the body 0.23 mm low, roll and pitch
    under 0.01°, the electrical saving within 0.3 percentage points of the prediction and each
    electrical energy within −2.5 % of the predicted (the Joule energies within −4 %)."""
    s = feedforward
    assert s.walks
    for run in (s.with_springs, s.baseline):
        w = run.walk
        assert abs(w.distance_per_cycle / s.motion.distance - 1) < 0.0025
        assert w.contact_losses == 0.0 and w.stances >= 6
        assert w.tracking_rms < 5e-4 and w.slip_max < 1.75e-4
        assert -2.5e-4 < w.height_drift < -2.2e-4
        assert max(w.roll_max, w.pitch_max) < np.radians(0.01)
        assert run.forces["normal_rms"] < 0.05 * run.forces["weight"]
    for metric, low in (("electrical", -0.025), ("joule", -0.04)):
        predicted, simulated = s.predicted(metric), s.simulated(metric)
        for p, q in zip(predicted[:2], simulated[:2], strict=True):
            assert low < q / p - 1 < 0
    assert 0 < s.simulated()[2] - s.predicted()[2] < 0.003


def test_position_servo_walks_but_tracks_worse(position, feedforward):
    """Without feedforward the servo lags: an order of magnitude more tracking error (docs:
    19 mrad RMS), and the electrical saving is gone (docs/simulate.md: −2.4 % against the
    predicted +8.2 %), the Joule saving halved (10 %)."""
    assert position.walks
    assert position.baseline.walk.tracking_rms > 5 * feedforward.baseline.walk.tracking_rms
    assert position.baseline.walk.tracking_rms == pytest.approx(0.0187, rel=0.02)
    assert position.simulated()[2] == pytest.approx(-0.024, abs=0.001)
    assert position.simulated("joule")[2] == pytest.approx(0.102, abs=0.002)


def test_a_conservative_spring_does_no_net_work_over_a_simulated_cycle(prepared):
    """A dead-zone spring on the femurs (engaged both ways over the gait): its work over a
    settled simulated cycle is zero up to the O(dt) of the rectangle rule — under 1 % of the work
    it exchanges."""
    robot, motion = prepared.robot, prepared.motion
    centre = {j: float(np.mean(motion.q[:, robot.model.joints[robot.model.getJointId(j)].idx_q]))
              for j in robot.joints("femur")}
    springs = SpringSet({j: DeadZoneSpring(stiffness=1.0, theta_k=0.05, neutral=c)
                         for j, c in centre.items()})
    s = simulate(robot, motion, prepared.motor, springs, QUICK, prepared=prepared)
    traj, sim = s.with_springs.trajectory, s.with_springs.sim
    steps = round(motion.period / sim.timestep)
    q, v = sim.joints.to_pinocchio(traj.qpos[-steps:], traj.qvel[-steps:])
    power = springs.torques(robot, q) * v[:, 6:]
    assert abs(power.sum()) < 0.01 * np.abs(power).sum()
    assert np.abs(power).sum() * sim.timestep > 1e-3  # the spring works


def test_a_robot_that_falls_is_a_verdict_with_when_and_how(prepared):
    """A servo 200 times too soft lets the body sink: the open-loop run stops at the fall, says
    when and how (docs/simulate.md quotes the message), and the comparison refuses to report
    energies."""
    s = simulate(prepared.robot, prepared.motion, prepared.motor, None,
                 dataclasses.replace(QUICK, controller="position", kp_scale=0.005,
                                     feedback="off"),
                 prepared=prepared)
    run = s.baseline
    assert run.verdict == "fell" and run.message.startswith(
        "the robot fell at t = 1.5240 s: base height 45.6 mm < 50% of the planned 91.3 mm; ")
    assert "servo gains (kp_scale, kd_scale)" in run.message  # neither at stall nor on two feet
    assert np.all(np.isfinite(run.trajectory.qpos)) and run.trajectory.t[-1] < 2.0
    with pytest.raises(SimulationError, match="fell"):
        s.simulated()


def test_an_open_loop_fall_is_simulated_again_with_balance_feedback(prepared):
    """``feedback = "auto"`` on a tripod (three stance feet: open loop first) that falls open
    loop (a position servo 200 times too soft: the body sinks by the stance torques over kp)
    runs both runs again with the balance controller, whose references carry the plan's
    torques over kp: the body stands and walks its stride, but the soft joints do not follow
    the gait between the stances ("untracked"), and the message says so."""
    s = simulate(prepared.robot, prepared.motion, prepared.motor, None,
                 dataclasses.replace(QUICK, controller="position", kp_scale=0.005),
                 prepared=prepared)
    for run in (s.baseline, s.with_springs):
        assert run.feedback and run.verdict == "untracked", (run.verdict, run.message)
        assert run.walk.distance_per_cycle == pytest.approx(prepared.motion.distance, rel=0.1)
        assert run.message.startswith("the joints did not follow the gait")


def test_a_servo_too_weak_to_keep_the_stride_does_not_walk(prepared):
    """A position servo at 0.15 of its gain stands and steps but covers 38 mm of the planned
    60 mm per cycle (63 %): it said "walks" before the 10 % tolerance; now "short", with the
    numbers, and the comparison refuses to report energies."""
    s = simulate(prepared.robot, prepared.motion, prepared.motor, None,
                 dataclasses.replace(QUICK, controller="position", kp_scale=0.15),
                 prepared=prepared)
    run = s.baseline
    assert run.verdict == "short" and not run.walks
    assert run.walk is not None and run.walk.distance_per_cycle < 0.9 * prepared.motion.distance
    assert "of the planned 60.0 mm" in run.message and "outside ±10%" in run.message
    with pytest.raises(SimulationError, match="short"):
        s.simulated()


def test_a_fixed_base_motion_is_refused(prepared):

    motion = dataclasses.replace(prepared.motion, periodic=False)
    with pytest.raises(InvalidParameterError, match="periodic gait"):
        simulate(prepared.robot, motion, prepared.motor, None, QUICK, prepared=prepared)


def test_walking_uphill_costs_more(prepared, feedforward):
    """An incline of 0.05 rad (gravity tilted in the ground frame): the robot still walks its
    stride, and lifting itself costs energy the flat plan does not have."""
    s = simulate(prepared.robot, prepared.motion, prepared.motor, None,
                 dataclasses.replace(QUICK, incline=0.05), prepared=prepared)
    assert s.baseline.walks
    assert s.baseline.metrics["electrical"] > 1.02 * feedforward.baseline.metrics["electrical"]


def test_per_joint_motors_and_the_automatic_timestep(robot, walk):
    """A stronger servo on the femurs (a MotorSet: per-joint stall torque and speed): per-joint
    gains, a timestep chosen below the stiffer servo's stability limit, and a walk that keeps
    the prediction."""
    from hexaleg.robot.catalogue import motor
    from hexaleg.robot.motor_set import MotorSet

    motors = MotorSet.per_class(robot.joint_classes, robot.joint_names,
                                {"coxa": motor("AX-18A"), "femur": motor("XM430-W350"),
                                 "tibia": motor("AX-18A")})
    s = simulate(robot, walk, motors, None, QUICK)
    femur = robot.column("LF_femur")
    assert s.baseline.sim.kp[femur] > 2 * s.baseline.sim.kp[robot.column("LF_tibia")]
    assert s.baseline.sim.timestep == pytest.approx(2.66e-4, rel=0.01)  # docs: 0.27 ms
    assert s.baseline.walks
    assert s.simulated()[1] == pytest.approx(s.predicted()[1], rel=0.1)


def test_a_reused_baseline_run_gives_the_same_simulation(prepared, optimal, feedforward):
    """Springs simulated beside a reused baseline equal a fresh simulation of both (same
    trajectory bit for bit), and a baseline of other settings is refused by name."""
    from conftest import SHORT

    from hexaleg.design.search.optimal import optimal_springs

    other = optimal_springs(prepared, ["tibia"], "linear").springs
    reused = simulate(prepared.robot, prepared.motion, prepared.motor, other, SHORT,
                      prepared=prepared, baseline=feedforward)
    fresh = simulate(prepared.robot, prepared.motion, prepared.motor, other, SHORT,
                     prepared=prepared)
    assert reused.baseline is feedforward.baseline
    np.testing.assert_array_equal(reused.with_springs.trajectory.qpos,
                                  fresh.with_springs.trajectory.qpos)
    assert reused.simulated() == fresh.simulated()
    with pytest.raises(InvalidParameterError, match="baseline"):
        simulate(prepared.robot, prepared.motion, prepared.motor, other,
                 dataclasses.replace(SHORT, controller="position"), prepared=prepared,
                 baseline=feedforward)


def test_steps_are_checked_before_anything_is_allocated(robot, monkeypatch):
    """--timestep 1e-8 used to allocate gigabytes before any bound: ``simulate`` refuses it
    before it prepares the gait or builds a model (the bound itself: test_timestep)."""
    def never(*_args, **_kwargs):  # nothing is prepared, built or allocated first
        raise AssertionError("prepared before the bound was checked")

    monkeypatch.setattr(run_module, "prepare", never)
    monkeypatch.setattr(run_module, "build_model", never)
    motion = hexaleg.gait(robot, hexaleg.GaitParams(samples=100))
    with pytest.raises(InvalidParameterError, match="invalid timestep = 1e-08"):
        simulate(robot, motion, None, None, Settings(timestep=1e-8))


@pytest.mark.parametrize("feedback", ["off", "on"])
def test_the_runs_stepped_side_by_side_are_the_runs_stepped_alone(prepared, optimal, feedback):
    """The springs' run and the baseline step at once on two threads (``side_by_side``); each
    is the same to the bit as the same run stepped alone on this thread, open loop and closed
    loop (the balance controllers' Python updates interleave with the other run's steps)."""
    s = simulate(prepared.robot, prepared.motion, prepared.motor, optimal.springs,
                 dataclasses.replace(QUICK, feedback=feedback), prepared=prepared)
    for r, a in ((s.with_springs, s.analysis), (s.baseline, s.baseline_analysis)):
        assert r.feedback == (feedback == "on")
        alone = run_module.simulate_run(r.name, r.sim, s.motion, a, s.settings, r.feedback)
        for field in ("qpos", "qvel", "servo", "controls"):
            np.testing.assert_array_equal(getattr(alone.trajectory, field),
                                          getattr(r.trajectory, field))
        assert alone.metrics == r.metrics and alone.verdict == r.verdict


def test_a_run_stops_between_chunks_when_told(feedforward):
    """A run whose ``stop`` event is set ends before its next chunk with ``Stopped`` (the run
    beside it failed, or Ctrl-C reached the thread that waits for both)."""
    import threading

    from hexaleg.simulation import stepping

    r, s = feedforward.baseline, feedforward
    stop = threading.Event()
    stop.set()
    with pytest.raises(stepping.Stopped, match=r"t = 0\.0000 s"):
        run_module.simulate_run(r.name, r.sim, s.motion, s.baseline_analysis, s.settings,
                                stop=stop)


@pytest.mark.parametrize("failing, other", [("springs", "baseline"), ("baseline", "springs")])
@pytest.mark.parametrize("error", [KeyboardInterrupt, ValueError])
def test_when_one_run_fails_the_other_is_told_to_stop(prepared, optimal, monkeypatch, error,
                                                      failing, other):
    """Runs side by side: where one ends in an error (or Ctrl-C), the other's ``stop`` is set
    and the error is what ``simulate`` raises — whichever of the two failed (the one waited
    for second too: a wait in order would block on the other's whole run)."""
    told = {}

    def fake(name, sim, motion, analysis, settings, feedback=False, stop=None):
        if name == failing:
            raise error("the run failed")
        told[name] = stop.wait(timeout=60)  # the real run checks it between its chunks
        raise run_module.stepping.Stopped("stopped")

    monkeypatch.setattr(run_module, "simulate_run", fake)
    with pytest.raises(error, match="the run failed"):
        simulate(prepared.robot, prepared.motion, prepared.motor, optimal.springs, QUICK,
                 prepared=prepared)
    assert told == {other: True}
