"""How close a walk on soles came to tipping: its centre of pressure against the sole's edge.

A sole (:mod:`hexaleg.robot.soles`) touches the ground at its four corners in the simulation
(:mod:`hexaleg.simulation.mjcf`). The centre of pressure of a foot is the normal-force-weighted
mean of its contact points, ``p = Σ fₙ,ᵢ pᵢ / Σ fₙ,ᵢ`` (Sardain & Bessonnet, "Forces acting on a
biped robot. Center of pressure — zero moment point", IEEE Trans. SMC-A 34(5), 2004, eq. 5);
it lies within the sole, and a foot whose centre of pressure reaches the sole's edge starts to
roll about it (Vukobratović & Borovac, "Zero-moment point — thirty five years of its life",
Int. J. Humanoid Robotics 1(1), 2004). Its distance to the nearest edge is the margin the walk
kept: :func:`cop_margins` takes its smallest value over the planned stances of the evaluated
window and says where (the leg and the edge) and when. A stance's first and last
:data:`~hexaleg.simulation.measures.LOSS_GRACE` are left out, as the contact losses leave them
out: there the load is handed over, and the first or last corner to touch carries all of it,
so the centre of pressure sits on that corner by construction.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from hexaleg.motion.trajectory import Motion
from hexaleg.simulation.measures import LOSS_GRACE, forward_states, planned_index
from hexaleg.simulation.mjcf import corner_site
from hexaleg.simulation.model import SimModel
from hexaleg.simulation.stepping import Trajectory

PRESSURE_SAMPLES = 2000
"""Recorded steps of the evaluated window at which the centre of pressure is taken, at most
(evenly spread; every step of a window shorter than this)."""
TIP_MARGIN = 1e-3
"""A sole alone on the ground whose centre of pressure came within this distance of its edge,
m, let the robot roll about that edge (the ZMP criterion, module docstring): the run "tipped",
whatever distance it covered. The margin is exact to about a micrometre (the contact points
and the corners are computed apart: Talos' heel read -0.24 µm). Under feedforward servos the
test biped keeps 39–44 mm of its 45 mm half-width in single support and Talos 54 of 55 mm;
under position servos 25–27 mm and 48 mm (asked only for the balance controller's change,
without the plan's torque, both rode an edge, their soles off the ground in 18–39 % of the
stance samples: :mod:`hexaleg.simulation.balance`, "Deflection")."""
EDGES: tuple[str, str, str, str] = ("toe", "heel", "left", "right")
"""The sole's edges, named in its own axes: the toe at +x (the heading), the left side at +y."""


@dataclass(frozen=True)
class CopMargin:
    """The smallest distance of a planted sole's centre of pressure to the sole's edge over a
    run's evaluated window (module docstring).

    Attributes:
        distance: The margin, m (0 — or a rounding of a micrometre below, the contact points
            and the corners being computed apart — on the edge; half the sole's width at
            most).
        leg: The leg whose sole it was.
        edge: The nearest edge then, one of :data:`EDGES`.
        time: When, s from the start of the run.
        load: The sole's normal load then, N.
    """

    distance: float
    leg: str
    edge: str
    time: float
    load: float


def tipping(margin: CopMargin | None) -> str | None:
    """Why a run on soles "tipped" (its single-support margin, the second of
    :func:`cop_margins`, under :data:`TIP_MARGIN`: the robot rotated about its one sole's
    edge), or None when it kept off the edges (or has no soles, or no single support)."""
    if margin is None or margin.distance >= TIP_MARGIN:
        return None
    return (f"in single support the {margin.leg} sole's centre of pressure reached its "
            f"{margin.edge} edge at t = {margin.time:.4f} s "
            f"({max(margin.distance, 0.0) * 1e3:.2f} mm from it, bound {TIP_MARGIN * 1e3:g} mm, "
            f"{margin.load:.1f} N on the sole): the robot rolled about the edge instead of "
            "standing on the sole")


def inner_stance(motion: Motion) -> np.ndarray:
    """Per plan sample and leg, whether the leg is in stance and not within
    :data:`~hexaleg.simulation.measures.LOSS_GRACE` of its stance's start or end (periodic:
    a stance over the cycle's end is one), shape (T, n_legs), bool."""
    stance = motion.stance.astype(bool)
    n, out = len(stance), np.zeros_like(stance)
    for leg in range(stance.shape[1]):
        s = stance[:, leg]
        if s.all():
            out[:, leg] = True
            continue
        swing = int(np.flatnonzero(~s)[0])  # rolled to start in swing: no stance is cut
        edges = np.flatnonzero(np.diff(np.r_[0, np.roll(s, -swing).astype(int), 0]))
        for a, b in zip(edges[::2], edges[1::2], strict=True):
            grace = int(np.ceil(LOSS_GRACE * (b - a)))
            out[(np.arange(a + grace, b - grace) + swing) % n, leg] = True
    return out


def cop_margins(sim: SimModel, motion: Motion, traj: Trajectory, window: slice,
                samples: int = PRESSURE_SAMPLES) -> tuple[CopMargin | None, CopMargin | None]:
    """The smallest centre-of-pressure margins of the robot's soles over the planned stances
    (:func:`inner_stance`) of ``window``, from the corner contact forces
    (``mj_contactForce``'s normal component) at the recorded states, in one pass: over every
    planted sole, and over the single supports alone.

    The second is the robot's own margin: in a single support (a sole the plan has as the only
    foot on the ground) the sole's centre of pressure is the whole robot's ZMP, and on the
    sole's edge the robot rotates about it (Vukobratović & Borovac 2004). In a double support
    a lightly loaded sole may roll onto an edge while the other carries the body (the test
    biped's heel, 27 N of its 161 N, under position servos): the first margin counts it, the
    second does not. The single supports are among the same sampled steps, so the second is
    never below the first.

    Args:
        sim: The model.
        motion: The plan (its stances).
        traj: The run.
        window: The evaluated steps.
        samples: Steps looked at, at most (≥ 1).

    Returns:
        ``(every stance, single supports)``: each a margin, or None for a robot without soles
        (or whose planted soles carried no load at the steps looked at; the second also where
        the plan has no single support there).
    """
    import mujoco

    robot, m = sim.robot, sim.model
    soles = [i for i, leg in enumerate(robot.legs) if leg.name in robot.soles]
    if not soles:
        return None, None
    sites = {i: [mujoco.mj_name2id(m, mujoco.mjtObj.mjOBJ_SITE,
                                   corner_site(robot.legs[i].name, j)) for j in range(4)]
             for i in soles}
    leg_of = {int(g): i for i in soles for g in sim.foot_contacts[i]}
    rows = np.arange(window.start or 0, window.stop or traj.n)
    rows = rows[np.unique(np.linspace(0, len(rows) - 1, min(samples, len(rows))).astype(int))]
    k = planned_index(motion, traj.t[rows])
    planted = inner_stance(motion)[k]
    single = motion.stance[k].astype(bool).sum(axis=1) == 1
    wrench = np.zeros(6)
    best: CopMargin | None = None
    alone: CopMargin | None = None
    for row, on, one, data in zip(rows, planted, single, forward_states(sim, traj, rows),
                                  strict=True):
        load = np.zeros(len(robot.legs))
        moment = np.zeros((len(robot.legs), 3))
        con = data.contact
        for c in range(data.ncon):
            g1, g2 = int(con.geom[c][0]), int(con.geom[c][1])
            i = leg_of.get(g2, leg_of.get(g1, -1))
            if i < 0 or con.efc_address[c] < 0:
                continue
            mujoco.mj_contactForce(m, data, c, wrench)
            load[i] += wrench[0]
            moment[i] += wrench[0] * con.pos[c]
        for i in soles:
            if not on[i] or load[i] <= 0:
                continue
            corners = data.site_xpos[sites[i]]  # front left, front right, back left, back right
            offset = moment[i] / load[i] - corners.mean(axis=0)
            along, across = corners[0] - corners[2], corners[0] - corners[1]
            u = float(offset @ along) / float(np.linalg.norm(along))
            v = float(offset @ across) / float(np.linalg.norm(across))
            ends = float(np.linalg.norm(along)) / 2 - abs(u)
            sides = float(np.linalg.norm(across)) / 2 - abs(v)
            toe, heel, left, right = EDGES
            distance, edge = ((ends, toe if u > 0 else heel) if ends <= sides
                              else (sides, left if v > 0 else right))
            if best is None or distance < best.distance:
                best = CopMargin(distance, robot.legs[i].name, edge, float(traj.t[row]),
                                 float(load[i]))
            if one and (alone is None or distance < alone.distance):
                alone = CopMargin(distance, robot.legs[i].name, edge, float(traj.t[row]),
                                  float(load[i]))
    return best, alone
