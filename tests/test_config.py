"""Tests of hexaleg.config: TOML tables → frozen dataclasses with clear errors."""

from __future__ import annotations

import os
import re
from dataclasses import dataclass
from pathlib import Path

import pytest

from hexaleg.config import (
    check_tables,
    from_mapping,
    load_toml,
    read_bytes,
    read_json,
    write_file,
)
from hexaleg.errors import ConfigError, OutputError, UnknownNameError


@dataclass(frozen=True)
class _Params:
    period: float = 1.0
    samples: int = 10
    name: str = "x"
    flag: bool = False
    legs: tuple[str, ...] = ()
    limit: float | None = None


def test_builds_and_coerces_ints_to_floats():
    p = from_mapping(_Params, {"period": 2, "samples": 5, "legs": ["LF", "RF"], "limit": 3})
    assert p == _Params(period=2.0, samples=5, legs=("LF", "RF"), limit=3.0)
    assert isinstance(p.period, float)


def test_unknown_key_lists_valid_keys():
    valid = "flag, legs, limit, name, period, samples"
    with pytest.raises(UnknownNameError, match=rf"'speed'.*{valid}"):
        from_mapping(_Params, {"speed": 1.0}, "gait.toml [gait]")


@pytest.mark.parametrize(("key", "value", "match"), [
    ("period", "fast", "expected a number"),
    ("samples", 1.5, "expected an integer"),
    ("samples", True, "expected an integer"),
    ("flag", 1, "expected true or false"),
    ("legs", "LF", "expected a list"),
    ("legs", ["LF", 3], r"legs\[1\]"),
    ("period", float("nan"), "not finite"),
])
def test_wrong_types_name_the_key(key, value, match):
    with pytest.raises(ConfigError, match=match):
        from_mapping(_Params, {key: value})


def test_load_toml_errors(tmp_path):
    with pytest.raises(ConfigError, match="not found"):
        load_toml(tmp_path / "none.toml")
    bad = tmp_path / "bad.toml"
    bad.write_text("a = = 1")
    with pytest.raises(ConfigError, match="not valid TOML"):
        load_toml(bad)
    good = tmp_path / "good.toml"
    good.write_text("[gait]\nperiod = 2.0\n")
    assert load_toml(good) == {"gait": {"period": 2.0}}


def test_text_files_are_regular_utf8_and_bounded(tmp_path, monkeypatch):
    from hexaleg import config
    from hexaleg.config import read_text

    latin = tmp_path / "latin.toml"
    latin.write_bytes("period = 1.0  # café\n".encode("latin-1"))
    with pytest.raises(ConfigError, match=r"latin\.toml is not UTF-8 text: byte 0xe9 at offset "
                                          r"19, line 1, column 20 .*allowed: UTF-8.*iconv"):
        load_toml(latin)
    for special in ("/dev/zero", str(tmp_path)):
        with pytest.raises(ConfigError, match=r"is not a regular file"):
            load_toml(special)
    big = tmp_path / "big.toml"
    big.write_text("x = 1\n", encoding="utf-8")
    monkeypatch.setattr(config, "MAX_TEXT_BYTES", 3)
    with pytest.raises(ConfigError, match=r"big\.toml has 6 bytes; allowed: at most 3"):
        read_text(big, "spec")
    monkeypatch.undo()
    assert read_text(big) == "x = 1\n"


def test_a_symbolic_link_loop_is_named_with_what_is_allowed(tmp_path):
    (tmp_path / "a.toml").symlink_to(tmp_path / "b.toml")
    (tmp_path / "b.toml").symlink_to(tmp_path / "a.toml")
    with pytest.raises(ConfigError, match=r"a\.toml: its symbolic links lead in a loop .*"
                                          r"allowed: a path that leads to a regular file"):
        load_toml(tmp_path / "a.toml")


def test_a_byte_order_mark_is_accepted(tmp_path):
    bom = tmp_path / "bom.toml"
    bom.write_bytes(b"\xef\xbb\xbf[gait]\nperiod = 2.0\n")  # as Windows Notepad saves UTF-8
    assert load_toml(bom) == {"gait": {"period": 2.0}}


@pytest.mark.parametrize("deep", ["{b = " * 3000 + "1" + "}" * 3000,
                                  "[" * 3000 + "1" + "]" * 3000,
                                  "[" * 40 + "1" + "]" * 40])
def test_deep_nesting_is_refused_with_the_bound(tmp_path, deep):
    path = tmp_path / "deep.toml"
    path.write_text(f"a = {deep}\n")
    with pytest.raises(ConfigError, match=r"deep\.toml nests tables or arrays (deeper than "
                                          r"Python's TOML parser can read|41 levels deep); "
                                          r"allowed: at most 32 levels"):
        load_toml(path)


def test_nesting_at_the_bound_is_read(tmp_path):
    path = tmp_path / "ok.toml"
    path.write_text("a = " + "[" * 31 + "1" + "]" * 31 + "\n")  # the document is the 32nd
    assert load_toml(path)["a"] == eval("[" * 30 + "[1]" + "]" * 30)


def test_check_tables_names_the_bad_table_and_the_allowed_ones():
    doc = {"gait": {}, "gaits": {}}
    with pytest.raises(UnknownNameError, match=r"'gaits'.*gait") as e:
        check_tables(doc, ("gait", "contact"), "run.toml")
    assert "run.toml" in str(e.value)
    with pytest.raises(ConfigError, match="document of tables"):
        check_tables([1, 2], ("gait",), "run.toml")
    assert check_tables({"gait": {}}, ("gait",), "run.toml") == {"gait": {}}


def test_the_reader_refuses_pipes_devices_and_directories_without_blocking(tmp_path):
    """A named pipe with no writer is refused at once (an ordinary open would wait forever)."""
    fifo = tmp_path / "pipe.json"
    os.mkfifo(fifo)
    for path in (fifo, Path("/dev/zero"), tmp_path):
        with pytest.raises(ConfigError, match=r"is not a regular file"):
            read_bytes(path, "design file")


def test_the_reader_bounds_what_it_reads(tmp_path):
    big = tmp_path / "big.json"
    big.write_bytes(b" " * 101)
    with pytest.raises(ConfigError, match=r"has 101 bytes; allowed: at most 100"):
        read_bytes(big, "design file", 100)
    assert read_bytes(big, "design file", 101) == b" " * 101


def test_links_are_refused_where_hexaleg_owns_the_directory(tmp_path):
    target = tmp_path / "elsewhere.json"
    target.write_text("{}")
    link = tmp_path / "manifest.json"
    link.symlink_to(target)
    assert read_json(link, "sweep manifest") == {}  # a user's own path may be a link
    with pytest.raises(ConfigError, match=r"manifest\.json is a symbolic link"):
        read_json(link, "sweep manifest", follow=False)


@pytest.mark.parametrize(("text", "says"), [
    ('{"a": NaN}', "NaN is not a JSON number"), ('{"a": -Infinity}', "-Infinity is not a JSON"),
    ('{"a": 1e400}', "1e400 is beyond the largest float"), ("[1]", "expected a JSON object"),
    ("{", "not valid JSON"), ("", "not valid JSON")])
def test_json_is_finite_and_an_object(tmp_path, text, says):
    path = tmp_path / "d.json"
    path.write_text(text)
    with pytest.raises(ConfigError, match=re.escape(says)):
        read_json(path, "design file")


def test_written_files_replace_a_link_and_leave_its_target(tmp_path):
    """A link planted where hexaleg writes is replaced by the file, never written through."""
    target = tmp_path / "precious.txt"
    target.write_text("keep me")
    out = tmp_path / "out"
    out.mkdir()
    (out / "report.json").symlink_to(target)
    write_file(out / "report.json", '{"ok": true}')
    assert target.read_text() == "keep me"
    assert not (out / "report.json").is_symlink()
    assert (out / "report.json").read_text() == '{"ok": true}'
    assert sorted(p.name for p in out.iterdir()) == ["report.json"]  # no temporary left
    with pytest.raises(OutputError, match=r"cannot write the report .*nowhere"):
        write_file(tmp_path / "nowhere" / "x.json", "{}", "the report")


def test_an_interrupted_write_leaves_the_old_file_and_no_temporary(tmp_path, monkeypatch):
    import os

    path = tmp_path / "page.html"
    path.write_text("old")

    def interrupted(fd, data):
        raise KeyboardInterrupt

    monkeypatch.setattr(os, "write", interrupted)
    with pytest.raises(KeyboardInterrupt):
        write_file(path, "new")
    monkeypatch.undo()
    assert [p.name for p in tmp_path.iterdir()] == ["page.html"] and path.read_text() == "old"


def test_keywords_are_checked_against_the_function_s_annotations():
    from hexaleg.config import keywords
    from hexaleg.errors import ConfigError, UnknownNameError

    def f(a: int = 1, b: bool = True, c: float | None = None) -> None:
        """A function with annotated keywords."""

    assert keywords(f, {"a": 2, "b": False, "c": None}, "t") == {"a": 2, "b": False, "c": None}
    with pytest.raises(ConfigError, match=r"t\.b = 'false'.*true or false"):
        keywords(f, {"b": "false"}, "t")
    with pytest.raises(UnknownNameError, match="d"):
        keywords(f, {"d": 1}, "t")
    with pytest.raises(UnknownNameError, match="c"):
        keywords(f, {"c": 1.0}, "t", keys=("a", "b"))


def test_json_text_writes_non_finite_numbers_as_null_and_says_where(tmp_path):
    import numpy as np

    from hexaleg.config import read_json
    from hexaleg.quantities import NON_FINITE, json_text

    text = json_text({"a": {"value": float("inf"), "unit": "Pa"},
                      "b": [1.0, np.float64("nan"), np.float64(2.0), np.int64(3), np.bool_(True)]})
    path = tmp_path / "x.json"
    path.write_text(text)
    data = read_json(path)
    assert data["a"]["value"] is None and data["b"] == [1.0, None, 2.0, 3, True]
    assert data[NON_FINITE]["paths"] == ["a.value", "b[1]"]
    assert NON_FINITE not in read_json_of(tmp_path, json_text({"a": 1.0}))


def read_json_of(tmp_path, text):
    from hexaleg.config import read_json

    path = tmp_path / "y.json"
    path.write_text(text)
    return read_json(path)


def test_read_json_refuses_a_key_given_twice(tmp_path):
    from hexaleg.errors import ConfigError

    with pytest.raises(ConfigError, match="'springs' is given twice"):
        read_json_of(tmp_path, '{"springs": [1], "title": "x", "springs": [2]}')
    assert read_json_of(tmp_path, '{"a": {"b": 1}, "c": {"b": 2}}')["c"]["b"] == 2
