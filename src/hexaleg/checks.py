"""The one set of input validators: every public boundary checks its values through these.

Each returns the value in its canonical type (float, int, str, float array) or raises a
:class:`~hexaleg.errors.InvalidParameterError` (or :class:`~hexaleg.errors.UnknownNameError`) that
names the parameter, the value given and what is allowed. Booleans are never numbers here
(``True`` is not μ = 1), and NaN or inf is never a number.
"""

from __future__ import annotations

import math
from collections.abc import Collection
from typing import Any, TypeGuard

import numpy as np
from numpy.typing import ArrayLike

from hexaleg.errors import InvalidParameterError, UnknownNameError

_REALS = (int, float, np.integer, np.floating)


def is_real(value: object) -> TypeGuard[float]:
    """True for a finite real number that is not a bool (int, float or a NumPy scalar)."""
    return (isinstance(value, _REALS) and not isinstance(value, (bool, np.bool_))
            and math.isfinite(value))


def is_integer(value: object) -> TypeGuard[int]:
    """True for an int or NumPy integer that is not a bool."""
    return isinstance(value, (int, np.integer)) and not isinstance(value, (bool, np.bool_))


def _bounds_text(low: float | None, high: float | None, low_open: bool, high_open: bool) -> str:
    parts = []
    if low is not None:
        parts.append(f"{'>' if low_open else '>='} {low:g}")
    if high is not None:
        parts.append(f"{'<' if high_open else '<='} {high:g}")
    return " and ".join(parts)


def real(name: str, value: Any, *, low: float | None = None, high: float | None = None,
         low_open: bool = False, high_open: bool = False, allowed: str | None = None) -> float:
    """``value`` as a float, checked to be a finite real number within the given bounds.

    Args:
        name: The parameter's name, for the error.
        value: The value given.
        low: Lower bound, or None for none.
        high: Upper bound, or None for none.
        low_open: Exclude the lower bound itself (``> low`` rather than ``>= low``).
        high_open: Exclude the upper bound itself (``< high`` rather than ``<= high``).
        allowed: What the error says is allowed; default "a finite number" and the bounds.

    Raises:
        InvalidParameterError: not a real number (a bool, a string, None, …), NaN or inf, or out
            of bounds.
    """
    if allowed is None:
        bounds = _bounds_text(low, high, low_open, high_open)
        allowed = "a finite number" + (f" {bounds}" if bounds else "")
    if not is_real(value):
        raise InvalidParameterError(name, value, allowed)
    x = float(value)
    if low is not None and (x <= low if low_open else x < low):
        raise InvalidParameterError(name, value, allowed)
    if high is not None and (x >= high if high_open else x > high):
        raise InvalidParameterError(name, value, allowed)
    return x


def positive(name: str, value: Any) -> float:
    """``value`` as a float > 0 (:func:`real` with an open lower bound at 0)."""
    return real(name, value, low=0.0, low_open=True)


def nonnegative(name: str, value: Any) -> float:
    """``value`` as a float ≥ 0."""
    return real(name, value, low=0.0)


def integer(name: str, value: Any, *, low: int | None = None, high: int | None = None) -> int:
    """``value`` as an int within ``[low, high]`` (a float such as ``1e9`` is refused).

    Raises:
        InvalidParameterError: not an integer, or out of bounds.
    """
    bounds = _bounds_text(low, high, False, False)
    allowed = "an integer" + (f" {bounds}" if bounds else "")
    if not is_integer(value):
        raise InvalidParameterError(name, value, allowed)
    if (low is not None and value < low) or (high is not None and value > high):
        raise InvalidParameterError(name, value, allowed)
    return int(value)


MEMORY_BUDGET = 2 * 1024**3
"""Bytes one computation may fill, the base of every resource bound: a count (samples,
keyframes, sweep points) is refused before any work when that many items would take more, so a
careless ``samples = 10**7`` is an error naming the bound instead of a ``MemoryError`` minutes
later. Each bound is this budget over the measured cost of one item (:func:`count`)."""


def count(name: str, value: Any, *, item_bytes: int, item: str, low: int = 1,
          fix: str = "") -> int:
    """``value`` as an int in ``[low, MEMORY_BUDGET // item_bytes]``: a count of things whose
    memory grows with it.

    Args:
        name: The parameter's name, for the error.
        value: The value given.
        item_bytes: Bytes one item costs (measured, with a margin), B.
        item: What one item is, e.g. ``"one gait sample"``, for the error.
        low: Smallest allowed count.
        fix: What to change when the count is above the bound, appended to the error.

    Raises:
        InvalidParameterError: not an integer (a bool or a float such as ``1e9`` included),
            below ``low``, or above the bound (the message states the bound and how it
            follows from :data:`MEMORY_BUDGET`).
    """
    high = MEMORY_BUDGET // item_bytes
    allowed = (f"an integer in [{low}, {high}] ({item} costs about {item_bytes / 1024:g} kB, "
               f"so {high} of them fill hexaleg's memory budget of "
               f"{MEMORY_BUDGET / 1024**3:g} GiB)")
    if not is_integer(value) or value < low:
        raise InvalidParameterError(name, value, allowed)
    if value > high:
        raise InvalidParameterError(name, value, allowed + (f"; {fix}" if fix else ""))
    return int(value)


def string(name: str, value: Any) -> str:
    """``value`` if it is a str.

    Raises:
        InvalidParameterError: any other type.
    """
    if not isinstance(value, str):
        raise InvalidParameterError(name, value, "a string")
    return value


def one_of(name: str, value: Any, allowed: Collection[str]) -> str:
    """``value`` if it is one of the names ``allowed``.

    Raises:
        UnknownNameError: anything else; the message lists the allowed names.
    """
    if not isinstance(value, str) or value not in allowed:
        raise UnknownNameError(name, value, allowed)
    return value


def finite_array(name: str, x: ArrayLike, shape: tuple[int, ...] | None = None,
                 meaning: str = "") -> np.ndarray:
    """``x`` as a float array of finite values, optionally of an exact shape.

    Args:
        name: The parameter's name, for the error.
        x: The array given.
        shape: Required shape, or None for any.
        meaning: What the axes are (e.g. ``"T samples × nj joints"``), for the error.

    Raises:
        InvalidParameterError: not numeric, wrong shape, or NaN/inf (the first bad value and its
            index named).
    """
    what = f" ({meaning})" if meaning else ""
    try:
        a = np.asarray(x, dtype=float)
    except (TypeError, ValueError):
        expected = f"a numeric array of shape {shape}" if shape else "an array of real numbers"
        raise InvalidParameterError(name, x, expected + what) from None
    if shape is not None and a.shape != shape:
        raise InvalidParameterError(name, f"array of shape {a.shape}", f"shape {shape}{what}")
    bad = ~np.isfinite(a)
    if np.any(bad):
        index = tuple(int(i) for i in np.argwhere(bad)[0])
        where = f" (the first bad value is at index {index})" if a.ndim else ""
        raise InvalidParameterError(name, float(a[index]),
                                    "finite numbers (no NaN or inf)" + what + where)
    return a
