"""HTML pages from Jinja2 templates (``hexaleg/outputs/templates/``), self-contained.

:func:`render_html` renders the gait energy report (``report.html.j2``) from plain data: the
report's JSON content, whose quantities are ``{"value": …, "unit": …}``, and the plots as
``data:`` URIs. Four filters format numbers on the pages: ``num`` (four significant digits, or
``num(n)`` n, always a plain number without an exponent; float noise below :data:`NOISE` reads
0), ``q`` (a quantity with its unit), ``pct`` (a percentage: the one precision rule of the
pages, two decimals, signed) and ``deg`` (an angle in rad shown in degrees, one decimal, signed,
never −0.0).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from decimal import Decimal
from typing import Any

import jinja2
import markupsafe

from hexaleg.checks import is_real
from hexaleg.design.families.family import ZERO_MAGNITUDE
from hexaleg.outputs.angles import format_degrees

NOISE = 1e-12
"""Magnitudes below this (in the SI unit of the number) are round-off, not values: the net work
of a conservative cycle (−2.2e-16 J), a solver's zero stiffness. They are shown as 0."""


def format_number(x: Any, digits: int = 4) -> str:
    """``digits`` significant digits written as a plain number, never with an exponent
    (``11030``, not ``1.103e+04``; ``0.00001235``, not ``1.235e-05``), as the pages write every
    other number; ``—`` for a missing value; 0 for float noise (:data:`NOISE`); a value that is
    not finite as it is."""
    if x is None:
        return "—"
    if not is_real(x):
        return str(x)
    if abs(x) < NOISE:
        return "0"
    text = f"{x:.{digits}g}"
    if "e" not in text or not math.isfinite(x):
        return text
    plain = format(Decimal(f"{x:.{digits - 1}e}"), "f")
    return plain.rstrip("0").rstrip(".") if "." in plain else plain


def format_percent(q: Mapping[str, Any] | float | None) -> str:
    """A percentage (a quantity in % or a number) with two decimals and its sign, as the design
    page's ``pct`` macro writes it: ``+15.46 %``, ``-1.21 %``; ``—`` for a missing value.

    Raises:
        ValueError: a quantity whose unit is not ``%`` (a fraction shown as a percentage).
    """
    x = q.get("value") if isinstance(q, Mapping) else q
    if x is None:
        return "—"
    if isinstance(q, Mapping) and q.get("unit") != "%":
        raise ValueError(f"pct: {q!r} is not a percentage")
    return f"{float(x):+.2f} %"


RELATIVE_NOISE = 1e-6
"""A value below this fraction of the magnitude it is read against is round-off: the net work of
a periodic gait (−3.8e-8 J beside 24 J of positive work on ANYmal's trot) reads 0."""


def format_quantity(q: Mapping[str, Any] | None,
                    scale: Mapping[str, Any] | None = None) -> str:
    """``{"value", "unit"}`` as text; dimensionless (unit ``"1"``) values without a unit.

    Args:
        q: The quantity, or None (``—``).
        scale: A quantity of the same unit that ``q`` is read against (the positive work a net
            work sits beside): below :data:`RELATIVE_NOISE` of it, ``q`` is round-off and reads
            0. None: only :data:`NOISE` applies.
    """
    if q is None or q["value"] is None:
        return "—"
    unit = "" if q["unit"] == "1" else q["unit"]
    value = q["value"]
    if (scale is not None and scale.get("value") is not None and is_real(value)
            and abs(value) < RELATIVE_NOISE * abs(scale["value"])):
        value = 0.0
    return f"{format_number(value)} {unit}".rstrip()


def environment() -> jinja2.Environment:
    """The Jinja2 environment of the package's templates: HTML autoescaped, undefined names an
    error, the ``num``, ``q`` and ``pct`` filters, and the design's zero magnitude
    (:data:`~hexaleg.design.families.family.ZERO_MAGNITUDE`)."""
    env = jinja2.Environment(loader=jinja2.PackageLoader("hexaleg.outputs", "templates"),
                             autoescape=jinja2.select_autoescape(("html", "j2")),
                             undefined=jinja2.StrictUndefined, trim_blocks=True,
                             lstrip_blocks=True)
    env.filters["num"] = format_number
    env.filters["q"] = format_quantity
    env.filters["pct"] = format_percent
    env.filters["deg"] = format_degrees
    env.globals["ZERO_MAGNITUDE"] = ZERO_MAGNITUDE
    return env


def render_html(data: Mapping[str, Any], images: Mapping[str, str]) -> str:
    """Render ``templates/report.html.j2`` with the report's numbers and embedded images.

    Args:
        data: The report's JSON content (``Report.data`` of :mod:`hexaleg.report.build`).
        images: Plot name → ``data:`` URI.

    Returns:
        The HTML page (self-contained).
    """
    return environment().get_template("report.html.j2").render(d=data, images=images)


def render_design_html(data: Mapping[str, Any], images: Mapping[str, str],
                       drawings: Mapping[str, str] | None = None) -> str:
    """Render ``templates/design.html.j2``: the spring design page of ``hexaleg design``.

    Args:
        data: The content of ``design.json`` (:func:`hexaleg.design.chain.result.design_data`).
        images: Plot name → ``data:`` URI.
        drawings: Drawing name → SVG of each spring to mount, as the writer wrote them to
            files; default :func:`hexaleg.outputs.spring_drawing.drawings` of
            ``data["mounting"]``.

    Returns:
        The HTML page (self-contained, the drawings inline).
    """
    from hexaleg.outputs.spring_drawing import drawings as draw

    svgs = draw(data.get("mounting") or []) if drawings is None else drawings
    return environment().get_template("design.html.j2").render(
        d=data, images=images, drawings={k: markupsafe.Markup(v) for k, v in svgs.items()})


def render_codesign_html(data: Mapping[str, Any], images: Mapping[str, str],
                         drawings: Mapping[str, str]) -> str:
    """Render ``templates/codesign.html.j2``: the page of ``hexaleg codesign``.

    Args:
        data: The content of ``codesign.json``.
        images: Plot name → ``data:`` URI.
        drawings: Drawing name → SVG of each spring to buy, as the writer wrote them.

    Returns:
        The HTML page (self-contained, the drawings inline). The optimal motion's figures are
        printed to the digits their spread leaves by the rule the text table uses
        (:func:`hexaleg.design.codesign.alternation.decimals`, handed to the template).
    """
    from hexaleg.design.codesign.alternation import decimals  # lazily: no other page needs it

    return environment().get_template("codesign.html.j2").render(
        d=data, images=images, drawings={k: markupsafe.Markup(v) for k, v in drawings.items()},
        decimals=decimals)


def render_simulate_html(data: Mapping[str, Any]) -> str:
    """Render ``templates/simulate.html.j2``: the page of ``hexaleg simulate``.

    Args:
        data: The content of ``simulate.json``
            (:func:`hexaleg.commands.simulate.write.simulation_data`).

    Returns:
        The HTML page (self-contained: no script, no external URL).
    """
    return environment().get_template("simulate.html.j2").render(d=data)
