import numpy as np
import pytest

from hexaleg.errors import InvalidParameterError
from hexaleg.robot.springs import StiffeningSpring


def test_conservative(conservative):
    s = StiffeningSpring(((0.1, 1.0), (0.4, 2.0)), ((-0.2, 0.5), (-0.5, 3.0)))
    conservative(s, kinks=[0.1, 0.4, -0.2, -0.5])


def test_stiffness_adds_up_stage_by_stage():
    s = StiffeningSpring(above=((0.1, 1.0), (0.4, 2.0)))
    h = 1e-6
    slope = [-(s.torque(np.array(q + h)) - s.torque(np.array(q - h))) / (2 * h)
             for q in (0.0, 0.2, 0.6)]
    np.testing.assert_allclose(slope, [0.0, 1.0, 3.0], atol=1e-6)


def test_bad_input():
    with pytest.raises(InvalidParameterError, match="stages"):
        StiffeningSpring()
    with pytest.raises(InvalidParameterError, match="above breakpoints"):
        StiffeningSpring(above=((0.4, 1.0), (0.1, 2.0)))
    with pytest.raises(InvalidParameterError, match="below breakpoints"):
        StiffeningSpring(below=((-0.4, 1.0), (-0.1, 2.0)))
    with pytest.raises(InvalidParameterError, match=r"above\[0\] stiffness"):
        StiffeningSpring(above=((0.1, -1.0),))
    with pytest.raises(InvalidParameterError, match=r"above\[0\]"):
        StiffeningSpring(above=((0.1,),))
