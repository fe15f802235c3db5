"""Tests of hexaleg.outputs.directory: the output directory is made and proved writable."""

from __future__ import annotations

import os

import pytest

from hexaleg.errors import OutputError
from hexaleg.outputs.directory import writable_directory


def test_creates_the_directory_and_leaves_no_probe(tmp_path):
    out = writable_directory(tmp_path / "a" / "b", "the report")
    assert out.is_dir() and not any(out.iterdir())


def test_a_file_in_the_way_is_named(tmp_path):
    (tmp_path / "taken").write_text("x")
    with pytest.raises(OutputError, match=r"cannot write the design to the directory .*taken"):
        writable_directory(tmp_path / "taken", "the design")


@pytest.mark.skipif(os.geteuid() == 0, reason="root writes into read-only directories")
def test_a_read_only_directory_is_refused(tmp_path):
    tmp_path.chmod(0o500)
    try:
        with pytest.raises(OutputError, match="the report"):
            writable_directory(tmp_path, "the report")
    finally:
        tmp_path.chmod(0o700)
