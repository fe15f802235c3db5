"""Tests of hexaleg.motion.trajectory: the Motion container's invariants and its refusals."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

import hexaleg
from hexaleg.errors import InvalidParameterError
from hexaleg.motion.trajectory import Motion
from hexaleg.motion.transform import transform_motion


def _motion(**changes) -> Motion:
    """A 4-sample, 1-joint, 1-leg motion: the smallest Motion there is."""
    T = 4
    fields = dict(t=np.arange(T) * 0.25, q=np.zeros((T, 8)), v=np.zeros((T, 7)),
                  a=np.zeros((T, 7)), stance=np.ones((T, 1), bool), feet=np.zeros((T, 1, 3)),
                  period=1.0)
    return Motion(**{**fields, **changes})


def test_periodic_grid_excludes_the_endpoint():
    m = _motion()
    assert m.n_samples == 4 and m.dt == 0.25 and m.n_samples * m.dt == m.period
    # A cycle integral of a periodic signal is x.sum() * dt: ∫₀¹ sin²(2πt) dt = 1/2 exactly.
    x = np.sin(2 * np.pi * m.t) ** 2
    assert x.sum() * m.dt == pytest.approx(0.5, abs=1e-15)


def test_supported_defaults_follow_fixed_base():
    assert not _motion().supported.any()
    held = _motion(fixed_base=True, stance=np.zeros((4, 1), bool))
    assert held.supported.all()


@pytest.mark.parametrize("name", ["q", "v", "a", "stance", "feet"])
def test_arrays_must_have_one_row_per_sample(name):
    m = _motion()
    with pytest.raises(InvalidParameterError, match=rf"Motion.{name}.*T = 4"):
        dataclasses.replace(m, **{name: getattr(m, name)[:3]})


def test_non_finite_values_are_refused_with_the_sample_and_time():
    q = np.zeros((4, 8))
    q[2, 7] = np.nan
    with pytest.raises(InvalidParameterError, match=r"Motion.q.*sample 2 \(t = 0.5\)"):
        _motion(q=q)


def test_supported_samples_have_no_stance_feet():
    with pytest.raises(InvalidParameterError, match=r"sample 0 .*feet are in stance"):
        _motion(supported=np.array([True, False, False, False]))
    with pytest.raises(InvalidParameterError, match="fixed-base"):
        _motion(fixed_base=True, stance=np.zeros((4, 1), bool),
                supported=np.array([True, True, False, True]))
    with pytest.raises(InvalidParameterError, match="bool array of shape"):
        _motion(supported=np.zeros(4))


@pytest.fixture(scope="module")
def fold(robot) -> Motion:
    """The stand → sphere transformation: its fold samples are supported by the body."""
    return transform_motion(robot, duration=2.0, samples=401)


def test_supported_samples_are_checked_by_motion(robot, fold):
    fields = {f: getattr(fold, f) for f in ("t", "q", "v", "a", "stance", "feet", "period",
                                            "periodic")}
    with pytest.raises(InvalidParameterError, match=r"Motion\.supported.*shape \(3,\)"):
        hexaleg.Motion(**fields, supported=np.ones(3, dtype=bool))
    with pytest.raises(InvalidParameterError, match=r"sample 0 .*feet are in stance"):
        hexaleg.Motion(**fields, supported=np.ones(fold.n_samples, dtype=bool))
    with pytest.raises(InvalidParameterError, match="fixed-base"):
        hexaleg.Motion(**{**fields, "stance": np.zeros_like(fold.stance)}, fixed_base=True,
                       supported=fold.supported)
    assert hexaleg.Motion(**{**fields, "stance": np.zeros_like(fold.stance)},
                          fixed_base=True).supported.all()


@pytest.mark.parametrize(("change", "says"), [
    ({"period": -1.0}, r"Motion\.period = -1\.0"),
    ({"period": 5.0}, r"Motion\.period = 5\.0; allowed: T × dt = 1\.0 s"),
    ({"distance": float("nan")}, r"Motion\.distance"),
    ({"stance": "twice"}, r"Motion\.stance = 'values \[0\.0, 2\.0\]'"),
    ({"t": "backwards"}, r"Motion\.t = 'not increasing'"),
])
def test_a_motion_s_own_numbers_are_checked(walk200, change, says):
    """A motion edited by hand (dataclasses.replace) that contradicts itself is named, not
    analysed: a negative period, one that is not T × dt, a NaN distance, stance values other
    than 0/1, times that go back."""
    import dataclasses

    key, value = next(iter(change.items()))
    if isinstance(value, str):  # arrays made from the motion
        value = (walk200.stance.astype(float) * 2 if value == "twice"
                 else walk200.t[::-1].copy())
    with pytest.raises(InvalidParameterError, match=says):
        dataclasses.replace(walk200, **{key: value})
