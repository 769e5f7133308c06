"""Keyword validation shared by the ship tasks: ranges, weights, positive values and points, each
error naming the argument as the user typed it, the bad value and what was expected.
"""

from __future__ import annotations

import math
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
        lo, hi = (float(v) for v in value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a (min, max) pair [{unit}], got {value!r}") from None
    if not (math.isfinite(lo) and math.isfinite(hi) and low <= lo <= hi <= high):
        raise ValueError(
            f"{name} must satisfy {low} <= min <= max <= {high} [{unit}], got {value!r}"
        )
    return lo, hi


def check_weight(name: str, value: Any) -> float:
    """A reward weight ≥ 0 (finite), else ValueError."""
    if (
        isinstance(value, bool)
        or not isinstance(value, int | float)
        or not (math.isfinite(value) and value >= 0.0)
    ):
        raise ValueError(f"{name} must be a finite weight >= 0, got {value!r}")
    return float(value)


def check_positive(name: str, value: Any, unit: str, high: float = math.inf) -> float:
    """A positive finite number ≤ ``high``, else ValueError."""
    if (
        isinstance(value, bool)
        or not isinstance(value, int | float)
        or not (math.isfinite(value) and 0.0 < value <= high)
    ):
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
