"""A drawing of one spring to mount on one joint, as SVG: what a builder needs at the bench.

The drawing is made from one entry of ``design.json``'s ``mounting`` (:func:`hexaleg.design.
chain.result.mounting_data`), so the angles drawn are the file's, to the last digit: each ray
carries its angle in rad in a ``data-angle`` attribute, from the joint's zero. It shows, looking
at the joint along its axis from the axis' tip (positive joint angles counter-clockwise, the
right-hand rule):

* the joint's zero, as its encoder reads it (the robot model's zero);
* the range of motion in the gait (a shaded sector) and its centre (dashed);
* the spring's stop: where its moving leg rests, preloaded (the contact angle);
* where that leg would rest unwound (the free leg), and the preload wind-up between the two;
* the hard stop that limits the wind-up over the joint's whole envelope, when one is needed;
* the way the spring pushes once engaged (an arrow).

Each label says from what its angle is measured: the joint's zero, with the angle from the
centre of motion in brackets. Plain SVG, no script, no external reference.
"""

from __future__ import annotations

import math
import re
from collections.abc import Mapping, Sequence
from typing import Any
from xml.sax.saxutils import escape

from hexaleg.outputs.html import format_degrees as degrees

SIZE = (900, 330)
"""Width and height of the drawing, px."""
CENTRE = (165.0, 165.0)
"""The joint's axis in the drawing, px."""
RADIUS = 120.0
"""Length of the rays, px."""


def _point(angle: float, r: float) -> tuple[float, float]:
    """The point at joint angle ``angle`` (rad) and radius ``r`` (px): counter-clockwise
    positive, so the drawing's y runs down."""
    return CENTRE[0] + r * math.cos(angle), CENTRE[1] - r * math.sin(angle)


def _arc_to(a: float, b: float, r: float) -> str:
    """The SVG arc command from joint angle ``min(a, b)`` to ``max(a, b)`` (rad) at radius r,
    counter-clockwise; a sweep of a full turn or more is drawn just short of one."""
    lo, hi = min(a, b), max(a, b)
    sweep = min(hi - lo, 2 * math.pi - 1e-3)
    x1, y1 = _point(lo + sweep, r)
    return f"A {r:.1f} {r:.1f} 0 {1 if sweep > math.pi else 0} 0 {x1:.2f} {y1:.2f}"


def _arc(a: float, b: float, r: float) -> str:
    """SVG path of the arc between joint angles ``a`` and ``b`` (rad, either order) at radius
    r, through the angles between them."""
    x0, y0 = _point(min(a, b), r)
    return f"M {x0:.2f} {y0:.2f} {_arc_to(a, b, r)}"


def _ray(kind: str, angle: float, length: float, style: str) -> str:
    x, y = _point(angle, length)
    return (f'<line class="{kind}" data-angle="{angle!r}" x1="{CENTRE[0]:.2f}" '
            f'y1="{CENTRE[1]:.2f}" x2="{x:.2f}" y2="{y:.2f}" {style}/>')


def _tag(text: str, angle: float, r: float, colour: str) -> str:
    x, y = _point(angle, r)
    anchor = "start" if math.cos(angle) >= -0.2 else "end"
    return (f'<text x="{x:.1f}" y="{y:.1f}" font-size="11" fill="{colour}" '
            f'text-anchor="{anchor}">{escape(text)}</text>')


def _value(entry: Mapping[str, Any], key: str) -> float | None:
    q = entry.get(key)
    return None if q is None or q.get("value") is None else float(q["value"])


def spring_svg(entry: Mapping[str, Any], title: str) -> str:
    """The drawing of one mounting entry (module docstring).

    Args:
        entry: One item of ``design.json`` ``mounting`` (angles ``{value, unit}`` in rad from the
            joint's zero; ``centre``, ``low``, ``high``, ``contact``, ``free``, ``hard_stop``,
            ``side``, ``joint``, ``engaged_throughout``).
        title: The drawing's heading (the group and side, for instance).

    Returns:
        An ``<svg>`` element (text).
    """
    c, low, high = (float(entry[k]["value"]) for k in ("centre", "low", "high"))
    contact, free, stop = (_value(entry, k) for k in ("contact", "free", "hard_stop"))

    def rel(a: float) -> str:
        return f"{degrees(a)} ({degrees(a - c)} from the centre of motion)"

    parts = [f'<svg xmlns="http://www.w3.org/2000/svg" class="spring-drawing" '
             f'width="{SIZE[0]}" height="{SIZE[1]}" viewBox="0 0 {SIZE[0]} {SIZE[1]}" '
             f'role="img" aria-label="{escape(title, {chr(34): "&quot;"})}">',
             f'<text x="8" y="18" font-size="13" font-weight="bold">{escape(title)}</text>']
    # the range of motion: a sector, its centre dashed
    x0, y0 = _point(low, RADIUS)
    parts.append(f'<path class="motion" d="M {CENTRE[0]:.2f} {CENTRE[1]:.2f} L {x0:.2f} '
                 f'{y0:.2f} {_arc_to(low, high, RADIUS)} Z" '
                 'fill="#9ecae1" fill-opacity="0.45" stroke="none"/>')
    parts.append(_ray("zero", 0.0, RADIUS + 25, 'stroke="#555" stroke-width="1"'))
    parts.append(_tag("0° joint zero", 0.0, RADIUS + 28, "#555"))
    parts.append(_ray("low", low, RADIUS, 'stroke="#3182bd" stroke-width="1"'))
    parts.append(_ray("high", high, RADIUS, 'stroke="#3182bd" stroke-width="1"'))
    parts.append(_ray("centre", c, RADIUS, 'stroke="#3182bd" stroke-dasharray="4 3"'))
    lines = [("#3182bd", f"motion in the gait: {degrees(low)} to {degrees(high)}, "
                         f"centre {degrees(c)}")]
    if free is not None:
        parts.append(_ray("free", free, RADIUS * 0.8,
                          'stroke="#31a354" stroke-width="2" stroke-dasharray="2 3"'))
        parts.append(_tag("free leg", free, RADIUS * 0.8 + 6, "#31a354"))
        lines.append(("#31a354", f"free leg (spring unwound): {rel(free)}"))
    if contact is not None:
        parts.append(_ray("contact", contact, RADIUS + 10, 'stroke="#08519c" stroke-width="3"'))
        parts.append(_tag("spring stop", contact, RADIUS + 14, "#08519c"))
        lines.append(("#08519c", f"spring stop (leg rests here, preloaded): {rel(contact)}"
                      ))
        if entry.get("engaged_throughout"):
            lines.append(("#08519c", "    outside the motion: the spring acts over the whole "
                                     "gait"))
    if free is not None and contact is not None:
        parts.append(f'<path class="windup" d="{_arc(free, contact, RADIUS * 0.45)}" '
                     'fill="none" stroke="#31a354" stroke-width="2"/>')
        lines.append(("#31a354", "preload wind-up at the stop: "
                                 f"{abs(math.degrees(contact - free)):.1f}°"))
    if stop is not None:
        parts.append(_ray("hard_stop", stop, RADIUS + 10, 'stroke="#de2d26" stroke-width="4"'))
        parts.append(_tag("hard stop", stop, RADIUS + 14, "#de2d26"))
        lines.append(("#de2d26", f"hard stop on the spring's leg: {rel(stop)}"))
    # the way it pushes once engaged: towards lower angles on the side above (the arc is drawn
    # counter-clockwise, so its arrow is at its end when it pushes towards higher angles)
    start = contact if contact is not None else free
    if start is not None:
        up = entry.get("side") != "above"
        marker = "marker-end" if up else "marker-start"
        push = _arc(start, start + (0.35 if up else -0.35), RADIUS * 0.65)
        parts.append(f'<path class="push" d="{push}" fill="none" stroke="#08519c" '
                     f'stroke-width="1.5" {marker}="url(#arrow)"/>')
        lines.append(("#08519c", "it pushes the joint towards "
                      + ("higher" if up else "lower") + " angles"))
    parts.append('<defs><marker id="arrow" viewBox="0 0 10 10" refX="5" refY="5" '
                 'markerWidth="6" markerHeight="6" orient="auto-start-reverse">'
                 '<path d="M 0 0 L 10 5 L 0 10 z" fill="#08519c"/></marker></defs>')
    parts.append(f'<circle cx="{CENTRE[0]:.2f}" cy="{CENTRE[1]:.2f}" r="6" fill="#333"/>')
    x = 360
    parts.append(f'<text x="{x}" y="44" font-size="12" font-weight="bold">joint '
                 f'{escape(str(entry["joint"]))}: angles from its zero</text>')
    parts.append(f'<text x="{x}" y="60" font-size="11" fill="#555">(counter-clockwise '
                 'positive, seen from the tip of its axis)</text>')
    for i, (colour, text) in enumerate(lines):
        parts.append(f'<text x="{x}" y="{84 + 18 * i}" font-size="11" fill="{colour}">'
                     f'{escape(text)}</text>')
    parts.append("</svg>")
    return "\n".join(parts)


def drawings(mounting: Sequence[Mapping[str, Any]]) -> dict[str, str]:
    """One drawing per spring to buy (``part``), of its first joint: ``spring_<group>_<side>``
    (a number after it where a group has two such parts; every run of characters a file name
    should not hold — a group ``hfe LH/RH`` — one ``_``) → SVG; the other joints' angles are in
    the page's table and ``design.json``."""
    out: dict[str, str] = {}
    drawn: set[int] = set()
    for entry in mounting:
        if entry["part"] in drawn:
            continue
        drawn.add(entry["part"])
        name = base = re.sub(r"[^A-Za-z0-9_-]+", "_", f"spring_{entry['group']}_{entry['side']}")
        n = 1
        while name in out:
            n += 1
            name = f"{base}_{n}"
        out[name] = spring_svg(entry, f"{entry['group']} spring ({entry['side']}, "
                                      f"{entry['role']}) on {entry['joint']}")
    return out


__all__ = ["drawings", "spring_svg"]
