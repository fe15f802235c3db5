"""Time profiles of the motions: the swing foot's curve and the paper's joint sinusoid (eq. 16).

* :func:`smoothstep` and :func:`swing_bump` — polynomial profiles on [0, 1] that start and stop
  with zero velocity, acceleration and jerk; :func:`swing_curve` combines them into a swing foot's
  path (:mod:`hexaleg.motion.legged`), and the smoothstep also times the hexapod → sphere
  transformation (:mod:`hexaleg.motion.transform`).
* :class:`Sinusoid` — the paper's joint trajectory f(t) = A sin(ωt + φ) + B (eq. 16) with exact
  derivatives (:mod:`hexaleg.motion.joint_motion`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from hexaleg.checks import real


def smoothstep(s: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The degree-7 smoothstep σ(s) = 35s⁴ − 84s⁵ + 70s⁶ − 20s⁷ and its first two derivatives.

    σ rises from 0 to 1 on [0, 1] with zero first, second and third derivatives at both ends
    (the lowest-degree polynomial with that property). Source: the "smootherstep" family of
    Hermite polynomials, e.g. Ebert et al., *Texturing & Modeling*, 3rd ed., 2003, ch. 2.

    Args:
        s: Normalised time, any shape, in [0, 1].

    Returns:
        σ, dσ/ds, d²σ/ds², each the shape of ``s``.
    """
    s = np.asarray(s, dtype=float)
    s3 = s**3
    value = s3 * s * (35.0 + s * (-84.0 + s * (70.0 - 20.0 * s)))
    d1 = 140.0 * s3 * (1.0 - s) ** 3
    d2 = 420.0 * s * s * (1.0 - s) ** 2 * (1.0 - 2.0 * s)
    return value, d1, d2


def swing_bump(s: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The lift profile b(s) = 256 s⁴ (1 − s)⁴ and its first two derivatives.

    b is 0 at s = 0 and 1, peaks at b(½) = 1, and has zero first, second and third derivatives
    at both ends. Source: chosen here (symmetric polynomial with the end conditions above).

    Args:
        s: Normalised time, any shape, in [0, 1].

    Returns:
        b, db/ds, d²b/ds², each the shape of ``s``.
    """
    s = np.asarray(s, dtype=float)
    u = s * (1.0 - s)
    du = 1.0 - 2.0 * s
    value = 256.0 * u**4
    d1 = 1024.0 * u**3 * du
    d2 = 3072.0 * u**2 * du**2 - 2048.0 * u**3
    return value, d1, d2


def swing_curve(s: np.ndarray, lift_off: np.ndarray, touch_down: np.ndarray, height: float
                ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """A swing foot's path: straight ground track by :func:`smoothstep`, lift by :func:`swing_bump`.

    ``p(s) = p₀ + (p₁ − p₀) σ(s) + h b(s) ẑ``: the foot leaves ``lift_off`` and lands on
    ``touch_down`` with zero velocity, acceleration and jerk, so contact switches are impact-free
    and the joint accelerations (and inverse-dynamics torques) stay continuous across them.

    Args:
        s: Normalised swing time, shape (N,), in [0, 1].
        lift_off: Lift-off points, shape (N, 3) or (3,), m.
        touch_down: Touch-down points, shape (N, 3) or (3,), m.
        height: Apex height above the straight line between them, m.

    Returns:
        p (N, 3) m, dp/ds (N, 3) m, d²p/ds² (N, 3) m.
    """
    sigma, d_sigma, dd_sigma = smoothstep(s)
    bump, d_bump, dd_bump = swing_bump(s)
    delta = np.asarray(touch_down, dtype=float) - np.asarray(lift_off, dtype=float)
    up = np.array([0.0, 0.0, height])
    p = lift_off + sigma[:, None] * delta + bump[:, None] * up
    return p, d_sigma[:, None] * delta + d_bump[:, None] * up, \
        dd_sigma[:, None] * delta + dd_bump[:, None] * up


@dataclass(frozen=True)
class Sinusoid:
    """The paper's joint trajectory f(t) = A sin(ωt + φ) + B (eq. 16), an absolute joint angle.

    Attributes:
        amplitude: A, rad.
        omega: ω, rad/s.
        phase: φ, rad.
        offset: B, rad.
    """

    amplitude: float
    omega: float
    phase: float = 0.0
    offset: float = 0.0

    def __post_init__(self) -> None:
        for name in ("amplitude", "omega", "phase", "offset"):
            real(f"Sinusoid.{name}", getattr(self, name), allowed="a finite number")

    def __call__(self, t: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Angle, angular velocity and acceleration at times ``t`` (eq. 16 and its derivatives).

        Args:
            t: Times, any shape, s.

        Returns:
            f (rad), ḟ = Aω cos(ωt + φ) (rad/s), f̈ = −Aω² sin(ωt + φ) (rad/s²), shape of ``t``.
        """
        arg = self.omega * np.asarray(t, dtype=float) + self.phase
        s, c = np.sin(arg), np.cos(arg)
        a = self.amplitude
        return a * s + self.offset, a * self.omega * c, -a * self.omega**2 * s
