import numpy as np
import pytest

from hexaleg.errors import UnknownNameError
from hexaleg.robot.springs import OneSidedSpring


@pytest.mark.parametrize("side", ["above", "below"])
def test_conservative(conservative, side):
    conservative(OneSidedSpring(3.0, 0.2, side, 0.1), kinks=[0.2])


def test_engages_on_one_side_only():
    up = OneSidedSpring(2.0, 0.1, "above", 0.05)
    down = OneSidedSpring(2.0, 0.1, "below", 0.05)
    q = np.array([0.0, 0.2])
    np.testing.assert_allclose(up.torque(q), [0.0, -0.05 - 0.2])
    np.testing.assert_allclose(down.torque(q), [0.05 + 0.2, 0.0])


def test_bad_side():
    with pytest.raises(UnknownNameError, match="side"):
        OneSidedSpring(1.0, 0.0, "left")
