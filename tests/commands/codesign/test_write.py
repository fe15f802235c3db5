"""``codesign.json``, ``codesign.html`` and ``speed.png`` on disk."""

from __future__ import annotations

import json

import pytest

from hexaleg.commands.codesign.write import curves, write_result
from hexaleg.errors import OutputError


def test_writes_json_page_and_plot(codesigned, tmp_path):
    data, files = write_result(codesigned, tmp_path / "out")
    names = sorted(p.name for p in files)
    assert names == ["codesign.html", "codesign.json", "speed.png"]
    assert json.loads((tmp_path / "out" / "codesign.json").read_text()) == data
    page = (tmp_path / "out" / "codesign.html").read_text()
    assert "chosen gait, its springs" in page and "data:image/png;base64," in page
    # without the rules the page says its springs are the ideal ones, not the springs to buy
    assert "an upper bound" in page and "friction cone used by the planned forces" in page
    assert set(curves(codesigned)) == {"default", "co-design"}


def test_unwritable_directory_is_named(codesigned, tmp_path):
    blocker = tmp_path / "file"
    blocker.write_text("x")
    with pytest.raises(OutputError, match="file"):
        write_result(codesigned, blocker / "out")


@pytest.mark.slow  # the co-design with its rules: ~30 s of the README's suite
def test_the_page_leads_with_the_worse_servo_and_draws_each_spring(ruled, tmp_path):
    """Issue #57: codesign.html showed only the feedforward servo's simulated saving; the
    position-only one is on the page, the worse first, and each spring to buy is drawn."""
    data, files = write_result(ruled, tmp_path / "out")
    rules = data["full_rules"]
    rows = rules["simulation"]
    assert [r["controller"] for r in rows] == sorted(
        (r["controller"] for r in rows),
        key=lambda c: next(r["simulated_saving"]["value"] for r in rows
                           if r["controller"] == c))
    assert {r["controller"] for r in rows} == {"feedforward", "position"}
    page = (tmp_path / "out" / "codesign.html").read_text()
    answer = page[page.index('<p class="answer'):]
    answer = answer[:answer.index("</p>")]
    shown = [f"{r['label']} {r['simulated_saving']['value']:+.2f} %" for r in rows]
    assert shown[0] in answer and shown[1] in answer
    assert answer.index(shown[0]) < answer.index(shown[1])
    assert rules["proof"]["proven"] is ("Walk with the gait below and fit these springs"
                                        in answer)
    svgs = sorted(p.name for p in files if p.suffix == ".svg")
    assert svgs and len(svgs) == len({m["part"] for m in rules["mounting"]})
    for name in svgs:
        assert (tmp_path / "out" / name).read_text() in page
