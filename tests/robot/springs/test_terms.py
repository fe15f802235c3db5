import numpy as np
import pytest

from hexaleg.errors import InvalidParameterError
from hexaleg.robot.springs import KINDS, Term, basis
from hexaleg.robot.springs.terms import potentials


@pytest.mark.parametrize("kind", KINDS)
def test_every_kind_is_minus_the_gradient_of_its_potential(kind):
    t = Term(kind, 0.3)
    q = np.linspace(-1, 1, 401)
    q = q[np.abs(q - 0.3) > 1e-4]
    h = 1e-7
    fd = -(t.potential(q + h) - t.potential(q - h)) / (2 * h)
    np.testing.assert_allclose(t.torque(q), fd, atol=1e-6)
    assert abs(t.potential(np.array(0.3 + 1e-12)) - t.potential(np.array(0.3 - 1e-12))) < 1e-9


def test_signs_push_back_toward_the_engagement_side():
    q = np.array([-1.0, 0.0, 1.0])
    assert list(Term("above", 0.0).torque(q)) == [0.0, 0.0, -1.0]
    assert list(Term("below", 0.0).torque(q)) == [1.0, 0.0, 0.0]
    assert list(Term("step_above", 0.0).torque(q)) == [0.0, 0.0, -1.0]
    assert list(Term("step_below", 0.0).torque(q)) == [1.0, 0.0, 0.0]
    assert list(Term("constant", 0.0).torque(q)) == [1.0, 1.0, 1.0]
    assert Term("constant", 0.0).nonnegative is False and Term("above", 0.0).nonnegative


def test_basis_stacks_terms_last():
    terms = (Term("above", 0.1), Term("linear", 0.0))
    q = np.zeros((5, 2))
    assert basis(terms, q).shape == (5, 2, 2) and potentials(terms, q).shape == (5, 2, 2)
    assert basis((), q).shape == (5, 2, 0)


def test_bad_terms():
    with pytest.raises(InvalidParameterError, match=r"Term\.kind"):
        Term("ramp", 0.0)
    with pytest.raises(InvalidParameterError, match=r"Term\.angle"):
        Term("above", float("nan"))
    with pytest.raises(InvalidParameterError, match="q"):
        basis((Term("above", 0.0),), [np.nan])


def test_many_joints_terms_at_once_are_each_term_s_numbers_to_the_bit():
    """:func:`basis_torque` of one kind at many terms' ``q − a`` at once (each column its own
    angle, as the optimal actuation's groups call it) is each :meth:`Term.torque` exactly: each
    entry its own (:meth:`Term.torque` calls it; each kind's φ is checked against its potential
    above). A step counts strictly past its angle: catches ``>=`` for ``>``."""
    from hexaleg.robot.springs.terms import basis_torque

    angles = np.array([-0.4, 0.0, 0.3])
    q = np.concatenate([np.linspace(-1, 1, 401), angles])  # the angles themselves: the steps
    for kind in KINDS:
        got = basis_torque(kind, q[:, None] - angles)
        for j, a in enumerate(angles):
            assert got[:, j].tobytes() == Term(kind, a).torque(q).tobytes()
    assert basis_torque("step_above", np.array([0.0, 1e-9]))[0] == 0.0  # strictly past a
