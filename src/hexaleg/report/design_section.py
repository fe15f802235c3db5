"""The report's lead read from a ``design.json``: the springs ``hexaleg design`` recommends.

The full design takes tens of seconds (families, maps, the robust program), so the report does
not recompute it: given ``[report] design = "DIR/design.json"`` (or ``hexaleg report --design``),
or finding ``hexaleg-design/design.json`` of the same robot and gait
(:mod:`hexaleg.report.answer`), it copies the recommendation's numbers — the saving, the
parts to buy, the worst case of the robustness maps, the robust design's worst case, the saving
predicted and simulated under each controller — into ``report.json`` and leads the page with
them.
"""

from __future__ import annotations

from collections.abc import Mapping
from pathlib import Path
from typing import TYPE_CHECKING, Any

from hexaleg.checks import is_real
from hexaleg.config import read_json
from hexaleg.design.chain.design_file import design_gait, recommended_saving, springs_of
from hexaleg.errors import ConfigError, InvalidParameterError, UnknownNameError

if TYPE_CHECKING:
    from hexaleg.robot.model import Robot

PART_FIELDS = ("material", "wire_diameter", "mean_diameter", "outer_diameter", "body_turns",
               "rate_nmm_per_deg", "preload_angle", "max_deflection", "stress", "yield_strength",
               "safety_factor", "arbor_diameter", "arbor_margin", "wound_inner_diameter", "mass")
"""The torsion spring's numbers the report shows (of ``TorsionSpring.table()``; the design page's
springs-to-buy table, ``design_macros.html.j2``)."""
POSITIVE = ("wire_diameter", "mean_diameter", "outer_diameter", "body_turns", "rate_nmm_per_deg",
            "mass")
"""Of :data:`PART_FIELDS`, those a part to buy has > 0 (a negative wire diameter was copied
into the parts to buy)."""


def design_section(path: str | Path | None, robot: Robot | None = None,
                   data: Mapping[str, Any] | None = None) -> dict[str, Any] | None:
    """The recommendation of a ``design.json``, or None without one.

    The file is read by the one bounded reader (:func:`hexaleg.config.read_json`: a regular
    file, bounded, no NaN or Infinity) and checked against what it claims before a number is
    copied: made for ``robot`` (its ``robot.name``), springs on ``robot``'s joints, and every
    saving, mass and part number the page shows finite.

    Args:
        path: The ``design.json`` written by ``hexaleg design``, or None.
        robot: The robot of the report; None: not checked against a robot.
        data: The file's JSON object when the caller has read it already (read here once
            otherwise).

    Returns:
        The section (:func:`recommendation`) with ``origin`` ``"given"``, ``source`` the path,
        ``html`` its ``design.html`` beside it (None when missing), ``actuator``, the maps'
        ``worst``, the ``robust`` design's worst case, the ``simulation`` rows (empty for a
        design.json without one) and the ``proof`` (``{proven, why}``: unproven for a file
        that does not say) — every number ``{value, unit}`` as in ``design.json``.

    Raises:
        ConfigError: the file cannot be read or is not a ``design.json`` (says how to make one).
        InvalidParameterError: a design for another robot, or a number that is not finite.
        UnknownNameError: a recommended spring on a joint ``robot`` does not have.
    """
    if path is None:
        return None
    path = Path(path)
    how = "write one with: hexaleg design --out DIR"
    try:
        data = read_json(path, "design file") if data is None else data
    except ConfigError as e:
        raise ConfigError(f"[report] design = {str(path)!r}: not a design.json of hexaleg design "
                          f"({e}); {how}") from e
    recommended_saving(data, str(path))  # a known metric; savings finite, at most 100 %
    try:
        section = _section(path, data)
    except KeyError as e:
        raise ConfigError(f"[report] design = {str(path)!r}: not a design.json of hexaleg design "
                          f"(it has no {e} entry; a hand-written {{robot, springs}} file is for "
                          f"hexaleg simulate --springs); {how}") from e
    except (ConfigError, ValueError, TypeError, AttributeError) as e:
        raise ConfigError(f"[report] design = {str(path)!r}: not a design.json of hexaleg design "
                          f"({type(e).__name__}: {e}); {how}") from e
    design_gait(data, None, str(path))  # the gait's keys and values, as [gait] takes them
    if robot is not None:
        _check_robot(path, data, robot)
        springs_of(data, path, robot)  # the springs, as hexaleg simulate reads them
    for key, where in (("savings", "recommended.saving"), ("net_saving", "recommended.net_saving"),
                       ("spring_mass", "recommended.spring_mass"), ("parts", "recommended.parts"),
                       ("worst", "worst"), ("robust", "robust.worst")):
        _check_finite(path, section[key], where)
    return section


def _check_robot(path: Path, data: Mapping[str, Any], robot: Robot) -> None:
    """Refuse a design made for another robot, or springs on joints ``robot`` lacks."""
    owner = data.get("robot")
    owner = owner.get("name") if isinstance(owner, Mapping) else owner
    if owner is not None and owner != robot.name:
        raise InvalidParameterError(f"{path}: robot.name", owner,
                                    f"a design of the report's robot, {robot.name!r} (write one "
                                    f"with: hexaleg design --robot {robot.name} --out DIR)")
    springs = data["recommended"].get("springs") or []
    for entry in springs:
        joint = entry.get("joint") if isinstance(entry, Mapping) else None
        if joint not in robot.joint_names:
            raise UnknownNameError(f"joint in {path} (recommended.springs) for {robot.name}",
                                   joint, robot.joint_names)


def _check_finite(path: Path, value: Any, where: str) -> None:
    """Every ``{value, unit}`` in ``value`` a finite number (or null where nothing was found)."""
    if isinstance(value, Mapping):
        if set(value) == {"value", "unit"}:
            v = value["value"]
            if v is not None and not is_real(v):
                raise InvalidParameterError(f"{path}: {where}", v, "a finite number "
                                            f"({value['unit']}), as hexaleg design writes it")
            return
        for k, v in value.items():
            _check_finite(path, v, f"{where}.{k}")
    elif isinstance(value, list):
        for i, v in enumerate(value):
            _check_finite(path, v, f"{where}[{i}]")
    elif isinstance(value, float) and not is_real(value):
        raise InvalidParameterError(f"{path}: {where}", value, "a finite number")


def recommendation(rec: Mapping[str, Any], metric: str, samples: int, pays: bool
                   ) -> dict[str, Any]:
    """The answer's common keys from a ``recommended`` entry of ``design.json``
    (:func:`hexaleg.design.chain.records.candidate_data`).

    Returns:
        ``{label, family, groups, pays, metric, samples, saving, savings, net_saving,
        spring_mass, parts, dropped_groups}``: ``saving`` the ranking metric's saving
        ``{value, unit}`` (the headline), ``savings`` every metric's, ``parts`` the torsion
        springs to buy as ``design.json`` writes them.

    Raises:
        KeyError: a key the page shows is missing (a part's torsion spring included).
    """
    parts = [dict(p) for p in rec["parts"]]
    for i, p in enumerate(parts):
        _require(p, ("group", "joints", "side", "role", "rate", "max_outer_diameter", "problem"),
                 f"recommended.parts[{i}]")
        if p.get("torsion_spring") is not None:
            where = f"recommended.parts[{i}].torsion_spring"
            _require(p["torsion_spring"], PART_FIELDS, where)
            for key in POSITIVE:  # a part to buy of no size is a damaged file, not a part
                value = p["torsion_spring"][key]
                number = value.get("value") if isinstance(value, Mapping) else value
                if not (is_real(number) and number > 0):
                    raise ValueError(f"{where}.{key} = {number!r}; a part to buy needs it > 0")
    savings = rec["saving"]
    return {"label": rec["label"], "family": rec.get("family", rec["label"].split(",")[0]),
            "groups": list(rec["groups"]), "pays": pays, "metric": metric, "samples": samples,
            "saving": savings[metric], "savings": savings, "net_saving": rec["net_saving"],
            "spring_mass": rec["spring_mass"], "parts": parts,
            "dropped_groups": dict(rec.get("dropped_groups") or {})}


def _require(entry: Mapping[str, Any], keys: tuple[str, ...], where: str) -> None:
    """KeyError naming the keys of ``keys`` that ``entry`` lacks (a design.json of an older
    hexaleg, or not one at all)."""
    missing = [k for k in keys if k not in entry]
    if missing:
        raise KeyError(f"{where} has no {', '.join(missing)}")


UNPROVEN_FILE = "this design.json says nothing of a simulation that backs it (written by an " \
    "older hexaleg: run hexaleg design again)"
"""Why a design.json without ``proof`` is not called proven."""


def _proof(proof: Any) -> dict[str, Any]:
    """``{proven, why}`` of a design.json's ``proof`` (:func:`hexaleg.design.chain.result.
    proof_data`); a file without one is unproven (:data:`UNPROVEN_FILE`)."""
    if not isinstance(proof, Mapping) or not isinstance(proof.get("proven"), bool):
        return {"proven": False, "why": UNPROVEN_FILE}
    why = proof.get("why")
    if not proof["proven"] and not isinstance(why, str):
        raise ValueError(f"proof.why = {why!r}: an unproven design says why (text)")
    return {"proven": proof["proven"], "why": why if not proof["proven"] else None}


def _section(path: Path, data: Mapping[str, Any]) -> dict[str, Any]:
    """The section from the parsed ``design.json`` (a missing key raises KeyError)."""
    metric = data["settings"]["metric"]
    html = path.with_name("design.html")
    robust = data.get("robust")
    return {
        "origin": "given", "source": str(path), "html": str(html) if html.is_file() else None,
        "actuator": data.get("actuator"),
        **recommendation(data["recommended"], metric, data["gait"]["samples"],
                         data.get("pays", True)),
        "worst": data["worst"], "robust": None if robust is None else robust["worst"],
        "simulation": data.get("simulation", []),
        "proof": _proof(data.get("proof")),
        "hard_stops": [{"group": e["group"], "side": e["side"],
                        "angle_from_centre": e["hard_stop"]["angle_from_centre"],
                        "safety_factor": e["safety_factor"]}
                       for e in data.get("envelope", []) if e.get("hard_stop") is not None],
    }
