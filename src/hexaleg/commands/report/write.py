"""The report on disk: ``report.html``, ``report.json`` and the plots.

:func:`write_report` computes the report (:func:`hexaleg.report.build.build_report`),
draws its figures (:mod:`hexaleg.outputs.plots`) as PNG (and SVG), renders the self-contained
page with Jinja2 (:func:`hexaleg.outputs.html.render_html`, plots embedded as base64 PNG) and
writes the JSON content next to it.
"""

from __future__ import annotations

import functools
import math
import os
from collections.abc import Callable
from pathlib import Path

from matplotlib.figure import Figure

from hexaleg.checks import typed
from hexaleg.commands.options import say
from hexaleg.outputs import plots
from hexaleg.outputs.directory import OutputFolder
from hexaleg.outputs.html import render_html
from hexaleg.quantities import json_text
from hexaleg.report.build import Report, build_report
from hexaleg.report.config import ReportConfig
from hexaleg.report.design_section import design_section
from hexaleg.robot.model import Robot
from hexaleg.robot.springs import DeadZoneSpring, LinearSpring, TermSpring

BAR_METRIC = "electrical"
"""Metric of the per-joint bar plot: the energy the servos draw (J)."""
PLOTS: tuple[str, ...] = ("joint_angles", "joint_torques", "joint_power", "foot_forces",
                          "energy_per_joint", "stiffness_curve")
"""Plot names: ``<name>.png`` / ``<name>.svg`` in the output directory."""
NMM_PER_DEG = 1000 * math.pi / 180
"""N·mm/deg per N·m/rad: the page gives spring rates in the spring makers' unit."""


PROGRESS = functools.partial(say, "report")
"""The command's status lines on stderr (``hexaleg report: …``)."""


def _figures(r: Report) -> dict[str, Figure]:
    """The report's figures by name (:data:`PLOTS`)."""
    a, robot, curve, key = r.analysis, r.robot, r.curve, BAR_METRIC
    zones = {j: (s.neutral + s.th_minus, s.neutral + s.th_plus)
             for j, s in a.springs.items() if isinstance(s, DeadZoneSpring)}
    contacts = {j: _contact_angles(s) for j, s in a.springs.items()
                if isinstance(s, TermSpring)}
    return {
        "joint_angles": plots.joint_angles(robot, a.t, a.q, zones, contacts),
        "joint_torques": plots.joint_torques(robot, a.t, a.tau_motor, a.tau_spring,
                                             r.baseline.tau_motor),
        "joint_power": plots.joint_power(robot, a.t, a.power, r.baseline.power),
        "foot_forces": plots.foot_forces(robot.leg_names, a.t, a.forces,
                                         r.motion.stance.astype(bool), r.usage),
        "energy_per_joint": plots.energy_bars(robot.joint_names, a.metrics["joint"][key],
                                              a.baseline["joint"][key], key, "J"),
        "stiffness_curve": _in_nmm_per_deg(plots.stiffness_curve_figure(
            NMM_PER_DEG * curve.stiffness, {m: 100 * curve.savings(m) for m in curve.totals},
            NMM_PER_DEG * r.data["stiffness_curve"]["k_M"]["value"],
            r.config.report.curve_joints)),
    }


def _contact_angles(spring: TermSpring) -> tuple[float, ...]:
    """Where a spring of the design families engages (its ramps' and steps' angles,
    :mod:`hexaleg.robot.springs.terms`), or a linear spring's equilibrium, rad."""
    if isinstance(spring, LinearSpring):
        return () if spring.equilibrium is None else (spring.equilibrium,)
    return tuple(sorted({t.angle for t in spring.terms() if t.kind not in ("linear", "constant")}))


def _in_nmm_per_deg(fig: Figure) -> Figure:
    """The stiffness curve drawn from rates in N·mm/deg, its labels saying so (the plot function
    labels its axis and k_M line in N·m/rad, the unit of its arguments)."""
    ax = fig.axes[0]
    ax.set_xlabel(ax.get_xlabel().replace("N·m/rad", "N·mm/deg"))
    for line in ax.get_lines():
        line.set_label(str(line.get_label()).replace("N·m/rad", "N·mm/deg"))
    ax.legend(fontsize=8)
    return fig


def _relative_link(data: dict, out: Path) -> dict:
    """``data`` with the answer's ``design.html`` as a link relative to ``out`` (where
    report.html is), so the pair still links when moved or served together."""
    g = data.get("design")
    if not g or not g.get("html"):
        return data
    link = Path(os.path.relpath(Path(g["html"]).resolve(), out.resolve())).as_posix()
    return {**data, "design": {**g, "html": link}}


@typed
def write_report(out: str | Path = "hexaleg-report", config: ReportConfig | None = None, *,
                 robot: Robot | None = None, svg: bool = False,
                 progress: Callable[[str], None] | None = PROGRESS
                 ) -> Report:
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
        DirectoryLockedError: another run writes into ``out`` (checked before computing).
        HexalegError: from the computation (see :func:`build_report`); ``out`` is then as it
            was (:class:`~hexaleg.outputs.directory.OutputFolder`).
    """
    if config is not None and config.report.design is not None:
        design_section(config.report.design, robot)  # a bad design.json: no directory made
    out = Path(out)
    with OutputFolder(out, "report") as folder:  # locked; published whole at the end
        r = build_report(config, robot=robot, progress=progress)
        say = progress or (lambda _msg: None)
        names: list[str] = []
        images = {}
        for name, fig in _figures(r).items():
            png, written = plots.save(fig, folder.path(f"{name}.png"), svg=svg)
            images[name] = plots.data_uri(png)
            names += [p.name for p in written]
            say(f"plot {name}")
        data = {**_relative_link(r.data, out),
                "files": [*sorted(names), "report.html", "report.json"]}
        folder.write("report.json", json_text(data))
        folder.write("report.html", render_html(data, images))
        files = folder.publish()
    say(f"wrote {out / 'report.html'}")
    return Report(config=r.config, robot=r.robot, motion=r.motion, analysis=r.analysis,
                  baseline=r.baseline, curve=r.curve, usage=r.usage, data=data,
                  files=tuple(files))
