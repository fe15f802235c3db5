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
    assert period == pytest.approx(0.83, abs=2e-4) and corr > 0.9  # measured 4.6e-5
    cycles = average_cycles(t, x, period, dt)
    assert cycles.count == 12 and cycles.spread.max() < 0.05


@pytest.mark.parametrize("cycles", [2, 3, 10])
def test_period_of_a_noise_free_log_is_exact(gait_100hz, cycles):
    """A noise-free log of 2, 3 or 10 cycles of the 1 s gait: the period to 1e-6 s (measured
    8e-9 s; the autocorrelation's peak alone gave 1.0014, 1.0007 and 1.00009 s)."""
    x = np.tile(gait_100hz.q[:, 7:], (cycles, 1))
    period, _ = find_period(x, 0.01)
    assert period == pytest.approx(1.0, abs=1e-6)


def test_no_repeat_is_named():
    noise = np.random.default_rng(0).normal(size=(400, 2))
    with pytest.raises(InvalidParameterError, match="cycle"):
        find_period(noise, 0.01)
