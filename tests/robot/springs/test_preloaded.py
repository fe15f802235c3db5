import numpy as np
import pytest

from hexaleg.errors import InvalidParameterError
from hexaleg.robot.springs import PreloadedSpring


def test_conservative(conservative):
    s = PreloadedSpring(1.5, 0.2, theta_minus=-0.2, theta_plus=0.3, neutral=0.1,
                        stiffness_minus=0.5, preload_minus=0.05)
    conservative(s, kinks=[-0.1, 0.4])


def test_torque_jumps_to_the_preload_at_contact():
    s = PreloadedSpring(2.0, 0.3, theta_k=0.1)
    assert float(s.torque(np.array(0.0999))) == 0.0
    assert float(s.torque(np.array(0.1001))) == pytest.approx(-0.3 - 2.0 * 1e-4)
    assert float(s.torque(np.array(-0.2))) == pytest.approx(0.3 + 2.0 * 0.1)
    assert float(s.energy(np.array(0.2))) == pytest.approx(0.3 * 0.1 + 0.5 * 2.0 * 0.01)


def test_zero_width_dead_zone_is_allowed():
    s = PreloadedSpring(0.0, 0.2, theta_minus=0.0, theta_plus=0.0)
    np.testing.assert_array_equal(s.torque(np.array([-0.1, 0.1])), [0.2, -0.2])


def test_bad_input():
    with pytest.raises(InvalidParameterError, match="theta_minus"):
        PreloadedSpring(1.0, 0.1, theta_minus=0.2, theta_plus=0.1)
    with pytest.raises(InvalidParameterError, match="theta_plus"):
        PreloadedSpring(1.0, 0.1, theta_minus=0.2)
    with pytest.raises(InvalidParameterError, match="preload"):
        PreloadedSpring(1.0, -0.1, theta_k=0.1)
