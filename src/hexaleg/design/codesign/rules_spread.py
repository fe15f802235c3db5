"""How far the springs to buy for the optimal motion move with the motion (issue #56).

The optimal motion with its springs is a local optimum known to its spread: the row's answer
repeated from its start moved by :data:`~hexaleg.design.codesign.alternation.MOVES` lands a
little elsewhere (:class:`~hexaleg.design.codesign.alternation.Spread`). The springs to buy are
designed on it by the full spring rules (:func:`~hexaleg.design.codesign.full_rules.
motion_rules`), a global design for the motion it is given; so they move with the motion, and
their continuous figures (the torque bound, the coil diameters, the hard stops, the savings)
are the method's only to the digits that motion leaves. :func:`rules_spread` designs them again
on each repeat and says whether every repeat buys the same springs — the family, the groups
fitted, each part's material, wire and turns (:func:`bought`) — and how far each kind of figure
moves over the answer and the repeats that buy the same springs: digits finer than that are not
the method's, and the terminal and codesign.json say so beside the springs to buy.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

from hexaleg.design.chain.result import DesignResult
from hexaleg.design.codesign.rules import per_metre
from hexaleg.quantities import quantity as q

KINDS = {"torque bound": "N·m", "energy per metre": "J/m", "saving": "%", "net saving": "%",
         "coil diameter": "mm", "hard stop": "°", "static safety": "1", "fatigue safety": "1",
         "wound-up inner diameter": "mm"}
"""The kinds of figure the springs to buy print (:func:`~hexaleg.design.codesign.rules.
rule_lines`), each in the unit it is printed in."""


@dataclass(frozen=True)
class Bought:
    """The springs a full-rules design buys, split into what names them and their figures.

    Attributes:
        names: The family, the groups fitted, and each part's group, side, material, wire
            diameter (its stock size) and body turns (quarter turns): what is ordered.
        figures: Each continuous figure as (kind of :data:`KINDS`, what it is of) → its value in
            that kind's unit.
    """

    names: tuple[str, ...]
    figures: dict[tuple[str, str], float]


def bought(r: DesignResult, stride: float) -> Bought | None:
    """What the design ``r`` buys (the motion's ``stride`` a cycle, m, for its energy per
    metre), or None when no springs pay there."""
    if not r.pays:
        return None
    rec = r.recommended
    names = [rec.family, ", ".join(rec.optimum.groups)]
    figures: dict[tuple[str, str], float] = {
        ("energy per metre", ""): per_metre(r, stride),
        ("saving", ""): 100 * float(rec.row[f"saving.{r.design.metric}"]),
        ("net saving", ""): 100 * float(rec.net[r.design.metric])}
    if rec.max_torque:
        figures[("torque bound", "")] = rec.max_torque
    for e, (p, f) in zip(r.envelope, r.fatigue, strict=True):
        s = p.spring
        assert s is not None  # the envelope holds the bought parts only
        part = f"{p.group} {p.side}"
        names.append(f"{part}: {s.material} d {1e3 * s.wire_diameter:.2f} mm, "
                     f"{s.body_turns:g} turns")
        figures[("coil diameter", part)] = 1e3 * s.mean_diameter
        figures[("static safety", part)] = e.safety_factor
        figures[("fatigue safety", part)] = f.safety_factor
        figures[("wound-up inner diameter", part)] = 1e3 * e.held_inner_diameter
        if e.stop is not None:
            figures[("hard stop", part)] = math.degrees(e.stop.angle_from_centre)
    return Bought(tuple(names), figures)


@dataclass(frozen=True)
class RulesSpread:
    """The springs to buy designed again on the repeats of the motion they were designed on.

    Attributes:
        moves: Each repeat's move of the row's start, m.
        same: Per repeat: whether its design buys the same springs as the answer's
            (:attr:`Bought.names`); None where it has none to compare (``why``).
        why: Per repeat: why there is nothing to compare (its alternation kept the gait, its
            rules could not run, no springs pay there); "" where there is.
        moved: Each kind of :data:`KINDS` → the largest range of a figure of that kind over the
            answer and the repeats that buy the same springs, in the kind's unit; empty where no
            repeat buys them (nothing measured).
    """

    moves: tuple[float, ...]
    same: tuple[bool | None, ...]
    why: tuple[str, ...]
    moved: dict[str, float]

    def line(self) -> str:
        """The terminal's line: how many repeats buy the same springs, and how far their
        figures move."""
        compared = [s for s in self.same if s is not None]
        moves = ", ".join(f"{m:+.0e}" for m in self.moves)
        head = (f"on the row's repeats (its start moved by {moves} m) the full rules buy the "
                f"same springs (family, groups, each part's wire and turns) on "
                f"{sum(compared)} of {len(self.same)}")
        skipped = sorted({w for w in self.why if w})
        if skipped:
            head += f" ({'; '.join(skipped)})"
        if not self.moved:
            return head
        each = ", ".join(f"{kind} {_amount(value, KINDS[kind])}"
                         for kind, value in self.moved.items())
        return (f"{head}; over those their figures move by up to: {each} — the digits above "
                "finer than that are not the method's")

    def data(self) -> dict[str, Any]:
        """codesign.json's ``optimal.rules_spread`` (``said``: the terminal's line)."""
        return {"said": self.line(), "moves": q(list(self.moves), "m"), "same": list(self.same),
                "why": list(self.why),
                "moved": {kind: q(value, KINDS[kind]) for kind, value in self.moved.items()}}


def _amount(value: float, unit: str) -> str:
    """A figure's range as printed: two significant digits, its unit."""
    text = f"{value:.2g}"
    return text + ("" if unit == "1" else "°" if unit == "°" else f" {unit}")


def rules_spread(answer: DesignResult | str | None, repeats: Sequence[DesignResult | str | None],
                 moves: Sequence[float], stride: float) -> RulesSpread | None:
    """The :class:`RulesSpread` of the springs to buy ``answer`` over the designs ``repeats``
    on the repeats moved by ``moves`` (a string: the rules' error there; None: the repeat's
    alternation kept the gait); None where the answer buys none to compare."""
    mine = bought(answer, stride) if isinstance(answer, DesignResult) else None
    if mine is None:
        return None
    same: list[bool | None] = []
    why: list[str] = []
    agreeing = [mine]
    for r in repeats:
        other = bought(r, stride) if isinstance(r, DesignResult) else None
        if other is None:
            same.append(None)
            why.append("the repeat kept the gait" if r is None else
                       f"no design on a repeat: {r}" if isinstance(r, str) else
                       "no springs pay on a repeat")
            continue
        same.append(other.names == mine.names)
        why.append("")
        if other.names == mine.names:
            agreeing.append(other)
    moved: dict[str, float] = {}
    for key in mine.figures if len(agreeing) > 1 else ():
        values = [b.figures[key] for b in agreeing if key in b.figures]
        kind = key[0]
        moved[kind] = max(moved.get(kind, 0.0), max(values) - min(values))
    order = {kind: k for k, kind in enumerate(KINDS)}
    return RulesSpread(tuple(moves), tuple(same), tuple(why),
                       dict(sorted(moved.items(), key=lambda item: order[item[0]])))


__all__ = ["KINDS", "Bought", "RulesSpread", "bought", "rules_spread"]
