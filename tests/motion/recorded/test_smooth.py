"""Savitzky–Golay smoothing: exact derivatives of a sinusoid, noise estimated, cut-off found."""

from __future__ import annotations

import numpy as np
import pytest

from hexaleg.motion.recorded.smooth import cutoff_frequency, noise_level, smooth


def test_noise_level_and_derivatives_of_a_noisy_sine():
    dt, n = 0.01, 1000
    t = np.arange(n) * dt
    rng = np.random.default_rng(1)
    x = (np.sin(2 * np.pi * t) + rng.normal(0, 1e-3, n))[:, None]
    sigma = noise_level(x)
    assert sigma[0] == pytest.approx(1e-3, rel=0.15)
    f_c = cutoff_frequency(x, dt, sigma, periodic=True)
    assert 1.0 <= f_c < 5.0
    out = smooth(x, dt, f_c, periodic=True)
    w = 2 * np.pi
    assert out.xd[:, 0] == pytest.approx(w * np.cos(w * t), abs=0.1 * w)
    assert out.xdd[:, 0] == pytest.approx(-w**2 * np.sin(w * t), abs=0.2 * w**2)
