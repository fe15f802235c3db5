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
