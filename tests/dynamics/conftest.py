"""Fixtures of the force-solver tests: one group's reduced programs."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from hexaleg.dynamics.prepare import prepare
from hexaleg.dynamics.reduction import reduce
from hexaleg.dynamics.solver import group_program


def _group_data(robot, motion, contact, objective, tau_s=None):
    """The first group's programs of ``motion`` (the tripod gait: the only group):
    ``(prepared, group, data, tau_spring)``."""
    prepared = prepare(robot, motion, contact=contact)
    sys = prepared.system
    tau_s = np.zeros_like(prepared.q) if tau_s is None else tau_s
    g = reduce(sys).groups[0]
    data = dataclasses.replace(group_program(sys, g, objective, prepared.weights(objective),
                                             contact), tau0=g.tau0(tau_s))
    return prepared, g, data, tau_s


@pytest.fixture
def group_data(robot):
    """``group_data(motion, contact, objective, tau_s=None)``: see :func:`_group_data`."""
    return lambda *args, **kw: _group_data(robot, *args, **kw)
