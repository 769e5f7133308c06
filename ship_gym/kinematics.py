"""Rotations and kinematic transformations (zyx Euler angles, body ↔ earth).

Conventions in :mod:`ship_gym.conventions`. Matusiak eq. (3) (linear velocities) and eq. (5)
(Euler-angle rates) are :func:`rotation_matrix` and :func:`euler_rate_matrix`.
"""

from __future__ import annotations

import numpy as np
import numpy.typing as npt

from ship_gym.conventions import GRAVITY


def rotation_matrix(roll: float, pitch: float, yaw: float) -> np.ndarray:
    """Rotation matrix R_b^n from body to earth axes for zyx Euler angles.

    A vector with body-axis components ``v_b`` has earth-axis components ``R @ v_b``
    (Fossen 2011, eq. 2.18; Matusiak eq. 3).

    Parameters
    ----------
    roll, pitch, yaw : float
        Euler angles φ, θ, ψ [rad].

    Returns
    -------
    numpy.ndarray
        (3, 3) orthonormal matrix.
    """
    cphi, sphi = np.cos(roll), np.sin(roll)
    cth, sth = np.cos(pitch), np.sin(pitch)
    cpsi, spsi = np.cos(yaw), np.sin(yaw)
    return np.array(
        [
            [cpsi * cth, -spsi * cphi + cpsi * sth * sphi, spsi * sphi + cpsi * cphi * sth],
            [spsi * cth, cpsi * cphi + sphi * sth * spsi, -cpsi * sphi + sth * spsi * cphi],
            [-sth, cth * sphi, cth * cphi],
        ]
    )


def euler_rate_matrix(roll: float, pitch: float) -> np.ndarray:
    """Matrix T such that (φ̇, θ̇, ψ̇) = T (p, q, r) (Fossen 2011 eq. 2.29; Matusiak eq. 5).

    Parameters
    ----------
    roll, pitch : float
        Euler angles φ, θ [rad]; singular at θ = ±π/2.
    """
    cphi, sphi = np.cos(roll), np.sin(roll)
    cth, tth = np.cos(pitch), np.tan(pitch)
    if abs(cth) < 1e-9:
        raise ValueError(f"Euler-rate matrix is singular at pitch = {pitch!r} rad (±π/2)")
    return np.array(
        [
            [1.0, sphi * tth, cphi * tth],
            [0.0, cphi, -sphi],
            [0.0, sphi / cth, cphi / cth],
        ]
    )


def skew(v: np.ndarray) -> np.ndarray:
    """Skew-symmetric matrix S(v) with S(v) @ w = v × w."""
    x, y, z = v
    return np.array([[0.0, -z, y], [z, 0.0, -x], [-y, x, 0.0]])


def encounter_frequency(
    omega: npt.ArrayLike, speed: npt.ArrayLike, beta: npt.ArrayLike, g: float = GRAVITY
) -> np.ndarray:
    """Frequency of encounter of a ship in deep-water waves.

    ω_e = ω − k U cos β = ω − ω² U cos β / g,

    with β = χ − ψ the relative heading (:mod:`ship_gym.conventions`): a ship at
    (X, Y) = U t (cos ψ, sin ψ) sees the phase ωt − k(X cos χ + Y sin χ) = (ω − kU cos β) t.
    Following seas (β = 0) lower the frequency (ω_e = ω − kU, negative when the ship overtakes
    the waves, U > g/ω — the sign is kept), head seas (β = π) raise it, beam seas (β = ±π/2)
    leave it unchanged. All arguments broadcast.

    Parameters
    ----------
    omega : array_like
        Absolute wave frequency ω [rad/s].
    speed : array_like
        Ship speed over ground U [m/s].
    beta : array_like
        Relative wave heading β [rad].
    g : float, optional
        Gravitational acceleration [m/s²].

    Returns
    -------
    numpy.ndarray
        Signed encounter frequency ω_e [rad/s].
    """
    if not (np.isfinite(g) and g > 0.0):
        raise ValueError(f"g must be a positive acceleration [m/s^2], got {g!r}")
    w = np.asarray(omega, dtype=float)
    return w - w * w * np.asarray(speed, dtype=float) * np.cos(np.asarray(beta, dtype=float)) / g
