"""Tests of hexaleg.checks: the validators refuse what they must and name the value."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from numpy.typing import ArrayLike

from hexaleg import checks
from hexaleg.errors import InvalidParameterError, UnknownNameError
from hexaleg.robot.actuator import Actuator


@pytest.mark.parametrize("value", [True, False, np.bool_(True), "1", None, [1.0], math.nan,
                                   math.inf, -math.inf, np.float64("nan")])
def test_real_refuses_non_numbers_bools_and_non_finite(value):
    with pytest.raises(InvalidParameterError, match=r"invalid mu = .*allowed: a finite number"):
        checks.real("mu", value)


def test_real_returns_floats_and_checks_bounds():
    assert checks.real("x", np.int64(3)) == 3.0 and isinstance(checks.real("x", 3), float)
    assert checks.positive("x", 1e-300) == 1e-300
    with pytest.raises(InvalidParameterError, match=r"x = 0.*> 0"):
        checks.positive("x", 0)
    assert checks.nonnegative("x", 0) == 0.0
    with pytest.raises(InvalidParameterError, match=r">= 0 and < 1"):
        checks.real("beta", 1.0, low=0.0, high=1.0, high_open=True)
    assert checks.real("beta", 0.0, low=0.0, high=1.0, high_open=True) == 0.0
    with pytest.raises(InvalidParameterError, match="the duty factor"):
        checks.real("beta", 2.0, high=1.0, allowed="the duty factor in (0, 1)")


@pytest.mark.parametrize("value", [1.0, 1e9, True, "3", None])
def test_integer_refuses_floats_bools_and_strings(value):
    with pytest.raises(InvalidParameterError, match=r"an integer >= 1"):
        checks.integer("samples", value, low=1)


def test_integer_bounds():
    assert checks.integer("n", np.int32(5), low=1, high=5) == 5
    with pytest.raises(InvalidParameterError, match=r"n = 6.*<= 5"):
        checks.integer("n", 6, low=1, high=5)


def test_string_and_one_of():
    assert checks.string("name", "x") == "x"
    with pytest.raises(InvalidParameterError, match="a string"):
        checks.string("name", 3)
    assert checks.one_of("cone", "soc", ("soc", "pyramid")) == "soc"
    with pytest.raises(UnknownNameError, match=r"'cube'.*pyramid.*soc|'cube'.*soc.*pyramid"):
        checks.one_of("cone", "cube", ("soc", "pyramid"))


def test_finite_array_names_the_first_bad_value_and_its_index():
    a = np.zeros((3, 2))
    a[2, 1] = np.inf
    with pytest.raises(InvalidParameterError, match=r"q = inf.*index \(2, 1\)"):
        checks.finite_array("q", a)
    with pytest.raises(InvalidParameterError, match=r"shape \(3, 2\).*shape \(2, 2\)"):
        checks.finite_array("q", np.zeros((3, 2)), (2, 2))
    with pytest.raises(InvalidParameterError, match="an array of real numbers"):
        checks.finite_array("q", ["a"])
    assert checks.finite_array("q", [1, 2]).dtype == float


def test_count_bounds_a_count_by_the_memory_budget():
    high = checks.MEMORY_BUDGET // 1024
    assert checks.count("n", np.int64(high), item_bytes=1024, item="one x") == high
    with pytest.raises(InvalidParameterError, match=rf"n = {high + 1}; allowed: an integer in "
                                                    rf"\[1, {high}\] \(one x costs about 1 kB.*"
                                                    r"2 GiB\); use fewer"):
        checks.count("n", high + 1, item_bytes=1024, item="one x", fix="use fewer")
    for bad in (0, 1e3, True, "5", None):
        with pytest.raises(InvalidParameterError, match=r"an integer in \[1, ") as e:
            checks.count("n", bad, item_bytes=1024, item="one x", fix="use fewer")
        assert "use fewer" not in str(e.value)  # the fix is for counts above the bound


def test_typed_checks_argument_types_against_the_annotations():
    from hexaleg.checks import typed

    @typed
    def f(a: int, b: float | None = None, c: str | Path = "x",
          d: np.ndarray | None = None) -> int:
        """A public function."""
        return a

    assert f(np.int64(3), 2, Path("p"), np.zeros(2)) == 3 and f(1, None) == 1
    for kwargs, says in ((dict(a=None), r"f\(a=…\) = None; allowed: a integer \(got a NoneType"),
                         (dict(a=True), r"a integer \(got a bool\)"),
                         (dict(a=1, b="x"), r"a None or number \(got a str\)"),
                         (dict(a=1, c=3), r"a Path or str"),
                         (dict(a=1, e=3), r"arguments of f.*unexpected keyword")):
        with pytest.raises(InvalidParameterError, match=says):
            f(**kwargs)
    assert f.__doc__ == "A public function." and f.__name__ == "f"


def test_typed_checks_hexalegs_runtime_protocols_not_numpys():
    """An ``Actuator`` argument is checked (structurally, the answer kept per class); ArrayLike,
    whose numpy protocols admit no float, is left to the function."""
    from hexaleg.checks import typed
    from hexaleg.robot.catalogue import CATALOGUE

    @typed
    def g(motor: Actuator, x: ArrayLike = 0.0) -> str:
        return motor.name

    assert g(CATALOGUE["AX-18A"], 1.5) == g(CATALOGUE["AX-18A"], [1.0]) == "AX-18A"
    for bad in ("AX-18A", None, {"coxa": CATALOGUE["AX-18A"]}):
        with pytest.raises(InvalidParameterError, match=r"g\(motor=…\).*a Actuator"):
            g(bad)


@pytest.mark.parametrize("name", ["ContactParams", "DeadZoneSpring", "DesignParams",
                                  "GaitParams", "LinearSpring", "Motion", "Motor",
                                  "OneSidedSpring", "PreloadedSpring", "StiffeningSpring",
                                  "SweepSpec"])
def test_a_public_dataclass_names_an_unknown_or_missing_argument(name):
    """``GaitParams(bogus=1)`` ended in Python's TypeError (#42's fourth probe): every public
    parameter class names the keyword, with its valid ones, or the missing argument."""
    import dataclasses

    import hexaleg
    from hexaleg.errors import InvalidParameterError, UnknownNameError

    cls = getattr(hexaleg, name)
    fields = [f.name for f in dataclasses.fields(cls) if f.init]
    with pytest.raises(UnknownNameError, match=rf"unknown {name} argument 'bogus'.*"
                                               rf"{fields[0]}"):
        cls(bogus=1)
    required = [f for f in dataclasses.fields(cls) if f.init and f.default is dataclasses.MISSING
                and f.default_factory is dataclasses.MISSING]
    if required:
        with pytest.raises(InvalidParameterError, match=rf"arguments of {name}.*missing"):
            cls()
