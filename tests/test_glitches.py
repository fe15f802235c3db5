"""Every page and terminal line the commands write, scanned for the glitches issue #57 found: a
missing space after a full stop ("it.The"), a word glued to a bracket ("them(the check)",
"J/m(spread"), minus zero ("-0.0°"), a float's exponent in a table ("-2.374e-09 N·mm"), a
dimensionless unit printed ("duty_factor 0.8 1"), a doubled word. The scanner is tested on the
issue's own examples first, so a scanner that finds nothing cannot pass."""

from __future__ import annotations

import re
from html import unescape

import pytest

PATTERNS = {
    "no space after a full stop": re.compile(r"[a-z)]\.[A-Z][a-z]"),
    "a word glued to a bracket": re.compile(r"(?<![\w/])(?!max\(|min\()[A-Za-z/]{2,}\([a-z]{2,}"),
    "minus zero": re.compile(r"[-−]0(?:\.0+)?(?![.\d]*[1-9])(?=\s*[°%]|\s|$)"),
    "a float's exponent": re.compile(r"\d[eE][-+]0\d"),
    "a dimensionless unit printed": re.compile(r"\d(?:\.\d+)? 1(?=[\s,;)]|$)"),
    "a doubled word": re.compile(r"\b([A-Za-z]{2,}) \1\b"),
}
"""What a glitch looks like in visible text."""


def visible(html: str) -> str:
    """A page's visible prose: no style, script, embedded image or drawing; code spans left out
    (a key or a file name is not prose); each cell and paragraph on its own line."""
    html = re.sub(r"<style>.*?</style>|<script.*?</script>|<svg.*?</svg>|<code>.*?</code>|"
                  r"src=\"data:[^\"]*\"", " ", html, flags=re.S)
    html = re.sub(r"<(td|th|li|p|h\d|tr|div|section|figure|br)[^>]*>", "\n", html)
    return unescape(re.sub(r"<[^>]+>", "", html))


def glitches(text: str) -> list[str]:
    """Each glitch of ``text`` with 30 characters around it."""
    out = []
    for name, pattern in PATTERNS.items():
        for m in pattern.finditer(text):
            around = text[max(0, m.start() - 30):m.end() + 30].replace("\n", " | ")
            out.append(f"{name}: …{around}…")
    return out


@pytest.mark.parametrize("text", [
    "these springs save it.The draw is a lower bound", "the servos (them(the check))",
    "13.2 J/m(spread 0.0)", "a stop at -0.0° from the centre", "preload -2.374e-09 N·mm",
    "duty_factor 0.8 1, period 1.28 s", "the the springs"])
def test_the_scanner_finds_the_issues_examples(text):
    assert glitches(text)


@pytest.mark.parametrize("text", [
    "positive work ∫ max(0, τq̇)", "8.148 W/(N·m)²", "hexaleg.design.springs.mounting, design.json",
    "+0.05 % at -0.04°", "period ×0.5, stride ×1.5", "springs(s)", "between 0 and 1 of it"])
def test_the_scanner_passes_prose(text):
    assert glitches(text) == []


def test_the_design_page_and_lines_have_no_glitch(design_written):
    written, out = design_written
    found = glitches(visible((out / "design.html").read_text()))
    r = written.result
    lines = [r.summary(), *([r.fold.line()] if r.fold else []),
             *([r.whole_draw.line()] if r.whole_draw else [])]
    found += [g for line in lines for g in glitches(line)]
    assert found == []


def test_the_report_page_and_lines_have_no_glitch(report_written):
    report, out = report_written
    found = glitches(visible((out / "report.html").read_text()))
    found += glitches(report.summary())
    assert found == []


def test_the_codesign_page_and_lines_have_no_glitch(ruled, tmp_path):
    from hexaleg.commands.codesign.write import write_result

    write_result(ruled, tmp_path)
    found = glitches(visible((tmp_path / "codesign.html").read_text()))
    found += glitches(ruled.summary())
    assert found == []
