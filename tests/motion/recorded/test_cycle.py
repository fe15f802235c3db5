"""The period by autocorrelation and the cycles' average."""

from __future__ import annotations

import numpy as np
import pytest

from hexaleg.errors import InvalidParameterError
from hexaleg.motion.recorded.cycle import average_cycles, find_period


def test_period_of_a_noisy_periodic_signal():
    dt = 0.01
    t = np.arange(1000) * dt
    x = np.stack([np.sin(2 * np.pi * t / 0.83), np.cos(4 * np.pi * t / 0.83)], 1)
    x += np.random.default_rng(0).normal(0, 0.02, x.shape)
    period, corr = find_period(x, dt)
    assert period == pytest.approx(0.83, abs=2e-3) and corr > 0.9
    cycles = average_cycles(t, x, period, dt)
    assert cycles.count == 12 and cycles.spread.max() < 0.05


def test_no_repeat_is_named():
    noise = np.random.default_rng(0).normal(size=(400, 2))
    with pytest.raises(InvalidParameterError, match="cycle"):
        find_period(noise, 0.01)
