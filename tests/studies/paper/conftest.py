"""Fixtures of the paper study's tests: the default joint, one reproduction and one forward
study on a coarse grid, made once."""

from __future__ import annotations

from typing import Any

import pytest

from hexaleg.studies.paper.forward import ForwardStudy, forward_study
from hexaleg.studies.paper.joint import PaperJoint
from hexaleg.studies.paper.reproduce import reproduce


@pytest.fixture(scope="session")
def paper_result() -> dict[str, Any]:
    """:func:`reproduce` of the default joint at 256 samples per period (``paper.json``)."""
    return reproduce(PaperJoint(), n=256)


FORWARD_GRID = (600.0, 800.0, 1000.0, 1300.0, 1400.0, 1500.0, 1600.0)
"""A coarse grid (eq. 19 units) that still brackets the forward optima of mean |M| (1350, 829
with friction) and ε (1473); ε with friction (about 300) lies below it, at the grid's end."""
FORWARD_SAMPLES = 512


@pytest.fixture(scope="session")
def forward() -> ForwardStudy:
    """:func:`forward_study` of the default joint on :data:`FORWARD_GRID` (about 2 s)."""
    return forward_study(PaperJoint(), FORWARD_GRID, FORWARD_SAMPLES)
