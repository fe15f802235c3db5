"""Resampling: irregular stamps onto a grid, short NaN runs filled, bad time and long gaps named."""

from __future__ import annotations

import numpy as np
import pytest

from hexaleg.errors import InvalidParameterError
from hexaleg.motion.recorded.read import Log
from hexaleg.motion.recorded.resample import resample


def test_dropped_rows_and_nan_are_filled():
    t = np.delete(np.arange(100) * 0.01, [40, 41])
    x = np.sin(t)
    x[10] = np.nan
    out = resample(Log(t=t, columns={"LF_femur": x}))
    assert out.resampled and len(out.log.t) == 100
    assert out.log.columns["LF_femur"] == pytest.approx(np.sin(np.arange(100) * 0.01), abs=1e-4)


def test_time_going_back_is_named():
    with pytest.raises(InvalidParameterError, match="increase"):
        resample(Log(t=np.array([0.0, 0.02, 0.01]), columns={}))


def test_long_nan_run_is_named():
    x = np.ones(100)
    x[20:40] = np.nan
    with pytest.raises(InvalidParameterError, match="LF_femur"):
        resample(Log(t=np.arange(100) * 0.01, columns={"LF_femur": x}))
