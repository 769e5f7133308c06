"""Rigid-body dynamics: explicit fixed-step integrators (and, later, the simulator).

:class:`RK4`, :class:`AdamsBashforthMoulton` and Holloway's stabilised μ-Taylor scheme
:class:`HollowayIntegrator` advance q̇ = f(q, v), v̇ = a(t, q, v[, z]), ż = g(…) by one step;
see :mod:`ship_gym.dynamics.integrators` for the calling conventions.
"""

from ship_gym.dynamics.integrators import (
    RK4,
    AdamsBashforthMoulton,
    HollowayIntegrator,
    Trajectory,
    acceleration_from_force,
    holloway_mu,
    integrate,
)

__all__ = [
    "RK4",
    "AdamsBashforthMoulton",
    "HollowayIntegrator",
    "Trajectory",
    "acceleration_from_force",
    "holloway_mu",
    "integrate",
]
