"""Helpers of the family tests: does one family's law reproduce another's on the motion?"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
import pytest

from hexaleg.design.families import embed, family
from hexaleg.robot.springs import basis

OFF = (-0.8, 0.9)
"""Angles below and above every sample of the test motion (rad from the centre)."""
CENTRE = 0.3
"""The joint's centre of motion, rad."""
Q = CENTRE + np.linspace(-0.75, 0.85, 401)
"""The motion's angles, rad: inside ``OFF``."""


@pytest.fixture
def motion() -> np.ndarray:
    """The motion's angles from the centre, rad (inside ``OFF``)."""
    return Q - CENTRE


@pytest.fixture
def residual() -> Callable[..., float]:
    """``residual(outer, inner, geometry, x)``: the largest torque the law of family ``outer``
    at ``embed(outer, inner, …)`` misses of ``inner``'s law of ``geometry`` and magnitudes
    ``x`` on the motion, its magnitudes fitted by least squares (N·m)."""
    def fit(outer: str, inner: str, geometry: dict, x: np.ndarray) -> float:
        f, i = family(outer), family(inner)
        tau = i.spring(geometry, CENTRE, x).torque(Q)
        g = f.check(embed(outer, inner, geometry, dict(zip(i.magnitudes, x, strict=True)), OFF),
                    "embedded")
        b = basis(f.terms(g, CENTRE), Q)
        y, *_ = np.linalg.lstsq(b, tau, rcond=None)
        return float(np.abs(b @ y - tau).max())
    return fit
