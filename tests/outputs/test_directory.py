"""Tests of hexaleg.outputs.directory: a run's output directory is locked for its life, its files
are published together at its end, and a failed or interrupted run leaves the earlier files as
they were and nothing of its own."""

from __future__ import annotations

import json
import os
import signal

import pytest

from hexaleg.errors import DirectoryLockedError, OutputError
from hexaleg.outputs.directory import RECORD, STAGING, OutputFolder
from hexaleg.parallel import interrupt
from hexaleg.parallel.lock import LOCK


def _listing(directory):
    """The folder's files by name → content, without the record of the last run's files."""
    return {p.name: p.read_bytes() for p in directory.iterdir()
            if not p.name.startswith(RECORD)}


def test_files_appear_only_when_published(tmp_path):
    out = tmp_path / "a" / "b"
    with OutputFolder(out, "report") as folder:
        assert (out / LOCK).is_file()
        folder.write("report.json", "{}")
        folder.write("plot.png", b"png")
        assert sorted(os.listdir(out)) == sorted([LOCK, folder.staging.name])
        files = folder.publish()
    assert files == [out / "plot.png", out / "report.json"]
    assert _listing(out) == {"plot.png": b"png", "report.json": b"{}"}  # no lock, no staging
    assert json.loads((out / f"{RECORD}report.json").read_text()) == {
        "files": ["plot.png", "report.json"]}


def test_the_previous_run_s_files_this_run_does_not_write_are_removed(tmp_path):
    """An earlier report's SVGs, an earlier design's maps: not left beside the new run's."""
    out = tmp_path / "out"
    out.mkdir()
    (out / "mine.txt").write_text("the user's")
    with OutputFolder(out, "report") as folder:
        for name in ("report.json", "a.svg", "b.png"):
            folder.write(name, "old")
        folder.publish()
    with OutputFolder(out, "design") as folder:  # another command's files stay
        folder.write("design.json", "d")
        folder.publish()
    with OutputFolder(out, "report") as folder:
        folder.write("report.json", "new")
        folder.write("b.png", "new")
        folder.publish()
    assert _listing(out) == {"mine.txt": b"the user's", "report.json": b"new", "b.png": b"new",
                             "design.json": b"d"}
    (tmp_path / "x").write_text("outside")
    (out / f"{RECORD}report.json").write_text(json.dumps({"files": ["../x", ".lock", 3]}))
    with OutputFolder(out, "report") as folder:  # what is not a plain name is never removed
        folder.publish()
    assert (tmp_path / "x").read_text() == "outside"


def test_a_second_run_is_refused_naming_the_first(tmp_path):
    with OutputFolder(tmp_path, "report"):
        with pytest.raises(DirectoryLockedError) as e:
            OutputFolder(tmp_path, "design")
    assert e.value.pid == os.getpid()
    assert f"another report (pid {os.getpid()} on host" in str(e.value)
    assert "give this design another --out directory" in str(e.value)
    OutputFolder(tmp_path, "design").discard()  # free again


@pytest.mark.parametrize("fault", [OutputError("cannot write it"), KeyboardInterrupt()])
def test_a_failed_or_interrupted_run_keeps_the_earlier_files(tmp_path, fault):
    (tmp_path / "report.json").write_text("old")
    with pytest.raises(type(fault)) as e:
        with OutputFolder(tmp_path, "report") as folder:
            folder.write("report.json", "new")
            folder.write("extra.png", b"new")
            raise fault
    assert _listing(tmp_path) == {"report.json": b"old"}
    if isinstance(fault, KeyboardInterrupt):
        assert interrupt.kept(e.value) == [f"{tmp_path} kept as it was, nothing of this run "
                                           "written"]


def test_a_failed_run_removes_the_directories_it_made(tmp_path):
    with pytest.raises(KeyboardInterrupt) as e:
        with OutputFolder(tmp_path / "new" / "out", "report") as folder:
            folder.write("report.json", "new")
            raise KeyboardInterrupt
    assert list(tmp_path.iterdir()) == []
    assert interrupt.kept(e.value) == [f"nothing of this run written to {tmp_path}/new/out"]


def test_a_write_error_names_the_published_path_not_the_staging_folder(tmp_path):
    (tmp_path / "report.json").write_text("old")
    with pytest.raises(OutputError) as e:
        with OutputFolder(tmp_path, "report") as folder:
            (folder.staging / "page.html").mkdir()  # a write fails as on a full disk
            folder.write("page.html", "x")
    assert str(e.value).startswith(f"cannot write the report {tmp_path}/page.html: ")
    assert str(e.value).endswith(f"{tmp_path} kept as it was, nothing of this run written")
    assert STAGING not in str(e.value) and _listing(tmp_path) == {"report.json": b"old"}


def test_a_link_at_a_published_name_is_replaced_not_followed(tmp_path):
    victim = tmp_path / "victim.txt"
    victim.write_text("keep me")
    out = tmp_path / "out"
    out.mkdir()
    (out / "report.html").symlink_to(victim)
    with OutputFolder(out, "report") as folder:
        folder.write("report.html", "page")
        folder.publish()
    assert victim.read_text() == "keep me"
    assert not (out / "report.html").is_symlink() and (out / "report.html").read_text() == "page"


def test_a_directory_in_the_way_is_named_before_anything_is_published(tmp_path):
    (tmp_path / "report.html").mkdir()
    with pytest.raises(OutputError, match=r"report.html is a directory; remove it"):
        with OutputFolder(tmp_path, "report") as folder:
            folder.write("a.json", "new")
            folder.write("report.html", "page")
            folder.publish()
    assert sorted(os.listdir(tmp_path)) == ["report.html"]


def test_a_killed_run_s_staging_folder_is_removed_by_the_next_run(tmp_path):
    stale = tmp_path / f"{STAGING}1-deadbeef"
    stale.mkdir()
    (stale / "report.html").write_text("half")
    with OutputFolder(tmp_path, "report") as folder:
        assert not stale.exists()
        folder.publish()
    assert [p.name for p in tmp_path.iterdir()] == [f"{RECORD}report.json"]  # its record only


def test_names_must_be_plain_file_names(tmp_path):
    with OutputFolder(tmp_path, "report") as folder:
        for name in ("../x", "sub/x", ".lock"):
            with pytest.raises(OutputError, match="is not a plain file name"):
                folder.path(name)


def test_a_file_in_the_way_is_named(tmp_path):
    (tmp_path / "taken").write_text("x")
    with pytest.raises(OutputError, match=r"cannot write the design to the directory .*taken"):
        OutputFolder(tmp_path / "taken", "design")


@pytest.mark.skipif(os.geteuid() == 0, reason="root writes into read-only directories")
def test_a_read_only_directory_is_refused(tmp_path):
    tmp_path.chmod(0o500)
    try:
        with pytest.raises(OutputError, match="report"):
            OutputFolder(tmp_path, "report")
    finally:
        tmp_path.chmod(0o700)


def test_an_interrupt_waits_for_the_last_rename(tmp_path):
    """A SIGTERM that arrives while the files are renamed in is raised after the last one."""
    with interrupt.handled():
        folder = OutputFolder(tmp_path, "report")
        for name in ("a", "b", "c"):
            folder.write(name, name)
        real = os.replace

        def replace(src, dst):
            real(src, dst)
            if str(dst).endswith("a"):
                os.kill(os.getpid(), signal.SIGTERM)

        os.replace = replace  # type: ignore[assignment]
        try:
            with pytest.raises(interrupt.Interrupted) as e:
                with folder:
                    folder.publish()
        finally:
            os.replace = real  # type: ignore[assignment]
    assert _listing(tmp_path) == {"a": b"a", "b": b"b", "c": b"c"}  # all three, no lock
    assert interrupt.kept(e.value) == [f"this run's files published in {tmp_path}"]
