"""Fixtures of the ``hexaleg design`` tests: one small design, computed once per session."""

from __future__ import annotations

from pathlib import Path

import pytest

from hexaleg.studies.design.config import DesignConfig
from hexaleg.studies.design.write import WrittenDesign, write_design

SMALL = {
    "gait": {"samples": 120},
    "design": {"samples": 120, "families": ["linear", "one_sided"],
               "map_period": [0.7, 1.0, 1.4], "map_stride": [0.75, 1.0],
               "map_payload": [0.0, 0.4], "map_mu": [0.3, 0.6],
               "map_slope": [0.0, 0.2617993877991494],  # level and 15° up × the robot's patterns
               "robust_period": [0.8, 1.25], "robust_stride": [1.0, 1.0],
               "robust_payload": [0.0, 0.2], "robust_mu": [0.6, 0.6],
               "pareto_fractions": [0.5]},
}
"""A design at 120 samples per cycle, two families, 3 × 2, 2 × 2 and 2 × 3 (slope × the hexapod's
three patterns) maps, a box of 4 corners."""


@pytest.fixture(scope="session")
def written(tmp_path_factory: pytest.TempPathFactory) -> tuple[WrittenDesign, Path]:
    """The small design, written once for the session, and its directory."""
    out = tmp_path_factory.mktemp("design")
    return write_design(out, DesignConfig.from_mapping(SMALL), progress=None), out
