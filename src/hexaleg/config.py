"""Parameters from TOML: frozen dataclasses filled from mappings, with errors that name the key.

Every parameter dataclass in hexaleg is built through :func:`from_mapping`, so an unknown key is an
error listing the valid keys and a value of the wrong type is an error naming the key, the value
and the expected type.
"""

from __future__ import annotations

import contextlib
import dataclasses
import errno
import json
import math
import os
import secrets
import stat
import sys
import types
import typing
from collections.abc import Mapping
from pathlib import Path
from typing import Any, TypeVar

from hexaleg.checks import is_integer, is_real
from hexaleg.errors import ConfigError, OutputError, UnknownNameError

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib

T = TypeVar("T")


MAX_TEXT_BYTES = 16 * 1024**2
"""Largest text file hexaleg reads (a TOML config, a URDF or SRDF, a design.json), B: far beyond
any real one, and a bound that keeps a wrong path (a log, a data set) from filling memory."""


def read_bytes(path: str | Path, what: str = "config file", limit: int | None = None, *,
               follow: bool = True) -> bytes:
    """The bytes of a regular file of at most ``limit`` bytes: the one reader of every file
    hexaleg takes (config, URDF/SRDF, design and simulation files, a sweep's own files).

    The file is opened without blocking (a named pipe with no writer would hang an ordinary
    open) and checked through its open descriptor, so what is checked is what is read: a
    regular file (not a directory, device such as ``/dev/zero``, pipe or socket), no larger than
    ``limit``; the read stops at ``limit`` + 1 bytes whatever the file claims.

    Args:
        path: The file.
        what: What the file is (``"config file"``, ``"design file"``, …), for the error.
        limit: Largest size allowed, B; default :data:`MAX_TEXT_BYTES`.
        follow: Whether a symbolic link is followed; False for files in a directory hexaleg
            owns (a sweep's manifest, its lock), where a link is refused.

    Raises:
        ConfigError: missing, a symbolic link (``follow=False``), not a regular file, larger
            than ``limit`` or unreadable; the message names the path and what is allowed.
    """
    path = Path(path)
    limit = MAX_TEXT_BYTES if limit is None else limit
    flags = os.O_RDONLY | os.O_NONBLOCK | getattr(os, "O_NOCTTY", 0) | getattr(os, "O_CLOEXEC", 0)
    if not follow:
        flags |= getattr(os, "O_NOFOLLOW", 0)
        if path.is_symlink():  # O_NOFOLLOW's ELOOP says less; also where it is missing
            raise ConfigError(f"{what} {path} is a symbolic link; hexaleg does not follow links "
                              "in a directory it owns: remove the link")
    try:
        fd = os.open(path, flags)
    except FileNotFoundError:
        raise ConfigError(f"{what} not found: {path}") from None
    except OSError as e:
        if e.errno == errno.ELOOP and follow:
            raise ConfigError(f"cannot read {what} {path}: its symbolic links lead in a loop (or "
                              "more than 40 deep); allowed: a path that leads to a regular "
                              "file: give the file's own path") from None
        raise ConfigError(f"cannot read {what} {path}: {e.strerror or e}") from e
    try:
        info = os.fstat(fd)
        if not stat.S_ISREG(info.st_mode):
            raise ConfigError(f"{what} {path} is not a regular file (a directory, device, pipe "
                              "or socket); give the path of a file")
        if info.st_size > limit:
            raise ConfigError(f"{what} {path} has {info.st_size} bytes; allowed: at most "
                              f"{limit} (is it the right file?)")
        os.set_blocking(fd, True)
        chunks, size = [], 0
        while size <= limit:
            chunk = os.read(fd, min(1 << 20, limit + 1 - size))
            if not chunk:
                break
            chunks.append(chunk)
            size += len(chunk)
    except OSError as e:
        raise ConfigError(f"cannot read {what} {path}: {e.strerror or e}") from e
    finally:
        os.close(fd)
    if size > limit:  # grew while being read
        raise ConfigError(f"{what} {path} has more than {limit} bytes; allowed: at most {limit}")
    return b"".join(chunks)


def read_text(path: str | Path, what: str = "config file", limit: int | None = None, *,
              follow: bool = True) -> str:
    """The text of a regular file (:func:`read_bytes`), decoded as UTF-8 (TOML and JSON require
    it; hexaleg's XML files too).

    A UTF-8 byte-order mark (which some Windows editors write) is dropped.

    Raises:
        ConfigError: as :func:`read_bytes`, or not UTF-8 (the message names the byte, its
            offset, line and column and how to convert the file).
    """
    data = read_bytes(path, what, limit, follow=follow)
    try:
        return data.decode("utf-8").removeprefix("\ufeff")  # a byte-order mark is no text
    except UnicodeDecodeError as e:
        line = data.count(b"\n", 0, e.start) + 1
        column = e.start - (data.rfind(b"\n", 0, e.start) + 1) + 1
        raise ConfigError(f"{what} {path} is not UTF-8 text: byte {data[e.start]:#04x} at offset "
                          f"{e.start}, line {line}, column {column} ({e.reason}); allowed: "
                          "UTF-8, with or without a byte-order mark: save it as UTF-8 (e.g. "
                          f"iconv -f latin1 -t utf-8 {path})") from None


def _no_constant(name: str) -> float:
    raise ValueError(f"{name} is not a JSON number (JSON has no NaN or Infinity); allowed: "
                     "finite numbers (hexaleg writes a value that is not finite as null)")


def _finite_float(text: str) -> float:
    value = float(text)
    if not math.isfinite(value):
        raise ValueError(f"{text} is beyond the largest float (about 1.8e308)")
    return value


def _unique_keys(pairs: list[tuple[str, Any]]) -> dict[str, Any]:
    """A JSON object's pairs as a dict; a key given twice is refused (Python's json keeps the
    last one and drops the first without a word)."""
    out: dict[str, Any] = {}
    for key, value in pairs:
        if key in out:
            raise ValueError(f"the key {key!r} is given twice in one object")
        out[key] = value
    return out


def read_json(path: str | Path, what: str = "JSON file", limit: int | None = None, *,
              follow: bool = True) -> dict[str, Any]:
    """A JSON object from a regular file (:func:`read_text`). ``NaN``, ``Infinity`` and
    ``-Infinity`` (which Python's json accepts and JSON does not) and numbers beyond a float
    (``1e400``) are refused, so every number read is finite; so is a key given twice in one
    object (which Python's json would silently resolve to the last).

    Raises:
        ConfigError: as :func:`read_text`, not JSON, a non-finite number, a duplicate key, or
            not an object.
    """
    text = read_text(path, what, limit, follow=follow)
    try:
        data = json.loads(text, parse_constant=_no_constant, parse_float=_finite_float,
                          object_pairs_hook=_unique_keys)
    except (ValueError, RecursionError) as e:
        raise ConfigError(f"cannot read {what} {path}: not valid JSON: {e}") from None
    if not isinstance(data, dict):
        raise ConfigError(f"{what} {path}: expected a JSON object, got {type(data).__name__}")
    return data


def write_file(path: str | Path, data: bytes | str, what: str = "file") -> Path:
    """Write ``data`` to ``path`` without following a symbolic link there: to a new hidden file
    beside it (``O_CREAT | O_EXCL | O_NOFOLLOW``), then renamed over it, so a link at ``path``
    is replaced, never written through, and readers see the old file or the whole new one.

    Raises:
        OutputError: the file cannot be written (named).
    """
    path = Path(path)
    raw = data.encode("utf-8") if isinstance(data, str) else data
    tmp = path.with_name(f".{path.name}.{os.getpid()}-{secrets.token_hex(4)}.tmp")
    flags = (os.O_WRONLY | os.O_CREAT | os.O_EXCL | getattr(os, "O_NOFOLLOW", 0)
             | getattr(os, "O_CLOEXEC", 0))
    try:
        fd = os.open(tmp, flags, 0o644)
        try:
            view = memoryview(raw)
            while view:
                view = view[os.write(fd, view):]
        finally:
            os.close(fd)
        os.replace(tmp, path)
    except BaseException as e:  # a full disk, or Ctrl-C: no temporary file left behind
        with contextlib.suppress(OSError):
            tmp.unlink()
        if isinstance(e, OSError):
            raise OutputError(f"cannot write {what} {path}: {e.strerror or e}") from e
        raise
    return path


MAX_NESTING = 32
"""Deepest nesting of tables and arrays in a TOML file hexaleg reads (``[a.b]`` is 2 deep, a
list of lists in it 4): hexaleg's own files nest 3 deep. Python's TOML parser recurses once a
level and fails with a ``RecursionError`` near a few hundred levels."""


def _nesting(data: object) -> int:
    """How deep tables (dicts) and arrays (lists) nest in ``data`` (0 for a scalar); iterative,
    so any depth is measured."""
    deepest, stack = 0, [(data, 0)]
    while stack:
        value, depth = stack.pop()
        if isinstance(value, dict):
            stack += [(v, depth + 1) for v in value.values()]
        elif isinstance(value, list):
            stack += [(v, depth + 1) for v in value]
        else:
            continue
        deepest = max(deepest, depth + 1)
    return deepest


def load_toml(path: str | Path) -> dict[str, Any]:
    """Read a TOML file (UTF-8, a regular file: :func:`read_text`) whose tables and arrays nest
    at most :data:`MAX_NESTING` deep (the document itself is a level).

    Raises:
        ConfigError: the file is missing, not a regular file, too large, unreadable, not UTF-8,
            not valid TOML or nested deeper than :data:`MAX_NESTING`.
    """
    path = Path(path)
    text = read_text(path, "config file")
    too_deep = (f"config file {path} nests tables or arrays {{}}; allowed: at most "
                f"{MAX_NESTING} levels (hexaleg's own files nest 3 deep)")
    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as e:
        raise ConfigError(f"config file {path} is not valid TOML: {e}") from e
    except RecursionError:  # the parser recurses once a level
        raise ConfigError(too_deep.format("deeper than Python's TOML parser can read")) from None
    depth = _nesting(data)
    if depth > MAX_NESTING:
        raise ConfigError(too_deep.format(f"{depth} levels deep"))
    return data


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


def keywords(fn: Any, data: Mapping[str, Any], where: str,
             keys: tuple[str, ...] | None = None) -> dict[str, Any]:
    """``data`` checked as keyword arguments of ``fn``: each key one of ``keys`` (default: the
    function's parameters), each value of the type its annotation says (as
    :func:`from_mapping` checks a dataclass's fields; a key without an annotation is passed as
    it is, for its own check).

    Raises:
        UnknownNameError: a key that is not allowed (lists the allowed ones).
        ConfigError: a value of the wrong type (``simulate = "false"`` is not false).
    """
    if not isinstance(data, Mapping):
        raise ConfigError(f"{where}: expected a table of keys, got {data!r}")
    hints = typing.get_type_hints(fn)
    allowed = keys if keys is not None else tuple(h for h in hints if h != "return")
    out = {}
    for key, value in data.items():
        if key not in allowed:
            raise UnknownNameError(f"{where} key", key, allowed)
        out[key] = _check_type(f"{where}.{key}", value, hints[key]) if key in hints else value
    return out


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
