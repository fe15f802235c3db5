"""Stance from contacts and from the feet's kinematics."""

from __future__ import annotations

import numpy as np

from hexaleg.motion.recorded.stance import detect, from_contacts


def test_contacts_threshold_at_half():
    assert from_contacts(np.array([[0.2, 0.8]])).stance.tolist() == [[False, True]]


def test_kinematic_stance_of_the_gait(gait_100hz):
    velocity = np.gradient(gait_100hz.feet, 0.01, axis=0)
    found = detect(gait_100hz.feet, velocity)
    assert found.height is not None and found.speed is not None
    assert np.all((found.stance != gait_100hz.stance).mean(axis=0) <= 0.06)
