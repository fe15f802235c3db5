"""Prepared gaits for the design-layer tests (spring-independent, computed once)."""

from __future__ import annotations

import numpy as np
import pytest

import hexaleg


@pytest.fixture(scope="session")
def prepared(robot, walk):
    """The default gait prepared (1000 samples, μ = 0.6: no inequality binds without springs)."""
    return hexaleg.prepare(robot, walk)


@pytest.fixture(scope="session")
def prepared200(robot, walk200):
    """The default gait at 200 samples, where the cvxpy reference solves the whole cycle fast."""
    return hexaleg.prepare(robot, walk200)


@pytest.fixture(scope="session")
def slippery200(robot, walk200):
    """200 samples on a floor with μ = 0.3 (the paper's Table 3 static friction): friction cones
    bind at most samples."""
    return hexaleg.prepare(robot, walk200, contact=hexaleg.ContactParams(mu=0.3))


@pytest.fixture(scope="session")
def femur_linear():
    """A design program: one linear spring (k ≥ 0, free constant) shared by the six femurs."""
    from hexaleg.design.search.program import DesignProblem

    def make(prepared):
        robot = prepared.robot
        cols = np.array([robot.column(j) for j in robot.joints("femur")])
        q = prepared.q[:, cols]
        B = np.stack([-(q - q.mean(0)), np.ones_like(q)], axis=-1)  # about the mean angle
        return DesignProblem(prepared, "joule", cols, B, np.array([True, False]),
                             np.zeros((0, 2)), np.zeros(0))

    return make
