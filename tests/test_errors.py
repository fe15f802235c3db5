"""Tests of hexaleg.errors: messages name the value and what is allowed; errors cross processes."""

from __future__ import annotations

import pickle

import pytest

from hexaleg import errors


def test_unknown_name_lists_the_valid_names_sorted():
    e = errors.UnknownNameError("pose", "crouch", ["zero", "stand", "sphere"])
    assert str(e) == "unknown pose 'crouch'; valid poses are: sphere, stand, zero"
    assert isinstance(e, KeyError) and isinstance(e, errors.HexalegError)


@pytest.mark.parametrize(("kind", "plural"), [
    ("pose", "poses"), ("spring family", "spring families"), ("key in spec [sweep]",
                                                             "keys in spec [sweep]"),
    ("class", "classes"), ("joint or joint class", "joint or joint classes")])
def test_unknown_name_says_the_plural(kind, plural):
    assert f"valid {plural} are:" in str(errors.UnknownNameError(kind, "x", ["a"]))


def test_invalid_parameter_names_value_and_range():
    e = errors.InvalidParameterError("mu", -1.0, "> 0")
    assert str(e) == "invalid mu = -1.0; allowed: > 0"
    assert isinstance(e, ValueError)


@pytest.mark.parametrize("error", [
    errors.UnknownNameError("joint", "LF_knee", ["LF_femur", "LF_tibia"]),
    errors.InvalidParameterError("period", 0.0, "> 0 s"),
    errors.InfeasibleForcesError("no forces at t = 0.1 s"),
])
def test_errors_survive_pickling(error):
    """A process pool sends a worker's exception back pickled; it must arrive intact."""
    back = pickle.loads(pickle.dumps(error))
    assert type(back) is type(error)
    assert str(back) == str(error)


def test_errors_carry_their_data_across_processes():
    """A worker's SpringDesignError keeps its nearest spring and a StaticMarginError its largest
    margin when pickled back to the parent (not just name, value and allowed)."""
    from hexaleg.errors import SpringDesignError, StaticMarginError

    design = pickle.loads(pickle.dumps(SpringDesignError("max_outer_diameter", 0.001, "≥ 2 mm",
                                                         nearest={"d": 0.0005})))
    assert design.nearest == {"d": 0.0005} and design.name == "max_outer_diameter"
    margin = pickle.loads(pickle.dumps(StaticMarginError("static_margin", 0.03, "≤ 0.021 m",
                                                         largest=0.021)))
    assert margin.largest == 0.021 and margin.value == 0.03
