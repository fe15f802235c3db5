"""Writing a motion as a log (CSV or NPZ) that :func:`hexaleg.load_motion` reads back exactly.

The export of a hexaleg motion (to compare with a robot's own log, or to feed another tool), and
the round trip the tests check: q, and with ``derivatives`` the exact v and a, stance as
``stance_<LEG>`` (the motion's own, which the reader takes as it is; not ``contact_<LEG>``,
a switch's, which it refines at the edges), at 17 significant digits (a float's exact decimal
round trip).
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from hexaleg.config import write_file
from hexaleg.errors import InvalidParameterError
from hexaleg.motion.recorded.read import BASE_POSITION, BASE_QUATERNION, BASE_VELOCITY
from hexaleg.motion.trajectory import Motion
from hexaleg.robot.model import Robot


def log_columns(robot: Robot, motion: Motion, *, derivatives: bool = True
                ) -> dict[str, np.ndarray]:
    """The columns of ``motion`` as a log, name → values (T,), SI (the names of
    :mod:`hexaleg.motion.recorded.read`; stance as 0/1 ``stance_<LEG>``)."""
    cols: dict[str, np.ndarray] = {"time": motion.t}
    for i, name in enumerate((*BASE_POSITION, *BASE_QUATERNION)):
        cols[name] = motion.q[:, i]
    for j, name in enumerate(robot.joint_names):
        cols[name] = motion.q[:, 7 + j]
    for i, leg in enumerate(robot.leg_names):
        cols[f"stance_{leg}"] = motion.stance[:, i].astype(float)
    if derivatives:
        for prefix, arr in (("v_", motion.v), ("a_", motion.a)):
            for i, name in enumerate((*BASE_VELOCITY, *robot.joint_names)):
                cols[prefix + name] = arr[:, i]
    return cols


def write_motion_log(robot: Robot, motion: Motion, path: str | Path, *,
                     derivatives: bool = True) -> Path:
    """Write ``motion`` of ``robot`` as a CSV (``.csv``) or NPZ (``.npz``) log.

    Args:
        robot: The robot (its joint and leg names head the columns).
        motion: The motion, shapes as :class:`~hexaleg.motion.trajectory.Motion`.
        path: The file; its suffix chooses the format.
        derivatives: Also write v and a (``v_<name>``, ``a_<name>``), so the log reads back to
            the same motion without smoothing (:func:`hexaleg.load_motion` uses them as given).

    Returns:
        The path written (through :func:`hexaleg.config.write_file`, never through a link).

    Raises:
        InvalidParameterError: a suffix other than ``.csv`` or ``.npz``; a motion of another
            robot.
        OutputError: the file cannot be written.
    """
    path = Path(path)
    if motion.q.shape[1] != robot.model.nq:
        raise InvalidParameterError("motion", f"q of shape {motion.q.shape}",
                                    f"a motion of {robot.name} (q with {robot.model.nq} columns)")
    cols = log_columns(robot, motion, derivatives=derivatives)
    suffix = path.suffix.lower()
    if suffix == ".npz":
        import io

        buffer = io.BytesIO()
        np.savez(buffer, **cols)  # type: ignore[arg-type]
        return write_file(path, buffer.getvalue(), "motion log")
    if suffix != ".csv":
        raise InvalidParameterError("path", str(path), "a file ending in .csv or .npz")
    table = np.stack(list(cols.values()), axis=1)
    buffer_text = [",".join(cols)]
    buffer_text += [",".join(repr(float(x)) for x in row) for row in table]
    return write_file(path, "\n".join(buffer_text) + "\n", "motion log")
