"""Angle arithmetic for numba kernels."""

from __future__ import annotations

import math

import numba as nb

__all__ = ["wrap_angle_scalar"]

_TWO_PI = 2.0 * math.pi


@nb.njit(cache=True)
def wrap_angle_scalar(angle: float) -> float:
    """One angle [rad] wrapped to [−π, π): the scalar form of
    :func:`ship_gym.conventions.wrap_angle`, callable from numba kernels (and from Python)."""
    return (angle + math.pi) % _TWO_PI - math.pi
