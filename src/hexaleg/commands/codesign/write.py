"""``hexaleg codesign`` on disk: ``codesign.json``, ``codesign.html`` and its plot.

:func:`write_codesign` computes the co-design (:func:`hexaleg.design.codesign.build.codesign`),
draws the energy-vs-speed curve (:mod:`hexaleg.outputs.codesign_plots`), renders the
self-contained page (``templates/codesign.html.j2``, the plot and a drawing of each spring to
mount embedded, the drawings also as ``spring_*.svg``) and writes the JSON
(:meth:`hexaleg.design.codesign.result.CodesignResult.to_dict`), which ``hexaleg.load_design``
and ``hexaleg simulate --springs`` read. When the full spring rules ran, their own
``design.json`` (:func:`hexaleg.design.chain.result.design_data` of the design on the chosen
gait) is written beside it, for ``hexaleg report --design``. With the optimal motion's rows
(``motion="optimal"``), each optimal motion is written as a motion log
(:func:`hexaleg.optimal.motion_file.write_optimal_motion`: ``optimal_no_springs.csv``,
``optimal_springs.csv``) that every command's ``--motion`` reads.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from hexaleg.design.chain.checkpoint import StageFiles, scenario_key
from hexaleg.design.codesign.build import codesign
from hexaleg.design.codesign.optimal_stage import SOLVE
from hexaleg.design.codesign.result import CodesignResult
from hexaleg.outputs import codesign_plots, plots
from hexaleg.outputs.directory import OutputFolder
from hexaleg.outputs.html import render_codesign_html
from hexaleg.outputs.spring_drawing import drawings
from hexaleg.parallel.interrupt import keep
from hexaleg.quantities import json_text
from hexaleg.scenario.scenario import Scenario

STAGES = ".hexaleg-codesign-stages"
"""The hidden folder of a co-design's finished stages in its output directory."""


def curves(result: CodesignResult) -> dict[str, tuple[list[float], list[float], list[float]]]:
    """The speed curve by gait: (speeds, J/m without, J/m with springs)."""
    out: dict[str, tuple[list[float], list[float], list[float]]] = {}
    for p in result.curve:
        v, bare, sprung = out.setdefault(p.label, ([], [], []))
        v.append(p.speed)
        bare.append(p.per_metre)
        sprung.append(p.per_metre_springs)
    return out


def write_result(result: CodesignResult, out: str | Path) -> tuple[dict[str, Any], list[Path]]:
    """Write a computed co-design to ``out``: the JSON, the page, the plot; (data, files).

    Raises:
        OutputError: ``out`` cannot be created or written (named); ``out`` is then as it was.
        DirectoryLockedError: another run writes into ``out``.
    """
    with OutputFolder(out, "co-design") as folder:
        return _write(result, folder)


def _write(result: CodesignResult, folder: OutputFolder) -> tuple[dict[str, Any], list[Path]]:
    """Write a computed co-design's files into ``folder`` and publish them; (data, files)."""
    data = result.to_dict()
    png, _ = plots.save(codesign_plots.speed_curve(curves(result), result.speed),
                        folder.path("speed.png"))
    rules = data.get("full_rules") or {}
    svgs = drawings(rules.get("mounting") or [])
    page = render_codesign_html(data, {"speed": plots.data_uri(png)}, svgs)
    folder.write("codesign.json", json_text(data) + "\n")
    folder.write("codesign.html", page)
    for name, svg in svgs.items():
        folder.write(f"{name}.svg", svg)
    if result.rules is not None and not isinstance(result.rules, str):
        folder.write("design.json", result.rules.to_json() + "\n")
    if result.optimal is not None:
        from hexaleg.optimal.motion_file import write_optimal_motion  # the optimal extra

        for stem, motion in result.optimal.motions.items():
            write_optimal_motion(result.optimal.robot, motion, folder.path(f"{stem}.csv"))
    return data, folder.publish()


def write_codesign(out: str | Path = "hexaleg-codesign", **kwargs: Any
                   ) -> tuple[CodesignResult, list[Path]]:
    """Compute the co-design (keywords of :func:`~hexaleg.design.codesign.build.codesign`)
    and write it to ``out``, the directory locked from the start and published whole at the
    end (:class:`~hexaleg.outputs.directory.OutputFolder`); (result, files).

    With the optimal motion (``motion="optimal"``), the finished parametric co-design is kept in
    ``out``'s hidden :data:`STAGES` (:class:`~hexaleg.design.chain.checkpoint.StageFiles`,
    keyed on the run and the settings) before the optimal motion's minutes: a run killed or
    interrupted there leaves the previous co-design as it was and that stage, which the same
    command reads back instead of searching again, and each optimal-control solve finished
    before the kill, which it reads back instead of solving again
    (:class:`~hexaleg.design.codesign.optimal_stage.KeptSolves`); a whole co-design removes
    them.
    """
    out = Path(out)
    robot = kwargs.get("robot", "hexaleg")
    scenario = robot if isinstance(robot, Scenario) else Scenario.load(robot)
    settings = {k: repr(v) for k, v in sorted(kwargs.items()) if k not in ("robot", "progress")}
    stages = StageFiles(out / STAGES, scenario_key(scenario, settings))
    try:
        with OutputFolder(out, "co-design") as folder:
            result = codesign(**{**kwargs, "robot": scenario}, stages=stages)
            files = _write(result, folder)[1]
    except KeyboardInterrupt as e:  # Ctrl-C or a kill: the finished stage stays for a re-run
        if stages.written:
            solves = sum(name.startswith(SOLVE) for name in stages.written)
            kept = "its parametric co-design" + (
                f" and {solves} optimal-control solve{'s' * (solves != 1)}" if solves else "")
            keep(e, f"but {kept} {'are' if solves else 'is'} kept in {out / STAGES} for the "
                    "same command to resume from")
        raise
    stages.clear()  # the co-design is whole: nothing to resume
    return result, files


__all__ = ["STAGES", "curves", "write_codesign", "write_result"]
