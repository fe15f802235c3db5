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
    # never an exponent (#59: ANYmal's table read "1.103e+04 N·mm"): plain, n significant digits
    assert format_number(11034.2) == "11030" and format_number(1.103e4) == "11030"
    assert format_number(9999.96) == "10000" and format_number(-12345.6) == "-12350"
    assert format_number(1.2346e-5) == "0.00001235" and format_number(2.5e-7, 2) == "0.00000025"
    assert format_number(1234.5, 3) == "1230" and format_number(10.8, 3) == "10.8"
    assert format_number(float("inf")) == "inf"


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


def test_percentages_have_one_rule_two_decimals_signed():
    """Every percentage of the report and design pages (simulated.html.j2 is on both) reads as
    the design page's pct macro writes it."""
    from hexaleg.outputs.html import format_percent

    assert format_percent({"value": 15.4567, "unit": "%"}) == "+15.46 %"
    assert format_percent({"value": -1.2149, "unit": "%"}) == "-1.21 %"
    assert format_percent(3.676) == "+3.68 %"
    assert format_percent({"value": None, "unit": "%"}) == format_percent(None) == "—"
    with pytest.raises(ValueError, match="not a percentage"):
        format_percent({"value": 0.15, "unit": "1"})
    macro = environment().from_string('{% import "design_macros.html.j2" as mc %}'
                                      "{{ mc.pct(x) }}|{{ x | pct }}")
    for v in (15.4567, -1.2149, 0.0, 123.456):
        shown = macro.render(x={"value": v, "unit": "%"}).strip().split("|")
        assert shown[0] == shown[1], shown


def test_float_noise_reads_zero():
    """The net work of a conservative cycle (−2.2e-16 J) is 0 on the page, not −2.224e-16."""
    assert format_number(-2.224e-16) == "0"
    assert format_quantity({"value": 4.6e-16, "unit": "N·m/rad"}) == "0 N·m/rad"
    assert format_number(2.5e-9) == "0.0000000025"  # small but real: kept, written plain
    # read against a scale: a periodic gait's net work beside its positive work is round-off
    # (ANYmal's trot: -3.759e-08 J beside 24.49 J printed "-0.00000003759 J")
    work = {"value": 24.49, "unit": "J"}
    assert format_quantity({"value": -3.759e-8, "unit": "J"}, work) == "0 J"
    assert format_quantity({"value": 0.05, "unit": "J"}, work) == "0.05 J"  # a real net work
    assert format_quantity({"value": -3.759e-8, "unit": "J"}) == "-0.00000003759 J"
    assert format_quantity({"value": 1e-9, "unit": "J"}, {"value": None, "unit": "J"}) == \
        "0.000000001 J"


def test_the_design_page_reads_the_one_design_zero():
    """The pages' N·mm macro prints a torque at most ZERO_MAGNITUDE as 0 and twice it as its
    value: the template's own ``< 1e-9`` printed the zero itself as 1e-06 N·mm."""
    from hexaleg.design.families import ZERO_MAGNITUDE

    macro = environment().from_string('{% import "design_macros.html.j2" as mc %}{{ mc.nmm(x) }}')
    assert macro.render(x={"value": -ZERO_MAGNITUDE, "unit": "N·m"}).strip() == "0 N·mm"
    assert macro.render(x={"value": 2 * ZERO_MAGNITUDE, "unit": "N·m"}).strip() != "0 N·mm"
