"""Benchmark of ``hexaleg.load_motion`` (issue #27: importing a 60 s log at 500 Hz ≤ 2 s).

Run:  python analysis/bench_motion.py

Writes a 60 s, 500 Hz CSV log of the default robot's tripod gait (60 cycles of 1 s, joints
quantised like a Dynamixel's encoder after Gaussian noise, 30 000 rows) to a temporary
directory, then times in this process, after a warm-up on a short log (imports and first calls
out of the way): numpy's ``loadtxt`` of the same file (the floor: reading the numbers), and
``load_motion`` twice — the log with its base pose and contact columns, and the joints alone
(stance from the feet's motion, base by leg odometry) — and a log no one here wrote: 60 s of
MuJoCo's walk after a drop and a 1 s stand, through the sensor model of
:func:`hexaleg.simulation.walk_log.walk_log`, joints alone (issue #38's row). Prints each wall
time against the target,
its ratio to numpy's load and its CPU share (process CPU time over wall time: on the shared
2-core machine a share well under 1 says other processes stretched the wall time).
"""

from __future__ import annotations

import tempfile
import time
from collections.abc import Callable
from functools import partial
from pathlib import Path
from typing import Any

import numpy as np

import hexaleg
from hexaleg.motion.recorded.write import log_columns
from hexaleg.simulation.walk_log import walk_log

TARGET = 2.0
"""Issue #27's target wall time for a 60 s log at 500 Hz, s."""
RATE = 500
"""Samples per second of the log (one 1 s gait cycle = 500 samples)."""
SECONDS = 60
"""Length of the log, s."""
TICK = np.deg2rad(300.0) / 1024
"""A Dynamixel AX/MX position tick, rad."""


def write_log(robot: hexaleg.Robot, motion: hexaleg.Motion, path: Path, cycles: int, *,
              base: bool, seed: int = 0) -> None:
    """``cycles`` repeats of ``motion`` as a CSV log: joints quantised to :data:`TICK` after
    noise of half a tick; base position (walking on) and quaternion and contacts when ``base``,
    else the joints alone."""
    rng = np.random.default_rng(seed)
    one = log_columns(robot, motion, derivatives=False)
    n = motion.n_samples
    step = motion.distance * np.asarray(motion.info.get("direction", [1.0, 0.0, 0.0]))
    cols: dict[str, np.ndarray] = {"time": np.arange(cycles * n) * motion.dt}
    for name, values in one.items():
        rep = np.tile(values, cycles)
        if name in robot.joint_names:
            cols[name] = np.round((rep + rng.normal(0.0, 0.5 * TICK, rep.shape)) / TICK) * TICK
        elif base and name in ("base_x", "base_y", "base_z"):
            cols[name] = rep + np.repeat(np.arange(cycles), n) * step["xyz".index(name[-1])]
        elif base and name.startswith("base_q"):
            cols[name] = rep
        elif base and name.startswith("stance_"):  # the gait's stance as contact switches
            cols[name.replace("stance_", "contact_", 1)] = rep
    np.savetxt(path, np.stack(list(cols.values()), axis=1), delimiter=",",
               header=",".join(cols), comments="", fmt="%.9g")


def timed(call: Callable[[], Any]) -> tuple[Any, float, float]:
    """``call()``'s result, wall time and CPU share (process CPU time / wall time)."""
    cpu, start = time.process_time(), time.perf_counter()
    out = call()
    wall = time.perf_counter() - start
    return out, wall, (time.process_time() - cpu) / wall


def main() -> None:
    robot = hexaleg.load()
    motion = hexaleg.gait(robot, hexaleg.GaitParams(samples=RATE))
    with tempfile.TemporaryDirectory() as tmp:
        d = Path(tmp)
        write_log(robot, motion, d / "warm.csv", 3, base=True)
        hexaleg.load_motion(robot, d / "warm.csv")  # imports and first calls
        simulated = walk_log(robot, hexaleg.gait(robot), rate=RATE, cycles=SECONDS - 1,
                             evaluate=1)
        for label, base in (("base pose and contacts", True), ("joints alone", False),
                            ("MuJoCo's walk after a drop and a stand, joints alone", None)):
            path = d / f"log-{base}.csv"
            if base is None:
                simulated.write(path, ("joints",))
            else:
                write_log(robot, motion, path, SECONDS, base=base)
            table, numpy_wall, _ = timed(partial(np.loadtxt, path, delimiter=",", skiprows=1))
            m, wall, share = timed(partial(hexaleg.load_motion, robot, path))
            q = m.info["report"]
            print(f"load_motion, {SECONDS} s at {RATE} Hz ({table.shape[0]} rows × "
                  f"{table.shape[1]} columns), {label}: {wall:.2f} s wall (target <= "
                  f"{TARGET:g} s: {'met' if wall <= TARGET else 'not met'}), "
                  f"{wall / numpy_wall:.2f}× numpy.loadtxt ({numpy_wall:.2f} s), CPU share "
                  f"{share:.2f}; period {q.period:.4f} s from {q.cycles} cycles, "
                  f"{m.n_samples} samples")


if __name__ == "__main__":
    main()
