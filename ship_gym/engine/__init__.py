"""The engine: rigid body, integrators, the row engine (N ≥ 1 ships) and its compiled backend.

:class:`RK4`, :class:`AdamsBashforthMoulton` and Holloway's stabilised μ-Taylor scheme
:class:`HollowayIntegrator` advance q̇ = f(q, v), v̇ = a(t, q, v[, z]), ż = g(…) by one step;
see :mod:`ship_gym.engine.integrators` for the calling conventions.
"""

from ship_gym.engine.integrators import (
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
