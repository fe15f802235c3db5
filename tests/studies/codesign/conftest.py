"""One co-design of the default robot at 0.06 m/s, shared by the co-design tests (~9 s on a
quiet machine: 50 samples a cycle in the search, 100 in the rows, 30 evaluations a search, 2
restarts — still ≤ 0.65 of the default gait and below the sequential design). The full-size run,
whose kept log asserts the issue's bars at the default budget, is ``analysis/codesign_hexaleg.py``
(run by ``tests/test_examples.py``)."""

from __future__ import annotations

import pytest

from hexaleg.studies.codesign.build import codesign

BUDGET = {"samples": 50, "final_samples": 100, "max_evaluations": 30, "restarts": 2}
"""The reduced search of the shared co-design (the default: 100, 200, 100, 3)."""


@pytest.fixture(scope="session")
def codesigned():
    return codesign("hexaleg", 0.06, **BUDGET)
