"""The paper's Adams experiment in MuJoCo: the single joint with its torsion springs as bodies.

The paper checks its analysis with Adams (Section 4.1): the lever of Table 6 is driven along
θ = 0.3 sin 2t (a "general point" motion driver; the required torque is measured), a main
torsion spring (Table 4) that the lever *contacts* (the contact law of Table 3), a secondary
spring (Table 5) and joint friction (Table 2). :func:`adams` rebuilds that in MuJoCo:

* the lever: a hinge whose state is set to the driver's θ, θ̇ before every step (kinematic); the
  required torque is its equation of motion ``M = J θ̈ + s m g l sin θ + k₂ θ + c₂ θ̇ + Σ τ_c
  + τ_f`` (its first two terms :meth:`~hexaleg.paper.joint.PaperJoint.baseline_torque`)
  with the contact torques τ_c of the arms and the friction τ_f;
* each main spring (one per side, the dead zone ±θ_k between them) is its own body: an arm on a
  hinge coaxial with the joint, with the torsion spring's stiffness and damping (joint
  ``stiffness``/``damping`` about ``springref`` ±θ_k), held at ±θ_k by a stop (a joint limit;
  Table 4: no preload) and an inertia the paper does not give (:attr:`AdamsJoint.arm_inertia`);
  coaxial, the arm carries the eq. 14 joint stiffness κ = k α (as
  :class:`~hexaleg.paper.joint.PaperJoint`);
* the lever–arm contact at radius r: Adams' IMPACT force ``F = K δᵉ + STEP(δ, 0, 0, d, c) δ̇``
  (δ the penetration, STEP the cubic 3u² − 2u³ ramp over 0…d; MSC Adams/Solver, "IMPACT"
  function), never pulling (F ≥ 0). Coaxial bodies do not slide at the contact, so Table 3's
  contact friction does no work and is left out;
* joint friction after Table 2: ``τ_f = μ(v) R_p |F_r| sgn θ̇``, F_r the pin's reaction force
  (lever inertia, gravity, the contact forces), R_p the pin radius, μ ramping linearly from 0 to
  μ_s over the static transition speed v_s at the pin and μ_d beyond — an approximation of Adams'
  stiction model (its deformation and bending/axial arms need the joint's geometry, which the
  paper does not give).

Units: the tables are in the paper's unit system, the one in which eq. 19 gives 713.5 — kg, mm,
s, rad, so force in kg·mm/s² = mN and torque in kg·mm²/s² = µN·m (docs/paper.md): stiffness
1 "N·mm/deg" = 1e-6 N·m/rad, damping 1 = 1e-6 N·m·s/rad, contact stiffness 1 mN/mm^e =
1e-3·1000^e N/m^e, contact damping 1 mN·s/mm = 1 N·s/m, lengths mm. ``units="printed"`` reads
the stiffness and damping as the printed N·mm/deg and N·mm·s/deg, and the contact in N and mm,
instead (its stiff contact damping needs a timestep of a few µs).

:func:`open_loop` is the simulation's invariant for this joint: the analysis' torque applied with
no feedback (the dead-zone spring native) follows the planned motion within the bound
:func:`open_loop_bound` derived there.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from hexaleg.checks import one_of, positive
from hexaleg.dynamics import energy
from hexaleg.paper.joint import POSTURES, PaperJoint
from hexaleg.robot.catalogue import motor
from hexaleg.units import DEG, MM

UNITS: tuple[str, ...] = ("paper", "printed")
"""How to read Tables 4–5: in the paper's consistent unit system (kg, mm, s, rad: 1e-6 N·m/rad),
or as the printed N·mm/deg."""


@dataclass(frozen=True)
class Tables:
    """Tables 2–5 as printed (the paper's units; Table 4's stiffness is the swept k).

    Attributes:
        mu_static: Table 2, 0.5. mu_dynamic: Table 2, 0.8. pin_radius: Table 2, 10 mm.
        static_speed: Table 2 static transition velocity, 0.1 mm/s.
        contact_stiffness: Table 3, 1e5 mN/mm^e. contact_exponent: Table 3, 2.2.
        contact_damping: Table 3, 10 mN·s/mm. penetration: Table 3, 0.1 mm.
        main_damping: Table 4, 1 (N·mm·s/deg as printed). secondary_stiffness: Table 5, 0.01.
        secondary_damping: Table 5, 1e-4.
    """

    mu_static: float = 0.5
    mu_dynamic: float = 0.8
    pin_radius: float = 10.0
    static_speed: float = 0.1
    contact_stiffness: float = 1e5
    contact_exponent: float = 2.2
    contact_damping: float = 10.0
    penetration: float = 0.1
    main_damping: float = 1.0
    secondary_stiffness: float = 0.01
    secondary_damping: float = 1e-4


@dataclass(frozen=True)
class AdamsJoint:
    """The Adams single-joint experiment (module docstring).

    Attributes:
        joint: Lever, trajectory, θ_k, α, gravity posture (Table 6, eq. 25, Section 4.2).
        tables: Tables 2–5.
        units: One of :data:`UNITS`.
        gravity: Include gravity, ``joint.gravity`` (the paper's analysis of k_M ignores it).
        friction: Include Table 2's joint friction.
        contact_radius: Where the lever meets an arm, m, > 0 (not in the paper: the pin radius).
        arm_inertia: Each arm's inertia about the axis, kg·m², > 0 (not in the paper, whose
            analysis takes the spring massless: 1 % of the lever's J).
        timestep: s, > 0.
    """

    joint: PaperJoint = field(default_factory=PaperJoint)
    tables: Tables = field(default_factory=Tables)
    units: str = "paper"
    gravity: bool = False
    friction: bool = True
    contact_radius: float = 10 * MM
    arm_inertia: float = 0.01 * PaperJoint().J
    timestep: float = 2e-4

    def __post_init__(self) -> None:
        one_of("units", self.units, UNITS)
        positive("contact_radius (m)", self.contact_radius)
        positive("arm_inertia (kg·m²)", self.arm_inertia)
        positive("timestep (s)", self.timestep)

    def stiffness_si(self, k: float) -> float:
        """A Table 4/5 stiffness number in N·m/rad (per :attr:`units`)."""
        return float(k) * (1e-6 if self.units == "paper" else 1e-3 / DEG)

    def contact_si(self) -> tuple[float, float, float]:
        """Table 3 in SI: (K N/m^e, c N·s/m, d m); forces in mN (``"paper"``) or N
        (``"printed"``), lengths in mm."""
        t = self.tables
        force = 1e-3 if self.units == "paper" else 1.0
        return (t.contact_stiffness * force * 1000.0**t.contact_exponent,
                t.contact_damping * force * 1000.0, t.penetration * MM)

    def xml(self, k: float) -> str:
        """The MJCF of the lever and the two spring arms for main stiffness k (paper units)."""
        j, tk = self.joint, self.joint.theta_k
        kappa = float(self.stiffness_si(k) * j.transmission)
        damp = float(self.stiffness_si(self.tables.main_damping) * j.transmission)
        g = j.gravity if self.gravity else 0.0
        s = POSTURES[j.posture]
        arm = 1e-3  # kg: a small mass at the axis; the inertia is arm_inertia

        def arm_body(name: str, lo: float, hi: float, ref: float) -> str:
            return (f'<body name="{name}"><joint name="{name}" type="hinge" axis="0 1 0" '
                    f'limited="true" range="{lo!r} {hi!r}" stiffness="{kappa!r}" '
                    f'springref="{ref!r}" damping="{damp!r}"/><inertial pos="0 0 0" '
                    f'mass="{arm!r}" diaginertia="{self.arm_inertia!r} {self.arm_inertia!r} '
                    f'{self.arm_inertia!r}"/></body>')

        return (f'<mujoco><compiler angle="radian"/><option timestep="{self.timestep!r}" '
                f'gravity="0 0 {-g!r}" '
                'integrator="Euler"><flag eulerdamp="disable" contact="disable"/></option>'
                '<worldbody><body name="lever"><joint name="lever" type="hinge" axis="0 1 0"/>'
                f'<inertial pos="0 0 {-s * j.com!r}" mass="{j.mass!r}" diaginertia="'
                f'{j.inertia!r} {j.inertia!r} {j.inertia!r}"/></body>'
                + arm_body("arm_plus", tk, tk + math.pi / 2, tk)
                + arm_body("arm_minus", -tk - math.pi / 2, -tk, -tk)
                + "</worldbody></mujoco>")


@dataclass(frozen=True)
class AdamsRun:
    """One run of :func:`adams` (its last period).

    Attributes:
        t: Times, shape (n,), s. theta: Lever angle, (n,), rad. theta_dot: (n,), rad/s.
        torque: Required motor torque M, (n,), N·m. contact: Torque of the arms on the lever,
            (n,), N·m. friction: Joint friction torque, (n,), N·m. arms: Arm angles, (n, 2),
            rad. k: The main stiffness, paper units. kappa: Joint stiffness κ = kα, N·m/rad.
    """

    t: np.ndarray
    theta: np.ndarray
    theta_dot: np.ndarray
    torque: np.ndarray
    contact: np.ndarray
    friction: np.ndarray
    arms: np.ndarray
    k: float
    kappa: float

    def metrics(self) -> dict[str, Any]:
        """The totals of :func:`hexaleg.dynamics.energy.metrics` of the required torque M and
        the lever's speed over the period (its electrical entries for the default servo,
        :func:`hexaleg.robot.catalogue.motor`): ``mean_abs_torque``, ``peak_torque``,
        ``rms_torque`` (N·m), ``positive_work`` (J), …."""
        return energy.metrics(self.torque, self.theta_dot, float(self.t[1] - self.t[0]),
                              motor())["total"]

    def mean_abs(self) -> float:
        """Mean |M| over the period (the paper's Figs 9–10: trapezoid of M over a period / T),
        N·m."""
        return float(self.metrics()["mean_abs_torque"])

    def positive_work(self) -> float:
        """∫ max(M θ̇, 0) dt over the period, J."""
        return float(self.metrics()["positive_work"])

    def epsilon(self, joint: PaperJoint) -> float:
        """Eq. 24 (:func:`hexaleg.dynamics.energy.epsilon`) as
        :func:`hexaleg.paper.metrics.energy_ratio`: E⁺/(J · 4A), 1/s²."""
        return energy.epsilon(self.positive_work(), joint.J, 4 * joint.amplitude)


def _impact(delta: float, rate: float, K: float, e: float, c: float, d: float) -> float:
    """Adams' IMPACT force ``K δᵉ + STEP(δ, 0, 0, d, c) δ̇`` for penetration δ > 0 (else 0), never
    pulling; STEP ramps as 3u² − 2u³ (u = δ/d) up to d, 1 beyond (MSC Adams/Solver, "IMPACT")."""
    if delta <= 0.0:
        return 0.0
    u = min(delta / d, 1.0)
    return max(K * delta**e + c * (u * u * (3 - 2 * u)) * rate, 0.0)


def adams(model: AdamsJoint, k: float, periods: int = 2) -> AdamsRun:
    """Simulate the Adams experiment for ``periods`` periods; the last is returned.

    Args:
        model: The experiment.
        k: Main spring stiffness, in the paper's units (per ``model.units``); 0 for none.
        periods: Periods simulated (the first lets the arms settle), ≥ 1.

    Returns:
        The last period.
    """
    import mujoco

    m = mujoco.MjModel.from_xml_string(model.xml(k))
    d = mujoco.MjData(m)
    j, tab = model.joint, model.tables
    K, c, depth = model.contact_si()
    r, e = model.contact_radius, tab.contact_exponent
    k2 = model.stiffness_si(tab.secondary_stiffness)
    c2 = model.stiffness_si(tab.secondary_damping)
    mu_s, mu_d = tab.mu_static, tab.mu_dynamic
    r_pin, v_s = tab.pin_radius * MM, tab.static_speed * MM
    g = j.gravity if model.gravity else 0.0
    s = POSTURES[j.posture]
    n_period = round(j.period / model.timestep)
    dt = j.period / n_period
    m.opt.timestep = dt
    n = periods * n_period
    t = np.arange(n) * dt
    th, thd, thdd = j.trajectory(t)
    lever = j.baseline_torque(t, model.gravity) + k2 * th + c2 * thd  # all but τ_c and τ_f
    d.qpos[1:], d.qvel[1:] = (j.theta_k, -j.theta_k), 0.0
    qpos, qvel, applied = d.qpos, d.qvel, d.qfrc_applied
    sprung = k > 0  # k = 0: no spring at all
    lever_moment, gravity_force = j.mass * j.com, s * j.mass * g
    out = np.zeros((n, 5))
    # Python floats step by step: 2-element arrays cost 5× the step itself
    for i, (q, v, acc, base) in enumerate(zip(th.tolist(), thd.tolist(), thdd.tolist(),
                                              lever.tolist(), strict=True)):
        qpos[0], qvel[0] = q, v
        a_plus, a_minus, v_plus, v_minus = (float(x) for x in (qpos[1], qpos[2], qvel[1],
                                                              qvel[2]))
        # penetration of the lever into each arm (beyond θ_k⁺, below −θ_k) and its rate
        f_plus = _impact(r * (q - a_plus), r * (v - v_plus), K, e, c, depth) if sprung else 0.0
        f_minus = _impact(r * (a_minus - q), r * (v_minus - v), K, e, c, depth) if sprung else 0.0
        applied[1], applied[2] = f_plus * r, -f_minus * r
        tau_c = (f_plus - f_minus) * r  # load of the arms on the lever (restoring)
        friction = 0.0
        if model.friction:
            # pin reaction = m a_com − m g − F_c, in the lever's frame (radial, tangential)
            radial = -lever_moment * v**2 - gravity_force * math.cos(q)
            tangential = lever_moment * acc + gravity_force * math.sin(q) + (f_plus - f_minus)
            speed = abs(v) * r_pin
            mu = mu_s * speed / v_s if speed < v_s else mu_d
            friction = mu * r_pin * math.hypot(radial, tangential) * math.copysign(1.0, v)
        out[i] = (base + tau_c + friction, tau_c, friction, a_plus, a_minus)
        mujoco.mj_step(m, d)
    last = slice(n - n_period, n)
    return AdamsRun(t=t[last] - t[n - n_period], theta=th[last], theta_dot=thd[last],
                    torque=out[last, 0], contact=out[last, 1], friction=out[last, 2],
                    arms=out[last, 3:5], k=float(k),
                    kappa=model.stiffness_si(k) * j.transmission)


def open_loop(joint: PaperJoint, k: float, timestep: float, periods: int = 1
              ) -> tuple[np.ndarray, np.ndarray]:
    """The analysis' torque applied open loop (no feedback) to the lever with the dead-zone
    spring built natively (joint-side stiffness κ = k·transmission as a tendon dead band).

    Args:
        joint: The joint (its gravity posture and g are used).
        k: Spring stiffness in the joint's convention, N·m/rad.
        timestep: s, > 0.
        periods: Periods simulated, ≥ 1.

    Returns:
        ``(t (n,), θ_sim − θ_plan (n,))``, s and rad.
    """
    import mujoco

    kappa = float(k * joint.transmission)
    tk = joint.theta_k
    s = POSTURES[joint.posture]
    xml = (f'<mujoco><compiler angle="radian"/><option timestep="{timestep!r}" '
           f'gravity="0 0 {-joint.gravity!r}" '
           'integrator="Euler"><flag eulerdamp="disable" contact="disable"/></option>'
           '<worldbody><body><joint name="lever" type="hinge" axis="0 1 0"/><inertial '
           f'pos="0 0 {-s * joint.com!r}" mass="{joint.mass!r}" diaginertia="{joint.inertia!r} '
           f'{joint.inertia!r} {joint.inertia!r}"/></body></worldbody><tendon><fixed '
           f'stiffness="{kappa!r}" springlength="{-tk!r} {tk!r}"><joint joint="lever" coef="1"/>'
           "</fixed></tendon></mujoco>")
    m = mujoco.MjModel.from_xml_string(xml)
    d = mujoco.MjData(m)
    n = round(periods * joint.period / timestep)
    t = np.arange(n + 1) * timestep
    th, thd, _ = joint.trajectory(t)
    torque = joint.motor_torque(t, k, gravity=joint.gravity > 0)
    d.qpos[0], d.qvel[0] = th[0], thd[0]
    err = np.empty(n + 1)
    err[0] = 0.0
    for i in range(n):
        d.qfrc_applied[0] = torque[i]
        mujoco.mj_step(m, d)
        err[i + 1] = d.qpos[0] - th[i + 1]
    return t, err


def open_loop_bound(joint: PaperJoint, timestep: float, t: np.ndarray) -> np.ndarray:
    """A bound on the open-loop error of :func:`open_loop` (no gravity, B = 0).

    Symplectic Euler on positions is the Störmer recursion ``θ_{n+1} − 2θ_n + θ_{n−1} =
    h² θ̈(θ_n, t_n)``, which the plan satisfies up to the truncation ``h⁴ θ⁽⁴⁾/12``; its first step
    misses the plan by ``h² θ̈(0)/2 + h³ θ⃛(0)/6`` (= h³Aω³/6 from rest at θ = 0). In the dead zone
    the error recursion is that of a free particle, so the error grows at most as
    ``|e(t)| ≤ (t/h) e₁ + (t/h)² h⁴ max|θ⁽⁴⁾|/24`` — with θ = A sin ωt,
    ``h² A ω³ (t/6 + ω t²/24)``; while engaged the restoring spring only rotates the error, so the
    same bound holds, doubled for safety. The error is second order in h.

    Args:
        joint: The joint.
        timestep: h, s.
        t: Times, s.

    Returns:
        The bound at ``t``, rad.
    """
    a, w, h = joint.amplitude, joint.omega, timestep
    return 2 * h * h * a * w**3 * (np.asarray(t) / 6 + w * np.asarray(t) ** 2 / 24) + 1e-15
