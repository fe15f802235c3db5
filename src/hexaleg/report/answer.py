"""The report's lead: which springs to fit, and what they save.

``hexaleg report`` leads its page and its last line with ``hexaleg design``'s answer, taken from
the first of:

1. ``given``: the ``design.json`` of ``[report] design`` (``--design``),
   :mod:`hexaleg.report.design_section`;
2. ``found``: ``hexaleg-design/design.json`` in the working directory (where ``hexaleg design``
   writes it), when it was made for the report's robot and gait — the same robot, actuator and
   gait parameters but for the number of samples, and no payload on the report's robot;
3. ``quick``: the design's core computed here, within the report's time budget: the
   :data:`QUICK_FAMILY` family's global optimum (linear springs have no geometry to search: one
   convex program) through ``hexaleg design``'s own chain, its first stage alone
   (:class:`~hexaleg.design.chain.chain.DesignChain` ``run(stages=("candidates",))``: groups
   under ``[design] min_group_saving`` left unfitted, the torsion springs to buy, the saving net
   of their mass) on the gait ``hexaleg design`` samples, without the other families, the
   stops' tolerance, the maps, the robust design or the simulation — the numbers equal that
   family's row of ``hexaleg design``.

Each answer's springs are also evaluated on the report's own gait (its samples, Joule-optimal
forces as the design ranks them), reported beside the design's number. Where no answer can be
had (a payload, a logged motion, a robot outside the registry, a motor outside the catalogue, a
design that fails) the section is None and a note says why; the paper's design stays the page's
reference.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping
from pathlib import Path
from typing import Any

from hexaleg.design.chain.result import QUICK_FAMILY
from hexaleg.dynamics.prepare import Prepared
from hexaleg.errors import HexalegError
from hexaleg.quantities import quantity
from hexaleg.report.config import ReportConfig
from hexaleg.report.design_section import design_section, recommendation
from hexaleg.robot.model import Robot
from hexaleg.robot.registry import description
from hexaleg.robot.springs import SpringSet
from hexaleg.scenario.scenario import Scenario

DESIGN_JSON = Path("hexaleg-design") / "design.json"
"""Where ``hexaleg design`` writes its answer by default, relative to the working directory."""
QUICK_UNPROVEN = "predicted, not simulated: hexaleg design simulates its answer"
"""Why the quick answer is unproven: no forward simulation runs within the report's budget."""


def answer_section(cfg: ReportConfig, robot: Robot, prepared: Prepared
                   ) -> tuple[dict[str, Any] | None, SpringSet | None, list[str]]:
    """The answer the report leads with (module docstring), its springs, and notes on what was
    not used.

    Args:
        cfg: The report's configuration.
        robot: The report's robot (with its payload, if any).
        prepared: The report's gait, prepared (the answer's springs are evaluated on it).

    Returns:
        The section — :func:`~hexaleg.report.design_section.design_section`'s keys with
        ``origin`` (``"given"``, ``"found"`` or ``"quick"``) and ``report_gait`` (``{samples,
        saving}``: the same springs on the report's gait, or None when they cannot be
        evaluated there) — or None; the notes.

    Raises:
        ConfigError, InvalidParameterError, UnknownNameError: a ``[report] design`` file that is
            not a design.json of this robot (:func:`design_section`).
    """
    notes: list[str] = []
    springs: SpringSet | None = None
    if cfg.report.design is not None:
        from hexaleg.design.chain.design_file import read_document, springs_of

        given = Path(cfg.report.design)
        try:
            document: Mapping[str, Any] | None = read_document(given)
        except HexalegError:  # design_section names it, with how to make one
            document = None
        section = design_section(given, robot, document)
        if section is not None and document is not None:  # read once: its springs, as simulate
            springs = springs_of(document, given, robot)
    elif getattr(cfg, "motion", None) is not None:  # a logged motion (--motion): no gait to match
        return None, None, ["no quick answer on a logged motion: hexaleg design --motion LOG "
                            "designs on it, then hexaleg report --design DIR/design.json leads "
                            "with it"]
    else:
        section, springs, why = _found(cfg, robot)
        if why:
            notes.append(why)
        if section is None:
            section, springs, why = _quick(cfg, robot)
            if why:
                notes.append(why)
    if section is None:
        return None, None, notes
    if springs is None:  # a given or found design.json: its springs, read as simulate does
        from hexaleg.design.chain.design_file import read_design

        springs = read_design(Path(section["source"]), robot)
    if section["origin"] == "given" and section["actuator"] != cfg.motor.name:
        notes.append(f"{section['source']} was designed for the actuator {section['actuator']}; "
                     f"this report's is {cfg.motor.name}: the design's saving is with "
                     f"{section['actuator']}, its springs' on this report's gait with "
                     f"{cfg.motor.name} (hexaleg design --config with its [motor] table "
                     "designs for it)")
    section["report_gait"] = _on_report_gait(prepared, springs, section["metric"])
    return section, springs, notes


def answer_springs(cfg: ReportConfig, prepared: Prepared
                   ) -> tuple[SpringSet | None, str, list[str]]:
    """The springs ``hexaleg report`` leads with on a run (:func:`answer_section`) for the
    commands that show or simulate them, where they come from in words, and the notes (why there
    is none: then None and "")."""
    section, springs, notes = answer_section(cfg, prepared.robot, prepared)
    if section is None or springs is None:
        return None, "", notes
    on = section.get("report_gait")
    origin = {"quick": "hexaleg report's quick answer", "found": f"the answer of {DESIGN_JSON}",
              "given": f"the answer of {section['source']}"}[section["origin"]]
    return springs, (f"{origin}: {section['label']} springs on {', '.join(section['groups'])} "
                     f"({section['saving']['value']:+.2f} % of the {section['metric']} energy "
                     f"on the design's {section['samples']}-sample gait"
                     + (f", {on['saving']['value']:+.2f} % on this gait" if on else "")
                     + ")"), notes


def _found(cfg: ReportConfig, robot: Robot
           ) -> tuple[dict[str, Any] | None, SpringSet | None, str | None]:
    """``hexaleg-design/design.json`` when it answers for this report's robot and gait, and
    its springs (the file read once); else None and why it was passed over (None when there is
    no such file)."""
    if not DESIGN_JSON.is_file():
        return None, None, None
    from hexaleg.design.chain.design_file import load_design

    try:
        loaded = load_design(DESIGN_JSON, robot.name)
        section = design_section(DESIGN_JSON, robot, loaded.document)
    except HexalegError as e:
        return None, None, f"{DESIGN_JSON} not used: {e}"
    assert section is not None  # a path was given
    differs = []
    if cfg.payload is not None:
        differs.append("this report carries a payload")
    if loaded.gait is None:
        differs.append("it names no gait")
    else:
        mine = cfg.gait
        theirs = dataclasses.replace(loaded.gait, samples=mine.samples)
        differs += [f"gait {f.name} {getattr(theirs, f.name)!r} (this report: "
                    f"{getattr(mine, f.name)!r})" for f in dataclasses.fields(mine)
                    if getattr(theirs, f.name) != getattr(mine, f.name)]
    if section["actuator"] != cfg.motor.name:
        differs.append(f"actuator {section['actuator']!r} (this report: {cfg.motor.name!r})")
    if differs:
        return None, None, (f"{DESIGN_JSON} not used: made for another robot or gait — "
                            + "; ".join(differs))
    return {**section, "origin": "found"}, loaded.springs, None


def _quick(cfg: ReportConfig, robot: Robot
           ) -> tuple[dict[str, Any] | None, SpringSet | None, str | None]:
    """The quick answer (module docstring), its springs, or None and why not."""
    from hexaleg.design.chain.chain import DesignChain
    from hexaleg.design.chain.config import DesignParams
    from hexaleg.design.chain.records import candidate_data
    what = "no quick answer"
    if cfg.payload is not None:
        return None, None, (f"{what}: this report carries a payload, hexaleg design designs "
                            "for the robot as it is (its payload map shows what a load does)")
    ref = cfg.robot or robot.name  # an own robot by its description file
    try:
        description(ref)
    except HexalegError as e:
        return None, None, f"{what}: {e}; run hexaleg design --robot FILE.toml"
    n = min(cfg.gait.samples, DesignParams().samples)
    params = DesignParams(families=(QUICK_FAMILY,), samples=n)
    # the report's run: its gait, contact and actuator ([motor], the one home; else the robot's)
    run = Scenario(robot=ref, gait=cfg.gait, contact=cfg.contact, actuator=cfg.motor)
    try:  # the design chain's first stage alone
        result = DesignChain(run, design=params).run(stages=("candidates",))
    except HexalegError as e:
        return None, None, f"{what}: the {QUICK_FAMILY} design failed: {e}"
    c = result.recommended
    rec = candidate_data(c, result.outer)
    section = {"origin": "quick", "source": None, "html": None, "actuator": result.actuator,
               **recommendation(rec, params.metric, n, result.pays),
               "worst": None, "robust": None, "simulation": [],
               "proof": {"proven": False, "why": QUICK_UNPROVEN}, "notes": list(c.notes)}
    return section, c.optimum.springs, None


def _on_report_gait(prepared: Prepared, springs: SpringSet | None, metric: str
                    ) -> dict[str, Any] | None:
    """The answer's springs on the report's own gait: its samples and the metric's saving in %
    (Joule-optimal forces, as the design ranks them); None when they cannot run there."""
    if springs is None:
        return None
    try:
        saving = prepared.evaluate(springs, "joule").savings["total"][metric]
    except (HexalegError, KeyError):
        return None
    return {"samples": prepared.motion.n_samples, "saving": quantity(100 * saving, "%")}


def answer_line(section: dict[str, Any] | None) -> str:
    """The terminal's line of the answer: where it comes from, the springs and the saving of the
    ranking metric (net of the springs' mass and on the report's own gait beside it), and on
    the whole draw (:func:`hexaleg.report.build.answer_draw`) when the report computed it."""
    if section is None:
        return "which springs to fit: hexaleg design answers it (the notes say why not here)"
    g = section
    where = {"quick": f"quick answer: optimal {g['label']} springs",
             "found": f"from {DESIGN_JSON}: {g['label']} springs",
             "given": f"from {g['source']}: {g['label']} springs"}[g["origin"]]
    on = g.get("report_gait")
    line = (f"{where} on {', '.join(g['groups'])} save {g['saving']['value']:+.2f} % of the "
            f"{g['metric']} energy ({g['net_saving'][g['metric']]['value']:+.2f} % net of their "
            f"{1e3 * g['spring_mass']['value']:.1f} g; {g['samples']} samples a cycle"
            + (f", {on['saving']['value']:+.2f} % on this report's {on['samples']}"
               if on else "") + ")")
    whole = g.get("whole_draw")
    if whole is not None:
        line += (f"; on the whole draw {'at most ' if whole.get('is_bound') else ''}"
                 f"{whole['saving']['value']:+.2f} % (the motors are "
                 f"{100 * whole['motor_share']['value']:.0f} % of it"
                 + ("" if whole["complete"] else ", counting what is known") + ")")
    if not g["pays"]:
        line = f"no springs pay here; the best: {line}"
    elif g["origin"] == "quick":
        line += f"; unproven ({QUICK_UNPROVEN})"
    elif not g["proof"]["proven"]:
        line = f"unproven ({g['proof']['why']}): {line}"
    return line
