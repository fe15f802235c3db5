"""Tests of hexaleg.outputs.html: the number and quantity filters, the Jinja2 environment
(autoescape, undefined names are errors) and the report template rendered from plain data."""

from __future__ import annotations

import jinja2
import numpy as np
import pytest

from hexaleg.outputs.html import environment, format_number, format_quantity


def test_numbers_have_four_significant_digits():
    assert format_number(1234.5678) == "1235"
    assert format_number(np.float64(0.000123456)) == "0.0001235"
    assert format_number(7) == "7"
    assert format_number(None) == "—"
    assert format_number(True) == "True"  # a bool is not a number
    assert format_number(float("nan")) == "nan"  # not finite: as it is
    assert format_number("soc") == "soc"


def test_quantities_carry_their_unit_except_dimensionless():
    assert format_quantity({"value": 1.23456, "unit": "J"}) == "1.235 J"
    assert format_quantity({"value": 0.5, "unit": "1"}) == "0.5"
    assert format_quantity({"value": None, "unit": "%"}) == "—"
    assert format_quantity(None) == "—"


def test_environment_escapes_html_and_rejects_undefined_names():
    env = environment()
    assert env.filters["q"] is format_quantity and env.filters["num"] is format_number
    page = env.from_string("{{ x }} {{ y | q }}", globals={}).render(
        x="<b>", y={"value": 2.0, "unit": "N·m"})
    assert page == "&lt;b&gt; 2 N·m"
    with pytest.raises(jinja2.UndefinedError):
        env.from_string("{{ d.missing }}").render(d={})
    assert env.get_template("report.html.j2") is not None  # shipped in the package
