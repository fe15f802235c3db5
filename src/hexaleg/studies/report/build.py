"""The gait energy report (``hexaleg report``): one gait, analysed with and without springs.

:func:`build_report` runs the pipeline — robot → gait (:func:`hexaleg.motion.gait.tripod_gait`) →
:func:`hexaleg.dynamics.prepare.prepare` once → :meth:`~hexaleg.dynamics.prepare.Prepared.evaluate`
with the springs, without them, and at every point of a stiffness curve; for a robot with ``stand``
and ``sphere`` poses also the stand → sphere transformation — and collects every number in a
JSON-ready dict whose quantities carry their unit (``{"value": …, "unit": "J"}``).
:func:`write_report` renders that dict with Jinja2 (``templates/report.html.j2``) into a
self-contained ``report.html`` (plots embedded as base64 PNG), and writes ``report.json`` and the
plots (:mod:`hexaleg.outputs.plots`) as PNG and SVG.

The configuration (:class:`ReportConfig`, from TOML through :func:`hexaleg.config.from_mapping`)
has the optional tables ``[gait]``, ``[motor]``, ``[contact]``, ``[springs]`` and ``[report]``;
``[view]`` is left to ``hexaleg view``, which reads the same file.

Sources of the models: the springs are the paper's dead-zone springs (eq. 7–8, 14) placed by
:mod:`hexaleg.design.rules` (centred dead zone, θ_k/A of Section 4.2, k_M of eq. 19); the energies
are :func:`hexaleg.dynamics.energy.metrics` (work eq. 20, cost of transport eq. 23, the motor model
of :mod:`hexaleg.robot.motor`); the friction usage ``|f_t| / (μ f_n)`` is the load of the Coulomb
friction cone that the force program (:mod:`hexaleg.dynamics.forces`) keeps ≤ 1; the paper's
single-joint numbers come from :func:`hexaleg.studies.paper.model.reproduce`.
"""

from __future__ import annotations

import functools
import json
import math
import sys
import time
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np
import pinocchio as pin

from hexaleg.config import from_mapping, load_toml
from hexaleg.design import rules as design
from hexaleg.dynamics import energy
from hexaleg.dynamics.forces import OBJECTIVES, ContactParams
from hexaleg.dynamics.prepare import Analysis, Prepared, prepare
from hexaleg.errors import (
    ConfigError,
    HexalegError,
    InfeasibleForcesError,
    InvalidParameterError,
    OutputError,
    TorqueLimitError,
    UnknownNameError,
)
from hexaleg.motion.gait import GaitParams, transform_motion, tripod_gait
from hexaleg.motion.trajectory import Motion
from hexaleg.robot.model import Robot, load_robot
from hexaleg.robot.motor import DEFAULT_MOTOR, Motor, motor_from_mapping
from hexaleg.robot.motor import motor as motor_by_name
from hexaleg.robot.registry import RobotDescription
from hexaleg.robot.springs import SpringSet

TABLES: tuple[str, ...] = ("gait", "motor", "contact", "springs", "report")
"""Tables of a report config file."""
SHARED_TABLES: tuple[str, ...] = ("view",)
"""Tables other commands read from the same config file; the report accepts and ignores them."""
SPRING_DESIGNS: tuple[str, ...] = ("paper", "centred", "none")
"""``[springs] design``: the paper's rule (:func:`hexaleg.design.rules.paper_style_springs`), a
centred dead zone with a given stiffness (:func:`hexaleg.design.rules.centred_springs`), or no
springs."""
CURVE_METRICS: tuple[str, ...] = (*(k for k in energy.ENERGY_KEYS
                                    if k not in energy.NO_SAVING_KEYS),
                                  "electrical_bus", *energy.TORQUE_KEYS)
"""Total metrics a stiffness curve can show (keys of ``metrics["total"]``)."""
ENERGY_TABLE_KEYS: tuple[str, ...] = ("positive_work", "joule", "electrical")
"""Metrics of the per-joint energy table."""
BAR_METRIC = "electrical"
"""Metric of the per-joint bar plot: the energy the servos draw (J)."""
PLOTS: tuple[str, ...] = ("joint_angles", "joint_torques", "joint_power", "foot_forces",
                          "energy_per_joint", "stiffness_curve")
"""Plot names: ``<name>.png`` / ``<name>.svg`` in the output directory."""


def _unit(metric: str) -> str:
    return "N·m" if metric in energy.TORQUE_KEYS else "J"


def _is_number(value: object) -> bool:
    """A finite real number (not a bool)."""
    return (isinstance(value, (int, float, np.integer, np.floating))
            and not isinstance(value, bool) and math.isfinite(value))


def _is_int(value: object) -> bool:
    return isinstance(value, (int, np.integer)) and not isinstance(value, bool)


@dataclass(frozen=True)
class ReportParams:
    """The ``[report]`` table: what the report shows.

    Attributes:
        title: Page title.
        objective: Force-distribution objective (:data:`hexaleg.dynamics.forces.OBJECTIVES`).
        curve_joints: Joint class (or one joint) whose spring stiffness the curve varies.
        curve_metrics: Total metrics on the curve (:data:`CURVE_METRICS`), one line each.
        stiffness_min: Smallest stiffness of the curve, N·m/rad, ≥ 0.
        stiffness_max: Largest stiffness, N·m/rad, > ``stiffness_min``; None: 10 × k_M (eq. 19)
            of the curve's joints.
        stiffness_points: Points of the curve, 2 … 1001.
        paper_samples: Samples per period of the paper's single-joint model, ≥ 8
            (:func:`hexaleg.studies.paper.model.reproduce`).
    """

    title: str = "hexaleg gait energy report"
    objective: str = "joule"
    curve_joints: str = "femur"
    curve_metrics: tuple[str, ...] = ("positive_work", "joule", "electrical")
    stiffness_min: float = 0.0
    stiffness_max: float | None = None
    stiffness_points: int = 41
    paper_samples: int = 1024

    def __post_init__(self) -> None:
        if not (isinstance(self.title, str) and self.title.strip()):
            raise InvalidParameterError("report.title", self.title, "a non-empty string")
        if not isinstance(self.curve_joints, str):
            raise InvalidParameterError("report.curve_joints", self.curve_joints,
                                        "a joint class or joint name")
        for name in ("stiffness_points", "paper_samples"):
            if not _is_int(getattr(self, name)):
                raise InvalidParameterError(f"report.{name}", getattr(self, name), "an integer")
        if not isinstance(self.curve_metrics, (tuple, list)):
            raise InvalidParameterError("report.curve_metrics", self.curve_metrics,
                                        "a list of metric names")
        if self.objective not in OBJECTIVES:
            raise InvalidParameterError("report.objective", self.objective,
                                        "one of " + ", ".join(OBJECTIVES))
        metrics = tuple(self.curve_metrics)
        if not metrics or len(set(metrics)) != len(metrics):
            raise InvalidParameterError("report.curve_metrics", self.curve_metrics,
                                        "a non-empty list of distinct metrics")
        for m in metrics:
            if m not in CURVE_METRICS:
                raise UnknownNameError("report.curve_metrics entry", m, CURVE_METRICS)
        object.__setattr__(self, "curve_metrics", metrics)
        if not (_is_number(self.stiffness_min) and self.stiffness_min >= 0):
            raise InvalidParameterError("report.stiffness_min", self.stiffness_min,
                                        "a finite number ≥ 0 (N·m/rad)")
        if self.stiffness_max is not None and not (_is_number(self.stiffness_max)
                                                   and self.stiffness_max > self.stiffness_min):
            raise InvalidParameterError("report.stiffness_max", self.stiffness_max,
                                        f"None or a finite number > stiffness_min = "
                                        f"{self.stiffness_min} (N·m/rad)")
        if not 2 <= self.stiffness_points <= 1001:
            raise InvalidParameterError("report.stiffness_points", self.stiffness_points,
                                        "an integer in [2, 1001]")
        if self.paper_samples < 8:
            raise InvalidParameterError("report.paper_samples", self.paper_samples,
                                        "an integer ≥ 8")


@dataclass(frozen=True)
class SpringDesign:
    """The ``[springs]`` table when it names a design instead of listing per-joint springs.

    Attributes:
        design: ``"paper"`` (centred dead zone θ_k/A = 0.426, α = 1.05, k_M of eq. 19 per joint:
            :func:`hexaleg.design.rules.paper_style_springs`), ``"centred"`` (centred dead zone with
            the
            given ``stiffness`` and ``dead_zone``, α = 1, eq. 7 convention:
            :func:`hexaleg.design.rules.centred_springs`) or ``"none"``.
        joints: Joint class (``"femur"``) or one joint that gets springs.
        stiffness: ``"centred"`` only (required): k, N·m/rad.
        dead_zone: ``"centred"`` only: θ_k as a fraction of the half range of motion, (0, 1);
            None: the paper's 0.426.
    """

    design: str = "paper"
    joints: str = "femur"
    stiffness: float | None = None
    dead_zone: float | None = None

    def __post_init__(self) -> None:
        if not isinstance(self.joints, str):
            raise InvalidParameterError("springs.joints", self.joints,
                                        "a joint class or joint name")
        if self.design not in SPRING_DESIGNS:
            raise InvalidParameterError("springs.design", self.design,
                                        "one of " + ", ".join(SPRING_DESIGNS))
        if self.design == "centred":
            if not (_is_number(self.stiffness) and self.stiffness >= 0):
                raise InvalidParameterError("springs.stiffness", self.stiffness,
                                            "a finite number ≥ 0 (N·m/rad) for design = centred")
            if self.dead_zone is not None and not (_is_number(self.dead_zone)
                                                   and 0 < self.dead_zone < 1):
                raise InvalidParameterError("springs.dead_zone", self.dead_zone,
                                            "a fraction of the half range of motion in (0, 1)")
        else:
            for name in ("stiffness", "dead_zone"):
                if getattr(self, name) is not None:
                    raise InvalidParameterError(
                        f"springs.{name}", getattr(self, name),
                        f"not set for design = {self.design} (only design = centred takes it; "
                        "the paper design takes k_M of eq. 19 and θ_k/A = 0.426)")

    def springs(self, robot: Robot, motion: Motion) -> SpringSet:
        """The springs of this design for ``motion``.

        Raises:
            UnknownNameError: ``joints`` is neither a joint class nor a joint (lists both).
        """
        if self.design == "none":
            robot.joints(self.joints)  # still reject a misspelt class
            return SpringSet()
        if self.design == "paper":
            return design.paper_style_springs(robot, motion, self.joints)
        dz = design.PAPER_DEAD_ZONE_RATIO if self.dead_zone is None else self.dead_zone
        return design.centred_springs(robot, motion, self.joints, float(self.stiffness),
                                      dead_zone=dz)


def _springs_from_mapping(data: Any, where: str) -> SpringDesign | SpringSet:
    """A ``[springs]`` table: a design (has ``design``) or per-joint tables (SI)."""
    if not isinstance(data, Mapping):
        raise ConfigError(f"{where}: expected a table, got {data!r}")
    if "design" in data:
        return from_mapping(SpringDesign, data, where)
    for key, value in data.items():
        if not isinstance(value, Mapping):  # a design key without design = … , or a typo
            raise UnknownNameError(
                f"key in {where} (give design = ... or per-joint tables [springs.<joint>])",
                key, ("design", "joints", "stiffness", "dead_zone"))
    return SpringSet.from_mapping(data, where)


@dataclass(frozen=True)
class ReportConfig:
    """Everything the report is computed from; the defaults are ``hexaleg report``'s.

    Attributes:
        gait: Gait parameters (``[gait]``).
        motor: The servo of every joint (``[motor]``,
            :func:`hexaleg.robot.motor.motor_from_mapping`).
        contact: Contact settings (``[contact]``).
        springs: A :class:`SpringDesign` (``[springs] design = …``) or explicit per-joint springs
            in SI (``[springs.LF_femur] stiffness = …``, :meth:`SpringSet.from_mapping`).
        report: What the report shows (``[report]``).
        notes: Caveats printed on the report page (set by :meth:`for_robot`; not a TOML table).
    """

    gait: GaitParams = field(default_factory=GaitParams)
    motor: Motor = field(default_factory=lambda: motor_by_name(DEFAULT_MOTOR))
    contact: ContactParams = field(default_factory=ContactParams)
    springs: SpringDesign | SpringSet = field(default_factory=SpringDesign)
    report: ReportParams = field(default_factory=ReportParams)
    notes: tuple[str, ...] = ()

    @classmethod
    def for_robot(cls, desc: RobotDescription, robot: Robot,
                  data: Mapping[str, Any] | None = None, where: str = "config") -> ReportConfig:
        """The configuration for a robot of the registry (:mod:`hexaleg.robot.registry`).

        The description's gait with the keys the file's ``[gait]`` sets on top; springs and the
        stiffness curve on the description's spring class unless the file names joints; the
        robot's title; the robot's own actuator (``desc.motor``) unless the file has a
        ``[motor]``; and for a robot without one whose URDF joint effort limits exceed every
        catalogue servo's stall torque (unless ``[contact]`` sets ``torque_limits``), no torque
        limits and a note that the servo's Joule/electrical figures do not describe its
        actuators.

        Args:
            desc: The robot description.
            robot: The robot it loads (``desc.load()``).
            data: A parsed config document (as for :meth:`from_mapping`), or None.
            where: Where ``data`` came from, for error messages.
        """
        import dataclasses

        from hexaleg.robot.motor import CATALOGUE

        data = data or {}
        config = cls.from_mapping(data, where)
        given = {t: data.get(t, {}) for t in ("gait", "springs", "report", "contact")}
        gait = desc.gait.updated(given["gait"], f"{where} [gait]")
        springs = config.springs
        if isinstance(springs, SpringDesign) and "joints" not in given["springs"]:
            springs = dataclasses.replace(springs, joints=desc.spring_class)
        report = config.report
        if "curve_joints" not in given["report"]:
            report = dataclasses.replace(report, curve_joints=desc.spring_class)
        if "title" not in given["report"]:
            report = dataclasses.replace(report, title=f"{desc.title}: gait energy report")
        contact, notes = config.contact, []
        strongest = max(m.stall_torque for m in CATALOGUE.values())
        effort = float(robot.model.effortLimit[6:].max())
        if desc.motor is not None and "motor" not in data:
            config = dataclasses.replace(config, motor=CATALOGUE[desc.motor])
        elif effort > strongest and "torque_limits" not in given["contact"]:
            contact = dataclasses.replace(contact, torque_limits=False)
            notes.append(f"{desc.title}: URDF joint effort limits up to {effort:g} N·m exceed "
                         f"every servo of the motor catalogue (≤ {strongest:g} N·m), so the "
                         f"torque limits are off; the {config.motor.name} figures (Joule, "
                         "electrical energy) do not describe this robot's actuators — compare "
                         "work and torques, or give a [motor] for them")
        return dataclasses.replace(config, gait=gait, springs=springs, report=report,
                                   contact=contact, notes=tuple(notes))

    @classmethod
    def from_mapping(cls, data: Mapping[str, Any], where: str = "config") -> ReportConfig:
        """The configuration from a parsed TOML document (all tables optional).

        Args:
            data: Table name → table.
            where: Where it came from (the file name), for error messages.

        Raises:
            UnknownNameError: an unknown table or key (the message lists the valid ones).
            ConfigError: a value of the wrong type.
            InvalidParameterError: a value out of range.
        """
        if not isinstance(data, Mapping):
            raise ConfigError(f"{where}: expected a TOML document of tables, got {data!r}")
        for key in data:
            if key not in TABLES + SHARED_TABLES:
                raise UnknownNameError(f"table in {where}", key, TABLES + SHARED_TABLES)
        out: dict[str, Any] = {}
        if "gait" in data:
            out["gait"] = from_mapping(GaitParams, data["gait"], f"{where} [gait]")
        if "motor" in data:
            out["motor"] = motor_from_mapping(data["motor"], f"{where} [motor]")
        if "contact" in data:
            out["contact"] = from_mapping(ContactParams, data["contact"], f"{where} [contact]")
        if "springs" in data:
            out["springs"] = _springs_from_mapping(data["springs"], f"{where} [springs]")
        if "report" in data:
            out["report"] = from_mapping(ReportParams, data["report"], f"{where} [report]")
        return cls(**out)

    @classmethod
    def from_toml(cls, source: str | Path | Mapping[str, Any]) -> ReportConfig:
        """The configuration from a TOML file (or an already parsed document).

        Raises:
            ConfigError: the file cannot be read or parsed, or a value has the wrong type.
            UnknownNameError: an unknown table or key (lists the valid ones).
            InvalidParameterError: a value out of range.
        """
        if isinstance(source, Mapping):
            return cls.from_mapping(source)
        return cls.from_mapping(load_toml(source), str(source))

    def spring_set(self, robot: Robot, motion: Motion) -> SpringSet:
        """The springs for ``motion`` (a design is evaluated on the motion's joint ranges)."""
        if isinstance(self.springs, SpringSet):
            return self.springs
        return self.springs.springs(robot, motion)


# ---- computations ------------------------------------------------------------------------------


def friction_usage(forces: np.ndarray, stance: np.ndarray, mu: float) -> np.ndarray:
    """Load of the Coulomb friction cone ``|f_t| / (μ f_n)`` of every foot (flat ground, z up).

    Args:
        forces: World-frame foot forces, shape (T, n_legs, 3), N.
        stance: Stance flags, shape (T, n_legs), bool.
        mu: Friction coefficient, > 0.

    Returns:
        Shape (T, n_legs), 1: 0 for swing feet and for stance feet without normal force, 1 on
        the cone's surface (the foot is about to slip).
    """
    fn = forces[..., 2]
    ft = np.hypot(forces[..., 0], forces[..., 1])
    out = np.zeros(fn.shape)
    np.divide(ft, mu * fn, out=out, where=stance & (fn > 0))
    return out


@dataclass(frozen=True)
class StiffnessCurve:
    """Total metrics of the gait against the stiffness of one joint class's springs.

    Every joint of the class gets the same stiffness k; dead zones, α and convention are kept.

    Attributes:
        joints: The joints whose stiffness varies.
        stiffness: k, shape (K,), N·m/rad.
        totals: Metric → total over the cycle at each k, shape (K,), J or N·m; NaN where the
            forces were infeasible (see ``errors``).
        baseline: Metric → the same total without any springs (J or N·m).
        errors: Per point, None or the message of the infeasibility / torque-limit error.
        k_M: Per joint, the eq. 19 stiffness for that joint's spring convention, N·m/rad.
    """

    joints: tuple[str, ...]
    stiffness: np.ndarray
    totals: dict[str, np.ndarray]
    baseline: dict[str, float]
    errors: tuple[str | None, ...]
    k_M: dict[str, float]

    @property
    def feasible(self) -> np.ndarray:
        """Points whose forces were feasible, shape (K,), bool."""
        return np.array([e is None for e in self.errors])

    def savings(self, metric: str) -> np.ndarray:
        """Fraction of ``metric`` saved against no springs at each k, shape (K,), 1 (NaN where
        infeasible; 0 where the baseline is 0)."""
        base = self.baseline[metric]
        return (base - self.totals[metric]) / base if base else np.zeros_like(self.stiffness)

    def best(self, metric: str) -> int | None:
        """Index of the feasible point with the smallest ``metric``; None if none is feasible."""
        ok = self.feasible
        if not ok.any():
            return None
        return int(np.flatnonzero(ok)[np.argmin(self.totals[metric][ok])])


def curve_springs(robot: Robot, motion: Motion, springs: SpringSet, spec: str) -> SpringSet:
    """The springs a stiffness curve varies: ``springs`` plus, on every joint of ``spec`` that has
    none, the paper's centred design (θ_k/A = 0.426, α = 1.05, eq. 14; stiffness set later)."""
    out = dict(springs)
    for j in robot.joints(spec):
        if j not in out:
            out[j] = design.centred_spring(robot, motion, j, 0.0, alpha=design.PAPER_ALPHA,
                                           convention="eq14")
    return SpringSet(out)


def stiffness_curve(prepared: Prepared, springs: SpringSet, spec: str, stiffness: np.ndarray,
                    metrics: tuple[str, ...], objective: str = "joule",
                    progress: Callable[[str], None] | None = None) -> StiffnessCurve:
    """Evaluate the gait with the springs of ``spec`` at each stiffness (one ``prepare``, many
    ``evaluate``).

    Args:
        prepared: :func:`hexaleg.dynamics.prepare.prepare` of the gait.
        springs: The springs (from :func:`curve_springs`: every joint of ``spec`` has one).
        spec: Joint class or joint whose stiffness varies.
        stiffness: k, shape (K,), N·m/rad, each ≥ 0.
        metrics: Total metrics to record (:data:`CURVE_METRICS`).
        objective: Force-distribution objective.
        progress: Called with a status line every 10 points.

    Returns:
        The curve.

    Raises:
        UnknownNameError: ``spec`` or a metric is unknown, or a joint of ``spec`` has no spring.
    """
    robot, motion = prepared.robot, prepared.motion
    joints = robot.joints(spec)
    for m in metrics:
        if m not in CURVE_METRICS:
            raise UnknownNameError("curve metric", m, CURVE_METRICS)
    ks = np.asarray(stiffness, dtype=float)
    totals = {m: np.empty(ks.size) for m in metrics}
    errors: list[str | None] = []
    for i, k in enumerate(ks):
        trial = SpringSet({**springs, **{j: springs[j].with_stiffness(float(k)) for j in joints}})
        try:
            total = prepared.evaluate(trial, objective).metrics["total"]
        except (InfeasibleForcesError, TorqueLimitError) as e:  # recorded, not hidden
            errors.append(str(e))
            for m in metrics:
                totals[m][i] = np.nan
        else:
            errors.append(None)
            for m in metrics:
                totals[m][i] = total[m]
        if progress and ((i + 1) % 10 == 0 or i + 1 == ks.size):
            progress(f"stiffness curve {i + 1}/{ks.size}")
    base = prepared.baseline(objective)["total"]
    k_m = {j: design.k_M(robot, motion, j, alpha=springs[j].transmission) for j in joints}
    return StiffnessCurve(joints=joints, stiffness=ks, totals=totals,
                          baseline={m: base[m] for m in metrics}, errors=tuple(errors), k_M=k_m)


@functools.lru_cache(maxsize=4)
def _paper_reproduction(n: int) -> str:
    """:func:`hexaleg.studies.paper.model.reproduce` as JSON text, cached (it takes seconds and is
    constant)."""
    from hexaleg.studies.paper import (
        model as paper,  # scipy.optimize: imported only when the report is made
    )

    return json.dumps(paper.reproduce(n=n))


def paper_reference(n: int = 1024) -> dict[str, Any]:
    """The paper's single-joint numbers (Table 6 lever, eq. 25) for the report, with units.

    Taken from :func:`hexaleg.studies.paper.model.reproduce` (not recomputed): eq. 19 k_M as
    printed and in
    SI, the closed-form no-gravity optima and peak-torque saving, the numerically optimal
    stiffness and saving per metric without gravity, and the verdicts on the printed k_E and
    52.81 % saving.

    Args:
        n: Samples per period of the single-joint model.
    """
    r = json.loads(_paper_reproduction(n))
    m, cf = r["model"], r["closed_forms_no_gravity"]
    k_unit = "N·m/rad"
    return {
        "model": {"amplitude": {"value": m["amplitude_rad"], "unit": "rad"},
                  "omega": {"value": m["omega_rad_per_s"], "unit": "rad/s"},
                  "theta_k": {"value": m["theta_k_rad"], "unit": "rad"},
                  "alpha": {"value": m["alpha"], "unit": "1"},
                  "J": {"value": m["J_axis_kg_m2"], "unit": "kg·m²"},
                  "convention": m["convention"]},
        "k_M_printed": {"value": r["k_M_paper_printed"], "unit": "paper eq. 19 number"},
        "k_M_paper_number": {"value": r["k_M_paper_units"], "unit": "paper eq. 19 number"},
        "k_M_paper_units_are": r["k_M_paper_units_are"],
        "k_M": {"value": r["k_M_SI_Nm_per_rad"], "unit": k_unit},
        "peak_flat_interval": {"value": cf["peak_flat_interval_N_m_per_rad"], "unit": k_unit},
        "peak_saving": {"value": cf["peak_saving_percent"], "unit": "%"},
        "closed_form_optima": {
            key: {"value": cf[key]["N_m_per_rad"], "unit": k_unit}
            for key in ("int_sq", "mean_abs", "positive_and_absolute_work")},
        "optima_no_gravity": {
            key: {"stiffness": {"value": o["k_N_m_per_rad"], "unit": k_unit},
                  "saving": {"value": o["saving_percent"], "unit": "%"}}
            for key, o in r["optima"]["no_gravity"].items()},
        "k_E_printed": {"value": r["k_E"]["paper_printed"], "unit": "paper eq. 19 number"},
        "k_E_verdict": r["k_E"]["verdict"],
        "saving_printed": {"value": r["saving_52_81"]["paper_printed_percent"], "unit": "%"},
        "saving_verdict": r["saving_52_81"]["verdict"],
        "samples": n,
    }


@dataclass(frozen=True, eq=False)
class Report:
    """A computed report: the analyses it was made from and its JSON content.

    Attributes:
        config: The configuration.
        robot: The robot.
        motion: The gait.
        analysis: The gait with the springs.
        rigid: The gait without springs (same objective).
        curve: The stiffness curve.
        usage: Friction usage of ``analysis``'s forces, shape (T, n_legs), 1.
        data: Every number of the report with its unit (the content of ``report.json``).
        files: Files written by :func:`write_report` (empty from :func:`build_report`).
    """

    config: ReportConfig
    robot: Robot
    motion: Motion
    analysis: Analysis
    rigid: Analysis
    curve: StiffnessCurve
    usage: np.ndarray
    data: dict[str, Any]
    files: tuple[Path, ...] = ()


def _stderr_progress(message: str) -> None:
    print(f"hexaleg report: {message}", file=sys.stderr, flush=True)


def _q(value: Any, unit: str) -> dict[str, Any]:
    """A quantity ``{"value", "unit"}``; arrays become lists, non-finite numbers None."""
    v = np.asarray(value, dtype=float)
    if v.ndim == 0:
        return {"value": float(v) if math.isfinite(v) else None, "unit": unit}
    return {"value": [float(x) if math.isfinite(x) else None for x in v.ravel()], "unit": unit}


def _comparison(with_: float, without: float, saving: float, unit: str) -> dict[str, Any]:
    return {"with_springs": _q(with_, unit), "without_springs": _q(without, unit),
            "saving": _q(100 * saving, "%")}


def _report_data(cfg: ReportConfig, robot: Robot, motion: Motion, a: Analysis, rigid: Analysis,
                 curve: StiffnessCurve, usage: np.ndarray) -> dict[str, Any]:
    import hexaleg

    rp, info, g = cfg.report, motion.info, cfg.gait
    names = robot.joint_names
    springs = a.springs
    cols = springs.columns(robot)
    met, base, sav = a.metrics, a.baseline, a.savings
    stance = motion.stance.astype(bool)
    joints = {}
    for j, name in enumerate(names):
        joints[name] = {
            "angle_min": _q(a.q[:, j].min(), "rad"), "angle_max": _q(a.q[:, j].max(), "rad"),
            "peak_motor_torque": _q(np.abs(a.tau_motor[:, j]).max(), "N·m"),
            "peak_motor_torque_no_springs": _q(np.abs(rigid.tau_motor[:, j]).max(), "N·m"),
            "peak_spring_torque": _q(np.abs(a.tau_spring[:, j]).max(), "N·m"),
            "peak_power": _q(np.abs(a.power[:, j]).max(), "W"),
            "peak_power_no_springs": _q(np.abs(rigid.power[:, j]).max(), "W"),
            "peak_spring_energy": _q(a.spring_energy[:, j].max(), "J"),
        }
    spring_rows = {}
    for name, s in springs.items():
        k_m = design.k_M(robot, motion, name, alpha=s.transmission)
        angle = a.q[:, cols[name]]
        spring_rows[name] = {
            "stiffness": _q(s.stiffness, "N·m/rad"), "k_M": _q(k_m, "N·m/rad"),
            "stiffness_over_k_M": _q(s.stiffness / k_m, "1"),
            "neutral": _q(s.neutral, "rad"), "theta_minus": _q(s.th_minus, "rad"),
            "theta_plus": _q(s.th_plus, "rad"), "alpha": _q(s.alpha, "1"),
            "convention": s.convention,
            "engaged_fraction": _q(float(s.engaged(angle).mean()), "1")}
    legs = {}
    for i, leg in enumerate(robot.leg_names):
        fn = a.forces[:, i, 2]
        legs[leg] = {"stance_fraction": _q(stance[:, i].mean(), "1"),
                     "peak_normal_force": _q(fn.max(), "N"),
                     "mean_normal_force_in_stance": _q(fn[stance[:, i]].mean()
                                                       if stance[:, i].any() else 0.0, "N"),
                     "peak_friction_usage": _q(usage[:, i].max(), "1")}
    energy_totals = {k: _comparison(met["total"][k], base["total"][k], sav["total"][k], _unit(k))
                     for k in sav["total"]}
    per_joint = {k: {name: _comparison(met["joint"][k][j], base["joint"][k][j],
                                       sav["joint"][k][j], _unit(k))
                     for j, name in enumerate(names)} for k in sav["joint"]}
    net = {"with_springs": _q(met["total"]["net_work"], "J"),
           "without_springs": _q(base["total"]["net_work"], "J")}
    cot = ({k: _comparison(met["cost_of_transport"][k], base["cost_of_transport"][k],
                           sav["cost_of_transport"][k], "1")
            for k in met["cost_of_transport"]} if "cost_of_transport" in met else {})
    k_M_mean = float(np.mean(list(curve.k_M.values())))
    curve_metrics = {}
    for m in curve.totals:
        best = curve.best(m)
        curve_metrics[m] = {
            "values": _q(curve.totals[m], _unit(m)), "baseline": _q(curve.baseline[m], _unit(m)),
            "saving": _q(100 * curve.savings(m), "%"),
            "best": None if best is None else {
                "stiffness": _q(curve.stiffness[best], "N·m/rad"),
                "stiffness_over_k_M": _q(curve.stiffness[best] / k_M_mean, "1"),
                "value": _q(curve.totals[m][best], _unit(m)),
                "saving": _q(100 * curve.savings(m)[best], "%")}}
    notes = list(cfg.notes)
    sway = info.get("balance", {})
    if sway.get("mode") == "sway":
        notes.append(f"two-foot gait: the body sways ±{1e3 * sway['amplitude']:.2f} mm so that the "
                     "two stance feet can carry it (no moment about the support line; "
                     f"{sway['iterations']} iterations, residual {sway['residual']:.1e} m g h)")
    return {
        "title": rp.title,
        "hexaleg_version": hexaleg.__version__,
        "notes": notes,
        "robot": {"name": robot.name, "mass": _q(robot.mass, "kg"), "joints": robot.nj,
                  "legs": list(robot.leg_names), "joint_names": list(names),
                  "joint_classes": {k: list(v) for k, v in robot.joint_classes.items()}},
        "gait": {"period": _q(motion.period, "s"), "duty_factor": _q(g.duty_factor, "1"),
                 "stride_length": _q(info["stride_length"], "m"),
                 "speed": _q(info["speed"], "m/s"), "step_height": _q(g.step_height, "m"),
                 "body_height": _q(info["body_height"], "m"),
                 "foot_radius": _q(info["foot_radius"], "m"), "yaw_rate": _q(g.yaw_rate, "rad/s"),
                 "samples": motion.n_samples, "groups": [list(x) for x in g.groups],
                 "min_stance_feet": int(info["min_stance_feet"]),
                 "static_margin": (_q(info["static_margin"], "m")
                                   if info["static_margin"] is not None else None)},
        "motor": {"name": cfg.motor.name,
                  "joule_coefficient": _q(cfg.motor.joule_coefficient, "W/(N·m)²"),
                  "stall_torque": _q(cfg.motor.stall_torque, "N·m"),
                  "gearbox_efficiency": _q(cfg.motor.gearbox_efficiency, "1"),
                  "regeneration": cfg.motor.regeneration, "source": cfg.motor.source},
        "contact": {"mu": _q(cfg.contact.mu, "1"), "cone": cfg.contact.cone,
                    "min_normal_force": _q(cfg.contact.min_normal_force, "N"),
                    "torque_limits": cfg.contact.torque_limits},
        "objective": rp.objective,
        "springs": {"design": (cfg.springs.design if isinstance(cfg.springs, SpringDesign)
                               else "explicit"), "joints": spring_rows},
        "joints": joints,
        "forces": {"legs": legs, "peak_friction_usage": _q(usage.max(), "1"),
                   "weight": _q(robot.mass * float(np.linalg.norm(robot.model.gravity.linear)),
                                "N"),
                   "peak_total_normal_force": _q(a.forces[..., 2].sum(1).max(), "N"),
                   "resolved_samples": int(a.resolved.sum())},
        "energy": {"totals": energy_totals, "net_work": net, "joints": per_joint,
                   "table_keys": list(ENERGY_TABLE_KEYS)},
        "cost_of_transport": {"distance": _q(motion.distance, "m"), "metrics": cot},
        "stiffness_curve": {
            "spec": rp.curve_joints, "joints": list(curve.joints),
            "stiffness": _q(curve.stiffness, "N·m/rad"), "k_M": _q(k_M_mean, "N·m/rad"),
            "k_M_per_joint": {j: _q(k, "N·m/rad") for j, k in curve.k_M.items()},
            "metrics": curve_metrics,
            "infeasible": [{"stiffness": _q(k, "N·m/rad"), "error": e}
                           for k, e in zip(curve.stiffness, curve.errors, strict=True) if e]},
    }


def transform_section(robot: Robot, cfg: ReportConfig, springs: SpringSet,
                      objective: str) -> dict[str, Any] | None:
    """The energy of folding from ``stand`` into ``sphere``, with the gait's springs and without.

    The motion is :func:`hexaleg.motion.gait.transform_motion` at its defaults (sit down on the
    feet,
    then fold with the body on the ground), analysed with the report's motor, contact settings
    and objective. Its joints' net work is the rise of the robot's potential energy m g Δz_com
    (at rest at both ends; the ground under the body does no work), reported alongside.

    Returns:
        The section's numbers; ``{"error": …}`` when the springs make it infeasible (e.g. a
        torque limit while folding); None for a robot without both poses.
    """
    if not {"stand", "sphere"} <= set(robot.poses):
        return None
    motion = transform_motion(robot)
    try:
        a = prepare(robot, motion, motor=cfg.motor, contact=cfg.contact).evaluate(springs,
                                                                                  objective)
    except HexalegError as e:
        return {"error": str(e)}
    data = robot.model.createData()
    z0, z1 = (pin.centerOfMass(robot.model, data, motion.q[k])[2] for k in (0, -1))
    g = float(np.linalg.norm(robot.model.gravity.linear))
    met, base, sav = a.metrics["total"], a.baseline["total"], a.savings["total"]
    info = motion.info
    return {
        "duration": _q(motion.period, "s"), "sit_time": _q(info["sit_time"], "s"),
        "stand_height": _q(info["stand_height"], "m"), "rest_height": _q(info["rest_height"], "m"),
        "potential_energy_rise": _q(robot.mass * g * (z1 - z0), "J"),
        "net_work": {"with_springs": _q(met["net_work"], "J"),
                     "without_springs": _q(base["net_work"], "J")},
        "totals": {k: _comparison(met[k], base[k], sav[k], _unit(k)) for k in sav},
    }


def build_report(config: ReportConfig | None = None, *, robot: Robot | None = None,
                 progress: Callable[[str], None] | None = None) -> Report:
    """Compute the report: gait, analysis with and without springs, stiffness curve, paper.

    Args:
        config: The configuration (default :class:`ReportConfig`: built-in robot, default tripod
            gait, default motor, paper-style femur springs).
        robot: The robot (default :func:`hexaleg.robot.model.load_robot`).
        progress: Called with one status line per step (e.g. print to stderr).

    Returns:
        The report (``files`` empty).

    Raises:
        HexalegError: from the gait, the springs or the analysis (unreachable foot targets,
            unknown joints, infeasible forces at the configured springs, …).
    """
    cfg = config or ReportConfig()
    say = progress or (lambda _msg: None)
    t0 = time.perf_counter()

    def step(msg: str) -> None:
        say(f"{msg} ({time.perf_counter() - t0:.1f} s)")

    robot = robot or load_robot()
    step(f"robot {robot.name}: {robot.nj} joints, {robot.mass:.3f} kg")
    motion = tripod_gait(robot, cfg.gait)
    step(f"gait: {motion.n_samples} samples over {motion.period:g} s")
    prepared = prepare(robot, motion, motor=cfg.motor, contact=cfg.contact)
    step("dynamics prepared (RNEA, Jacobians, force program)")
    springs = cfg.spring_set(robot, motion)
    objective = cfg.report.objective
    analysis = prepared.evaluate(springs, objective)
    rigid = prepared.evaluate(None, objective)
    step(f"analysed with {len(springs)} springs and without")
    base = curve_springs(robot, motion, springs, cfg.report.curve_joints)
    joints = robot.joints(cfg.report.curve_joints)
    k_hi = cfg.report.stiffness_max
    if k_hi is None:
        k_hi = 10 * float(np.mean([design.k_M(robot, motion, j, alpha=base[j].transmission)
                                   for j in joints]))
    ks = np.linspace(cfg.report.stiffness_min, k_hi, cfg.report.stiffness_points)
    curve = stiffness_curve(prepared, base, cfg.report.curve_joints, ks,
                            cfg.report.curve_metrics, objective, step)
    usage = friction_usage(analysis.forces, motion.stance.astype(bool), cfg.contact.mu)
    data = _report_data(cfg, robot, motion, analysis, rigid, curve, usage)
    data["transform"] = transform_section(robot, cfg, springs, objective)
    if data["transform"] is not None:
        step("stand → sphere transformation analysed")
    step("paper's single-joint reference (hexaleg.studies.paper.model.reproduce)")
    data["paper"] = paper_reference(cfg.report.paper_samples)
    step("numbers collected")
    return Report(config=cfg, robot=robot, motion=motion, analysis=analysis, rigid=rigid,
                  curve=curve, usage=usage, data=data)


def _figures(r: Report) -> dict[str, Any]:
    """The report's figures by name (:data:`PLOTS`)."""
    from hexaleg.outputs import plots  # matplotlib: imported only when the report is written

    a, robot, curve, key = r.analysis, r.robot, r.curve, BAR_METRIC
    zones = {j: (s.neutral + s.th_minus, s.neutral + s.th_plus) for j, s in a.springs.items()}
    return {
        "joint_angles": plots.joint_angles(robot, a.t, a.q, zones),
        "joint_torques": plots.joint_torques(robot, a.t, a.tau_motor, a.tau_spring,
                                             r.rigid.tau_motor),
        "joint_power": plots.joint_power(robot, a.t, a.power, r.rigid.power),
        "foot_forces": plots.foot_forces(robot.leg_names, a.t, a.forces,
                                         r.motion.stance.astype(bool), r.usage),
        "energy_per_joint": plots.energy_bars(robot.joint_names, a.metrics["joint"][key],
                                              a.baseline["joint"][key], key, "J"),
        "stiffness_curve": plots.stiffness_curve(
            curve.stiffness, {m: 100 * curve.savings(m) for m in curve.totals},
            r.data["stiffness_curve"]["k_M"]["value"], r.config.report.curve_joints),
    }


def render_html(data: Mapping[str, Any], images: Mapping[str, str]) -> str:
    """Render ``templates/report.html.j2`` with the report's numbers and embedded images.

    Args:
        data: The report's JSON content (:attr:`Report.data`).
        images: Plot name → ``data:`` URI.

    Returns:
        The HTML page (self-contained).
    """
    import jinja2

    env = jinja2.Environment(loader=jinja2.PackageLoader("hexaleg.outputs", "templates"),
                             autoescape=jinja2.select_autoescape(("html", "j2")),
                             undefined=jinja2.StrictUndefined, trim_blocks=True,
                             lstrip_blocks=True)
    env.filters["num"] = _format_number
    env.filters["q"] = _format_quantity
    return env.get_template("report.html.j2").render(d=data, images=images)


def _format_quantity(q: Mapping[str, Any] | None) -> str:
    """``{"value", "unit"}`` as text; dimensionless (unit ``"1"``) values without a unit."""
    if q is None or q["value"] is None:
        return "—"
    unit = "" if q["unit"] == "1" else q["unit"]
    return f"{_format_number(q['value'])} {unit}".rstrip()


def _format_number(x: Any) -> str:
    """Four significant digits; ``—`` for a missing value."""
    if x is None:
        return "—"
    if isinstance(x, bool) or not _is_number(x):
        return str(x)
    return f"{x:.4g}"


def write_report(out: str | Path = "hexaleg-report", config: ReportConfig | None = None, *,
                 robot: Robot | None = None, svg: bool = False,
                 progress: Callable[[str], None] | None = _stderr_progress) -> Report:
    """Compute the report and write ``report.html``, ``report.json`` and the plots into ``out``.

    Args:
        out: Output directory (created with its parents if missing).
        config: The configuration (default :class:`ReportConfig`).
        robot: The robot (default the built-in one).
        svg: Also write every plot as SVG (doubles the plotting time).
        progress: Called with one status line per step (default: print to stderr); None: quiet.

    Returns:
        The report, with ``files`` the files written.

    Raises:
        OutputError: ``out`` cannot be created or written (checked before computing; names it).
        HexalegError: from the computation (see :func:`build_report`).
    """
    out = Path(out)
    try:
        out.mkdir(parents=True, exist_ok=True)
        probe = out / ".hexaleg-write-test"
        probe.write_bytes(b"")
        probe.unlink()
    except OSError as e:
        raise OutputError(f"cannot write the report to the directory {out}: {e}") from e
    from hexaleg.outputs import plots

    r = build_report(config, robot=robot, progress=progress)
    say = progress or (lambda _msg: None)
    files: list[Path] = []
    images = {}
    for name, fig in _figures(r).items():
        png, written = plots.save(fig, out / f"{name}.png", svg=svg)
        images[name] = plots.data_uri(png)
        files += written
        say(f"plot {name}")
    data = {**r.data, "files": [*sorted(p.name for p in files), "report.html", "report.json"]}
    html = render_html(data, images)
    for path, text in ((out / "report.json", json.dumps(data, indent=1, ensure_ascii=False)),
                       (out / "report.html", html)):
        try:
            path.write_text(text, encoding="utf-8")
        except OSError as e:
            raise OutputError(f"cannot write {path}: {e}") from e
        files.append(path)
    say(f"wrote {out / 'report.html'}")
    return Report(config=r.config, robot=r.robot, motion=r.motion, analysis=r.analysis,
                  rigid=r.rigid, curve=r.curve, usage=r.usage, data=data, files=tuple(files))
