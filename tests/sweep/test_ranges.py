"""Tests of hexaleg.sweep.ranges: command-line ranges and a spec's axis values."""

from __future__ import annotations

import numpy as np
import pytest

from hexaleg.errors import ConfigError, InvalidParameterError, UnknownNameError
from hexaleg.sweep.ranges import axis_values, parse_range


def test_parse_range():
    assert parse_range("k", "0.5") == 0.5
    assert parse_range("k", "0.1,0.2") == (0.1, 0.2)
    np.testing.assert_allclose(parse_range("k", "0.1:10:3:log"), [0.1, 1.0, 10.0])
    np.testing.assert_allclose(parse_range("k", "0:1:5"), np.linspace(0, 1, 5))
    with pytest.raises(InvalidParameterError, match=r"num"):
        parse_range("k", "0:1:0")
    with pytest.raises(InvalidParameterError, match=r"start:stop:num"):
        parse_range("k", "a:b")


def test_axis_values_scalars_lists_and_range_tables():
    assert axis_values("k", 2) == 2.0 and isinstance(axis_values("k", 2), float)
    assert axis_values("k", [1, 2.5]) == (1.0, 2.5)
    np.testing.assert_allclose(axis_values("k", {"start": 1, "stop": 100, "num": 3,
                                                 "scale": "log"}), [1.0, 10.0, 100.0])
    with pytest.raises(UnknownNameError, match=r"range key of k 'step'.*num, scale, start, stop"):
        axis_values("k", {"start": 0, "stop": 1, "step": 0.1})
    with pytest.raises(ConfigError, match=r"k: a range needs start, stop and num; missing 'num'"):
        axis_values("k", {"start": 0, "stop": 1})
    with pytest.raises(InvalidParameterError, match=r"k\[1\] = 'a'; allowed: a finite num"):
        axis_values("k", [1.0, "a"])
    with pytest.raises(InvalidParameterError, match=r"k\.start"):
        axis_values("k", {"start": 0, "stop": 1, "num": 3, "scale": "log"})
    with pytest.raises(InvalidParameterError, match=r"finite"):
        axis_values("k", float("nan"))


def test_a_parsed_value_out_of_range_keeps_its_own_reason():
    with pytest.raises(InvalidParameterError, match=r"--period = nan; .*NaN and inf are not"):
        parse_range("--period", "nan")
    with pytest.raises(InvalidParameterError, match=r"--k\.start = 0\.0; .*> 0 for a log range"):
        parse_range("--k", "0:1:5:log")
    with pytest.raises(InvalidParameterError, match=r"--k\[1\] = inf"):
        parse_range("--k", "1,inf")
    with pytest.raises(InvalidParameterError, match=r"--k\.num = 10000000000; .*1048576"):
        parse_range("--k", "0:1:10000000000")
    with pytest.raises(InvalidParameterError, match=r"--k = 'x:y'; allowed: a number"):
        parse_range("--k", "x:y")
