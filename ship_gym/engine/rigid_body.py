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

import numpy as np

from ship_gym.kinematics import euler_rate_matrix, rotation_matrix, skew


def _cross(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """a × b for 3-vectors (np.cross's axis handling costs ~60 µs per call on small arrays)."""
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
