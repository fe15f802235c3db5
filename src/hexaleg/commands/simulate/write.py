"""``simulate.json``, ``simulate.md`` and ``simulate.html``: a simulation beside the analysis'
prediction.

Every number in the JSON is a quantity ``{"value", "unit"}``
(:func:`hexaleg.quantities.quantity`); ``predicted`` and ``simulated`` each hold
``electrical`` and ``joule`` (with the springs, the baseline without, the saving in %) and the
headline ``saving`` (of the electrical energy, the metric designs are ranked by). The page
(``simulate.md``) shows the same with the walk's measures: distance against the plan, body drift,
foot slip, contact losses, tracking, foot forces.
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import numpy as np

from hexaleg.config import write_file
from hexaleg.design.chain.design_file import design_table
from hexaleg.errors import OutputError
from hexaleg.outputs.html import render_simulate_html
from hexaleg.quantities import comparison, file_data, json_text, quantity
from hexaleg.simulation import balance, foot_placement
from hexaleg.simulation.result import Run, Simulation
from hexaleg.simulation.sensitivity import sensitivity_row

METRICS: tuple[str, ...] = ("electrical", "joule")
"""The energies compared (J per cycle)."""


def _run_data(r: Run) -> dict[str, Any]:
    """One run's verdict and measures."""
    out: dict[str, Any] = {"verdict": r.verdict, "message": r.message,
                           "realtime_factor": quantity(r.realtime_factor, "1"),
                           "cpu_share": quantity(r.cpu_share, "1"),
                           "feedback": r.feedback,
                           "feedback_constrained": quantity(100 * r.constrained, "%")}
    if r.walk is None:
        return out
    w = r.walk
    out.update({
        "distance_per_cycle": quantity(w.distance_per_cycle, "m"),
        "height_drift": quantity(w.height_drift, "m"),
        "roll_max": quantity(w.roll_max, "rad"), "pitch_max": quantity(w.pitch_max, "rad"),
        "tracking_rms": quantity(w.tracking_rms, "rad"),
        "tracking_max": quantity(w.tracking_max, "rad"),
        "tracking_rms_joint": quantity(w.tracking_rms_joint, "rad"),
        "slip_max": quantity(w.slip_max, "m"), "slip_mean": quantity(w.slip_mean, "m"),
        "contact_losses": quantity(100 * w.contact_losses, "%"),
        "stances": quantity(w.stances, "1"),
        "electrical_per_cycle": quantity([c["total"]["electrical"] for c in r.cycles], "J"),
        "forces": {k: quantity(v, "N") for k, v in r.forces.items()},
    })
    for key, c in (("cop_margin", r.cop_margin), ("alone_margin", r.alone_margin)):
        if c is not None:
            out[key] = {"distance": quantity(c.distance, "m"), "leg": c.leg, "edge": c.edge,
                        "time": quantity(c.time, "s"), "load": quantity(c.load, "N")}
    return out


def cop_text(margin: dict[str, Any]) -> str:
    """A run's ``cop_margin`` in words, as the pages print it."""
    return (f"{_v(margin['distance'], 1e3)} mm from the {margin['leg']} sole's "
            f"{margin['edge']} edge at {_v(margin['time'], digits=4)} s "
            f"({_v(margin['load'], digits=4)} N on it)")


def _energies(values: dict[str, tuple[float, float, float]]) -> dict[str, Any]:
    out: dict[str, Any] = {m: comparison(*values[m], "J") for m in METRICS}
    out["saving"] = quantity(100 * values["electrical"][2], "%")
    return out


def simulation_data(s: Simulation, *, design: str = "", notes: tuple[str, ...] = (),
                    sensitivity: list[dict[str, Any]] | None = None,
                    warnings: tuple[str, ...] = (),
                    gait_defaults: dict[str, Any] | None = None) -> dict[str, Any]:
    """The content of ``simulate.json`` (module docstring).

    Args:
        s: The simulation.
        design: Where the springs came from (a file, or the optimal design).
        notes: Caveats to record.
        sensitivity: Rows of :func:`hexaleg.simulation.sensitivity.sensitivity`, or None.
        warnings: The run's warnings (:func:`hexaleg.scenario.run_warnings.run_warnings`).
        gait_defaults: What the sized gait defaults chose
            (:func:`hexaleg.scenario.run_warnings.gait_defaults`), or None.
    """
    st, sim = s.settings, s.with_springs.sim
    predicted = {m: s.predicted(m) for m in METRICS}
    data: dict[str, Any] = {
        "robot": s.robot.name, "verdict": "walks" if s.walks else "did not walk",
        "controller": st.controller, "design": design,
        "springs": design_table(s.springs)["springs"],
        "predicted": _energies(predicted),
        "planned_distance_per_cycle": quantity(s.motion.distance, "m"),
        "realtime_factor": quantity(_realtime(s), "1"),
        "timing": timing_data(s),
        "settings": {
            "timestep": quantity(sim.timestep, "s"), "cycles": st.cycles,
            "evaluated_cycles": st.evaluate,
            "ground": {"stiffness": quantity(sim.ground.stiffness, "N/m"),
                       "damping": quantity(sim.ground.damping, "N·s/m"),
                       "mu": quantity(sim.ground.mu, "1"), "noslip": sim.ground.noslip,
                       "incline": quantity(sim.ground.incline, "rad")},
            "servo": {"kp": quantity(sim.kp, "N·m/rad"), "kd": quantity(sim.kd, "N·m·s/rad"),
                      "back_emf_damping": quantity(sim.damping, "N·m·s/rad"),
                      "stall_torque": quantity(sim.stall, "N·m")}},
        "feedback": feedback_data(s),
        "runs": {"springs": _run_data(s.with_springs), "baseline": _run_data(s.baseline)},
        "warnings": list(warnings), "gait_defaults": gait_defaults,
        "notes": [*notes, *sim.notes],
    }
    if sensitivity is not None:
        data["sensitivity"] = [sensitivity_row(r) for r in sensitivity]
    if s.walks:
        simulated = {m: s.simulated(m) for m in METRICS}
        data["simulated"] = _energies(simulated)
        data["distance_per_cycle"] = data["runs"]["springs"]["distance_per_cycle"]
        data["difference"] = {
            "saving": quantity(100 * (simulated["electrical"][2] - predicted["electrical"][2]),
                               "percentage points"),
            **{f"{m}_{which}": quantity(100 * (simulated[m][i] / predicted[m][i] - 1), "%")
               for m in METRICS for i, which in ((0, "springs"), (1, "baseline"))}}
    return file_data(data)


def feedback_data(s: Simulation) -> dict[str, Any]:
    """Which controller closed the loop on the body: the setting (``[simulate] feedback``),
    whether the balance controller ran in each run, its gains, and a sentence for the pages."""
    ran = {r.name: r.feedback for r in (s.with_springs, s.baseline)}
    setting = s.settings.feedback
    if not any(ran.values()):
        text = ("off: open loop, the servos track the plan alone"
                + (" (auto: the gait stands on three or more feet and did not fall)"
                   if setting == "auto" else ""))
    else:
        g = balance.size_gains(s.robot, s.motion)
        why = ("" if setting != "auto" else " (auto: the gait stands on fewer than three feet"
               " at times)" if balance.needed(s.motion) else " (auto: open loop fell)")
        text = (f"on{why}: the body's pose and velocity (MuJoCo's, a perfect estimator) fed "
                f"back at {1 / g.period:.0f} Hz, ω {g.omega:.3g} rad/s, "
                "stance forces by a QP within the friction cones and torque limits, swing feet "
                + ("set down at Raibert's neutral point from the measured hip and velocity"
                   if balance.needed(s.motion) and len(s.robot.soles) < len(s.robot.legs)
                   else "aimed at their planned footholds")
                + ", through the servos' references")
    out: dict[str, Any] = {"setting": setting, "runs": ran, "text": text}
    if any(ran.values()):
        g = balance.size_gains(s.robot, s.motion)
        out["gains"] = {"omega": quantity(g.omega, "rad/s"), "zeta": quantity(g.zeta, "1"),
                        "capture": quantity(g.capture, "s"),
                        "hold": quantity(foot_placement.HOLD, "1"),
                        "period": quantity(g.period, "s")}
    return out


def _realtime(s: Simulation) -> float:
    """Simulated time of both runs per wall-clock time of their stepping
    (:attr:`~hexaleg.simulation.run.Simulation.stepping_wall`: the two step at once)."""
    wall = s.stepping_wall
    simulated = s.with_springs.simulated_time + s.baseline.simulated_time
    return simulated / wall if wall > 0 else math.inf


BUSY = 0.9
"""A stepping thread that got less than this share of a core waited for other processes: its
wall-clock real-time factor measures the machine's load as much as the simulation."""


def timing_data(s: Simulation) -> dict[str, Any]:
    """What ``simulate.json``'s real-time factor counts, and what it leaves out.

    ``realtime_factor`` is the simulated time of both runs over the wall-clock time of their
    stepping (MuJoCo's steps, and closed loop the balance controller's updates), nothing else:
    the two runs step at once, each on a thread of its own
    (:func:`hexaleg.simulation.run.side_by_side`), so it is their union's wall time
    (``stepping_wall``), and two cores give up to twice one's factor; ``cpu_realtime_factor``
    the same over the stepping threads' CPU time (what one core gives, the runs one after the
    other); ``cpu_share`` each thread's CPU time over its own wall time (1 where each had a
    core, ½ where another process shared it); ``simulation_realtime_factor`` over the wall
    time of the whole :func:`hexaleg.simulation.run.simulate` (the analyses, the models'
    building, both runs and their measures). The command's imports, its inputs and the files it
    writes are in none of them.
    """
    runs = (s.with_springs, s.baseline)
    simulated = sum(r.simulated_time for r in runs)
    wall, cpu, walls = s.stepping_wall, sum(r.cpu for r in runs), sum(r.wall for r in runs)
    share = cpu / walls if walls > 0 else 1.0
    factor, per_cpu = _realtime(s), simulated / cpu if cpu > 0 else math.inf
    whole = simulated / s.wall if s.wall > 0 else math.inf
    text = (f"{factor:.3g}× real time: {simulated:.3g} s simulated (both runs, at once) in "
            f"{wall:.3g} s of stepping, {per_cpu:.3g}× per CPU second; the whole simulation "
            f"(analysis, models, runs, measures) {s.wall:.3g} s, {whole:.3g}× real time")
    if share < BUSY:
        text += (f"; each run's stepping got {share:.0%} of a core (the machine was busy)")
    return {"simulated_time": quantity(simulated, "s"), "stepping_wall": quantity(wall, "s"),
            "stepping_cpu": quantity(cpu, "s"), "cpu_share": quantity(share, "1"),
            "realtime_factor": quantity(factor, "1"),
            "cpu_realtime_factor": quantity(per_cpu, "1"),
            "simulation_wall": quantity(s.wall, "s"),
            "simulation_realtime_factor": quantity(whole, "1"), "text": text}


def _v(q: dict[str, Any], scale: float = 1.0, digits: int = 3) -> str:
    value = q["value"]
    return "—" if value is None else f"{value * scale:.{digits}g}"


def _pct(q: dict[str, Any]) -> str:
    """A saving as every page prints one: signed, two decimals."""
    return "—" if q["value"] is None else f"{q['value']:+.2f} %"


def page(data: dict[str, Any]) -> str:
    """``simulate.md``: the simulation's tables in Markdown."""
    lines = [f"# Forward simulation: {data['robot']}, {data['controller']} servo",
             "", f"Verdict: **{data['verdict']}**. Springs: {data['design']}.", "",
             f"Balance feedback: {data['feedback']['text']}.", "",
             f"Speed: {data['timing']['text']}.", ""]
    if "simulated" in data:
        lines += ["| per cycle | predicted | simulated |", "|---|---|---|"]
        for m in METRICS:
            for key, label in (("with_springs", f"{m} with springs (J)"),
                               ("baseline", f"{m} baseline (J)"), ("saving", f"{m} saving (%)")):
                lines.append(f"| {label} | {_v(data['predicted'][m][key], digits=4)} | "
                             f"{_v(data['simulated'][m][key], digits=4)} |")
        lines += ["", f"Distance per cycle: {_v(data['distance_per_cycle'], 1e3, 4)} mm "
                      f"(planned {_v(data['planned_distance_per_cycle'], 1e3, 4)} mm).", ""]
    lines += ["| run | verdict | tracking RMS / max (mrad) | slip max (mm) | contact losses (%) "
              "| height drift (mm) | roll / pitch max (°) | normal force RMS error (N) |",
              "|---|---|---|---|---|---|---|---|"]
    for name, r in data["runs"].items():
        if "tracking_rms" not in r:
            lines.append(f"| {name} | {r['verdict']}: {r['message']} | | | | | | |")
            continue
        lines.append(
            f"| {name} | {r['verdict']} | {_v(r['tracking_rms'], 1e3)} / "
            f"{_v(r['tracking_max'], 1e3)} | {_v(r['slip_max'], 1e3)} | "
            f"{_v(r['contact_losses'])} | {_v(r['height_drift'], 1e3)} | "
            f"{_v(r['roll_max'], float(np.degrees(1)))} / "
            f"{_v(r['pitch_max'], float(np.degrees(1)))} | "
            f"{_v(r['forces']['normal_rms']) if r['forces'] else '—'} |")
    margins = [f"{name}: {cop_text(r['cop_margin'])}"
               + (f", in single support {cop_text(r['alone_margin'])}" if "alone_margin" in r
                  else "") for name, r in data["runs"].items() if "cop_margin" in r]
    if margins:
        lines += ["", "Centre of pressure, closest to a sole's edge: " + "; ".join(margins) + "."]
    if "sensitivity" in data:
        lines += ["", "| variant | controller | verdict | predicted saving (%) | simulated saving "
                      "(%) | electrical / baseline (J) | distance (mm) | tracking RMS (mrad) |",
                  "|---|---|---|---|---|---|---|---|"]
        for r in data["sensitivity"]:
            sim = ("| — | — | — | — |" if "simulated_saving" not in r else
                   f"| {_v(r['simulated_saving'])} | {_v(r['electrical'], 1, 4)} / "
                   f"{_v(r['baseline'], 1, 4)} | {_v(r['distance_per_cycle'], 1e3, 4)} | "
                   f"{_v(r['tracking_rms'], 1e3)} |")
            lines.append(f"| {r['label']} | {r['controller'] or '—'} | {r['verdict']} | "
                         f"{_v(r['predicted_saving'])} {sim}")
    lines += ["", *(f"- warning: {w}" for w in data.get("warnings", ())),
              *(f"- note: {n}" for n in data["notes"])]
    return "\n".join(lines) + "\n"


def write_simulation(out: str | Path, data: dict[str, Any]) -> tuple[Path, Path, Path]:
    """Write ``simulate.json``, ``simulate.md`` and ``simulate.html`` (the same tables as a
    self-contained page: :func:`hexaleg.outputs.html.render_simulate_html`) into ``out``
    (created if missing).

    Returns:
        The three paths.

    Raises:
        OutputError: the directory or a file cannot be written (named).
    """
    out = Path(out)
    try:
        out.mkdir(parents=True, exist_ok=True)
    except OSError as e:
        raise OutputError(f"cannot write the simulation to {out}: {e}") from e
    paths = out / "simulate.json", out / "simulate.md", out / "simulate.html"
    for path, text in zip(paths, (json_text(data), page(data), render_simulate_html(data)),
                          strict=True):
        write_file(path, text, "the simulation")  # never through a link there
    return paths


def summary(data: dict[str, Any]) -> str:
    """One paragraph for the terminal."""
    p = data["predicted"]
    loop = "" if not any(data["feedback"]["runs"].values()) else ", balance feedback"
    text = (f"{data['robot']} ({data['controller']} servo{loop}): predicted saving "
            f"{_pct(p['saving'])} (electrical {_v(p['electrical']['with_springs'], 1, 4)} J vs "
            f"{_v(p['electrical']['baseline'], 1, 4)} J per cycle)")
    if "simulated" not in data:
        msgs = "; ".join(f"{k}: {r['message']}" for k, r in data["runs"].items()
                         if r["verdict"] != "walks")
        return text + f"; simulation: {msgs}"
    s = data["simulated"]
    return (text + f"; simulated {_pct(s['saving'])} ({_v(s['electrical']['with_springs'], 1, 4)}"
            f" J vs {_v(s['electrical']['baseline'], 1, 4)} J); distance "
            f"{_v(data['distance_per_cycle'], 1e3, 4)} mm per cycle (planned "
            f"{_v(data['planned_distance_per_cycle'], 1e3, 4)} mm); "
            f"{data['timing']['text']}")
