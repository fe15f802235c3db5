"""Stance from contacts and from the feet's kinematics (the swing's edges fitted, the body's
support kept)."""

from __future__ import annotations

import numpy as np

from hexaleg.motion.recorded.checks import centre_of_mass
from hexaleg.motion.recorded.stance import detect, from_contacts


def test_contacts_threshold_at_half():
    assert from_contacts(np.array([[0.2, 0.8]])).stance.tolist() == [[False, True]]


def test_kinematic_stance_of_the_gait_is_exact(robot, gait_100hz):
    """Noise-free, the fitted swing edges give the gait's own stance but at the switch sample,
    where both tripods are on the ground (h = 0) and the gait counts the lifting one in swing
    (low and still alone counts 3-4 samples of each gentle lift-off and touch-down as stance)."""
    velocity = np.gradient(gait_100hz.feet, 0.01, axis=0)
    com = centre_of_mass(robot, gait_100hz.q[:, 7:], gait_100hz.q[:, :7])
    found = detect(gait_100hz.feet, velocity, com, periodic=True)
    assert found.height is not None and found.speed is not None
    assert ((found.stance != gait_100hz.stance).sum(axis=0) <= 1).all()


def test_a_foot_the_body_needs_stays_down(robot, gait_100hz):
    """With the centre of mass moved over the lifting tripod's side, no edge-band foot can be
    lifted without leaving the body on an edge: the stance is step 1's, longer than the gait's."""
    velocity = np.gradient(gait_100hz.feet, 0.01, axis=0)
    com = gait_100hz.feet[:, gait_100hz.stance[0]].mean(axis=1)  # tripod down at t = 0
    com[:, :2] = gait_100hz.feet[:, 0, :2]  # on the LF foot: no polygon without it holds it
    found = detect(gait_100hz.feet, velocity, com, periodic=True)
    assert found.stance[:, 0].sum() > gait_100hz.stance[:, 0].sum()
