"""Parameters from TOML: frozen dataclasses filled from mappings, with errors that name the key.

Every parameter dataclass in hexaleg is built through :func:`from_mapping`, so an unknown key is an
error listing the valid keys and a value of the wrong type is an error naming the key, the value
and the expected type.
"""

from __future__ import annotations

import dataclasses
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


def load_toml(path: str | Path) -> dict[str, Any]:
    """Read a TOML file.

    Raises:
        ConfigError: the file is missing, unreadable or not valid TOML.
    """
    path = Path(path)
    try:
        return tomllib.loads(path.read_text())
    except FileNotFoundError as e:
        raise ConfigError(f"config file not found: {path}") from e
    except OSError as e:
        raise ConfigError(f"cannot read config file {path}: {e}") from e
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
