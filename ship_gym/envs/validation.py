"""Keyword validation shared by the ship tasks: ranges, weights, positive values and points, each
error naming the argument as the user typed it, the bad value and what was expected.
"""

from __future__ import annotations

import math
import numbers
from collections.abc import Mapping
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

if TYPE_CHECKING:
    pass


def check_range(
    name: str, value: Any, *, low: float, high: float, unit: str
) -> tuple[float, float]:
    """A (min, max) pair of floats with low ≤ min ≤ max ≤ high, else ValueError."""
    try:
        lo_v, hi_v = value
    except (TypeError, ValueError):
        lo_v = hi_v = None
    if isinstance(value, str | bytes) or not (is_real(lo_v) and is_real(hi_v)):
        raise ValueError(
            f"{name} must be a (min, max) pair of numbers [{unit}] with "
            f"{low} <= min <= max <= {high}, got {value!r}"
        )
    lo, hi = float(lo_v), float(hi_v)
    if not (math.isfinite(lo) and math.isfinite(hi) and low <= lo <= hi <= high):
        raise ValueError(
            f"{name} must satisfy {low} <= min <= max <= {high} [{unit}], got {value!r}"
        )
    return lo, hi


def is_real(value: Any) -> bool:
    """True for a real number: Python int/float or a NumPy integer/floating scalar, not a bool."""
    return isinstance(value, numbers.Real) and not isinstance(value, bool | np.bool_)


def check_real(
    name: str,
    value: Any,
    *,
    low: float = -math.inf,
    high: float = math.inf,
    unit: str,
    low_open: bool = False,
    high_open: bool = False,
    why: str = "",
) -> float:
    """A finite real number (NumPy scalars included) in the interval from ``low`` to ``high``
    (open ends where asked), else ValueError naming ``name``, the value and the interval."""
    lb, hb = ("(" if low_open else "["), (")" if high_open else "]")
    expected = f"{name} must be a finite number in {lb}{low:g}, {high:g}{hb} [{unit}]{why}"
    if not is_real(value):
        raise ValueError(f"{expected}, got {value!r} ({type(value).__name__})")
    # a float32/float16 scalar as the decimal the user typed (np.float32(0.1) is 0.1, not
    # 0.10000000149, which is no integer fraction of a 0.5 s control step)
    v = float(str(value)) if isinstance(value, np.floating) and value.itemsize < 8 else float(value)
    ok = math.isfinite(v) and (v > low if low_open else v >= low)
    ok = ok and (v < high if high_open else v <= high)
    if not ok:
        raise ValueError(f"{expected}, got {value!r}")
    return v


def check_options(options: Any, accepted: tuple[str, ...], name: str = "options") -> dict[str, Any]:
    """``reset(options=...)`` as a dict: None or a mapping with string keys among ``accepted``,
    else TypeError (not a mapping) or ValueError (unknown keys, named, with the accepted ones)."""
    if options is None:
        return {}
    if not isinstance(options, Mapping):
        raise TypeError(
            f"{name} must be a mapping (dict) of reset options or None, got "
            f"{type(options).__name__} {options!r}; accepted keys: {', '.join(accepted)}"
        )
    unknown = [k for k in options if k not in accepted]
    if unknown:
        raise ValueError(
            f"unknown reset options {', '.join(repr(k) for k in unknown)} in {name}; "
            f"accepted keys: {', '.join(accepted)}"
        )
    return dict(options)


def check_weight(name: str, value: Any) -> float:
    """A reward weight ≥ 0 (finite), else ValueError."""
    if not is_real(value) or not (math.isfinite(value) and value >= 0.0):
        raise ValueError(f"{name} must be a finite weight >= 0, got {value!r}")
    return float(value)


def check_positive(name: str, value: Any, unit: str, high: float = math.inf) -> float:
    """A positive finite number ≤ ``high``, else ValueError."""
    if not is_real(value) or not (math.isfinite(value) and 0.0 < value <= high):
        raise ValueError(f"{name} must be in (0, {high}] [{unit}], got {value!r}")
    return float(value)


def check_point(name: str, value: Any) -> NDArray:
    """A finite body-frame point (x, y, z) within ±200 m [m], else ValueError."""
    try:
        point = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise ValueError(
            f"{name} must be a body-frame point (x, y, z) [m], got {value!r}"
        ) from None
    if point.shape != (3,) or not np.all(np.isfinite(point)) or np.any(np.abs(point) > 200.0):
        raise ValueError(f"{name} must be a finite (x, y, z) within ±200 m [m], got {value!r}")
    return point
