"""Fixtures of the force-solver tests: one group's reduced programs."""

from __future__ import annotations

import numpy as np
import pytest

from hexaleg.dynamics.blocks import Data
from hexaleg.dynamics.pieces import pieces
from hexaleg.dynamics.prepare import prepare
from hexaleg.dynamics.reduction import reduce


def _group_data(robot, motion, contact, objective, tau_s=None):
    """The first group's programs of ``motion`` (the tripod gait: the only group):
    ``(prepared, group, data, tau_spring)``."""
    prepared = prepare(robot, motion, contact=contact)
    sys = prepared.system
    tau_s = np.zeros_like(prepared.q) if tau_s is None else tau_s
    g = reduce(sys).groups[0]
    J = g.joints
    eff = np.broadcast_to(np.asarray(sys.efficiency, dtype=float), (robot.nj,))
    w = prepared.weights(objective)
    data = Data(g.fp, g.N, g.E, g.tau0(tau_s),
                pieces(objective, w[J], sys.qdot[g.rows, J], eff[J], contact.regularization),
                sys.tau_max[J] if contact.torque_limits else None, contact)
    return prepared, g, data, tau_s


@pytest.fixture
def group_data(robot):
    """``group_data(motion, contact, objective, tau_s=None)``: see :func:`_group_data`."""
    return lambda *args, **kw: _group_data(robot, *args, **kw)
