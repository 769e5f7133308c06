"""NumPy's ``np.clip`` of one value as numba functions (for the environments' per-step kernels),
and the distance along a voyage course of the voyage tasks.

NumPy 2 clips with two loops that treat a value equal to a bound differently, which shows only
for signed zeros (−0.0 against a bound of 0.0): with scalar bounds it keeps the value, with array
bounds it takes the bound (max with ``>``, then min with ``<``). A kernel that replaces an
``np.clip`` uses the function of the same kind of bounds, so that it gives the same bits.
"""

from __future__ import annotations

import math

import numba

__all__ = ["along_course_kernel", "clip_array_bound", "clip_scalar_bound"]


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


@numba.njit(cache=True, nogil=True)
def along_course_kernel(eta, origin, cos_c, sin_c, weight, scale, out):  # pragma: no cover
    """out = weight · ((x − x₀) cos c + (y − y₀) sin c) / scale (x − 0.0 is x: with a zero
    origin and weight = scale = 1 it is the distance of O along the course, bit for bit)."""
    for i in range(eta.shape[0]):
        along = (eta[i, 0] - origin[i, 0]) * cos_c + (eta[i, 1] - origin[i, 1]) * sin_c
        out[i] = weight * along / scale
