"""6-DOF rigid-body terms of the equations of motion (Matusiak eq. 3, 5, 6; Fossen 2011 ch. 3).

In body axes about the body origin O (not at G), the rigid-body equations are

    M_RB ν̇ + C_RB(ν) ν = τ,

with M_RB from :meth:`ship_gym.hull.MassProperties.rigid_body_matrix` and the Coriolis–centripetal
matrix in the velocity-independent parametrisation (Fossen 2011, eq. 3.57)

    C_RB(ν) = [[0, −S(M₁₁ν₁ + M₁₂ν₂)], [−S(M₁₁ν₁ + M₁₂ν₂), −S(M₂₁ν₁ + M₂₂ν₂)]].

Kinematics η̇ = J(η) ν: the position rate is R(φ, θ, ψ) ν₁ (Matusiak eq. 3) and the Euler-angle rate
is T(φ, θ) ν₂ (Matusiak eq. 5).
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import TYPE_CHECKING

import numba as nb
import numpy as np

from ship_gym.kinematics import euler_rate_matrix, rotation_matrix, skew

if TYPE_CHECKING:
    from ship_gym.hull.hull import Hull


def _cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """a × b for 3-vectors (np.cross's axis handling is slow on small arrays; measured:
    docs/benchmarks.md)."""
    return np.array(
        [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]
    )


def coriolis_force(mass_matrix: np.ndarray, nu: np.ndarray) -> np.ndarray:
    """C_RB(ν) ν [N, N·m] for a 6×6 rigid-body mass matrix (Fossen 2011, eq. 3.57).

    Parameters
    ----------
    mass_matrix : numpy.ndarray
        (6, 6) M_RB about O [kg, kg·m, kg·m²].
    nu : numpy.ndarray
        (6,) body velocities (u, v, w, p, q, r) [m/s, rad/s].
    """
    h1 = mass_matrix[:3, :3] @ nu[:3] + mass_matrix[:3, 3:] @ nu[3:]  # linear momentum
    h2 = mass_matrix[3:, :3] @ nu[:3] + mass_matrix[3:, 3:] @ nu[3:]  # angular momentum about O
    # C(ν)ν = [−S(h1) ν2 ; −S(h1) ν1 − S(h2) ν2] = [ν2 × h1 ; ν1 × h1 + ν2 × h2]
    return np.concatenate([np.cross(nu[3:], h1), np.cross(nu[:3], h1) + np.cross(nu[3:], h2)])


def gravity_force(mass: float, cog: np.ndarray, rotation: np.ndarray, g: float) -> np.ndarray:
    """Weight m g (earth +z) at G, as a body-axis force and moment about O [N, N·m].

    Parameters
    ----------
    mass : float
        Ship mass [kg].
    cog : numpy.ndarray
        (3,) G in the body frame [m].
    rotation : numpy.ndarray
        (3, 3) body-to-earth rotation matrix.
    g : float
        Gravity [m/s²].
    """
    f_body = rotation.T @ np.array([0.0, 0.0, mass * g])
    return np.concatenate([f_body, _cross(cog, f_body)])


def kinematics(eta: np.ndarray, nu: np.ndarray) -> np.ndarray:
    """η̇ = J(η) ν: earth position rate and Euler-angle rates (Matusiak eq. 3 and 5).

    Parameters
    ----------
    eta : numpy.ndarray
        (6,) (x, y, z) of O in NED [m] and (φ, θ, ψ) [rad].
    nu : numpy.ndarray
        (6,) body velocities [m/s, rad/s].
    """
    rot = rotation_matrix(eta[3], eta[4], eta[5])
    return np.concatenate([rot @ nu[:3], euler_rate_matrix(eta[3], eta[4]) @ nu[3:]])


__all__ = ["coriolis_force", "gravity_force", "kinematics", "skew"]


# =============================================================================================
# row kernels (numba; the engine's numpy path and its compiled loop call these)
# =============================================================================================
@nb.njit(cache=True, nogil=True)
def rigid_body_terms(q, v, mass, weight, cog, held_angle, rot, total, qdot):  # pragma: no cover
    """R(φ, θ, ψ), gravity − Coriolis (body axes, about O) and η̇ = J(η) ν of one ship.

    The arithmetic of ``ship_gym.engine.batch._ship_terms`` (one row); η̇ of a held angle
    is 0, and η̇'s angular rows are NaN where |cos θ| < 1e-9 (reported as a divergence).
    """
    cphi, sphi = math.cos(q[3]), math.sin(q[3])
    cth, sth = math.cos(q[4]), math.sin(q[4])
    cpsi, spsi = math.cos(q[5]), math.sin(q[5])
    rot[0, 0] = cpsi * cth
    rot[0, 1] = -spsi * cphi + cpsi * sth * sphi
    rot[0, 2] = spsi * sphi + cpsi * cphi * sth
    rot[1, 0] = spsi * cth
    rot[1, 1] = cpsi * cphi + sphi * sth * spsi
    rot[1, 2] = -cpsi * sphi + sth * spsi * cphi
    rot[2, 0] = -sth
    rot[2, 1] = cth * sphi
    rot[2, 2] = cth * cphi
    fx, fy, fz = rot[2, 0] * weight, rot[2, 1] * weight, rot[2, 2] * weight
    h0 = h1 = h2 = h3 = h4 = h5 = 0.0
    for j in range(6):
        h0 += mass[0, j] * v[j]
        h1 += mass[1, j] * v[j]
        h2 += mass[2, j] * v[j]
        h3 += mass[3, j] * v[j]
        h4 += mass[4, j] * v[j]
        h5 += mass[5, j] * v[j]
    u, vv, w, p, qq, rr = v[0], v[1], v[2], v[3], v[4], v[5]
    total[0] = fx - (qq * h2 - rr * h1)
    total[1] = fy - (rr * h0 - p * h2)
    total[2] = fz - (p * h1 - qq * h0)
    total[3] = (cog[1] * fz - cog[2] * fy) - ((vv * h2 - w * h1) + (qq * h5 - rr * h4))
    total[4] = (cog[2] * fx - cog[0] * fz) - ((w * h0 - u * h2) + (rr * h3 - p * h5))
    total[5] = (cog[0] * fy - cog[1] * fx) - ((u * h1 - vv * h0) + (p * h4 - qq * h3))
    for i in range(3):
        qdot[i] = rot[i, 0] * u + rot[i, 1] * vv + rot[i, 2] * w
    if abs(cth) < 1e-9:
        qdot[3] = np.nan
        qdot[4] = np.nan
        qdot[5] = np.nan
    else:
        tth = math.tan(q[4])
        qdot[3] = p + sphi * tth * qq + cphi * tth * rr
        qdot[4] = cphi * qq - sphi * rr
        qdot[5] = sphi / cth * qq + cphi / cth * rr
    for i in range(3):
        if held_angle[i]:
            qdot[3 + i] = 0.0


@nb.njit(cache=True, nogil=True)
def healthy_state(q, v, z, v_max):  # pragma: no cover - compiled
    """q, z finite and max |v| ≤ v_max (False for NaN): the simulators' divergence test."""
    good = True
    for i in range(q.shape[0]):
        good &= np.isfinite(q[i])
    for i in range(v.shape[0]):
        good &= abs(v[i]) <= v_max
    for i in range(z.shape[0]):
        good &= np.isfinite(z[i])
    return good


def left_hand_side(
    hull: Hull, forces: Sequence, free_dofs: Sequence[bool] | None
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Held-DOF mask, rigid-body mass matrix and the added mass the models put on the left.

    Parameters
    ----------
    hull : Hull
        Mass properties.
    forces : sequence
        Force models; each may declare ``added_mass`` (6×6) for the left-hand side.
    free_dofs : sequence of bool or None
        Which DOFs are integrated (None: all).

    Returns
    -------
    free : numpy.ndarray
        (6,) bool.
    mass_rb, added_mass : numpy.ndarray
        (6, 6) M_RB about O and Σ A_lhs [kg, kg·m, kg·m²].
    """
    free = np.ones(6, bool) if free_dofs is None else np.asarray(free_dofs, bool)
    if free.shape != (6,):
        raise ValueError(f"free_dofs must have 6 booleans, got {free_dofs!r}")
    a_lhs = np.zeros((6, 6))
    for f in forces:
        if f.added_mass is not None:
            a_lhs = a_lhs + np.asarray(f.added_mass, float)
    return free, hull.mass.rigid_body_matrix(), a_lhs
