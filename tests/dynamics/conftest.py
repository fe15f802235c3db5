"""Fixtures of the force-solver tests: one group's reduced programs, a gait on one foot."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

import hexaleg
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


@pytest.fixture
def one_foot(walk200):
    """The 200-sample gait with sample 5 on the LF foot alone (a one-foot stance)."""
    stance = walk200.stance.copy()
    stance[5] = False
    stance[5, 0] = True
    return hexaleg.Motion(t=walk200.t, q=walk200.q, v=walk200.v, a=walk200.a, stance=stance,
                          feet=walk200.feet, period=walk200.period, distance=walk200.distance)
