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
