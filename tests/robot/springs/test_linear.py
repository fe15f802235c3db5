import numpy as np
import pytest

from hexaleg.errors import InvalidParameterError
from hexaleg.robot.springs import LinearSpring


def test_conservative(conservative):
    conservative(LinearSpring(2.0, 0.1, 0.3), kinks=[])
    conservative(LinearSpring(0.0, 0.1, -0.2), kinks=[])  # a constant-torque spring


def test_hookes_law_and_equilibrium():
    s = LinearSpring(2.0, reference=0.1, torque_at_reference=0.3)
    assert s.equilibrium == pytest.approx(0.25)
    assert float(s.torque(np.array(0.25))) == pytest.approx(0.0)
    assert float(s.torque(np.array(0.35))) == pytest.approx(-0.2)
    assert LinearSpring(0.0, 0.1, 0.5).equilibrium is None
    assert LinearSpring(0.0, 0.1).equilibrium == 0.1
    np.testing.assert_allclose(LinearSpring(0.0, 0.0, 0.5).torque(np.linspace(-1, 1, 5)), 0.5)


def test_bad_input():
    with pytest.raises(InvalidParameterError, match="stiffness"):
        LinearSpring(-1.0)
    with pytest.raises(InvalidParameterError, match="reference"):
        LinearSpring(1.0, reference=float("nan"))
