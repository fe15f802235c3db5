import numpy as np
import pytest

from hexaleg.errors import InvalidParameterError
from hexaleg.robot.springs import DeadZoneSpring, LinearSpring, PreloadedSpring, basis
from hexaleg.robot.springs.law import magnitude


def test_torque_is_the_basis_times_the_magnitudes():
    s = PreloadedSpring(2.0, 0.1, theta_minus=-0.2, theta_plus=0.3, neutral=0.05)
    q = np.linspace(-1, 1, 11)
    np.testing.assert_array_equal(s.torque(q), basis(s.terms(), q) @ s.magnitudes())


def test_dead_zone_terms_reproduce_its_elastic_law(conservative):
    s = DeadZoneSpring(2.0, theta_minus=-0.2, theta_plus=0.1, stiffness_minus=0.7, k2=0.01,
                       alpha=1.05, neutral=0.2)
    q = np.linspace(-1, 1, 101)
    np.testing.assert_allclose(basis(s.terms(), q) @ s.magnitudes(), s.elastic_torque(q),
                               atol=1e-15)


def test_velocity_must_match_q():
    with pytest.raises(InvalidParameterError, match=r"v\.shape"):
        LinearSpring(1.0).torque(np.zeros(3), np.zeros(2))


def test_magnitude_refuses_negative_and_bool():
    assert magnitude("k", 0) == 0.0
    for bad in (-1.0, True, "1", float("inf")):
        with pytest.raises(InvalidParameterError, match="k"):
            magnitude("k", bad)
