"""Fixtures of the report tests: one small report, written once per session, and the same gait
analysed through the public API without the report's modules."""

from __future__ import annotations

import json
from pathlib import Path
from typing import Any

import pytest

import hexaleg
from hexaleg import analyze
from hexaleg.design.rules import paper_style_springs
from hexaleg.robot.catalogue import DEFAULT_MOTOR
from hexaleg.robot.springs import SpringSet
from hexaleg.studies.report.build import Report
from hexaleg.studies.report.config import ReportConfig
from hexaleg.studies.report.write import write_report

SMALL = """
[gait]
samples = 200

[report]
title = "test report"
stiffness_points = 5

[view]
fps = 30
"""
"""The report's config: the 200-sample default gait (the ``walk200`` fixture's), 5 curve
points."""


@pytest.fixture(scope="session")
def written(tmp_path_factory: pytest.TempPathFactory,
            robot: hexaleg.Robot) -> tuple[Report, Path]:
    """The report of a 200-sample default gait and its directory, written once for the session
    (the paper's single-joint numbers at the default samples are cached for the other runs)."""
    out = tmp_path_factory.mktemp("report")
    (out / "small.toml").write_text(SMALL)
    r = write_report(out / "out", ReportConfig.from_toml(out / "small.toml"), robot=robot,
                     progress=None)
    return r, out / "out"


TINY_DESIGN = {"design": {"samples": 100, "families": ["linear"], "map_period": [1.0],
                          "map_stride": [1.0], "map_payload": [0.0], "map_mu": [0.6],
                          "map_slope": [0.0], "map_pattern": ["tripod"],
                          "robust_period": [1.0, 1.25], "robust_stride": [1.0, 1.0],
                          "robust_payload": [0.0, 0.0], "robust_mu": [0.6, 0.6],
                          "pareto_fractions": []}}
"""``hexaleg design`` at its smallest: linear springs on the 100-sample default gait, one-cell
maps, a two-corner robust box."""


@pytest.fixture(scope="session")
def design_json(tmp_path_factory: pytest.TempPathFactory) -> Path:
    """A ``design.json`` (and ``design.html``) of :data:`TINY_DESIGN`, written once a session."""
    from hexaleg.studies.design.config import DesignConfig
    from hexaleg.studies.design.write import write_design

    out = tmp_path_factory.mktemp("design")
    write_design(out, DesignConfig.from_mapping(TINY_DESIGN), progress=None)
    return out / "design.json"


@pytest.fixture(scope="session")
def data(written: tuple[Report, Path]) -> dict[str, Any]:
    """The written ``report.json``."""
    return json.loads((written[1] / "report.json").read_text())


@pytest.fixture(scope="session")
def independent(robot: hexaleg.Robot, walk200: hexaleg.Motion
                ) -> tuple[hexaleg.Motion, SpringSet, hexaleg.Analysis]:
    """The same gait analysed through the public API, without the report modules."""
    springs = paper_style_springs(robot, walk200, "femur")
    a = analyze(robot, walk200, springs, motor=DEFAULT_MOTOR, objective="joule")
    return walk200, springs, a
