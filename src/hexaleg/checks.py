"""The one set of input validators: every public boundary checks its values through these.

Each returns the value in its canonical type (float, int, str, float array) or raises a
:class:`~hexaleg.errors.InvalidParameterError` (or :class:`~hexaleg.errors.UnknownNameError`) that
names the parameter, the value given and what is allowed. Booleans are never numbers here
(``True`` is not μ = 1), and NaN or inf is never a number.
"""

from __future__ import annotations

import collections.abc
import functools
import inspect
import math
import numbers
import reprlib
import types
import typing
from collections.abc import Callable, Collection
from typing import Any, TypeGuard, TypeVar

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


F = TypeVar("F", bound=Callable[..., Any])
NAMES: dict[type, str] = {numbers.Real: "number", numbers.Integral: "integer",
                          type(None): "None"}
"""How :func:`typed` names the classes it checks."""
_SHORT = reprlib.Repr()
_SHORT.maxstring = _SHORT.maxother = 80


def _checked_protocol(hint: type) -> bool:
    """Whether ``isinstance`` checks protocol ``hint`` in :func:`typed`: a runtime-checkable one
    of hexaleg's own (such as :class:`hexaleg.robot.actuator.Actuator`); numpy's (inside
    ArrayLike) admit no float, so they are not checked."""
    return (getattr(hint, "_is_runtime_protocol", False)
            and hint.__module__.split(".")[0] == "hexaleg")


def _classes(hint: Any) -> tuple[type, ...] | None:
    """The runtime classes an annotation admits, or None where it cannot be checked by
    ``isinstance`` (Any, a type variable, a literal, a protocol such as ArrayLike's; hexaleg's
    own runtime-checkable protocols are checked)."""
    if hint is Any:  # a class since Python 3.11, but no isinstance target
        return None
    if hint is None or hint is type(None):
        return (type(None),)
    if hint is float:
        return (numbers.Real,)
    if hint is int:
        return (numbers.Integral,)
    origin = typing.get_origin(hint)
    if origin in (typing.Union, types.UnionType):
        out: list[type] = []
        for option in typing.get_args(hint):
            classes = _classes(option)
            if classes is None:
                return None
            out += classes
        return tuple(out)
    if origin is collections.abc.Callable:
        return (collections.abc.Callable,)
    if isinstance(origin, type):
        return (origin,)
    if isinstance(hint, type) and (not getattr(hint, "_is_protocol", False)
                                   or _checked_protocol(hint)):
        return (hint,)
    return None


_STRUCTURAL: dict[tuple[tuple[type, ...], type], bool] = {}
"""(classes with a runtime-checkable protocol, a value's class) → whether it is admitted: a
protocol's ``isinstance`` looks up each of its members (tens of µs for
:class:`hexaleg.robot.actuator.Actuator`, on the hot path of the energy metrics), and a class
either has them or not."""


def _admits(classes: tuple[type, ...], value: Any) -> bool:
    if isinstance(value, (bool, np.bool_)) and bool not in classes:
        return False  # True is no number here
    if not any(getattr(c, "_is_protocol", False) for c in classes):
        return isinstance(value, classes)
    key = (classes, type(value))
    if key not in _STRUCTURAL:
        _STRUCTURAL[key] = isinstance(value, classes)
    return _STRUCTURAL[key]


def _hints(fn: Callable[..., Any]) -> dict[str, tuple[type, ...]]:
    """Parameter → the classes its annotation admits, for the annotations that can be checked
    (one that names a type imported only for type checkers is skipped)."""
    out = {}
    for name, text in getattr(fn, "__annotations__", {}).items():
        if name == "return":
            continue
        try:
            hint = eval(text, fn.__globals__) if isinstance(text, str) else text
        except Exception:  # a name imported under TYPE_CHECKING only
            continue
        classes = _classes(hint)
        if classes is not None:
            out[name] = classes
    return out


C = TypeVar("C", bound=type)


def named_arguments(cls: C) -> C:
    """Class decorator for a public dataclass: a keyword its constructor does not take is an
    :class:`~hexaleg.errors.UnknownNameError` listing the fields (``GaitParams(perod=1)``), a
    missing or surplus argument an :class:`~hexaleg.errors.InvalidParameterError` — not Python's
    TypeError. Apply it above ``@dataclass``; the arguments bind exactly as before."""
    init = cls.__init__  # type: ignore[misc]
    signature = inspect.signature(init)
    fields = [p for p in signature.parameters if p != "self"]

    @functools.wraps(init)
    def checked(self: Any, *args: Any, **kwargs: Any) -> None:
        unknown = [k for k in kwargs if k not in signature.parameters]
        if unknown:
            raise UnknownNameError(f"{cls.__name__} argument", unknown[0], fields)
        try:
            signature.bind(self, *args, **kwargs)
        except TypeError as e:
            raise InvalidParameterError(f"arguments of {cls.__name__}", f"{e}",
                                        f"those of {cls.__name__}({', '.join(fields)})") from None
        init(self, *args, **kwargs)

    cls.__init__ = checked  # type: ignore[misc]
    return cls


def typed(fn: F) -> F:
    """``fn`` with its arguments' types checked against its annotations at every call: a public
    entry point's wrong argument (None, a name where a robot is expected, a string where
    parameters are) is an :class:`~hexaleg.errors.InvalidParameterError` naming the argument,
    the type given and the types allowed — not an AttributeError from deep inside. Values are
    still checked by the function itself (ranges, shapes: the validators above)."""
    signature = inspect.signature(fn)
    positional = [p.name for p in signature.parameters.values()
                  if p.kind in (p.POSITIONAL_ONLY, p.POSITIONAL_OR_KEYWORD)]
    hints: dict[str, tuple[type, ...]] | None = None

    def refuse(name: str, value: Any, classes: tuple[type, ...]) -> None:
        allowed = " or ".join(sorted({NAMES.get(c, c.__name__) for c in classes}))
        shown = value if isinstance(value, (str, int, float, type(None))) else \
            _SHORT.repr(value)
        raise InvalidParameterError(f"{fn.__name__}({name}=…)", shown,
                                    f"a {allowed} (got a {type(value).__name__})")

    @functools.wraps(fn)
    def checked(*args: Any, **kwargs: Any) -> Any:
        # by position and by name, without binding the signature: a public function such as
        # metrics is also called on hot paths, where binding cost 4 % of an evaluation
        nonlocal hints
        if hints is None:
            hints = _hints(fn)
        if len(args) > len(positional) or any(k not in signature.parameters for k in kwargs):
            try:  # an unknown keyword, too many arguments: Python's own words, named
                signature.bind_partial(*args, **kwargs)
            except TypeError as e:
                raise InvalidParameterError(f"arguments of {fn.__name__}", f"{e}",
                                            f"those of {fn.__name__}{signature}") from None
        for name, value in zip(positional, args, strict=False):  # the rest by name
            classes = hints.get(name)
            if classes is not None and not _admits(classes, value):
                refuse(name, value, classes)
        for name, value in kwargs.items():
            classes = hints.get(name)
            if classes is not None and not _admits(classes, value):
                refuse(name, value, classes)
        return fn(*args, **kwargs)

    return checked  # type: ignore[return-value]
