"""NumPy's ``np.clip`` of one value as numba functions (for the environments' per-step kernels).

NumPy 2 clips with two loops that treat a value equal to a bound differently, which shows only
for signed zeros (−0.0 against a bound of 0.0): with scalar bounds it keeps the value, with array
bounds it takes the bound (max with ``>``, then min with ``<``). A kernel that replaces an
``np.clip`` uses the function of the same kind of bounds, so that it gives the same bits.
"""

from __future__ import annotations

import math

import numba

__all__ = ["clip_array_bound", "clip_scalar_bound"]


@numba.njit(cache=True, nogil=True)
def clip_scalar_bound(v: float, low: float, high: float) -> float:  # pragma: no cover - compiled
    """``np.clip(x, low, high)`` of one entry with scalar (Python float) bounds."""
    if low != low or high != high:
        return math.nan
    v = low if v < low else v
    return high if v > high else v


@numba.njit(cache=True, nogil=True)
def clip_array_bound(v: float, low: float, high: float) -> float:  # pragma: no cover - compiled
    """``np.clip(x, low, high)`` of one entry with array bounds (``low``, ``high`` its own)."""
    if v == v:
        v = v if v > low else low
    if v == v:
        v = v if v < high else high
    return v
