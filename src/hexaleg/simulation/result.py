"""What a simulation found: each :class:`Run` (with the springs or without, its verdict of
:data:`VERDICTS`, its energy and walk) and the :class:`Simulation` of both beside the analysis —
what :func:`hexaleg.simulation.run.simulate` returns."""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from hexaleg.dynamics.analysis import Analysis
from hexaleg.dynamics.energy import saving
from hexaleg.dynamics.prepare import Prepared
from hexaleg.errors import SimulationError
from hexaleg.motion.trajectory import Motion
from hexaleg.robot.model import Robot
from hexaleg.robot.springs import SpringSet
from hexaleg.simulation import measures, pressure, stepping
from hexaleg.simulation.model import SimModel
from hexaleg.simulation.settings import Settings

VERDICTS: tuple[str, ...] = ("walks", "stalled", "short", "overran", "untracked", "tipped",
                              "fell", "diverged")
"""How a run ended (:func:`hexaleg.simulation.measures.verdict`): it walked — the planned distance
within :data:`~hexaleg.simulation.measures.DISTANCE_TOLERANCE` and the RMS tracking error within
:data:`~hexaleg.simulation.measures.TRACKING_BOUND`; it stood but covered less than
:data:`STALL` of the planned distance; it fell short of or overran the tolerance; it covered the
distance without following the joints' gait; it walked, but on soles the robot rolled about
the edge of its one sole on the ground (:func:`hexaleg.simulation.pressure.tipping`); the base
fell; the integration diverged."""
STALL = measures.STALL
"""A run that covers less than this fraction of the planned distance per cycle stalled."""


def verdict_meanings() -> dict[str, str]:
    """What each verdict of :data:`VERDICTS` means (:func:`hexaleg.simulation.measures.verdict`,
    and the runs that did not reach the end), in words with the bounds, for the pages."""
    tol, bound = measures.DISTANCE_TOLERANCE, measures.TRACKING_BOUND * 1e3
    return {
        "walks": (f"it covered the planned distance per cycle within ±{tol:.0%} and followed "
                  f"the joints' gait (RMS tracking error at most {bound:.0f} mrad)"),
        "stalled": f"it stood but covered less than {STALL:.0%} of the planned distance per cycle",
        "short": f"it covered {STALL:.0%} to {1 - tol:.0%} of the planned distance per cycle",
        "overran": f"it covered more than {1 + tol:.0%} of the planned distance per cycle",
        "untracked": (f"it covered the distance, but its joints did not follow the gait (RMS "
                      f"tracking error over {bound:.0f} mrad)"),
        "tipped": (f"it covered the distance and followed the joints, but in single support "
                   f"its sole's centre of pressure came within {pressure.TIP_MARGIN * 1e3:g} mm "
                   "of the sole's edge: the robot rolled about the edge instead of standing "
                   "on the sole"),
        "fell": (f"the body fell: its height under {stepping.FALL_HEIGHT:.0%} of the planned "
                 f"or its roll or pitch beyond ±{np.degrees(stepping.FALL_TILT):.0f}°"),
        "diverged": "the integration diverged",
    }


@dataclass(frozen=True, eq=False)
class Run:
    """One simulation of the gait (with the springs or without: the baseline).

    Attributes:
        name: ``"springs"`` or ``"baseline"``.
        sim: The model.
        trajectory: The recorded run.
        verdict: One of :data:`VERDICTS`.
        message: When and how a run that did not walk ended.
        cycles: :func:`hexaleg.dynamics.energy.metrics` of each evaluated cycle (empty when it
            fell or diverged).
        metrics: Their totals averaged per cycle (J, N·m; empty when it fell or diverged).
        walk: Distance, drift, tracking, slip, contacts (None when it fell or diverged).
        forces: Foot forces against the analysis' (:func:`measures.foot_forces`), or empty.
        wall: Wall-clock time of the stepping (MuJoCo's steps and, closed loop, the balance
            controller's updates between them), s.
        cpu: CPU time of the thread that stepped, over the same span, s: ``wall`` less the
            time the machine gave to other processes (:attr:`cpu_share`).
        started: When its stepping began, s on :func:`time.perf_counter`'s clock (two runs
            that stepped at once overlap: :attr:`Simulation.stepping_wall`).
        feedback: Whether the balance controller ran (:mod:`hexaleg.simulation.balance`).
        constrained: Of its updates, the fraction at which a friction cone bound the force
            correction (0 open loop).
        reason: Why it fell in one clause where the gait alone explains it (a stand on one
            point foot, or on two longer than the balance controller holds, that the
            controller ran on: :class:`~hexaleg.simulation.falls.PointFoot`), else "".
        cop_margin: On soles, how close the centre of pressure came to a sole's edge over the
            evaluated window (:func:`hexaleg.simulation.pressure.cop_margins`); None on point
            feet or when it did not run to the end.
        alone_margin: The same over the single supports only, the robot's own
            tipping margin (:func:`hexaleg.simulation.pressure.tipping`); None also when the
            gait has no single support.
    """

    name: str
    sim: SimModel
    trajectory: stepping.Trajectory
    verdict: str
    message: str
    cycles: list[dict[str, Any]] = field(default_factory=list)
    metrics: dict[str, float] = field(default_factory=dict)
    walk: measures.Walk | None = None
    forces: dict[str, float] = field(default_factory=dict)
    wall: float = 0.0
    feedback: bool = False
    constrained: float = 0.0
    cpu: float = 0.0
    started: float = 0.0
    reason: str = ""
    cop_margin: pressure.CopMargin | None = None
    alone_margin: pressure.CopMargin | None = None

    @property
    def walks(self) -> bool:
        """Whether the robot walked the whole run."""
        return self.verdict == "walks"

    @property
    def simulated_time(self) -> float:
        """Time the run covered (its recorded steps), s."""
        return self.trajectory.n * self.sim.timestep

    @property
    def realtime_factor(self) -> float:
        """Simulated time per wall-clock time of the stepping (the model's building, the
        analysis and the measures left out: :attr:`Simulation.wall` holds them)."""
        return self.simulated_time / self.wall if self.wall > 0 else math.inf

    @property
    def cpu_share(self) -> float:
        """The stepping thread's CPU time over its wall time: 1 on a core of its own, ½ where
        another process shared it (the real-time factor is then halved by the machine, not by
        the simulation)."""
        return self.cpu / self.wall if self.wall > 0 else 1.0


@dataclass(frozen=True, eq=False)
class Simulation:
    """The gait simulated with and without the springs, beside the analysis.

    Attributes:
        robot: The robot. motion: The gait. settings: How it was simulated.
        springs: The springs simulated.
        analysis: The analysis with the springs (its ``baseline`` metrics are without).
        baseline_analysis: The analysis without springs.
        with_springs: The run with the springs. baseline: The run without.
        prepared: The prepared gait (reused by reruns with other settings).
        wall: Wall-clock time of :func:`~hexaleg.simulation.run.simulate`, s: the analysis
            with and without the springs, the timestep's probe, building the models, both runs
            and their measures (and the gait's inverse dynamics where ``prepared`` was not
            given); not MuJoCo's import, which a process's first simulation loads before the
            clock starts.
    """

    robot: Robot
    motion: Motion
    settings: Settings
    springs: SpringSet
    analysis: Analysis
    baseline_analysis: Analysis
    with_springs: Run
    baseline: Run
    prepared: Prepared
    wall: float = 0.0

    @property
    def walks(self) -> bool:
        """Whether both runs walked."""
        return self.with_springs.walks and self.baseline.walks

    @property
    def stepping_wall(self) -> float:
        """Wall-clock time in which one of the two runs stepped, s: the union of their
        stepping spans (:func:`~hexaleg.simulation.run.side_by_side` steps them at once; a
        baseline reused from another simulation stepped apart, its span its own)."""
        spans = sorted((r.started, r.started + r.wall) for r in (self.with_springs, self.baseline))
        (a0, a1), (b0, b1) = spans
        return (a1 - a0) + max(0.0, b1 - max(a1, b0))

    def predicted(self, metric: str = "electrical") -> tuple[float, float, float]:
        """The analysis' ``(with springs, baseline, saving)`` of a metric (J or N·m per cycle,
        saving a fraction)."""
        a = self.analysis
        return (a.metrics["total"][metric], a.baseline["total"][metric],
                a.savings["total"][metric])

    def simulated(self, metric: str = "electrical") -> tuple[float, float, float]:
        """The simulation's ``(with springs, baseline, saving)`` of a metric per cycle.

        Raises:
            SimulationError: a run did not walk (its verdict and message).
        """
        for r in (self.with_springs, self.baseline):
            if not r.walks:
                raise SimulationError(f"the {r.name} run {r.verdict}: {r.message}")
        w, b = self.with_springs.metrics[metric], self.baseline.metrics[metric]
        return w, b, saving(w, b)
