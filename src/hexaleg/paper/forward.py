"""The paper's Adams experiment forward in MuJoCo, beside the analytic reproduction.

Section 4.1 checks the analysis in Adams; :func:`forward_study` reruns that check with
:func:`hexaleg.paper.simulated_joint.adams` (the Table 6 lever driven along θ = 0.3 sin 2t,
eq. 25; the main springs as bodies the lever contacts through Table 3's impact law; Table 5's
secondary spring; no gravity, as the paper's k_M and k_E analysis) and sets three columns side by
side for every stiffness:

* ``analytic``: the model of :mod:`hexaleg.paper.metrics` (eq. 13/14, no friction);
* ``simulated``: the forward run without friction;
* ``friction``: the forward run with Table 2's joint friction.

Over a grid of k (the paper swept 100…1200 in Figs 7–13; default 100…1600 to bracket the
analytic optima) it gives the mean |M| (Figs 9–10) and the energy ratio ε (eq. 24, Figs 12–13),
and the stiffness minimising each: the vertex of the parabola through the grid's minimum and its
two neighbours (:func:`parabola_vertex`), against the closed form
(:meth:`~hexaleg.paper.joint.PaperJoint.closed_form_mean_abs`, ``closed_form_work``) and
the paper's Adams readings (740 in Fig. 10, 800 in Fig. 13). At the named stiffnesses of
:data:`NAMED` (rigid, Table 4's 400, k_M, 740) it keeps the required torque over a period
(Figs 5–8).

Stiffnesses are numbers in the paper's eq. 19 unit (kg·mm²·s⁻²/rad = 1e-6 N·m/rad, the unit in
which eq. 19 gives 713.5 — the paper labels it N·mm/deg; docs/paper.md), in the paper's
convention κ = kα; torques are N·m, ε 1/s².
"""

from __future__ import annotations

import dataclasses
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from hexaleg.checks import real
from hexaleg.dynamics.energy import saving
from hexaleg.errors import InvalidParameterError
from hexaleg.paper.joint import PaperJoint
from hexaleg.paper.metrics import energy_ratio, metric, paper_samples
from hexaleg.paper.readings import (
    PAPER_K_E,
    PAPER_K_M,
    paper_number_to_si,
    si_to_paper_number,
)
from hexaleg.paper.simulated_joint import AdamsJoint, AdamsRun, adams

K_GRID: tuple[float, ...] = tuple(float(k) for k in range(100, 1700, 100))
"""The default grid of k, eq. 19 units: the paper's 100…1200 (Fig. 7), extended to 1600 so that
the analytic optima (1320, 1462) are bracketed."""
MAX_GRID = 200
"""The most stiffnesses a grid may hold (each costs two forward runs of a period)."""
PAPER_MEAN_MIN = 740.0
"""Section 4.2 / Fig. 10: the stiffness of least mean torque in the paper's Adams run, read off."""
PAPER_EPS_MIN = 800.0
"""Fig. 13: the stiffness of least ε in the paper's Adams run, read off."""
NAMED: tuple[tuple[str, str, float], ...] = (
    ("rigid", "rigid", 0.0), ("table4_400", "Table 4, 400", 400.0),
    ("k_M", "k_M 713.5", PAPER_K_M), ("paper_740", "740", PAPER_MEAN_MIN))
"""(key, label, k in eq. 19 units) of the required-torque curves (Figs 5, 6, 8): no spring,
Table 4's main spring, eq. 19's k_M as printed, the paper's mean-torque optimum."""
TORQUE_METRICS: tuple[str, ...] = ("peak", "mean_abs", "rms")
"""The torque metrics of the named stiffnesses (:func:`hexaleg.paper.metrics.metric`'s
names), N·m."""
CURVES: dict[str, tuple[str, float, float]] = {
    "mean_abs": ("Figs 9–10", PAPER_MEAN_MIN, PAPER_K_M),
    "epsilon": ("Figs 12–13", PAPER_EPS_MIN, PAPER_K_E)}
"""The metrics drawn against k → (the paper's figures, its Adams optimum read off them, the
stiffness it prints for that metric: eq. 19's k_M, Section 4.2's k_E)."""
COLUMNS: tuple[str, ...] = ("analytic", "simulated", "friction")
"""The three models compared, in the order of every (3,) tuple and (3, K) array here."""
_RUN_KEYS = {"peak": "peak_torque", "mean_abs": "mean_abs_torque", "rms": "rms_torque"}
"""Metric names → keys of :meth:`~hexaleg.paper.simulated_joint.AdamsRun.metrics`."""


@dataclass(frozen=True)
class RequiredTorque:
    """The required motor torque over a period at one stiffness (Figs 5, 6, 8).

    Attributes:
        key: Name of the stiffness (:data:`NAMED`). label: Its label.
        k: Stiffness, eq. 19 units.
        t: Times over the forward run's last period, s, (n,).
        torque: Torque, N·m, (3, n) over :data:`COLUMNS` (analytic: eq. 13/14 at ``t``).
        metrics: :data:`TORQUE_METRICS` name → (analytic, simulated, friction), N·m.
    """

    key: str
    label: str
    k: float
    t: np.ndarray
    torque: np.ndarray
    metrics: dict[str, tuple[float, float, float]]


@dataclass(frozen=True)
class ForwardOptimum:
    """The stiffness minimising one metric of :data:`CURVES`, eq. 19 units.

    Attributes:
        metric: ``"mean_abs"`` or ``"epsilon"``. figures: The paper's figures of it.
        closed_form: The analytic optimum (closed form, no gravity).
        simulated: The forward run's optimum without friction (:func:`parabola_vertex`).
        friction: The same with Table 2's friction.
        bracketed: (simulated, friction): the grid's minimum is inside the grid, so the optimum
            is the parabola's vertex; else it is the grid's end (widen the grid).
        paper: The paper's Adams reading (740 or 800).
        printed: The stiffness the paper prints for the metric (k_M of eq. 19, or k_E).
        saving: Fraction saved at the grid's best k against k = 0, per :data:`COLUMNS`.
    """

    metric: str
    figures: str
    closed_form: float
    simulated: float
    friction: float
    bracketed: tuple[bool, bool]
    paper: float
    printed: float
    saving: tuple[float, float, float]


@dataclass(frozen=True)
class ForwardStudy:
    """The result of :func:`forward_study`.

    Attributes:
        model: The experiment with friction (the frictionless run is the same with
            ``friction=False``).
        samples: Samples per period of the analytic metrics.
        grid: Stiffnesses, eq. 19 units, increasing, (K,).
        curves: :data:`CURVES` name → values over ``grid``, (3, K) over :data:`COLUMNS`.
        baseline: :data:`CURVES` name → the values at k = 0, per :data:`COLUMNS`.
        torques: The required torque at each stiffness of :data:`NAMED`.
        optima: :data:`CURVES` name → the optimum.
        period_check: |1 − mean |M| of the second period / of the first| at k_M with friction:
            how little the arms' settling changes the one-period run.
    """

    model: AdamsJoint
    samples: int
    grid: np.ndarray
    curves: dict[str, np.ndarray]
    baseline: dict[str, tuple[float, float, float]]
    torques: tuple[RequiredTorque, ...]
    optima: dict[str, ForwardOptimum]
    period_check: float


def adams_model(joint: PaperJoint) -> AdamsJoint:
    """The forward run's model of ``joint``: Table 2's, arms of 1 % of the lever's inertia."""
    return AdamsJoint(joint=joint, arm_inertia=0.01 * joint.J)


def max_stiffness(model: AdamsJoint) -> float:
    """The stiffest main spring the forward run integrates stably, eq. 19 units: an arm on its
    spring is an oscillator of ω = √(κ/I_arm), and explicit Euler at step h needs h ω < 2; the
    bound keeps h ω ≤ 1 (a factor 4 on κ below the limit: at half the limit the runs stay
    finite, at 0.9 of it they diverge; 4.5e7 for Table 2's joint)."""
    per_unit = model.stiffness_si(1.0) * model.joint.transmission
    return float(model.arm_inertia / (model.timestep**2 * per_unit))


def stiffness_grid(grid: Sequence[float] | np.ndarray, high: float | None = None) -> np.ndarray:
    """``grid`` checked: 3 to :data:`MAX_GRID` increasing stiffnesses > 0 and at most ``high``,
    eq. 19 units.

    Args:
        grid: The stiffnesses.
        high: The stiffest allowed; default :func:`max_stiffness` of Table 2's joint.

    Raises:
        InvalidParameterError: names the first bad value, or the grid, and what is allowed.
    """
    high = max_stiffness(adams_model(PaperJoint())) if high is None else high
    allowed = (f"3 to {MAX_GRID} increasing stiffnesses > 0 in eq. 19 units (1e-6 N·m/rad; the "
               "paper swept 100…1200)")
    values = list(grid)
    for x in values:
        real("stiffness grid value", x, low=0.0, low_open=True, high=high,
             allowed=f"a finite stiffness > 0 and <= {high:.3g} in eq. 19 units (1e-6 N·m/rad; "
                     f"above {high:.3g} the forward run's explicit integration at its "
                     "timestep is no longer stable: max_stiffness)")
    ks = np.asarray(values, dtype=float)
    if not 3 <= ks.size <= MAX_GRID or np.any(np.diff(ks) <= 0):
        raise InvalidParameterError("stiffness grid", values, allowed)
    return ks


def parabola_vertex(ks: np.ndarray, values: np.ndarray) -> tuple[float, bool]:
    """The minimum of the parabola through the grid's least value and its two neighbours
    (vertex −b/2a of the fitted a k² + b k + c).

    Args:
        ks: Stiffnesses, increasing, (K,), K ≥ 3.
        values: The metric at each, (K,).

    Returns:
        ``(k, bracketed)``: the vertex and True when the least value is inside the grid; the
        grid's end and False when it is at an end (the minimum is not bracketed).
    """
    i = int(np.argmin(values))  # the first least value: its left neighbour is greater
    if i in (0, len(ks) - 1):
        return float(ks[i]), False
    a, b, _ = np.polyfit(ks[i - 1:i + 2], values[i - 1:i + 2], 2)  # a > 0: convex through them
    return float(-b / (2 * a)), True


def without_friction(run: AdamsRun) -> AdamsRun:
    """The run without Table 2's friction, from the run with it.

    The lever is driven (the paper's motion driver: its θ, θ̇ are set every step), so the
    friction torque on its pin moves nothing: the arms, the contact forces and every other term
    of the required torque are those of the run without friction, whose torque is the torque
    less the friction (tested against the run with ``friction=False``). Half the runs.
    """
    return dataclasses.replace(run, torque=run.torque - run.friction,
                               friction=np.zeros_like(run.friction))


def _three(x: np.ndarray) -> tuple[float, float, float]:
    """One value per :data:`COLUMNS`."""
    a, b, c = (float(v) for v in x)
    return a, b, c


def _analytic(j: PaperJoint, name: str, ks: np.ndarray, n: int) -> np.ndarray:
    """A metric of the analytic model, no gravity, at stiffnesses ``ks`` in eq. 19 units."""
    si = np.asarray(paper_number_to_si(ks))
    if name == "epsilon":
        return np.asarray(energy_ratio(j, si, gravity=False, n=n))
    return np.asarray(metric(j, name, si, gravity=False, n=n))


def _simulated(run: AdamsRun, j: PaperJoint, name: str) -> float:
    """A metric of a forward run: its torque metrics, or ε of eq. 24 (its positive work)."""
    return run.epsilon(j) if name == "epsilon" else float(run.metrics()[_RUN_KEYS[name]])


def forward_study(joint: PaperJoint | None = None, grid: Sequence[float] | np.ndarray = K_GRID,
                  n: int = 2048) -> ForwardStudy:
    """The Adams experiment forward, without and with friction, beside the analytic model.

    One period per stiffness (the arms start at rest on their stops and the lever at θ = 0, so
    the first period is already periodic: :attr:`ForwardStudy.period_check`), run with friction;
    the run without is the same less the friction torque (:func:`without_friction`).

    Args:
        joint: The joint (default Table 6, eq. 25, the paper's eq. 14 convention); gravity is
            left out.
        grid: Stiffnesses, eq. 19 units (:func:`stiffness_grid`).
        n: Samples per period of the analytic metrics
            (:func:`~hexaleg.paper.metrics.paper_samples`).

    Returns:
        The curves, required torques and optima.

    Raises:
        InvalidParameterError: a bad grid (:func:`stiffness_grid`) or ``n``.
    """
    j = joint or PaperJoint()
    table2 = adams_model(j)
    ks_grid = stiffness_grid(grid, max_stiffness(table2))
    n = paper_samples(n)
    ks = sorted({*(k for _, _, k in NAMED), *ks_grid.tolist()})
    with_friction = {k: adams(table2, k, periods=1) for k in ks}
    runs = [{k: without_friction(r) for k, r in with_friction.items()}, with_friction]
    names = (*TORQUE_METRICS, *CURVES)
    analytic = {name: dict(zip(ks, _analytic(j, name, np.array(ks), n).tolist(), strict=True))
                for name in names}

    def columns(name: str, k: float) -> tuple[float, float, float]:
        return (analytic[name][k], _simulated(runs[0][k], j, name),
                _simulated(runs[1][k], j, name))

    torques = tuple(
        RequiredTorque(key, label, k, runs[0][k].t, np.array(
            [j.motor_torque(runs[0][k].t, float(paper_number_to_si(k)), False),
             runs[0][k].torque, runs[1][k].torque]),
            {name: columns(name, k) for name in TORQUE_METRICS})
        for key, label, k in NAMED)
    curves = {name: np.array([columns(name, k) for k in ks_grid]).T for name in CURVES}
    baseline = {name: columns(name, 0.0) for name in CURVES}
    closed = {"mean_abs": j.closed_form_mean_abs(), "epsilon": j.closed_form_work()}
    optima = {}
    for name, (figures, paper, printed) in CURVES.items():
        (k_sim, in_sim), (k_fric, in_fric) = (parabola_vertex(ks_grid, curves[name][c])
                                              for c in (1, 2))
        best, zero = curves[name].min(axis=1), baseline[name]
        optima[name] = ForwardOptimum(
            name, figures, float(si_to_paper_number(closed[name])), k_sim, k_fric,
            (in_sim, in_fric), paper, printed, _three(saving(best, np.array(zero))))
    two = adams(table2, PAPER_K_M, periods=2)
    check = abs(two.mean_abs() / runs[1][PAPER_K_M].mean_abs() - 1)
    return ForwardStudy(table2, n, ks_grid, curves, baseline, torques, optima, check)
