"""The checked inputs of a spring design: what does not change while the geometry is searched.

:class:`DesignSetup` holds the prepared gait, the family, the groups, each joint's range of
motion and the design limits of :func:`hexaleg.design.search.optimal.optimal_springs`, builds the
design program of a geometry (:class:`hexaleg.design.search.program.DesignProblem`: the basis B and
the design rows ``G x ≤ h`` of the codesign module docstring) and solves it: the force objective's
own program (:func:`hexaleg.design.search.program.solve_design`, or the cvxpy reference for the
non-quadratic objectives), or — for another metric of the Joule-optimal forces, or the worst
case over stop shifts — the condensed program
(:func:`hexaleg.design.search.condensed.solve_condensed`). Both :mod:`hexaleg.design.search.optimal`
and :mod:`hexaleg.design.search.geometry` import it.
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass
from typing import cast

import numpy as np

from hexaleg.checks import real
from hexaleg.design import families
from hexaleg.design.families import Family, Geometry
from hexaleg.design.search.condensed import Condensed, solve_condensed
from hexaleg.design.search.program import ENGAGED, DesignProblem, DesignSolution, solve_design
from hexaleg.dynamics.contact import QUADRATIC_OBJECTIVES, check_objective
from hexaleg.dynamics.prepare import Prepared
from hexaleg.errors import (
    InfeasibleForcesError,
    InvalidParameterError,
    TorqueLimitError,
    UnknownNameError,
)
from hexaleg.robot.springs import Term, basis

METRICS: tuple[str, ...] = ("joule", "electrical")
"""Metrics of the Joule-optimal forces the magnitudes may minimise (``metric``)."""

Groups = Mapping[str, Sequence[str] | str] | Sequence[str]
Shift = Mapping[str, float]
"""Group → angle added to every angle of its geometry, rad (a stop mounted off)."""


def resolve_groups(prepared: Prepared, groups: Groups) -> dict[str, tuple[str, ...]]:
    """Group name → joints, from ``{name: [joints] or a joint spec}`` or a list of joint specs.

    Raises:
        InvalidParameterError: no group, an empty group, a joint in two groups.
        UnknownNameError: an unknown joint or class (lists them).
    """
    robot = prepared.robot
    if isinstance(groups, str) or not isinstance(groups, (Mapping, Sequence)):
        raise InvalidParameterError("groups", groups, "{name: [joints]} or a list of joint "
                                    "classes/joints")
    items = groups.items() if isinstance(groups, Mapping) else ((g, g) for g in groups)
    out: dict[str, tuple[str, ...]] = {}
    owner: dict[str, str] = {}
    for name, spec in items:
        joints = tuple(robot.joints(spec)) if isinstance(spec, str) else tuple(spec)
        if not joints:
            raise InvalidParameterError(f"group {name}", list(joints), "at least one joint")
        for j in joints:
            robot.column(j)  # UnknownNameError listing the joints
            if j in owner:
                raise InvalidParameterError(f"joint {j}", f"in groups {owner[j]} and {name}",
                                            "each joint in one group")
            owner[j] = name
        out[str(name)] = joints
    if not out:
        raise InvalidParameterError("groups", groups, "at least one group")
    return out


def motion_centres(prepared: Prepared, joints: Sequence[str]) -> dict[str, float]:
    """Joint → the centre of its range of motion in the gait, rad (the origin of a design's
    angles)."""
    q = {j: prepared.q[:, prepared.robot.column(j)] for j in joints}
    return {j: float(v.min() + v.max()) / 2 for j, v in q.items()}


def shifted(fam: Family, geometry: Mapping[str, Geometry], shift: Shift
            ) -> dict[str, dict[str, float | str]]:
    """``geometry`` with every angle of each group moved by its shift (rad; groups not in
    ``shift`` unmoved): the springs as mounted with a stop off by that angle."""
    return {g: {k: (float(v) + float(shift.get(g, 0.0)) if k in fam.angles else v)
                for k, v in geo.items()} for g, geo in geometry.items()}


@dataclass(frozen=True, eq=False)
class _Block:
    """One group's part of a design program: its joints' basis, shape (T, joints, magnitudes),
    and its design rows on the group's magnitudes (row, right-hand side, label)."""

    B: np.ndarray
    rows: list[np.ndarray]
    h: list[float]
    labels: list[str]


@dataclass(frozen=True, eq=False)
class DesignSetup:
    """What does not change while the geometry is searched (module docstring).

    Attributes:
        prepared: The prepared gait. objective: The force program's objective.
        fam: The spring family. groups: Group → joints.
        centre, q_min, q_max: Joint → centre, lowest and highest angle of its motion, rad.
        max_torque: N·m or None. max_deflection: rad or None.
        metric: None: the objective's own program; ``"joule"`` / ``"electrical"`` (objective
            joule): that metric of the Joule-optimal forces, by the condensed program.
        shifts: Stop shifts (group → rad) whose worst case the magnitudes minimise; empty: the
            geometry as given.
        mirrored: Joints that count their angle the other way round from their group's design
            (:mod:`hexaleg.robot.mirror`): each gets the group's spring mirrored,
            ``τ(q) = −τ_design(2c − q)`` (:meth:`~hexaleg.design.families.Family.mirror`).
    """

    prepared: Prepared
    objective: str
    fam: Family
    groups: dict[str, tuple[str, ...]]
    centre: dict[str, float]
    q_min: dict[str, float]
    q_max: dict[str, float]
    max_torque: float | None
    max_deflection: float | None
    metric: str | None = None
    shifts: tuple[Shift, ...] = ()
    mirrored: frozenset[str] = frozenset()

    @property
    def condensed(self) -> bool:
        """Whether :meth:`solve` takes the condensed program."""
        return self.metric is not None or bool(self.shifts)

    def check_geometry(self, geometry: Mapping[str, Geometry]
                       ) -> dict[str, dict[str, float | str]]:
        """Every group's geometry checked by its family; no geometry for an unknown group.

        Raises:
            UnknownNameError: a group that does not exist (lists the groups), or a geometry
                parameter the family does not have.
            InvalidParameterError: a group without its angles, angles out of order.
        """
        unknown = [g for g in geometry if g not in self.groups]
        if unknown:
            raise UnknownNameError("geometry group", unknown[0], tuple(self.groups))
        missing = [g for g in self.groups if g not in geometry and self.fam.angles]
        if missing:
            raise InvalidParameterError(f"geometry of group {missing[0]}", None,
                                        f"the angles {', '.join(self.fam.angles)} (rad)")
        return {g: self.fam.check(geometry.get(g, {}), f"geometry[{g}]") for g in self.groups}

    def half_range(self, group: str) -> float:
        return max((self.q_max[j] - self.q_min[j]) / 2 for j in self.groups[group])

    def relative(self, group: str) -> np.ndarray:
        """Every sample's angle of the group's joints from their centre of motion, rad, shape
        (T, joints); a mirrored joint's reflected (its spring is the design's law at
        ``2c − q``, :meth:`problem`): the angle the design's stops are placed on."""
        p = self.prepared
        return np.stack([(p.q[:, p.robot.column(j)] - self.centre[j])
                         * (-1.0 if j in self.mirrored else 1.0) for j in self.groups[group]],
                        axis=1)

    def problem(self, geometry: Mapping[str, Geometry],
                blocks: dict[tuple[object, ...], _Block] | None = None) -> DesignProblem:
        """The design program of ``geometry`` (group → geometry); ``blocks``: each group's part
        kept by its geometry across calls (:meth:`problems`: the stop shifts repeat a group's
        geometry)."""
        p, fam = self.prepared, self.fam
        nm = len(fam.magnitudes)
        joints = [j for js in self.groups.values() for j in js]
        cols = np.array([p.robot.column(j) for j in joints])
        B = np.zeros((p.motion.n_samples, len(joints), nm * len(self.groups)))
        rows: list[np.ndarray] = []
        h: list[float] = []
        labels: list[str] = []
        i = 0
        for g_index, (g, js) in enumerate(self.groups.items()):
            key = (g, tuple(sorted(geometry[g].items())))
            if blocks is None or key not in blocks:
                block = self._block(g, geometry[g])
                if blocks is not None:
                    blocks[key] = block
            else:
                block = blocks[key]
            sl = slice(g_index * nm, (g_index + 1) * nm)
            B[:, i:i + len(js), sl] = block.B
            for row, rhs, label in zip(block.rows, block.h, block.labels, strict=True):
                full = np.zeros(B.shape[2])
                full[sl] = row
                rows.append(full)
                h.append(rhs)
                labels.append(label)
            i += len(js)
        G = np.array(rows) if rows else np.zeros((0, B.shape[2]))
        return DesignProblem(p, self.objective, cols, B, np.tile(fam.nonnegative(), len(
            self.groups)), G, np.array(h), tuple(labels))

    def _block(self, group: str, geometry: Geometry) -> _Block:
        """One group's part of :meth:`problem`: its joints' basis and its design rows."""
        p, fam = self.prepared, self.fam
        nm = len(fam.magnitudes)
        js = self.groups[group]
        B = np.zeros((p.motion.n_samples, len(js), nm))
        rows: list[np.ndarray] = []
        h: list[float] = []
        labels: list[str] = []
        engaged = np.zeros(nm, dtype=bool)
        for i, j in enumerate(js):
            terms = fam.terms(geometry, self.centre[j])
            q = p.q[:, p.robot.column(j)]
            if j in self.mirrored:  # the design's law reflected about the centre of motion
                B[:, i] = -basis(terms, 2.0 * self.centre[j] - q)
            else:
                B[:, i] = basis(terms, q)
            engaged |= np.any(np.abs(B[:, i]) > ENGAGED, axis=0)
            for row, rhs, label in self._rows(terms, j):
                rows.append(row)
                h.append(rhs)
                labels.append(label)
        for m in np.flatnonzero(~engaged):  # a term that never acts over the gait: x = 0
            row = np.zeros(nm)
            row[m] = 1.0
            rows.append(row)
            h.append(0.0)
            labels.append("never engaged")
        return _Block(B, rows, h, labels)

    def _rows(self, terms: tuple[Term, ...], joint: str) -> list[tuple[np.ndarray, float, str]]:
        """Design rows ``row · x_group ≤ rhs`` on one joint (codesign module docstring)."""
        out = []
        lo, hi = self.q_min[joint], self.q_max[joint]
        if self.max_torque is not None:
            out.append((basis(terms, lo), self.max_torque, "max_torque"))
            out.append((-basis(terms, hi), self.max_torque, "max_torque"))
        if self.max_deflection is not None:
            d = self.max_deflection
            for e in self.fam.elements:
                if e.linear:  # |τ₀ − k (q − q_r)| ≤ k Δ at both ends of the motion
                    for q in (lo, hi):
                        r = terms[e.stiffness].angle
                        for s in (1.0, -1.0):
                            row = np.zeros(len(terms))
                            row[e.stiffness] = -s * (q - r) - d
                            row[cast(int, e.preload)] = s  # the linear law's constant
                            out.append((row, 0.0, "max_deflection"))
                    continue
                term = terms[e.stiffness]
                q = hi if term.kind == "above" else lo
                row = np.zeros(len(terms))
                row[e.stiffness] = abs(float(term.torque(np.array(q)))) - d
                if e.preload is not None:
                    row[e.preload] = abs(float(terms[e.preload].torque(np.array(q))))
                out.append((row, 0.0, "max_deflection"))
        return out

    def problems(self, geometry: Mapping[str, Geometry]) -> list[DesignProblem]:
        """The design program of every stop shift of ``geometry`` (just ``geometry``'s own
        without shifts)."""
        if not self.shifts:
            return [self.problem(geometry)]
        blocks: dict[tuple[object, ...], _Block] = {}
        return [self.problem(shifted(self.fam, geometry, s), blocks) for s in self.shifts]

    def _start(self, problems: Sequence[DesignProblem]) -> np.ndarray | None:
        """Where the condensed program's bundle method starts: the Joule-optimal magnitudes of
        the unshifted geometry (:func:`~hexaleg.design.search.program.solve_design`, the fast exact
        path, milliseconds) when the metric is electrical or there are stop shifts; else None
        (the baseline, x = 0). The program is convex, so the start changes its cost, not its
        optimal value: on a two-joint quadruped's bound the stop-tolerance stage's bundle steps
        fell from 26,126 to 5,113 (99 s to 15 s, before the bundle's working set; with it, the
        default robot's stage takes 10.2 s warm and 15.0 s cold), and on ANYmal the certified
        solve of the tolerant design, which from the baseline ended at the bundle's 400-step
        limit short of its tolerance, converges (worst saving 33.40 % → 33.61 %). The worst
        case's minimiser need not be unique; the certified solve picks one by a stated rule
        (:func:`~hexaleg.design.search.condensed.solve_condensed`'s ``prefer``). A geometry whose
        Joule program has no solution starts from the baseline."""
        if self.metric != "electrical" and len(problems) == 1:
            return None
        try:
            return solve_design(problems[self._unshifted]).x
        except (InfeasibleForcesError, TorqueLimitError):
            return None

    @property
    def _unshifted(self) -> int:
        """The problem of the stops where they are meant to be (no shift), else the first."""
        return next((i for i, shift in enumerate(self.shifts) if not any(shift.values())), 0)

    def solve(self, geometry: Mapping[str, Geometry], exact: bool = True) -> DesignSolution:
        """The optimal magnitudes of ``geometry``; ``value`` is what the search minimises: the
        objective's value (J), or the condensed program's worst metric per cycle (J).
        ``exact=False``: the condensed program's fast path, for comparing geometries."""
        if not self.condensed:
            problem = self.problem(geometry)
            if self.objective in QUADRATIC_OBJECTIVES:
                return solve_design(problem)
            from hexaleg.design.search.program_reference import solve_design_reference

            return solve_design_reference(problem)
        problems = self.problems(geometry)
        data = [Condensed(p, self.metric or "joule") for p in problems]
        s = solve_condensed(problems, self.metric or "joule", "worst",
                            self._start(problems), exact=exact, data=data,
                            prefer=self._unshifted if len(problems) > 1 else None)
        worst = int(np.argmax(s.values))
        return DesignSolution(s.x, float(s.values[worst] * data[worst].base),
                              np.flatnonzero(~data[worst].condensed),
                              int(s.solver.get("iterations", s.solver.get("newton_steps", 1))),
                              data[worst].forces(s.x))


def design_setup(prepared: Prepared, groups: Groups, family: str, objective: str,
                 max_torque: float | None, max_deflection: float | None,
                 metric: str | None = None, shifts: Sequence[Shift] = (),
                 mirrored: Iterable[str] = ()) -> DesignSetup:
    """The checked inputs of :func:`~hexaleg.design.search.optimal.optimal_springs` and each joint's
    range of motion.

    Raises:
        UnknownNameError: an unknown family, objective, joint or metric.
        InvalidParameterError: τ_max or Δ_max not > 0, a metric with an objective other than
            joule, a shift that is not finite or of an unknown group.
    """
    fam = families.family(family)
    check_objective(objective)
    if metric is not None:
        if metric not in METRICS:
            raise UnknownNameError("metric", metric, METRICS)
        if objective != "joule":
            raise InvalidParameterError(
                "objective", objective, "joule with a metric (the magnitudes minimise that "
                "metric of the Joule-optimal forces every evaluation uses)")
    if max_torque is not None:
        max_torque = real("max_torque", max_torque, low=0.0, low_open=True,
                          allowed="a finite torque > 0 (N·m), or None")
    if max_deflection is not None:
        max_deflection = real("max_deflection", max_deflection, low=0.0, low_open=True,
                              allowed="a finite angle > 0 (rad), or None")
    resolved = resolve_groups(prepared, groups)
    checked = []
    for s in shifts:
        for g, v in s.items():
            if g not in resolved:
                raise UnknownNameError("stop shift group", g, tuple(resolved))
            real(f"stop shift of {g}", v, allowed="a finite angle (rad)")
        checked.append({g: float(v) for g, v in s.items()})
    joints = [j for js in resolved.values() for j in js]
    qs = {j: prepared.q[:, prepared.robot.column(j)] for j in joints}
    return DesignSetup(prepared, objective, fam, resolved,
                       centre=motion_centres(prepared, joints),
                       q_min={j: float(q.min()) for j, q in qs.items()},
                       q_max={j: float(q.max()) for j, q in qs.items()},
                       max_torque=max_torque, max_deflection=max_deflection,
                       metric=metric, shifts=tuple(checked),
                       mirrored=frozenset(j for j in mirrored if j in qs))
