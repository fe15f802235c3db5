"""``hexaleg design`` on disk: ``design.json``, ``design.html`` and the plots.

:func:`write_design` computes the design (:class:`hexaleg.design.chain.chain.DesignChain`), draws
its figures (:mod:`hexaleg.outputs.design_plots`) as PNG, renders the self-contained page
(:func:`hexaleg.outputs.html.render_design_html`, plots embedded) and writes the JSON content
(:meth:`hexaleg.design.chain.result.DesignResult.to_json`) next to it. The page is its own, not a
section of ``report.html``: the design takes seconds to tens of seconds (families, maps, the robust
program) and the report must stay fast; the report links to it when it sits beside it.
"""

from __future__ import annotations

import functools
import math
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path
from typing import Any

import numpy as np
from matplotlib.figure import Figure

from hexaleg.checks import typed
from hexaleg.commands.options import say
from hexaleg.design.chain.chain import DesignChain
from hexaleg.design.chain.checkpoint import FOLDER
from hexaleg.design.chain.result import DesignResult, mounting_data
from hexaleg.design.search.tolerance import TolerantSprings
from hexaleg.outputs import design_plots, plots
from hexaleg.outputs.directory import OutputFolder
from hexaleg.outputs.html import render_design_html
from hexaleg.outputs.spring_drawing import drawings
from hexaleg.parallel.interrupt import keep
from hexaleg.quantities import json_text
from hexaleg.scenario.run_warnings import gait_defaults, run_warnings
from hexaleg.scenario.scenario import Scenario

PROGRESS = functools.partial(say, "design")
"""The command's status lines on stderr (``hexaleg design: …``)."""


@dataclass(frozen=True, eq=False)
class WrittenDesign:
    """A computed and written design: the result, the JSON content, the files."""

    result: DesignResult
    data: dict[str, Any]
    files: tuple[Path, ...]


def figures(r: DesignResult) -> dict[str, Figure]:
    """The design's figures by name: one heat map per robustness map (``map_<a>_<b>``), the
    Pareto front, the robust design against the nominal one and the saving against a common
    stop shift (``tolerance``: the tolerant and the tolerance-blind design)."""
    m = r.design.metric
    out = {f"map_{mp.axes[0]}_{mp.axes[1]}": design_plots.robustness_heatmap(
        mp.axes, _map_values(mp.axes, mp.values), 100 * mp.saving[m], m)
        for mp in r.maps}
    points = [c for _, c in r.pareto]
    if points:
        chosen = next((i for i, c in enumerate(points) if c is r.recommended), None)
        out["pareto"] = design_plots.pareto_figure(
            np.array([np.abs(c.optimum.analysis.tau_spring).max() for c in points]),
            np.array([c.optimum.analysis.spring_energy.max() for c in points]),
            {f"{m} (net)": 100 * np.array([c.net[m] for c in points]),
             "joule": 100 * np.array([c.row["saving.joule"] for c in points])}, chosen)
    if r.robust is not None:
        sv = r.robust.savings
        out["robust"] = design_plots.robust_figure(
            [c.short_label() for c in r.robust.conditions],
            {k: 100 * v["robust"] for k, v in sv.items()},
            {k: 100 * v["nominal"] for k, v in sv.items()})
    if r.tolerance is not None:
        out["tolerance"] = tolerance_figure(r.tolerance)
    return out


def _map_values(axes: tuple[str, str], values: tuple[Any, Any]) -> tuple[Any, Any]:
    """A map's axis values as the page plots them: a slope in deg, the rest as they are."""
    a, b = (np.degrees(np.asarray(v, dtype=float)) if name == "slope" else v
            for name, v in zip(axes, values, strict=True))
    return a, b


def tolerance_figure(t: TolerantSprings) -> Figure:
    """:func:`~hexaleg.outputs.design_plots.tolerance_figure` of ``t`` in deg and %, the design
    recommended so named (the tolerant one when its worst case is the better, as the design
    chooses)."""
    names = {"tolerant": f"designed for ±{math.degrees(t.tolerance):g}°",
             "blind": "tolerance-blind"}
    names[t.chosen] += " (recommended)"
    return design_plots.tolerance_figure(
        np.degrees(t.shifts), {names[k]: 100 * t.curve[k] for k in names},
        math.degrees(t.tolerance), {names[k]: 100 * t.worst[k] for k in names}, t.metric)


def design_warnings(r: DesignResult) -> tuple[str, ...]:
    """The warnings of the design's run (:func:`hexaleg.scenario.run_warnings.run_warnings`):
    its nominal gait, or the logged motion's cycle, on the robot and actuators it designed
    with."""
    from hexaleg.motion.legged import gait as make_gait

    run = r.run
    robot = run.model
    if r.motion is not None:  # the logged cycle the design was made on, as the chain read it
        return run_warnings(robot, r.motion, run.actuator)
    return run_warnings(robot, make_gait(robot, r.gait), run.actuator,
                        desc=run.description, gait=r.gait)


@typed
def write_design(out: str | Path = "hexaleg-design", scenario: Scenario | None = None, *,
                 controller: str | None = None,
                 progress: Callable[[str], None] | None = PROGRESS) -> WrittenDesign:
    """Compute the design and write ``design.json``, ``design.html`` and the plots into ``out``.

    Args:
        out: Output directory (created with its parents if missing).
        scenario: The run (default: the built-in robot, its gait, the defaults); its
            ``[design]`` and ``[mission]`` tables the design's settings.
        controller: The servo the robot runs over ``[design] controller`` (``--controller``).
        progress: Called with one status line per step (default: print to stderr); None: quiet.

    Returns:
        The result, the JSON content and the files written.

    Raises:
        OutputError: ``out`` cannot be created or written (checked before computing; names it).
        DirectoryLockedError: another run writes into ``out`` (checked before computing).
        HexalegError: from the computation (:class:`DesignChain`); ``out`` is then as it was
            (:class:`~hexaleg.outputs.directory.OutputFolder`).

    Each finished stage is kept in ``out``'s hidden :data:`~hexaleg.design.chain.checkpoint.
    FOLDER` as it goes (:class:`~hexaleg.design.chain.checkpoint.StageFiles`): a run killed
    or interrupted leaves the previous design as it was and its finished stages, which the same
    command reads back instead of computing them again. A stage after the candidates that
    fails ends the stages after it: the design is written with the stages before it (its
    ``failed`` names the stage and the keys that set it, ``result.failed``) and they stay kept;
    a whole design removes them.
    """
    out = Path(out)
    chain: DesignChain | None = None
    try:
        with OutputFolder(out, "design") as folder:  # locked; published whole at the end
            chain = DesignChain(scenario, progress, controller=controller, files=out / FOLDER)
            r = chain.run()
            data, files = _write(folder, r)
    except KeyboardInterrupt as e:  # Ctrl-C or a kill: the finished stages stay for a re-run
        kept = [] if chain is None or chain.files is None else chain.files.written
        if kept:
            keep(e, f"but its finished stages ({', '.join(kept)}) are kept in {out / FOLDER} "
                    "for the same command to resume from")
        raise
    if r.failed is None and chain is not None and chain.files is not None:
        chain.files.clear()  # the design is whole: nothing to resume
    if progress:
        progress(f"wrote {out / 'design.html'}")
    return WrittenDesign(result=r, data=data, files=tuple(files))


def _write(folder: OutputFolder, r: DesignResult) -> tuple[dict[str, Any], list[Path]]:
    """The design's figures, drawings, page and JSON written into ``folder`` and published;
    the JSON content and the files."""
    names: list[str] = []
    images = {}
    for name, fig in figures(r).items():
        png, written = plots.save(fig, folder.path(f"{name}.png"))
        images[name] = plots.data_uri(png)
        names += [p.name for p in written]
    svgs = drawings(mounting_data(r))
    extra = {"warnings": list(design_warnings(r)),
             "gait_defaults": gait_defaults(r.run.description,
                                            r.gait if r.run.log is None else None),
             "files": sorted([*names, *(f"{n}.svg" for n in svgs), "design.html",
                              "design.json"])}
    data = r.to_dict(**extra)
    folder.write("design.json", json_text(data))  # the same document, built once
    for n, svg in svgs.items():
        folder.write(f"{n}.svg", svg)
    folder.write("design.html", render_design_html(data, images, svgs))
    return data, folder.publish()
