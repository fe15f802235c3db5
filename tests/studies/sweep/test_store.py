"""Tests of hexaleg.studies.sweep.store: part files written chunk by chunk, the manifest, reading
the rows back in point order, resuming (finished points known, a different spec refused), stray
temporary files, and unwritable directories."""

from __future__ import annotations

import json

import pandas as pd
import pytest

from hexaleg.errors import ConfigError, OutputError
from hexaleg.studies.sweep.store import MANIFEST, ResultStore, spec_differences

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
    assert not list((tmp_path / "out").glob("*.tmp"))  # renamed into place
    pd.testing.assert_frame_equal(pd.read_parquet(first), rows([0, 1, 2]))


def test_manifest_holds_the_canonical_spec_and_metadata(tmp_path):
    ResultStore(tmp_path / "out", SPEC, {"motor": "AX-18A", "n_points": 2})
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
    again = ResultStore(tmp_path / "out", SPEC, {"note": "second"})
    assert again.finished() == {0, 1, 2}
    assert again.manifest["note"] == "first"  # metadata of a resumed sweep is not rewritten
    todo = [i for i in range(6) if i not in again.finished()]
    assert todo == [3, 4, 5]
    again.write(rows(todo))
    pd.testing.assert_frame_equal(again.table(), rows(list(range(6))))


def test_a_different_spec_is_refused_with_its_differences(tmp_path):
    ResultStore(tmp_path / "out", SPEC)
    other = {"gait": {"samples": 100}, "springs": {"coxa": {"k": (0.1, 0.2)}}}
    with pytest.raises(ConfigError, match=r"holds a different sweep.*gait\.samples: 50 → 100; "
                                          r"springs\.coxa\.theta_k: 0\.01 → \(absent\)"):
        ResultStore(tmp_path / "out", other)
    assert spec_differences({"a": 1}, {"a": 1, "b": {"c": 2}}) == ["b.c: (absent) → 2"]


def test_unreadable_manifest_and_stray_temporary_files(tmp_path):
    out = tmp_path / "out"
    store = ResultStore(out, SPEC)
    stray = out / "part-0000000-0000002.parquet.tmp"
    stray.write_bytes(b"half a file")
    ResultStore(out, SPEC)
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
