"""Tests of hexaleg.outputs.viewer.page: the self-contained page and its legend."""

from __future__ import annotations

import re
from typing import Any

import numpy as np
import pytest
from meshcat_scene import ARROW, PERIOD, T, page_commands

from hexaleg.errors import OutputError
from hexaleg.outputs.viewer.page import page_html, write_page

_UUID = re.compile(r"[0-9a-f]{8}-[0-9a-f]{4}-[0-9a-f]{4}-[0-9a-f]{4}-[0-9a-f]{12}")
_DRAWING = {"fps": T / PERIOD, "arrow_length": ARROW, "marker_radius": 0.018}


@pytest.fixture(scope="module")
def page(robot, motion, forces, tmp_path_factory):
    """Page of the synthetic motion with one keyframe per sample (fps = T / period)."""
    path = tmp_path_factory.mktemp("view") / "walk.html"
    write_page(path, page_html(robot, motion, forces=forces, joint_values=motion.v[:, 6:],
                               joint_label="joint velocity (rad/s)",
                               springs="test springs <b>", **_DRAWING))
    return path.read_text()


def _numbered_uuids(value: Any, seen: dict[str, str]) -> Any:
    """``value`` with each object UUID replaced by its order of first appearance."""
    if isinstance(value, dict):
        return {k: _numbered_uuids(v, seen) for k, v in value.items()}
    if isinstance(value, list):
        return [_numbered_uuids(v, seen) for v in value]
    if isinstance(value, str) and _UUID.fullmatch(value):
        return seen.setdefault(value, f"uuid{len(seen)}")
    return value


def test_page_embeds_the_scene_in_order(page, scene):
    """The page holds exactly the commands the scene sends, in the order they were sent (up to
    the random UUIDs of the objects)."""
    assert _numbered_uuids(page_commands(page), {}) == _numbered_uuids(scene, {})


def test_page_is_self_contained(page):
    assert "<script src" not in page and "<link" not in page
    assert "MeshCat.Viewer" in page  # the viewer's JavaScript is inlined
    urls = set(re.findall(r"https?://[^\s\"'<>)]+", page))
    # The only URLs are XML namespace names inside the inlined JavaScript, never fetched.
    assert urls <= {"http://www.w3.org/1999/xhtml"}, urls


def test_legend_names_the_springs_and_the_scales(page, forces):
    assert "<div>springs: test springs &lt;b&gt;</div>" in page  # escaped
    assert "joint velocity (rad/s)" in page
    fmax = np.linalg.norm(forces, axis=-1).max()
    assert f"{ARROW * 100:.3g} cm = {fmax:.3g} N" in page


def test_unwritable_path_is_output_error(tmp_path):
    for path in (tmp_path / "missing" / "x.html", tmp_path):
        with pytest.raises(OutputError, match=re.escape(str(path))):
            write_page(path, "<html></html>")


def test_a_page_replaces_a_link_and_a_full_disk_keeps_the_old_page(tmp_path, monkeypatch):
    """`view --html` had written in place: through a link, and a full disk had truncated the
    earlier page (#58)."""
    import errno
    import os

    victim = tmp_path / "victim.txt"
    victim.write_text("keep me")
    page = tmp_path / "page.html"
    page.symlink_to(victim)
    write_page(page, "<html>old</html>")
    assert victim.read_text() == "keep me" and not page.is_symlink()

    def full(fd, data):
        raise OSError(errno.ENOSPC, os.strerror(errno.ENOSPC))

    monkeypatch.setattr(os, "write", full)  # the disk fills at the first write
    with pytest.raises(OutputError, match=r"cannot write the HTML page .*page\.html: No space"):
        write_page(page, "<html>new</html>")
    monkeypatch.undo()
    assert page.read_text() == "<html>old</html>"
    assert sorted(p.name for p in tmp_path.iterdir()) == ["page.html", "victim.txt"]
