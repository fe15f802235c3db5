"""The design answer for hexaleg's default robot and gait: ``hexaleg design`` with its defaults.

Run:  python analysis/answer_hexaleg.py   (expected output: analysis/logs/answer_hexaleg.log)

The default tripod gait at 200 samples per cycle, the robot's own actuator (AX-18A), forces of
minimum Joule loss. Every allowed family's globally optimal springs on coxa, femur and tibia
(one design per class, max wind-up π), ranked by the electrical energy the servos draw, net of
the springs' mass; the recommended family's Pareto front (spring torque bounded); the torsion
springs to buy (Shigley §10-12); the robustness maps of the recommended springs frozen; the
robust design over the box period ×0.75…1.5, stride ×0.75…1.25, payload 0…25 %, μ 0.5…1; the
recommendation simulated forward in MuJoCo under both controllers (predicted / simulated);
every ranked design simulated under the default servo, the recommendation designed for its stops
mounted within ±1°, each part checked over its whole envelope and for fatigue, and where each
spring mounts on each joint (joint angles from the joint's zero, as docs/design.md quotes them),
the fold into the sphere and back with the springs and without, and the story of the numbers a
user meets for this gait (design.html's table, docs/design.md).
"""

from __future__ import annotations

import numpy as np

from hexaleg.design.chain.chain import DesignChain
from hexaleg.design.chain.ranking import under
from hexaleg.design.chain.result import mounting_data, story_data


def pct(x: float) -> str:
    return f"{100 * x:+7.2f} %" if np.isfinite(x) else "    n/a"


def magnitude(v: float) -> str:
    """A spring magnitude (N·m/rad or N·m) to 4 digits; one under 1e-12, the convex solver's
    rounding about zero (its sign and digits change with the last bit of the inputs), as 0."""
    return "0" if abs(v) < 1e-12 else f"{v:.4g}"


def tick(axis: str, value: object) -> str:
    """A map axis value as printed: a pattern's name, a slope in degrees, else the number."""
    if isinstance(value, str):
        return value
    return f"{np.degrees(float(value)):+g}°" if axis == "slope" else f"{float(value):g}"


def main() -> None:
    r = DesignChain().run()
    m = r.design.metric
    print(f"{r.title}, {r.mass:.3f} kg, {r.actuator}; gait period {r.gait.period:g} s, "
          f"stride {r.gait.stride:g} m, {r.gait.samples} samples")
    print(f"without springs: {m} {r.baseline[m]:.4f} J, joule {r.baseline['joule']:.4f} J "
          "per cycle")
    print(f"\nfamilies ranked by {m} saving net of the springs' mass")
    print(f"  {'design':12s} {m:>10s} {'net':>10s} {'joule':>10s} {'springs':>8s}  buildable")
    for c in r.candidates:
        print(f"  {c.label:12s} {pct(c.row[f'saving.{m}'])} {pct(c.net[m])} "
              f"{pct(c.row['saving.joule'])} {1e3 * c.spring_mass:6.1f} g  "
              f"{'yes' if c.buildable else 'no'}")
    print(f"\nPareto front of {r.recommended.family} (spring torque bounded)")
    print(f"  {'bound':>10s} {'peak τ_s':>9s} {'peak U':>8s} {m:>10s} {'net':>10s} {'joule':>10s}")
    for f, c in r.pareto:
        a = c.optimum.analysis
        mark = "  <- recommended" if c is r.recommended else ""
        print(f"  {f:8.2f} × {np.abs(a.tau_spring).max():7.4f} {1e3 * a.spring_energy.max():6.2f}mJ"
              f" {pct(c.row[f'saving.{m}'])} {pct(c.net[m])} {pct(c.row['saving.joule'])}{mark}")
    print(f"\nevery design simulated under {under(r.design.controller)} ({m} saving)")
    print(f"  {'design':40s} {'servo':11s} {'predicted':>10s} {'simulated':>10s} "
          f"{'sim. net':>10s}")
    for row in r.ranking:
        sim = pct(row.simulated) if row.simulated is not None else f"{row.verdict:>10s}"
        flag = "  under half the prediction" if row.flagged else ""
        print(f"  {row.candidate.label:40s} {row.controller:11s} {pct(row.predicted)} {sim} "
              f"{pct(row.net)}{flag}")
    t = r.tolerance
    if t is not None:
        print(f"\nstops mounted within ±{np.degrees(t.tolerance):g}° ({m} saving): nominal / worst")
        for name in ("tolerant", "blind"):
            print(f"  {name:9s} {pct(t.nominal[name])} / {pct(t.worst[name])}")
    rec = r.recommended
    print(f"\nrecommended: {rec.label}; {m} {pct(rec.row[f'saving.{m}'])}, net "
          f"{pct(rec.net[m])} ({1e3 * rec.spring_mass:.1f} g of springs)")
    for g, share in rec.marginal.items():
        print(f"  {g:6s} lost without it {pct(share)}   "
              + ", ".join(f"{k} {magnitude(v)}" for k, v in rec.optimum.magnitudes[g].items()))
    print("\nsprings to buy (one per joint of the group)")
    for p in rec.parts:
        s = p.spring
        if s is None:
            print(f"  {p.group:6s} {p.side:5s} {p.role}: {p.problem}")
            continue
        print(f"  {p.group:6s} {p.side:5s} needs {p.rate:.4f} N·m/rad -> {s.material} "
              f"d {1e3 * s.wire_diameter:.2f} mm, D {1e3 * s.mean_diameter:.2f} mm, OD "
              f"{1e3 * s.outer_diameter:.2f} (≤ {1e3 * p.max_outer_diameter:.0f}) mm, "
              f"{s.body_turns:g} turns, legs {1e3 * s.leg_length:.1f} mm, "
              f"{s.table()['rate_nmm_per_deg']['value']:.4f} N·mm/deg, preload "
              f"{np.degrees(s.preload_angle):.0f}°, wind-up {np.degrees(s.max_deflection):.0f}°,"
              f" σ {s.stress / 1e6:.0f}/{s.yield_strength / 1e6:.0f} MPa, {1e3 * s.mass:.2f} g")
    for g, share in rec.dropped.items():
        print(f"  {g:6s} not fitted: it would add {pct(share)} (under the "
              f"{100 * r.design.min_group_saving:g} point bar)")
    print(f"\nwhole envelope (design factor {r.design.safety_factor:g}) and fatigue at "
          f"{r.design.life_cycles:.0e} cycles")
    for e, (p, f) in zip(r.envelope, r.fatigue, strict=True):
        stop = ("no stop needed" if e.stop is None else
                f"hard stop at {np.degrees(e.stop.angle_from_centre):+.1f}° from the centre, "
                f"holding {e.stop.torque:.4f} N·m")
        print(f"  {p.group:6s} {p.side:5s} worst S_y/σ {e.safety_factor:.2f} ({e.source}); "
              f"{stop}; fatigue n_f {f.safety_factor:.2f}")
    print("\nwhere to mount them: joint angles from each joint's zero (from its centre of motion)")
    for e in mounting_data(r):
        deg = {k: f"{np.degrees(e[k]['value']):+.1f}°" if e[k] else "—"
               for k in ("centre", "contact", "contact_from_centre", "free", "hard_stop")}
        print(f"  {e['joint']:9s} {e['side']:5s} centre {deg['centre']:>7s}, spring stop "
              f"{deg['contact']:>7s} ({deg['contact_from_centre']}), free leg {deg['free']:>7s}, "
              f"hard stop {deg['hard_stop']}")
    if r.fold is not None:
        print("\nthe fold into the sphere and back, electrical J with the springs / without")
        for w in r.fold.ways:
            print(f"  {w.label}  {w.electrical:.3f} / {w.baseline:.3f}, torque "
                  f"{w.torque_share:.3f} / {w.baseline_share:.3f} of the limit")
        be = r.fold.break_even
        print("  the springs pay for a fold out and back after "
              + (f"{be:.2f} m of walking" if be is not None else "— (they save nothing)"))
    for mp in r.maps:
        a, b = mp.axes
        print(f"\n{m} saving of the recommended springs, % ({a} down, {b} across)")
        print("  " + " " * 8 + "".join(f"{tick(b, v):>8s}" for v in mp.values[1]))
        for v, row in zip(mp.values[0], mp.saving[m], strict=True):
            print(f"  {tick(a, v):>8s}" + "".join(f"{100 * x:8.1f}" for x in row))
        w, where = mp.worst(m)
        print(f"  worst {pct(w)} at {where.label() if where else '—'}")
    rb = r.robust
    if rb is not None:
        d = rb.design
        print(f"\nrobust design ({d.mode} {d.metric} saving over {len(rb.conditions)} conditions)")
        for metric in ("electrical", "joule"):
            print(f"  worst {metric:10s}: robust {pct(rb.worst(metric))}, nominal "
                  f"{pct(rb.worst(metric, 'nominal'))}")
        for g in d.groups:
            print(f"  {g:6s} " + ", ".join(f"{k} {magnitude(v)}"
                                           for k, v in d.magnitudes[g].items()))

    print("\nthe recommendation simulated in MuJoCo "
          "(electrical J per cycle, predicted / simulated)")
    print(f"  {'controller':17s} {'with springs':>15s} {'without':>15s} {'saving':>19s} "
          f"{'distance':>9s}  tracking RMS")
    for row in r.simulation:
        if row["simulated"] is None:
            print(f"  {row['label']:17s} {row['verdict']}")
            continue
        print(f"  {row['label']:17s} {row['predicted_electrical']:.4f} / {row['electrical']:.4f}"
              f" {row['predicted_baseline']:.4f} / {row['baseline']:.4f} "
              f"{pct(row['predicted'])} / {pct(row['simulated'])} "
              f"{1e3 * row['distance_per_cycle']:6.2f} mm  {1e3 * row['tracking_rms']:.2f} mrad")

    print(f"\none gait, several numbers ({m} saving): what each is")
    for row in story_data(r):
        value = row["saving"]["value"] if row["saving"] else float("nan")
        print(f"  {value:+7.2f} %  {row['figure']}: {row['why']}")


if __name__ == "__main__":
    main()
