"""Parameters from TOML: frozen dataclasses filled from mappings, with errors that name the key.

Every parameter dataclass in hexaleg is built through :func:`from_mapping`, so an unknown key is an
error listing the valid keys and a value of the wrong type is an error naming the key, the value
and the expected type.
"""

from __future__ import annotations

import dataclasses
import stat
import sys
import types
import typing
from collections.abc import Mapping
from pathlib import Path
from typing import Any, TypeVar

from hexaleg.checks import is_integer, is_real
from hexaleg.errors import ConfigError, UnknownNameError

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

T = TypeVar("T")


MAX_TEXT_BYTES = 16 * 1024**2
"""Largest text file hexaleg reads (a TOML config, a URDF or SRDF), B: far beyond any real one, and
a bound that keeps a wrong path (a log, a data set) from filling memory."""


def read_text(path: str | Path, what: str = "config file") -> str:
    """The text of a regular file, decoded as UTF-8 (TOML requires it; hexaleg's XML files too).

    Args:
        path: The file.
        what: What the file is (``"config file"``, ``"URDF"``, …), for the error.

    Raises:
        ConfigError: the path does not exist or is not a regular file (a directory, a device
            such as ``/dev/zero``, a pipe: refused before reading), is larger than
            :data:`MAX_TEXT_BYTES`, cannot be read, or is not UTF-8 (the message names the
            byte offset and how to convert the file).
    """
    path = Path(path)
    try:
        info = path.stat()
    except FileNotFoundError:
        raise ConfigError(f"{what} not found: {path}") from None
    except OSError as e:
        raise ConfigError(f"cannot read {what} {path}: {e}") from e
    if not stat.S_ISREG(info.st_mode):
        raise ConfigError(f"{what} {path} is not a regular file (a directory, device or pipe); "
                          "give the path of a text file")
    if info.st_size > MAX_TEXT_BYTES:
        raise ConfigError(f"{what} {path} has {info.st_size} bytes; allowed: at most "
                          f"{MAX_TEXT_BYTES} (is it the right file?)")
    try:
        data = path.read_bytes()
    except OSError as e:
        raise ConfigError(f"cannot read {what} {path}: {e}") from e
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as e:
        raise ConfigError(f"{what} {path} is not UTF-8 text: byte {data[e.start]:#04x} at offset "
                          f"{e.start} ({e.reason}); save it as UTF-8 (e.g. iconv -f latin1 -t "
                          "utf-8)") from None


def load_toml(path: str | Path) -> dict[str, Any]:
    """Read a TOML file (UTF-8, a regular file: :func:`read_text`).

    Raises:
        ConfigError: the file is missing, not a regular file, too large, unreadable, not UTF-8
            or not valid TOML.
    """
    path = Path(path)
    text = read_text(path, "config file")
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as e:
        raise ConfigError(f"config file {path} is not valid TOML: {e}") from e


def _check_type(key: str, value: Any, hint: Any) -> Any:
    """Check (and lightly coerce: int → float) one value against a type hint."""
    origin = typing.get_origin(hint)
    if origin in (typing.Union, types.UnionType):
        errors = []
        for option in typing.get_args(hint):
            try:
                return _check_type(key, value, option)
            except ConfigError as e:
                errors.append(e)
        raise ConfigError(f"{key} = {value!r} has type {type(value).__name__}; expected {hint}")
    if hint is type(None):
        if value is None:
            return None
        raise ConfigError(f"{key} = {value!r}; expected None")
    if hint is float:
        if is_real(value):
            return float(value)
        if isinstance(value, float):  # NaN or inf
            raise ConfigError(f"{key} = {value!r} is not finite; expected a finite number")
        raise ConfigError(f"{key} = {value!r} has type {type(value).__name__}; "
                          "expected a number")
    if hint is int:
        if not is_integer(value):
            raise ConfigError(f"{key} = {value!r} has type {type(value).__name__}; "
                              "expected an integer")
        return value
    if hint is bool:
        if not isinstance(value, bool):
            raise ConfigError(f"{key} = {value!r} has type {type(value).__name__}; "
                              "expected true or false")
        return value
    if hint is str:
        if not isinstance(value, str):
            raise ConfigError(f"{key} = {value!r} has type {type(value).__name__}; "
                              "expected a string")
        return value
    if origin in (tuple, list):
        if not isinstance(value, (list, tuple)):
            raise ConfigError(f"{key} = {value!r} has type {type(value).__name__}; "
                              "expected a list")
        args = typing.get_args(hint)
        inner = args[0] if args else Any
        seq = [_check_type(f"{key}[{i}]", v, inner) for i, v in enumerate(value)]
        return tuple(seq) if origin is tuple else seq
    return value


def check_tables(data: object, allowed: tuple[str, ...], where: str) -> Mapping[str, Any]:
    """A parsed TOML document whose top-level names are all in ``allowed``.

    Raises:
        ConfigError: ``data`` is not a document of tables.
        UnknownNameError: a top-level name that is not allowed (lists the allowed ones).
    """
    if not isinstance(data, Mapping):
        raise ConfigError(f"{where}: expected a TOML document of tables, got {data!r}")
    for key in data:
        if key not in allowed:
            raise UnknownNameError(f"table in {where}", key, allowed)
    return data


def from_mapping(cls: type[T], data: Mapping[str, Any], where: str = "") -> T:
    """Build dataclass ``cls`` from ``data``, checking keys and value types.

    Args:
        cls: A dataclass type.
        data: Keys are field names.
        where: Where the data came from (e.g. ``"gait.toml [gait]"``), for error messages.

    Returns:
        The instance (its ``__post_init__`` validation runs as usual).

    Raises:
        UnknownNameError: a key is not a field; the message lists the valid keys.
        ConfigError: a value has the wrong type.
    """
    if not isinstance(data, Mapping):
        raise ConfigError(f"{where or cls.__name__}: expected a table of keys, got {data!r}")
    fields = {f.name: f for f in dataclasses.fields(cls) if f.init}  # type: ignore[arg-type]
    hints = typing.get_type_hints(cls)
    kwargs = {}
    for key, value in data.items():
        if key not in fields:
            kind = f"key in {where}" if where else f"{cls.__name__} key"
            raise UnknownNameError(kind, key, fields)
        kwargs[key] = _check_type(f"{where + '.' if where else ''}{key}", value, hints[key])
    required = [name for name, f in fields.items() if f.default is dataclasses.MISSING
                and f.default_factory is dataclasses.MISSING]
    missing = [name for name in required if name not in kwargs]
    if missing:
        raise ConfigError(f"{where or cls.__name__}: missing {', '.join(missing)}; required "
                          f"keys: {', '.join(required)}")
    return cls(**kwargs)
