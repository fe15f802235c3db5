"""The centre-of-pressure margin of a walk on soles: the stances it is taken over, none on point
feet. (Its value on a walking biped, against the test's own centre of pressure, is in
tests/simulation/test_balance.py's slow walk.)"""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np

from hexaleg.simulation import pressure
from hexaleg.simulation.measures import LOSS_GRACE


def test_inner_stance_leaves_out_each_stances_grace_at_both_ends_across_the_cycle_end():
    """Leg 0 stands over the cycle's end (samples 70–99 and 0–29: one stance of 60), leg 1 in
    the middle (20–79), leg 2 always: the first and last ⌈2 % · 60⌉ = 2 samples of each stance
    are left out, the whole cycle of a leg that never swings is in."""
    n = 100
    stance = np.zeros((n, 3), dtype=bool)
    stance[70:, 0] = stance[:30, 0] = True
    stance[20:80, 1] = True
    stance[:, 2] = True
    inner = pressure.inner_stance(SimpleNamespace(stance=stance.astype(float)))
    grace = int(np.ceil(LOSS_GRACE * 60))
    assert grace == 2
    expected0 = np.zeros(n, dtype=bool)
    expected0[70 + grace:] = expected0[:30 - grace] = True
    np.testing.assert_array_equal(inner[:, 0], expected0)
    expected1 = np.zeros(n, dtype=bool)
    expected1[20 + grace:80 - grace] = True
    np.testing.assert_array_equal(inner[:, 1], expected1)
    assert inner[:, 2].all()


def test_point_feet_have_no_margin(feedforward):
    """The hexapod stands on point feet: no sole, no margin, and its runs record none."""
    run = feedforward.with_springs
    assert pressure.cop_margins(run.sim, feedforward.motion, run.trajectory,
                                slice(0, run.trajectory.n)) == (None, None)
    assert run.cop_margin is None and feedforward.baseline.cop_margin is None


def test_a_sole_on_its_edge_tipped_and_one_off_it_did_not():
    """The bound is the margin's: at 0.2 mm (Talos' position-servo heel read -0.24 µm) the foot
    rolled about its edge and the message names the leg, the edge, the time and the bound; at
    1 mm and at the test biped's 39.5 mm it stood flat; point feet have no margin to tip."""
    on_edge = pressure.CopMargin(2e-4, "L1", "heel", 8.625, 83.08)
    message = pressure.tipping(on_edge)
    assert message is not None
    for words in ("L1 sole", "heel edge", "t = 8.6250 s", "0.20 mm", "bound 1 mm", "83.1 N"):
        assert words in message, words
    assert pressure.tipping(pressure.CopMargin(pressure.TIP_MARGIN, "L1", "heel", 0, 1)) is None
    assert pressure.tipping(pressure.CopMargin(0.0395, "R1", "left", 1.0, 80.0)) is None
    assert pressure.tipping(None) is None


def test_a_run_whose_sole_rode_its_edge_is_tipped_not_walks(prepared, monkeypatch):
    """A run that covered its distance and tracked its joints, but whose margin was on the edge,
    is "tipped" (the verdict the design's proof and the page read), not "walks"; a run that did
    not walk keeps its own verdict. The hexapod has no soles, so its margin is stood in for."""
    import dataclasses

    from hexaleg.simulation.result import VERDICTS, verdict_meanings
    from hexaleg.simulation.run import Settings, simulate

    assert set(verdict_meanings()) == set(VERDICTS) and "tipped" in VERDICTS
    edge = pressure.CopMargin(0.0, "LF", "toe", 1.0, 4.5)
    monkeypatch.setattr(pressure, "cop_margins", lambda *a, **k: (edge, edge))
    quick = Settings(cycles=2, evaluate=1, force_samples=0)
    s = simulate(prepared.robot, prepared.motion, prepared.motor, None, quick,
                 prepared=prepared)
    assert s.baseline.verdict == "tipped" and not s.baseline.walks and not s.walks
    assert "LF sole's centre of pressure reached its toe edge" in s.baseline.message
    weak = simulate(prepared.robot, prepared.motion, prepared.motor, None,
                    dataclasses.replace(quick, controller="position", kp_scale=0.15),
                    prepared=prepared)
    assert weak.baseline.verdict == "short"
