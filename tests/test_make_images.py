"""docs/make_images.py regenerates every picture of docs/img (the pictures themselves are made
by running it: they need Chromium and a minute)."""

from __future__ import annotations

import importlib.util
import re
import sys
from pathlib import Path
from types import ModuleType

ROOT = Path(__file__).resolve().parents[1]


def _script() -> ModuleType:
    spec = importlib.util.spec_from_file_location("make_images", ROOT / "docs" / "make_images.py")
    assert spec is not None and spec.loader is not None
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module  # dataclasses look their module up there
    try:
        spec.loader.exec_module(module)
    finally:
        del sys.modules[spec.name]
    return module


def test_every_picture_of_the_docs_is_made_by_the_script():
    made = {p.name for p in _script().PICTURES}
    stored = {p.stem for p in (ROOT / "docs" / "img").glob("*.png")}
    assert made == stored
    shown = set(re.findall(r"img/(\w+)\.png", (ROOT / "README.md").read_text()
                           + "".join(p.read_text() for p in (ROOT / "docs").glob("*.md"))))
    assert shown <= made, shown - made


def test_each_picture_runs_a_command_that_writes_its_page():
    from hexaleg.cli import build_parser

    parser = build_parser()
    for picture in _script().PICTURES:
        args = parser.parse_args([a.replace("{dir}", "/tmp/x") for a in picture.command])
        written = getattr(args, "out", None) or getattr(args, "html", None)
        page = f"/tmp/x/{picture.page}"
        assert page == written or page.startswith(f"{written}/"), (picture.name, written)


def test_an_unknown_picture_is_named(capsys):
    assert _script().main(["nope"]) == 2
    assert "'nope': one of report, view, sphere" in capsys.readouterr().err
