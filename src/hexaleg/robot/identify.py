"""An actuator's constants fitted to its own measurements: the energy model of the user's robot.

The model is :mod:`hexaleg.robot.motor`'s, per joint and sample (Verstraten et al., IEEE RA-L
1(1), 2016, constant-efficiency gearbox)::

    i   = τ / (k_t G)                                   the current for an output torque
    P_e = max(τ q̇ / η, η τ q̇) + c τ²,   c = R / (k_t G)²   the electrical power drawn

Given samples of the output torque τ (N·m) and the joint speed q̇ (rad/s) of joints driven by one
actuator model, with the measured current i (A), the measured electrical power P_e (W), or
both, :func:`identify_actuator` fits by least squares:

* ``k_t G`` from the currents: ``i = τ / (k_t G)`` is a line through the origin, so
  ``1 / (k_t G) = Σ τ i / Σ τ²``;
* ``η`` and ``c`` from the powers: for a given η the power is linear in c, whose least-squares
  value is closed-form; η is the minimiser of that residual over a dense grid on
  :data:`EFFICIENCY_BOUNDS`, refined between the grid's neighbours by a bounded scalar
  minimisation — the grid makes the answer the global one, the same on any machine to the
  refinement's tolerance. Without regeneration the servo's driver burns negative power, so the
  measured power is ``max(0, P_e)``: samples drawing nothing are left out of the fit (there the
  model's power is negative and unknown);
* ``R = c (k_t G)²`` when both are known; with powers alone the base motor's ``k_t G`` is kept and
  ``R`` follows from ``c``, so the energy (which depends on c and η only) is the fitted one.

Each fit reports its root-mean-square residual and that residual relative to the RMS of what it
fits, so a user sees whether the model describes the actuator at all (a residual of tens of
percent says it does not: friction, a driver's own draw, a wrong torque).
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from hexaleg.checks import finite_array
from hexaleg.errors import InvalidParameterError
from hexaleg.robot.actuator import Actuator
from hexaleg.robot.motor import Motor

EFFICIENCY_BOUNDS = (0.05, 1.0)
"""The gearbox efficiencies η the fit searches (a geared servo's lies well inside)."""
EFFICIENCY_GRID = 951
"""Points of the dense η grid before the refinement (0.001 apart on the bounds)."""
MIN_SAMPLES = 10
"""Fewest samples a fit takes (two or three constants, and noise)."""


@dataclass(frozen=True)
class Fit:
    """One least-squares fit: its constants, residual and samples.

    Attributes:
        constants: Name → fitted value, SI (``"output_torque_constant"`` N·m/A,
            ``"gearbox_efficiency"`` 1, ``"joule_coefficient"`` W/(N·m)²).
        residual_rms: Root-mean-square residual, in the unit of what is fitted (A or W).
        relative_residual: ``residual_rms`` over the RMS of the measurements fitted, 1.
        samples: Samples used.
    """

    constants: dict[str, float]
    residual_rms: float
    relative_residual: float
    samples: int


@dataclass(frozen=True)
class Identification:
    """An actuator identified from measurements (:func:`identify_actuator`).

    Attributes:
        motor: The base motor with the fitted constants (its name ends in "(identified)";
            ``source`` and ``notes`` say what was fitted and what kept).
        current: The fit of ``k_t G`` from the currents, or None without currents.
        power: The fit of η and c from the powers, or None without powers.
    """

    motor: Motor
    current: Fit | None
    power: Fit | None


def _samples(name: str, value: ArrayLike | None, shape: tuple[int, ...] | None
             ) -> np.ndarray | None:
    if value is None:
        return None
    arr = finite_array(name, value)
    if shape is not None and arr.shape != shape:
        raise InvalidParameterError(f"{name}.shape", arr.shape, f"the shape of tau, {shape}")
    return arr.ravel()


def _current_fit(tau: np.ndarray, current: np.ndarray) -> Fit:
    """``k_t G`` from ``i = τ / (k_t G)`` (least squares through the origin)."""
    moving = tau != 0
    if moving.sum() < MIN_SAMPLES:
        raise InvalidParameterError("tau", f"{int(moving.sum())} nonzero samples",
                                    f"at least {MIN_SAMPLES} to fit k_t G from the currents")
    slope = float(tau @ current / (tau @ tau))  # 1 / (k_t G)
    if slope <= 0:
        raise InvalidParameterError("current", f"1/(k_t G) = {slope:.3g} A/(N·m)",
                                    "currents that grow with the torque (same sign): check "
                                    "their sign convention against the torques'")
    resid = current - slope * tau
    rms = float(np.sqrt(np.mean(resid**2)))
    return Fit({"output_torque_constant": 1.0 / slope}, rms,
               rms / float(np.sqrt(np.mean(current**2))), int(current.size))


def _power_fit(tau: np.ndarray, qdot: np.ndarray, power: np.ndarray,
               regeneration: bool) -> Fit:
    """η and c of ``P_e = max(τq̇/η, ητq̇) + c τ²`` (module docstring)."""
    use = np.ones(power.shape, bool) if regeneration else power > 0
    if use.sum() < MIN_SAMPLES:
        raise InvalidParameterError("power", f"{int(use.sum())} samples drawing power",
                                    f"at least {MIN_SAMPLES} to fit η and c")
    t, w, p = tau[use], qdot[use], power[use]
    mech, sq = t * w, t**2
    if sq @ sq == 0:
        raise InvalidParameterError("tau", "all zero", "torques that load the actuator")

    def solve(eta: float) -> tuple[float, float]:
        """c(η) by least squares and the residual's sum of squares."""
        rest = p - np.maximum(mech / eta, mech * eta)
        c = max(float(sq @ rest / (sq @ sq)), 0.0)
        r = rest - c * sq
        return c, float(r @ r)

    from scipy.optimize import minimize_scalar  # here: scipy.optimize costs every command ~1 s

    grid = np.linspace(*EFFICIENCY_BOUNDS, EFFICIENCY_GRID)
    costs = np.array([solve(e)[1] for e in grid])
    k = int(np.argmin(costs))
    lo, hi = grid[max(k - 1, 0)], grid[min(k + 1, len(grid) - 1)]
    eta = float(minimize_scalar(lambda e: solve(e)[1], bounds=(lo, hi), method="bounded",
                                options={"xatol": 1e-9}).x)
    if solve(eta)[1] > costs[k]:  # the refinement never loses to the grid
        eta = float(grid[k])
    c, ss = solve(eta)
    if c <= 0:
        raise InvalidParameterError("power", "no Joule loss in the fit (c = 0)",
                                    "powers that grow with the squared torque at rest (check "
                                    "that they are this actuator's electrical power, W)")
    rms = float(np.sqrt(ss / p.size))
    return Fit({"gearbox_efficiency": eta, "joule_coefficient": c}, rms,
               rms / float(np.sqrt(np.mean(p**2))), int(p.size))


def identify_actuator(base: Actuator, tau: ArrayLike, qdot: ArrayLike, *,
                      current: ArrayLike | None = None,
                      power: ArrayLike | None = None) -> Identification:
    """Fit an actuator's constants to measurements of the joints it drives (module docstring).

    Args:
        base: The actuator as known before (a catalogue motor, a generic one): a
            :class:`~hexaleg.robot.motor.Motor`, the only model this fit knows; its gear ratio,
            limits, voltage and regeneration are kept; what is fitted replaces its ``k_t``,
            ``R`` and ``η``.
        tau: Output torques, any shape (e.g. (T, n) for n joints of this actuator), N·m.
        qdot: Joint speeds, the shape of ``tau``, rad/s.
        current: Measured currents (the q-axis current of a brushless drive), the shape of
            ``tau``, A; or None.
        power: Measured electrical power of each joint, the shape of ``tau``, W; or None.

    Returns:
        The identification: the motor with the fitted constants and each fit's residual.

    Raises:
        InvalidParameterError: ``base`` not a Motor (another actuator model has no ``k_t``, ``R``
            and ``η`` to fit); neither currents nor powers; an array of another shape or with
            NaN/inf; too few usable samples; currents of the opposite sign to the torques.
    """
    if not isinstance(base, Motor):
        raise InvalidParameterError("base", type(base).__name__, "a Motor (the actuator as "
                                    "known before, e.g. hexaleg.robot.catalogue.motor(name))")
    t = finite_array("tau", tau)
    shape = t.shape
    w = _samples("qdot", qdot, shape)
    i = _samples("current", current, shape)
    p = _samples("power", power, shape)
    if i is None and p is None:
        raise InvalidParameterError("current, power", None, "measured currents (A), "
                                    "electrical powers (W) or both, the shape of tau")
    assert w is not None
    t = t.ravel()
    by_current = None if i is None else _current_fit(t, i)
    by_power = None if p is None else _power_fit(t, w, p, base.regeneration)
    ktg = (base.torque_constant * base.gear_ratio if by_current is None
           else by_current.constants["output_torque_constant"])
    eta = base.gearbox_efficiency if by_power is None else by_power.constants[
        "gearbox_efficiency"]
    c = base.joule_coefficient if by_power is None else by_power.constants["joule_coefficient"]
    fitted = [f"{k} {v:.4g}" for fit in (by_current, by_power) if fit is not None
              for k, v in fit.constants.items()]
    kept = ([] if by_current is not None else ["k_t G"]) + (
        [] if by_power is not None else ["η", "c"])
    motor = dataclasses.replace(
        base, name=f"{base.name} (identified)", torque_constant=ktg / base.gear_ratio,
        resistance=c * ktg**2, gearbox_efficiency=eta,
        source=f"identified by least squares from measured "
               f"{' and '.join(n for n, a in (('currents', i), ('powers', p)) if a is not None)}"
               f" (hexaleg.robot.identify); base {base.name}: {base.source}",
        notes=f"Fitted: {', '.join(fitted)}"
              + (f"; kept from {base.name}: {', '.join(kept)}" if kept else "")
              + ". R = c (k_t G)².")
    return Identification(motor=motor, current=by_current, power=by_power)


__all__ = ["EFFICIENCY_BOUNDS", "Fit", "Identification", "identify_actuator"]
