"""Reading a motion log: CSV with a header row or NPZ with the same names, into SI columns.

Column names (docs/motion.md): ``time``; optional base pose ``base_x, base_y, base_z`` (world,
m) and ``base_qx, base_qy, base_qz, base_qw``; one column per actuated joint named as the robot's
joints (rad); optional ``contact_<LEG>`` (0/1, a switch's) or ``stance_<LEG>`` (0/1, a plan's);
optional exact derivatives ``v_<name>`` and
``a_<name>`` of every joint and of the base (``v_base_x … v_base_z`` the LOCAL linear velocity,
``v_base_rx … v_base_rz`` the LOCAL angular velocity, Pinocchio's free-flyer convention; ``a_``
their time derivatives), as :func:`hexaleg.motion.recorded.write.write_motion_log` writes them.
A unit in brackets after a name overrides the default: ``LF_femur [deg]``, ``time [ms]``,
``base_z [mm]``. Values are converted to SI here, by the factors of
:data:`~hexaleg.motion.recorded.columns.UNITS` (through :mod:`hexaleg.units`), and nowhere else.
The names, their kinds and units and the :class:`Log` read into are in
:mod:`hexaleg.motion.recorded.columns` (importable from here too); a ROS 2 bag is read by
:mod:`hexaleg.motion.recorded.bag`.
"""

from __future__ import annotations

import io
import re
import warnings
import zipfile
from pathlib import Path

import numpy as np

from hexaleg.config import read_bytes
from hexaleg.errors import ConfigError, InvalidParameterError
from hexaleg.motion.recorded.bag import bag_directory, read_bag
from hexaleg.motion.recorded.columns import (
    BASE_POSITION,
    BASE_QUATERNION,
    BASE_VELOCITY,
    MAX_LOG_BYTES,
    UNITS,
    Log,
    column_kind,
)
from hexaleg.robot.model import Robot

_HEADER = re.compile(r"^\s*([^\[\]]+?)\s*(?:\[\s*([^\]]*?)\s*\])?\s*$")


def _parse_header(robot: Robot, header: list[str], ignore: tuple[str, ...], where: str
                  ) -> list[tuple[str, str, float] | None]:
    """(name, unit, factor) of every column, None for an ignored one."""
    out: list[tuple[str, str, float] | None] = []
    seen: set[str] = set()
    for raw in header:
        match = _HEADER.match(raw)
        if match is None:
            raise ConfigError(f"{where}: cannot read the column header {raw!r}; write a name "
                              "and optionally a unit in brackets, e.g. 'LF_femur [deg]'")
        name, unit = match.group(1), match.group(2)
        if name in ignore:
            out.append(None)
            continue
        if name in seen:
            raise ConfigError(f"{where}: column {name!r} appears twice; keep one")
        seen.add(name)
        table = UNITS[column_kind(robot, name)]
        unit = next(iter(table)) if unit is None else unit
        if unit not in table:
            raise InvalidParameterError(f"unit of column {name!r} in {where}", unit,
                                        ", ".join(repr(u) for u in table))
        out.append((name, unit, table[unit]))
    return out


def _csv_values(text: str, n_columns: int, where: str) -> np.ndarray:
    """The numeric rows of a CSV body, shape (N, n_columns); empty fields and 'nan' are NaN."""
    if not text.strip():
        return np.zeros((0, n_columns))
    try:
        values = np.loadtxt(io.StringIO(text), delimiter=",", ndmin=2, dtype=float,
                            comments="#")
    except ValueError:
        with warnings.catch_warnings():  # a short row: named below, not warned of
            warnings.simplefilter("ignore", np.exceptions.VisibleDeprecationWarning)
            warnings.simplefilter("ignore", UserWarning)
            values = np.genfromtxt(io.StringIO(text), delimiter=",", dtype=float,
                                   comments="#", invalid_raise=False, missing_values="",
                                   filling_values=np.nan)
        values = np.atleast_2d(values)
        rows = _data_rows(text)
        bad = [row for row, fields in rows if len(fields) != n_columns]
        if bad or values.shape[1] != n_columns:
            row = bad[0] if bad else rows[0][0]
            raise ConfigError(f"{where}: row {row} does not have the header's {n_columns} "
                              "comma-separated fields; every row needs one value per column "
                              "(leave a field empty for a missing value)") from None
        text_bad = np.isnan(values) & ~_empty_or_nan(rows, values.shape)
        if text_bad.any():
            r, c = (int(i) for i in np.argwhere(text_bad)[0])
            raise ConfigError(f"{where}: row {rows[r][0]}, column {c + 1} is not a number; "
                              "write numbers, 'nan' or an empty field") from None
    if values.shape[1] != n_columns:
        raise ConfigError(f"{where}: rows have {values.shape[1]} fields, the header "
                          f"{n_columns}; every row needs one value per column")
    return values


def _data_rows(text: str) -> list[tuple[int, list[str]]]:
    """A CSV body's data rows as numpy reads them — blank lines and everything from a ``#`` on
    left out — each with its row number in the file (the header is row 1) and its fields."""
    out = []
    for i, line in enumerate(text.splitlines()):
        data = line.split("#", 1)[0]
        if data.strip():
            out.append((i + 2, data.split(",")))
    return out


def _empty_or_nan(rows: list[tuple[int, list[str]]], shape: tuple[int, ...]) -> np.ndarray:
    """Which fields of a CSV body's data rows (:func:`_data_rows`) are written as empty or
    'nan' (a missing value), (N, n)."""
    out = np.zeros(shape, dtype=bool)
    for i, (_, row) in enumerate(rows[:shape[0]]):
        for j, f in enumerate(row[:shape[1]]):
            out[i, j] = f.strip().lower() in ("", "nan")
    return out


def _npz_columns(data: bytes, where: str) -> tuple[list[str], np.ndarray]:
    """Names and stacked values (N, n) of an NPZ log's 1-D arrays."""
    try:
        with np.load(io.BytesIO(data), allow_pickle=False) as npz:
            arrays = {k: np.asarray(npz[k]) for k in npz.files}
    except (ValueError, OSError, zipfile.BadZipFile) as e:
        raise ConfigError(f"{where}: not a readable NPZ file ({e}); save it with "
                          "numpy.savez") from None
    names = list(arrays)
    for k in names:  # the array at fault named, with what it is
        a = arrays[k]
        if a.ndim != 1 or not np.issubdtype(a.dtype, np.number) \
                or np.issubdtype(a.dtype, np.complexfloating):
            raise ConfigError(f"{where}: array {k!r} is {a.dtype} of shape {a.shape}; every "
                              "array must be a real numeric 1-D column (one per log column, "
                              "e.g. "
                              "numpy.savez(path, time=t, LF_femur=q[:, 0], …))")
    lengths = {k: len(arrays[k]) for k in names}
    if len(set(lengths.values())) > 1:
        first = names[0]
        odd = next(k for k in names if lengths[k] != lengths[first])
        raise ConfigError(f"{where}: array {odd!r} has {lengths[odd]} values and {first!r} "
                          f"{lengths[first]}; every column must have one value per row")
    values = np.stack([arrays[k].astype(float) for k in names], axis=1) if names else \
        np.zeros((0, 0))
    return names, values


def _check_values(name: str, x: np.ndarray, where: str) -> None:
    """A column's values: NaN marks a missing value (filled over short gaps), infinity is not
    a value; a contact or stance column is 0 or 1.

    Raises:
        InvalidParameterError: the first infinite value, or a contact or stance value not 0 or
            1, with its row (1 = the first row under the header).
    """
    bad = np.isinf(x)
    if bad.any():
        row = int(np.argmax(bad))
        raise InvalidParameterError(f"{where}: column {name!r}, row {row + 1}", float(x[row]),
                                    "a finite number, or NaN / an empty field for a missing "
                                    "value")
    if name.startswith(("contact_", "stance_")):
        bad = ~np.isnan(x) & (x != 0.0) & (x != 1.0)
        if bad.any():
            row = int(np.argmax(bad))
            raise InvalidParameterError(f"{where}: column {name!r}, row {row + 1}",
                                        float(x[row]), "0 (swing) or 1 (stance)" + (
                                            "; a sensor's reading is thresholded before it is "
                                            "logged as contact" if name.startswith("contact_")
                                            else ""))


def read_log(robot: Robot, path: str | Path, *, ignore: tuple[str, ...] = ()) -> Log:
    """Read a CSV (``.csv``, ``.txt``) or NPZ (``.npz``) motion log of ``robot`` into SI, or a
    ROS 2 bag (:mod:`hexaleg.motion.recorded.bag`).

    Through hexaleg's one bounded file reader (:func:`hexaleg.config.read_bytes`, at most
    :data:`MAX_LOG_BYTES`).

    Args:
        robot: The robot the log is of (its joints and legs name the columns).
        path: The log file (a bag: its directory).
        ignore: Column names to skip (e.g. servo currents or temperatures the log also holds);
            in a bag, topics and joint names.

    Raises:
        ConfigError: unreadable, not UTF-8, malformed rows, no ``time`` column.
        UnknownNameError: a column that is not one of a log of ``robot`` (valid names listed).
        InvalidParameterError: a unit not allowed for its column (the allowed ones listed).
    """
    path = Path(path)
    if bag_directory(path) is not None:
        return read_bag(robot, path, ignore=ignore)
    where = f"motion log {path}"
    data = read_bytes(path, "motion log", MAX_LOG_BYTES)
    if path.suffix.lower() == ".npz":
        names, values = _npz_columns(data, where)
    else:
        try:
            text = data.decode("utf-8")
        except UnicodeDecodeError as e:
            raise ConfigError(f"{where} is not UTF-8 text (byte offset {e.start}); save it as "
                              "UTF-8 CSV, or as NPZ") from None
        lines = text.lstrip("\ufeff").split("\n", 1)
        names = [h for h in lines[0].strip().split(",")]
        values = _csv_values(lines[1] if len(lines) > 1 else "", len(names), where)
    parsed = _parse_header(robot, names, tuple(ignore), where)
    columns: dict[str, np.ndarray] = {}
    units: dict[str, str] = {}
    for j, spec in enumerate(parsed):
        if spec is not None:
            name, unit, factor = spec
            _check_values(name, values[:, j], where)
            columns[name] = values[:, j] * factor
            units[name] = unit
    if "time" not in columns:
        raise ConfigError(f"{where} has no 'time' column; the first row must name the columns, "
                          "one of them 'time' (s, or e.g. 'time [ms]')")
    return Log(t=columns.pop("time"), columns=columns, units=units, path=str(path))


__all__ = ["BASE_POSITION", "BASE_QUATERNION", "BASE_VELOCITY", "MAX_LOG_BYTES", "UNITS", "Log",
           "column_kind", "read_log"]
