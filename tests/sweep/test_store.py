"""Tests of hexaleg.sweep.store: part files written chunk by chunk, the manifest, reading
the rows back in point order (also with ``pandas.read_parquet(DIR)``, as docs/sweep.md says),
resuming (finished points known, a different spec refused, an unreadable part set aside), the
directory's lock, stray temporary files, and unwritable directories."""

from __future__ import annotations

import json
import os

import pandas as pd
import pytest

from hexaleg.errors import ConfigError, DirectoryLockedError, HexalegWarning, OutputError
from hexaleg.sweep.store import (
    LEGACY_MANIFEST,
    MANIFEST,
    ResultStore,
    read_table,
    spec_differences,
)

SPEC = {"gait": {"samples": 50}, "springs": {"coxa": {"k": (0.1, 0.2), "theta_k": 0.01}}}


def rows(points: list[int]) -> pd.DataFrame:
    return pd.DataFrame({"point": points, "value": [float(10 * p) for p in points],
                         "status": ["ok"] * len(points)})


def test_parts_are_written_as_chunks_finish(tmp_path):
    store = ResultStore(tmp_path / "out", SPEC)
    assert store.parts() == [] and store.finished() == set()
    first = store.write(rows([0, 1, 2]))
    assert first.name == "part-0000000-0000002.parquet" and first.exists()
    assert store.parts() == [first] and store.finished() == {0, 1, 2}
    second = store.write(rows([3, 4]))
    assert store.parts() == [first, second] and store.finished() == {0, 1, 2, 3, 4}
    assert not list((tmp_path / "out").glob("*tmp*"))  # renamed into place
    pd.testing.assert_frame_equal(pd.read_parquet(first), rows([0, 1, 2]))


def test_manifest_holds_the_canonical_spec_and_metadata(tmp_path):
    ResultStore(tmp_path / "out", SPEC, {"motor": "AX-18A", "n_points": 2}).close()
    manifest = json.loads((tmp_path / "out" / MANIFEST).read_text())
    assert manifest["spec"]["springs"]["coxa"]["k"] == [0.1, 0.2]  # tuples → lists
    assert manifest["motor"] == "AX-18A" and manifest["n_points"] == 2


def test_table_reads_all_parts_back_in_point_order(tmp_path):
    store = ResultStore(tmp_path / "out", SPEC)
    assert store.table().empty
    store.write(rows([5, 6]))  # chunks may finish out of order
    store.write(rows([0, 1, 2]))
    store.write(rows([3, 4]))
    pd.testing.assert_frame_equal(store.table(), rows(list(range(7))))


def test_reopening_with_the_same_spec_resumes(tmp_path):
    store = ResultStore(tmp_path / "out", SPEC, {"note": "first"})
    store.write(rows([0, 1, 2]))
    store.close()
    again = ResultStore(tmp_path / "out", SPEC, {"note": "second"})
    assert again.finished() == {0, 1, 2}
    assert again.manifest["note"] == "first"  # metadata of a resumed sweep is not rewritten
    todo = [i for i in range(6) if i not in again.finished()]
    assert todo == [3, 4, 5]
    again.write(rows(todo))
    pd.testing.assert_frame_equal(again.table(), rows(list(range(6))))


def test_a_different_spec_is_refused_with_its_differences(tmp_path):
    ResultStore(tmp_path / "out", SPEC).close()
    other = {"gait": {"samples": 100}, "springs": {"coxa": {"k": (0.1, 0.2)}}}
    with pytest.raises(ConfigError, match=r"holds a different sweep.*gait\.samples: 50 → 100; "
                                          r"springs\.coxa\.theta_k: 0\.01 → \(absent\)"):
        ResultStore(tmp_path / "out", other)
    assert spec_differences({"a": 1}, {"a": 1, "b": {"c": 2}}) == ["b.c: (absent) → 2"]


def test_unreadable_manifest_and_stray_temporary_files(tmp_path):
    out = tmp_path / "out"
    store = ResultStore(out, SPEC)
    stray = out / f".part-0000000-0000002.parquet.{os.getpid() + 1}-0123abcd.tmp"
    stray.write_bytes(b"half a file")
    store.close()
    ResultStore(out, SPEC).close()
    assert not stray.exists() and store.finished() == set()
    (out / MANIFEST).write_text("{not json")
    with pytest.raises(ConfigError, match=r"is not a hexaleg sweep manifest"):
        ResultStore(out, SPEC)


def test_unwritable_directory_is_an_output_error(tmp_path):
    blocker = tmp_path / "file"
    blocker.write_text("")
    with pytest.raises(OutputError, match=r"cannot write the sweep manifest"):
        ResultStore(blocker / "out", SPEC)
    store = ResultStore(tmp_path / "out", SPEC)
    store.directory = blocker / "gone"
    with pytest.raises(OutputError, match=r"cannot write sweep results"):
        store.write(rows([0]))


# --------------------------------------------------------------------------- one writer


def test_a_second_writer_is_refused_naming_the_first(tmp_path):
    with ResultStore(tmp_path / "out", SPEC):
        with pytest.raises(DirectoryLockedError, match=rf"pid {os.getpid()} on host .*started "
                                                       r".*another --out") as e:
            ResultStore(tmp_path / "out", SPEC)
        assert e.value.pid == os.getpid() and e.value.host
    with ResultStore(tmp_path / "out", SPEC) as again:  # released: the next writer may come
        assert again.lock.stale is None


def test_a_refused_writer_leaves_the_directory_as_it_was(tmp_path):
    with ResultStore(tmp_path / "out", SPEC) as store:
        store.write(rows([0, 1]))
        before = sorted(p.name for p in (tmp_path / "out").iterdir())
        with pytest.raises(DirectoryLockedError):
            ResultStore(tmp_path / "out", {"a different": "spec"})
        assert sorted(p.name for p in (tmp_path / "out").iterdir()) == before
        assert store.finished() == {0, 1}


def test_unique_hidden_temporary_names(tmp_path, monkeypatch):
    from hexaleg.sweep import store as store_module

    seen = []
    real = store_module._temporary

    def spy(path):
        seen.append(real(path))
        return seen[-1]

    monkeypatch.setattr(store_module, "_temporary", spy)
    with ResultStore(tmp_path / "out", SPEC) as store:
        store.write(rows([0, 1]))
        store.write(rows([0, 1]))  # the same part twice: two different temporary names
    assert len(seen) == 3 and len(set(seen)) == 3  # the manifest's and the two parts'
    assert all(p.name.startswith(".") and str(os.getpid()) in p.name for p in seen)


# --------------------------------------------------------------------------- reading, resuming


def test_pandas_reads_the_directory_as_documented(tmp_path):
    def sided(points, side):  # a column with no value in some chunks (an optimal sweep's
        return rows(points).assign(side=side)  # "<group>.side"): one schema for every part

    with ResultStore(tmp_path / "out", SPEC) as store:
        store.write(sided([3, 4], [None, None]))
        store.write(sided([0, 1, 2], [None] * 3))
        store.write(sided([7], [None]))
        store.write(sided([5, 6], ["above", None]))
        (tmp_path / "out" / ".part-0000009-0000009.parquet.1-deadbeef.tmp").write_bytes(b"x")
        table = pd.read_parquet(tmp_path / "out")  # the manifest, lock and temporary are skipped
    table = table.sort_values("point").reset_index(drop=True)
    assert list(table["point"]) == list(range(8))
    assert table["side"].iloc[5] == "above" and table["side"].drop(5).isna().all()
    pd.testing.assert_frame_equal(table, read_table(tmp_path / "out"), check_dtype=False)


def test_a_truncated_part_is_set_aside_and_its_points_counted_missing(tmp_path):
    with ResultStore(tmp_path / "out", SPEC) as store:
        store.write(rows([0, 1, 2]))
        bad = store.write(rows([3, 4]))
        store.write(rows([5]))
    bad.write_bytes(bad.read_bytes()[: bad.stat().st_size // 2])
    with pytest.raises(OutputError, match=r"cannot read sweep part .*part-0000003-0000004"):
        read_table(tmp_path / "out")
    with ResultStore(tmp_path / "out", SPEC) as store:
        with pytest.warns(HexalegWarning, match=r"part-0000003-0000004\.parquet cannot be read "
                                                r".*points \(3…4\) will be computed again"):
            assert store.finished() == {0, 1, 2, 5}
        assert not bad.exists() and (tmp_path / "out" / f"_unreadable-{bad.name}").exists()
        store.write(rows([3, 4]))
        pd.testing.assert_frame_equal(store.table(), rows(list(range(6))))
    assert len(pd.read_parquet(tmp_path / "out")) == 6  # the set-aside file is not read


@pytest.mark.parametrize(("name", "points", "why"), [
    ("part-0000000-0000001.parquet", [0, 5], "other points than its name"),
    ("part-0000003-0000004.parquet", [3, 4], "repeats points of another part")])
def test_a_part_that_does_not_hold_what_its_name_says_is_set_aside(tmp_path, name, points, why):
    with ResultStore(tmp_path / "out", SPEC) as store:
        store.write(rows([2, 3, 4]))
        rows(points).to_parquet(tmp_path / "out" / name, index=False)
        with pytest.warns(HexalegWarning, match=why):
            assert store.finished() == {2, 3, 4}


def test_a_directory_of_the_unlocked_layout_is_resumed(tmp_path):
    out = tmp_path / "out"
    with ResultStore(out, SPEC) as store:
        store.write(rows([0, 1]))
    os.replace(out / MANIFEST, out / LEGACY_MANIFEST)  # as written before the lock existed
    with ResultStore(out, SPEC) as store:
        assert store.finished() == {0, 1}
    assert (out / MANIFEST).exists() and not (out / LEGACY_MANIFEST).exists()


def test_a_manifest_that_is_a_link_or_a_device_is_refused(tmp_path):
    """The manifest is read by the bounded reader, not through a link: a link to /dev/zero
    would fill memory, one to a pipe would hang."""
    out = tmp_path / "out"
    out.mkdir()
    (out / MANIFEST).symlink_to("/dev/zero")
    with pytest.raises(ConfigError, match=r"not a hexaleg sweep manifest: .*symbolic link"):
        ResultStore(out, SPEC)
    (out / MANIFEST).unlink()
    os.mkfifo(out / MANIFEST)
    with pytest.raises(ConfigError, match=r"not a regular file"):
        ResultStore(out, SPEC)
    assert not (out / ".lock").exists()  # the lock is released
