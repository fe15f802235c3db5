"""Benchmark of the core analysis: time per stiffness choice, every regime, against fair peers.

Run:  python analysis/bench_core.py [--samples 1000] [--designs 20] [--peer-samples 100]
      (the peers need the bench extra: pip install -e ".[bench]")

Prints, in one run on the default tripod gait (femur springs, the stiffness swept over
``--designs`` values as a sweep does):

1. ``Prepared.evaluate`` per stiffness choice in each regime of issue #15's table and a few more,
   with how its samples were certified (the last design's active sets, repaired, or the interior
   point), as milliseconds and as a ratio to a plain Pinocchio RNEA loop over the samples,
   timed again right after each regime (the machine's speed drifts).
2. The peers a user would write instead, per stiffness choice at the same sample count (each
   measured on ``--peer-samples`` samples and scaled), as ratios to this solver: cvxpy with
   parameters (DPP, compiled once) per sample; per-sample ProxSuite and OSQP dense/sparse QPs,
   set up once and warm-started (TSID-style; the friction pyramid, the Joule objective — QP
   solvers take no cone); the whole cycle stacked in one cvxpy program. With the largest force
   difference to this solver.
3. Scaling: time per stiffness choice and per sample over 250 … 16000 samples.

Times are process CPU time, best of ``--repeat`` runs (another process on the machine slows
both sides alike; the ratios are what to compare), with one BLAS thread (below).
"""

from __future__ import annotations

import argparse
import os

# One BLAS thread: on 16000 samples the metrics' matrix-vector products wake OpenBLAS's threads,
# which spin on the second core without shortening the wall time (measured: 18.5 ms wall either
# way) and so double the process CPU time this benchmark reads. Set before NumPy loads BLAS.
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

import time
import warnings

import numpy as np

import hexaleg
from hexaleg.dynamics.conic import base_row_space
from hexaleg.dynamics.contact import ContactParams
from hexaleg.dynamics.prepare import prepare
from hexaleg.dynamics.reference import solve_reference

REGIMES = [  # (objective, μ, cone): the table first
    ("joule", 0.6, "soc"), ("joule", 0.3, "soc"), ("joule", 0.25, "soc"),
    ("electrical", 0.6, "soc"), ("positive_work", 0.6, "soc"),
    ("joule", 0.25, "pyramid"), ("electrical", 0.3, "soc"), ("positive_work", 0.3, "soc")]


def _best(fn, repeat: int) -> float:
    times = []
    for _ in range(repeat):
        t0 = time.process_time()
        fn()
        times.append(time.process_time() - t0)
    return min(times)


def _designs(robot, n):
    return [{leg.joint_names[1]: hexaleg.DeadZoneSpring(stiffness=k, theta_k=0.1, neutral=0.5)
             for leg in robot.legs} for k in np.linspace(0.2, 3.0, n)]


def rnea_loop(robot, motion) -> None:
    """A plain RNEA loop over the motion's samples (what "faster than inverse dynamics" means)."""
    import pinocchio as pin

    model, data = robot.model, robot.model.createData()
    for k in range(motion.n_samples):
        pin.rnea(model, data, motion.q[k], motion.v[k], motion.a[k])


def sweep_time(robot, motion, objective, mu, cone, designs, repeat):
    """Per stiffness choice: Prepared.evaluate over the designs, each from the last's active
    sets (the baseline's for the first), best of ``repeat`` passes."""
    prepared = prepare(robot, motion, contact=ContactParams(mu=mu, cone=cone))
    t0 = time.process_time()
    prepared.evaluate(None, objective)  # prepares the baseline (cold)
    cold = time.process_time() - t0

    def run():
        prepared.reset_warm_start(objective)
        for springs in designs:
            prepared.evaluate(springs, objective)

    best = _best(run, repeat) / len(designs)
    prepared.reset_warm_start(objective)
    stats = prepared._warm[objective].stats
    base = (stats.guessed, stats.repaired, stats.interior)
    for springs in designs:
        prepared.evaluate(springs, objective)
    counts = [a - b for a, b in zip((stats.guessed, stats.repaired, stats.interior), base,
                                    strict=True)]
    return prepared, best, cold, counts


# --------------------------------------------------------------------------- peers


class _QP:
    """One sample's Joule QP with the friction pyramid and torque limits, on its stance columns:
    minimise ½ fᵀ H f + gᵀ f, A f = b, l ≤ C f ≤ u (g, l, u depend on the springs)."""

    def __init__(self, system, k, weights, contact):
        cols = np.flatnonzero(np.repeat(system.stance[k], 3))
        self.cols, self.k = cols, k
        D = system.D[k][:, cols]
        self.D, self.w = D, weights
        self.H = 2 * D.T @ (weights[:, None] * D)
        self.A, self.b = base_row_space(system, k, system.A[k][:, cols])
        n = cols.size
        s = contact.mu / np.sqrt(2)
        rows = []
        for i in range(n // 3):
            for sign, axis in ((-1, 0), (1, 0), (-1, 1), (1, 1)):
                r = np.zeros(n)
                r[3 * i + 2], r[3 * i + axis] = s, sign
                rows.append(r)
        self.P = np.array(rows)  # pyramid: P f ≥ 0
        self.C = np.vstack([self.P, D])
        self.tmax = system.tau_max

    def data(self, c):
        g = -2 * self.D.T @ (self.w * c)
        m = self.P.shape[0]
        lower = np.concatenate([np.zeros(m), c - self.tmax])
        upper = np.concatenate([np.full(m, 1e20), c + self.tmax])
        return g, lower, upper


def proxsuite_peer(prepared, tau_list, rows):
    """Per-sample ProxSuite dense QPs, set up once, warm-started by ``update`` (TSID-style)."""
    import proxsuite

    sys = prepared.system
    w = prepared.weights("joule")
    qps, solvers = [], []
    for k in rows:
        q = _QP(sys, k, w, prepared.contact)
        g, lo, up = q.data(sys.b_joint[k] - tau_list[0][k])
        solver = proxsuite.proxqp.dense.QP(q.H.shape[0], q.A.shape[0], q.C.shape[0])
        solver.settings.eps_abs = 1e-9
        solver.settings.verbose = False
        solver.init(q.H, g, q.A, q.b, q.C, lo, up)
        qps.append(q)
        solvers.append(solver)
    out = np.zeros((len(rows), sys.A.shape[2]))

    def run():
        for tau_s in tau_list:
            for i, (q, solver) in enumerate(zip(qps, solvers, strict=True)):
                g, lo, up = q.data(sys.b_joint[q.k] - tau_s[q.k])
                solver.update(g=g, l=lo, u=up)
                solver.solve()
                out[i, q.cols] = solver.results.x

    return run, out


def osqp_peer(prepared, tau_list, rows):
    """Per-sample OSQP QPs, set up once, warm-started by ``update`` (polished, 1e-9)."""
    import osqp
    import scipy.sparse as sp

    sys = prepared.system
    w = prepared.weights("joule")
    items = []
    for k in rows:
        q = _QP(sys, k, w, prepared.contact)
        g, lo, up = q.data(sys.b_joint[k] - tau_list[0][k])
        A = sp.csc_matrix(np.vstack([q.A, q.C]))
        solver = osqp.OSQP()
        solver.setup(sp.csc_matrix(np.triu(q.H)), g, A, np.concatenate([q.b, lo]),
                     np.concatenate([q.b, up]), verbose=False, eps_abs=1e-9, eps_rel=1e-9,
                     polishing=True, max_iter=20000)
        items.append((q, solver))
    out = np.zeros((len(rows), sys.A.shape[2]))

    def run():
        for tau_s in tau_list:
            for i, (q, solver) in enumerate(items):
                g, lo, up = q.data(sys.b_joint[q.k] - tau_s[q.k])
                solver.update(q=g, l=np.concatenate([q.b, lo]), u=np.concatenate([q.b, up]))
                out[i, q.cols] = solver.solve().x

    return run, out


def stacked_peer(prepared, tau_list, rows):
    """The samples ``rows`` stacked in one cvxpy program (DPP: the spring torques a parameter),
    the friction pyramid, Joule objective; solved with Clarabel per stiffness choice."""
    import cvxpy as cp

    sys = prepared.system
    w = prepared.weights("joule")
    qs = [_QP(sys, k, w, prepared.contact) for k in rows]
    fs = [cp.Variable(q.H.shape[0]) for q in qs]
    cs = [cp.Parameter(sys.D.shape[1]) for _ in qs]
    cost = sum(cp.sum(cp.multiply(w, cp.square(c - q.D @ f)))
               for q, f, c in zip(qs, fs, cs, strict=True))
    cons = []
    for q, f, c in zip(qs, fs, cs, strict=True):
        cons += [q.A @ f == q.b, q.P @ f >= 0, q.D @ f >= c - q.tmax, q.D @ f <= c + q.tmax]
    problem = cp.Problem(cp.Minimize(cost), cons)
    out = np.zeros((len(rows), sys.A.shape[2]))

    def run():
        for tau_s in tau_list:
            for q, c in zip(qs, cs, strict=True):
                c.value = sys.b_joint[q.k] - tau_s[q.k]
            problem.solve(solver=cp.CLARABEL)
            for i, (q, f) in enumerate(zip(qs, fs, strict=True)):
                out[i, q.cols] = f.value

    for q, c in zip(qs, cs, strict=True):  # compile once, outside the timing
        c.value = sys.b_joint[q.k] - tau_list[0][q.k]
    problem.solve(solver=cp.CLARABEL)
    return run, out


def peers(robot, motion, designs, args, t_rnea):
    print(f"\n2. peers per stiffness choice at {motion.n_samples} samples (measured on "
          f"{args.peer_samples} samples, scaled), the Joule objective:")
    rows = np.linspace(0, motion.n_samples - 1, args.peer_samples).astype(int)
    scale = motion.n_samples / rows.size
    few = designs[:: max(1, len(designs) // 4)]
    for mu, cone in ((0.6, "pyramid"), (0.25, "pyramid"), (0.3, "soc")):
        prepared, t_ours, _, _ = sweep_time(robot, motion, "joule", mu, cone, designs,
                                            args.repeat)
        tau_list = [prepared.spring_torques(s) for s in few]
        prepared.reset_warm_start("joule")
        ours = [prepared.solve(t, "joule")[0].reshape(motion.n_samples, -1) for t in tau_list]
        print(f"   μ = {mu} {cone}: this solver {t_ours * 1e3:.2f} ms "
              f"({t_ours / t_rnea:.2f}× RNEA)")
        makers = [("cvxpy DPP per sample", None)]
        if cone == "pyramid":
            makers += [("ProxSuite per sample", proxsuite_peer), ("OSQP per sample", osqp_peer),
                       ("stacked cvxpy program", stacked_peer)]
        for name, maker in makers:
            try:
                if maker is None:
                    def run(p=prepared, t=tau_list):
                        for tau_s in t:
                            solve_reference(p.system, tau_s, "joule", p.weights("joule"),
                                            p.contact, samples=rows)
                    t = _best(run, 1) / len(few) * scale
                    f_peer = solve_reference(prepared.system, tau_list[-1], "joule",
                                             prepared.weights("joule"), prepared.contact,
                                             samples=rows)[rows]
                else:
                    run, out = maker(prepared, tau_list, rows)
                    t = _best(run, 1) / len(few) * scale
                    f_peer = out
            except ImportError as e:
                print(f"     {name:24s} not installed ({e.name}; pip install -e \".[bench]\")")
                continue
            diff = np.max(np.abs(f_peer - ours[-1][rows]))
            print(f"     {name:24s} {t * 1e3:9.1f} ms  = {t / t_ours:7.0f}× this solver; "
                  f"max |Δf| {diff:.1e} N")


def scaling(robot, args, t_rnea_per_sample):
    print("\n3. scaling, per stiffness choice (20 designs, warm starts):")
    print("   samples   joule μ = 0.6               joule μ = 0.3")
    per: dict[tuple[float, int], float] = {}
    for n in (250, 1000, 4000, 16000):
        motion = hexaleg.gait(robot, hexaleg.GaitParams(samples=n))
        cells = []
        for mu in (0.6, 0.3):
            _, t, _, _ = sweep_time(robot, motion, "joule", mu, "soc", _designs(robot, 20),
                                    args.repeat)
            per[mu, n] = t / n
            cells.append(f"{t * 1e3:9.2f} ms {t / n * 1e6:5.2f} µs/sample")
        print(f"   {n:7d}   {cells[0]}   {cells[1]}")
    for mu in (0.6, 0.3):
        print(f"   μ = {mu}: cost per sample at 16000 / at 1000 = "
              f"{per[mu, 16000] / per[mu, 1000]:.2f}")
    print(f"   (RNEA: {t_rnea_per_sample * 1e6:.2f} µs/sample)")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--samples", type=int, default=1000)
    parser.add_argument("--designs", type=int, default=20)
    parser.add_argument("--peer-samples", type=int, default=100)
    parser.add_argument("--repeat", type=int, default=7)
    parser.add_argument("--skip", nargs="*", default=[], choices=["peers", "scaling"])
    args = parser.parse_args()
    warnings.filterwarnings("ignore", category=UserWarning)

    robot = hexaleg.load()
    motion = hexaleg.gait(robot, hexaleg.GaitParams(samples=args.samples))
    designs = _designs(robot, args.designs)
    t_rnea = _best(lambda: rnea_loop(robot, motion), 5)
    t_prep = _best(lambda: prepare(robot, motion), 3)
    print(f"default tripod gait, {motion.n_samples} samples per cycle, femur springs, "
          f"{len(designs)} stiffness choices")
    print(f"RNEA loop over the samples: {t_rnea * 1e3:.2f} ms; prepare (once per motion): "
          f"{t_prep * 1e3:.1f} ms")
    print("\n1. Prepared.evaluate per stiffness choice (the last design's active sets as the "
          "guess):")
    print("   regime                          ms   RNEA ms  × RNEA   first (cold) ms   samples"
          " certified by: guess / repairs / interior point")
    for objective, mu, cone in REGIMES:
        _, t, cold, counts = sweep_time(robot, motion, objective, mu, cone, designs,
                                        args.repeat)
        # The RNEA loop again, right after: the machine's speed drifts between regimes.
        here = _best(lambda: rnea_loop(robot, motion), 5)
        print(f"   {objective:13s} μ = {mu:<4} {cone:7s} {t * 1e3:7.2f} {here * 1e3:7.2f} "
              f"{t / here:7.2f}   {cold * 1e3:9.1f}           {counts[0]} / {counts[1]} / "
              f"{counts[2]}")
    if "peers" not in args.skip:
        peers(robot, motion, designs, args, t_rnea)
    if "scaling" not in args.skip:
        scaling(robot, args, t_rnea / motion.n_samples)


if __name__ == "__main__":
    main()
