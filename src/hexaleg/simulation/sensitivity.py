"""How the simulated saving depends on what the analysis leaves out: servo gains, ground, friction,
controller.

:func:`sensitivity` reruns a simulation (with and without the springs) for each variant of
:data:`VARIANTS` — the servo gains ×0.25…×4, the ground 4 × softer and stiffer, half the friction,
MuJoCo's no-slip pass, the other controller — and tabulates the simulated saving beside the
prediction (which none of them changes: the analysis has rigid feet and exact tracking).
:func:`controller_check` is the short table ``hexaleg design`` proves its recommendation with:
the springs simulated under each controller of :data:`CONTROLLER_VARIANTS`.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable, Sequence
from typing import Any

from hexaleg.dynamics.prepare import Prepared
from hexaleg.errors import HexalegError
from hexaleg.quantities import quantity
from hexaleg.robot.springs import SpringSet
from hexaleg.simulation.result import Simulation
from hexaleg.simulation.run import simulate
from hexaleg.simulation.settings import Settings

Variant = tuple[str, Callable[[Settings], Settings]]
"""A label and how it changes the settings."""


def _scaled(field: str, factor: float) -> Callable[[Settings], Settings]:
    return lambda s: dataclasses.replace(s, **{field: getattr(s, field) * factor})


def _other_controller(s: Settings) -> Settings:
    return dataclasses.replace(s, controller="position" if s.controller == "feedforward"
                               else "feedforward")


VARIANTS: tuple[Variant, ...] = (
    ("as set", lambda s: s),
    ("servo gains ×0.25", lambda s: _scaled("kd_scale", 0.25)(_scaled("kp_scale", 0.25)(s))),
    ("servo gains ×0.5", lambda s: _scaled("kd_scale", 0.5)(_scaled("kp_scale", 0.5)(s))),
    ("servo kp ×2", _scaled("kp_scale", 2.0)),
    ("servo kp ×4", _scaled("kp_scale", 4.0)),
    ("ground stiffness ×0.25", _scaled("stiffness", 0.25)),
    ("ground stiffness ×4", _scaled("stiffness", 4.0)),
    ("friction μ 0.3", lambda s: dataclasses.replace(s, mu=0.3)),
    ("no-slip pass", lambda s: dataclasses.replace(s, noslip=True)),
    ("other controller", _other_controller),
)
"""The variants of :func:`sensitivity` (with the automatic timestep a stiffer variant steps finer
where its explicit-stability limit asks for it)."""

CONTROLLER_VARIANTS: tuple[Variant, ...] = (
    ("feedforward + PD", lambda s: dataclasses.replace(s, controller="feedforward")),
    ("position only", lambda s: dataclasses.replace(s, controller="position")),
)
"""The variants of :func:`controller_check`: the two controllers a servo robot runs
(:data:`hexaleg.simulation.controllers.CONTROLLERS`), the other settings the defaults."""


def sensitivity(base: Simulation, variants: Sequence[Variant] = VARIANTS
                ) -> list[dict[str, Any]]:
    """The simulated saving of ``base``'s springs under each variant of its settings.

    Args:
        base: A simulation (its robot, gait, springs, analysis and settings are reused).
        variants: ``(label, settings → settings)`` pairs.

    Returns:
        One row per variant: ``label``, ``controller``, ``verdict`` (``"walks"`` or why not),
        ``predicted`` and ``simulated`` electrical saving (fractions; ``simulated`` None unless
        both runs walked), ``predicted_electrical`` and ``predicted_baseline`` (J per cycle, the
        analysis'), ``electrical`` and ``baseline`` (J per cycle, simulated),
        ``distance_per_cycle`` (m), ``tracking_rms`` (rad), ``feedback`` (whether the balance
        controller ran in both runs, :mod:`hexaleg.simulation.balance`), ``why`` (where a
        run fell for a reason the gait alone explains, :attr:`~hexaleg.simulation.run.Run.
        reason`, else absent).
    """
    p = base.analysis
    rows = []
    for label, change in variants:
        row: dict[str, Any] = {"label": label, "predicted": p.savings["total"]["electrical"],
                               "predicted_electrical": p.metrics["total"]["electrical"],
                               "predicted_baseline": p.baseline["total"]["electrical"]}
        try:
            settings = change(base.settings)
            row["controller"] = settings.controller
            s = base if settings == base.settings else simulate(
                base.robot, base.motion, p.motor, base.springs, settings, contact=p.contact,
                objective=p.objective, prepared=base.prepared)
        except HexalegError as e:
            row.update(verdict=f"{type(e).__name__}: {e}", simulated=None)
            rows.append(row)
            continue
        row["feedback"] = s.with_springs.feedback and s.baseline.feedback
        row["verdict"] = "walks" if s.walks else "; ".join(
            f"{r.name} {r.verdict}" for r in (s.with_springs, s.baseline) if not r.walks)
        why = next((r.reason for r in (s.with_springs, s.baseline) if r.reason), "")
        if why:
            row["why"] = why
        if s.walks:
            with_, without, saved = s.simulated()
            w = s.with_springs.walk
            assert w is not None
            row.update(simulated=saved, electrical=with_, baseline=without,
                       distance_per_cycle=w.distance_per_cycle, tracking_rms=w.tracking_rms)
        else:
            row["simulated"] = None
        rows.append(row)
    return rows


def controller_check(prepared: Prepared, springs: SpringSet, objective: str,
                     settings: Settings | None = None) -> list[dict[str, Any]]:
    """``springs`` on ``prepared``'s gait simulated under each controller of
    :data:`CONTROLLER_VARIANTS`: rows of :func:`sensitivity` (the predicted and the simulated
    electrical saving, the energies, the walk).

    Args:
        prepared: The gait, prepared with the motor and contact settings of the design.
        springs: The springs (SI).
        objective: The analysis' force objective.
        settings: The other settings (default :class:`Settings` without the foot-force
            comparison).

    Raises:
        InvalidParameterError: a gait too coarse for the automatic timestep, a non-periodic
            motion. InfeasibleForcesError, TorqueLimitError: from the analysis.
    """
    base = simulate(prepared.robot, prepared.motion, prepared.motor, springs,
                    settings or Settings(force_samples=0), contact=prepared.contact,
                    objective=objective, prepared=prepared)
    return sensitivity(base, CONTROLLER_VARIANTS)


def sensitivity_row(row: dict[str, Any]) -> dict[str, Any]:
    """A row of :func:`hexaleg.simulation.sensitivity.sensitivity` as quantities."""
    out: dict[str, Any] = {"label": row["label"], "controller": row.get("controller"),
                           "feedback": row.get("feedback"), "verdict": row["verdict"],
                           **({"why": row["why"]} if row.get("why") else {}),
                           "predicted_saving": quantity(100 * row["predicted"], "%"),
                           "predicted_electrical": quantity(row["predicted_electrical"], "J"),
                           "predicted_baseline": quantity(row["predicted_baseline"], "J")}
    if row.get("simulated") is not None:
        out.update(simulated_saving=quantity(100 * row["simulated"], "%"),
                   electrical=quantity(row["electrical"], "J"),
                   baseline=quantity(row["baseline"], "J"),
                   distance_per_cycle=quantity(row["distance_per_cycle"], "m"),
                   tracking_rms=quantity(row["tracking_rms"], "rad"))
    return out
