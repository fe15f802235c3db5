"""An optimal cycle written as a motion log that every command's ``--motion`` reads.

The log format is hexaleg's own (:func:`hexaleg.motion.recorded.write.write_motion_log`: q, the
exact v and a, the stance as ``stance_<LEG>``, which it reads back as it is);
:func:`hexaleg.load_motion` finds a log's period from two
cycles or more, so the cycle is written ``cycles`` times, each the previous one moved by the
cycle's rigid displacement ``H`` (:mod:`~hexaleg.optimal.periodic`): base placement
``H^c · oM_b``, feet ``H^c · p``, joints, stance and the base-frame velocities unchanged.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pinocchio as pin

from hexaleg.checks import integer
from hexaleg.motion.recorded.write import write_motion_log
from hexaleg.motion.trajectory import Motion
from hexaleg.optimal.periodic import cycle_displacement
from hexaleg.robot.model import Robot


def repeated(motion: Motion, cycles: int) -> Motion:
    """``cycles`` copies of the periodic ``motion`` one after the other (module docstring), as
    one motion of ``cycles × T`` samples that is not itself a single period."""
    cycles = integer("cycles", cycles, low=1)
    h = cycle_displacement(motion)
    q, feet = [], []
    step = pin.SE3(h[:3, :3], h[:3, 3])
    move = pin.SE3.Identity()
    for _ in range(cycles):
        qc = motion.q.copy()
        for k in range(len(qc)):
            qc[k, :7] = pin.SE3ToXYZQUAT(move * pin.XYZQUATToSE3(qc[k, :7]))
        q.append(qc)
        feet.append(motion.feet @ move.rotation.T + move.translation)
        move = step * move
    n = motion.n_samples * cycles
    return Motion(t=motion.t[0] + np.arange(n) * motion.dt, q=np.vstack(q),
                  v=np.tile(motion.v, (cycles, 1)), a=np.tile(motion.a, (cycles, 1)),
                  stance=np.tile(motion.stance, (cycles, 1)), feet=np.concatenate(feet),
                  period=motion.period * cycles, distance=motion.distance * cycles,
                  periodic=False, info=dict(motion.info))


def write_optimal_motion(robot: Robot, motion: Motion, path: str | Path, *,
                         cycles: int = 3) -> Path:
    """Write the optimal cycle ``motion`` of ``robot`` as a CSV or NPZ log of ``cycles`` cycles
    that :func:`hexaleg.load_motion` (and every command's ``--motion``) reads back to it.

    Raises:
        InvalidParameterError: ``cycles`` < 2 (the reader needs two to find the period), a
            suffix other than ``.csv`` or ``.npz``, a motion of another robot.
        OutputError: the file cannot be written.
    """
    integer("cycles", cycles, low=2)
    return write_motion_log(robot, repeated(motion, cycles), path)
