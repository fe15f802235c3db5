"""Tests of hexaleg.config: TOML tables → frozen dataclasses with clear errors."""

from __future__ import annotations

from dataclasses import dataclass

import pytest

from hexaleg.config import check_tables, from_mapping, load_toml
from hexaleg.errors import ConfigError, UnknownNameError


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
                                          r"19 .*iconv"):
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


def test_check_tables_names_the_bad_table_and_the_allowed_ones():
    doc = {"gait": {}, "gaits": {}}
    with pytest.raises(UnknownNameError, match=r"'gaits'.*gait") as e:
        check_tables(doc, ("gait", "contact"), "run.toml")
    assert "run.toml" in str(e.value)
    with pytest.raises(ConfigError, match="document of tables"):
        check_tables([1, 2], ("gait",), "run.toml")
    assert check_tables({"gait": {}}, ("gait",), "run.toml") == {"gait": {}}
