import numpy as np
import pytest

from hexaleg.design.families import FAMILIES, family
from hexaleg.errors import InvalidParameterError, UnknownNameError
from hexaleg.robot.springs import basis

GEOMETRY = {"linear": {}, "dead_zone": {"theta_minus": -0.1, "theta_plus": 0.2},
            "preloaded": {"theta_minus": -0.1, "theta_plus": 0.2},
            "one_sided": {"contact": 0.1, "side": "below"},
            "stiffening": {"above_1": 0.0, "above_2": 0.2, "below_1": -0.1, "below_2": -0.3}}


@pytest.mark.parametrize("name", FAMILIES)
def test_spring_of_magnitudes_is_the_basis_times_them(name):
    fam = family(name)
    geometry = fam.check(GEOMETRY[name], "g")
    terms = fam.terms(geometry, 0.5)
    assert [t.name for t in terms] == list(fam.magnitudes)
    x = np.linspace(0.3, 1.2, len(terms))
    q = np.linspace(-0.5, 1.5, 201)
    np.testing.assert_allclose(fam.spring(geometry, 0.5, x).torque(q), basis(terms, q) @ x,
                               atol=1e-15)
    assert fam.nonnegative().shape == (len(terms),)


def test_only_the_linear_constant_may_be_negative():
    assert list(family("linear").nonnegative()) == [True, False]
    assert family("preloaded").nonnegative().all()


def test_check_names_what_is_wrong():
    with pytest.raises(UnknownNameError, match="spring family"):
        family("coil")
    with pytest.raises(UnknownNameError, match="theta_k"):
        family("dead_zone").check({"theta_k": 0.1}, "g")
    with pytest.raises(InvalidParameterError, match=r"g\.theta_plus"):
        family("dead_zone").check({"theta_minus": 0.1}, "g")
    with pytest.raises(InvalidParameterError, match=r"g\.theta_minus"):
        family("dead_zone").check({"theta_minus": 0.1, "theta_plus": 0.1}, "g")
    family("preloaded").check({"theta_minus": 0.1, "theta_plus": 0.1}, "g")  # zero width is fine
    with pytest.raises(InvalidParameterError, match=r"g\.above_1"):
        family("stiffening").check({**GEOMETRY["stiffening"], "above_1": 0.3}, "g")
    with pytest.raises(UnknownNameError, match=r"g\.side"):
        family("one_sided").check({"contact": 0.0, "side": "up"}, "g")
    with pytest.raises(InvalidParameterError, match=r"g\.contact"):
        family("one_sided").check({"contact": "0"}, "g")
