"""Fixtures of the recorded-motion tests: a hexaleg gait written as a robot's log — repeated for
several cycles, its joints quantised like a Dynamixel's encoder (1024 ticks per 300°) plus
noise, at 100 Hz — and the noise-free motion it came from."""

from __future__ import annotations

import numpy as np
import pytest

import hexaleg
from hexaleg.motion.recorded.write import log_columns

TICK = np.deg2rad(300.0) / 1024
"""A Dynamixel AX/MX position tick, rad."""


def noisy_log(robot: hexaleg.Robot, motion: hexaleg.Motion, *, cycles: int = 10,
              noise: float = 0.5 * TICK, base_noise: float = 0.5e-3, base: bool = True,
              contacts: bool = True, seed: int = 0) -> dict[str, np.ndarray]:
    """``cycles`` repeats of the periodic ``motion`` as log columns (SI), joints quantised to
    :data:`TICK` after Gaussian noise of ``noise`` rad; base position with ``base_noise`` m
    (and its quaternion) when ``base``; contact columns when ``contacts`` (the motion's stance
    as a robot's contact switches give it, ``contact_<LEG>``: the writer's ``stance_<LEG>`` is
    a plan's, which the reader takes as it is)."""
    rng = np.random.default_rng(seed)
    one = log_columns(robot, motion, derivatives=False)
    cols: dict[str, np.ndarray] = {}
    n = motion.n_samples
    cols["time"] = np.arange(cycles * n) * motion.dt
    step = motion.distance * np.asarray(motion.info.get("direction", [1.0, 0.0, 0.0]))
    for name, values in one.items():
        if name == "time":
            continue
        name = name.replace("stance_", "contact_", 1) if name.startswith("stance_") else name
        rep = np.tile(values, cycles)
        if name in robot.joint_names:
            rep = np.round((rep + rng.normal(0.0, noise, rep.shape)) / TICK) * TICK
        elif name in ("base_x", "base_y", "base_z"):
            if not base:
                continue
            axis = "xyz".index(name[-1])
            rep = rep + np.repeat(np.arange(cycles), n) * step[axis]
            rep = rep + rng.normal(0.0, base_noise, rep.shape)
        elif name.startswith("base_q") and not base:
            continue
        elif name.startswith("contact_") and not contacts:
            continue
        cols[name] = rep
    return cols


def write_csv(path, cols: dict[str, np.ndarray]) -> None:
    """Write log columns as CSV (plain numbers, one row a sample)."""
    table = np.stack(list(cols.values()), axis=1)
    np.savetxt(path, table, delimiter=",", header=",".join(cols), comments="", fmt="%.9g")


@pytest.fixture(scope="session")
def gait_100hz(robot):
    """The default tripod gait at 100 samples per 1 s cycle (100 Hz)."""
    return hexaleg.gait(robot, hexaleg.GaitParams(samples=100))


@pytest.fixture(scope="session")
def logs():
    """The log helpers: ``logs.noisy_log(...)``, ``logs.write_csv(path, cols)``."""
    import types

    return types.SimpleNamespace(noisy_log=noisy_log, write_csv=write_csv)
