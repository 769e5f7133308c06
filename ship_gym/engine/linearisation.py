"""Linear sway–yaw steering model of an assembled ship, and its Nomoto approximation.

Around a straight run at speed U (calm water, ν₀ = (U, 0, 0, 0, 0, 0)), the sway and yaw
equations of the assembled force models linearise to

    M_s (v̇, ṙ)ᵀ = J (v, r)ᵀ + b δ,

with M_s the sway–yaw block of M_RB + A_lhs, J = ∂(Y, N)/∂(v, r) of Σ forces − C_RB(ν)ν by central
differences (the hull manoeuvring derivatives, the rudder's and propeller's inflow effects and the
rigid-body m U r term all appear), and b = ∂(Y, N)/∂δ of the rudder. The yaw-rate step response of
this model, fitted by T ṙ + r = K δ (:meth:`NomotoModel.identify`), gives the Nomoto K, T used to
place the autopilot's poles — identified for the hull as built, not taken from a table.
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from scipy.linalg import expm

from ship_gym.control.autopilot import NomotoModel
from ship_gym.engine.rigid_body import coriolis_force
from ship_gym.forces.base import ForceContext, ForceModel
from ship_gym.hull.hull import Hull
from ship_gym.kinematics import rotation_matrix

_SWAY_YAW = (1, 5)


def _yaw_plane_force(
    models: Sequence[ForceModel], mass_rb: np.ndarray, nu: np.ndarray, commands: dict
) -> np.ndarray:
    ctx = ForceContext(
        t=0.0,
        eta=np.zeros(6),
        nu=nu,
        rotation=rotation_matrix(0.0, 0.0, 0.0),
        forward_speed=float(nu[0]),
        commands=dict(commands),
    )
    total = -coriolis_force(mass_rb, nu)
    for m in models:
        total = total + m.evaluate(ctx, np.zeros(m.n_states))[0]
    return total[list(_SWAY_YAW)]


def linear_steering_model(
    hull: Hull,
    models: Sequence[ForceModel],
    speed: float,
    *,
    added_mass: np.ndarray,
    rudder_key: str = "rudder",
    commands: dict | None = None,
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(M_s, J, b) of the linear sway–yaw model (see the module docstring).

    Parameters
    ----------
    hull : Hull
        Mass properties.
    models : sequence of ForceModel
        Stateless force models acting in the yaw plane (hull manoeuvring, rudder, propeller,
        resistance…); the rudder reads ``commands[rudder_key]``.
    speed : float
        Forward speed U [m/s] (> 0).
    added_mass : numpy.ndarray
        (6, 6) added mass on the left-hand side (A(∞) of the radiation model).
    commands : dict, optional
        Other commands held fixed (e.g. the shaft speed).
    """
    if not speed > 0.0:
        raise ValueError(f"speed must be positive to linearise the steering [m/s], got {speed!r}")
    mass_rb = hull.mass.rigid_body_matrix()
    m_s = (mass_rb + added_mass)[np.ix_(_SWAY_YAW, _SWAY_YAW)]
    base = {rudder_key: 0.0, **(commands or {})}
    nu0 = np.array([speed, 0.0, 0.0, 0.0, 0.0, 0.0])
    jac = np.zeros((2, 2))
    for col, (dof, h) in enumerate(((1, 1e-3 * speed), (5, 1e-3 * speed / hull.particulars.lpp))):
        plus, minus = nu0.copy(), nu0.copy()
        plus[dof] += h
        minus[dof] -= h
        jac[:, col] = (
            _yaw_plane_force(models, mass_rb, plus, base)
            - _yaw_plane_force(models, mass_rb, minus, base)
        ) / (2 * h)
    hd = np.radians(1.0)
    b = (
        _yaw_plane_force(models, mass_rb, nu0, {**base, rudder_key: hd})
        - _yaw_plane_force(models, mass_rb, nu0, {**base, rudder_key: -hd})
    ) / (2 * hd)
    return m_s, jac, b


def nomoto_from_models(
    hull: Hull,
    models: Sequence[ForceModel],
    speed: float,
    *,
    added_mass: np.ndarray,
    duration: float | None = None,
    commands: dict | None = None,
) -> NomotoModel:
    """Nomoto K, T fitted to the yaw-rate step response of :func:`linear_steering_model`.

    Raises
    ------
    ValueError
        If the linear model is straight-line unstable (then no first-order Nomoto model exists).
    """
    m_s, jac, b = linear_steering_model(
        hull, models, speed, added_mass=added_mass, commands=commands
    )
    a = np.linalg.solve(m_s, jac)
    bb = np.linalg.solve(m_s, b)
    if np.any(np.linalg.eigvals(a).real >= 0.0):
        raise ValueError(
            f"the linear sway-yaw model at U = {speed} m/s is not straight-line stable "
            f"(eigenvalues {np.linalg.eigvals(a)}); a first-order Nomoto model does not apply"
        )
    slowest = float(np.min(-np.linalg.eigvals(a).real))
    t_end = duration or 6.0 / slowest
    t = np.linspace(0.0, t_end, 600)
    dt = t[1] - t[0]
    # exact zero-order-hold discretisation of the step response
    aug = np.zeros((3, 3))
    aug[:2, :2] = a * dt
    aug[:2, 2] = bb * dt
    phi = expm(aug)
    x = np.zeros(2)
    r = np.empty_like(t)
    delta = np.radians(1.0)
    for i in range(len(t)):
        r[i] = x[1]
        x = phi[:2, :2] @ x + phi[:2, 2] * delta
    return NomotoModel.identify(t, r, delta)
