"""Frames, degree-of-freedom order, units, sign and time conventions of ship_gym.

Everything in the package quotes this module; nothing here imports anything heavy.

Frames
------
* **Body (hull) frame** — x forward, y starboard, z down (SNAME / Fossen), right-handed.
  Origin ``O`` is fixed in the hull: amidships (Lpp/2), on the centreline, **at the design
  waterline** of the loading condition. Meshes, mass properties and hydrodynamic databases are
  all given in this frame; the centre of gravity is a point ``(x_G, y_G, z_G)`` in it (for the S175
  ``z_G = T − KG = −0.05 m``, i.e. slightly above the waterline).
* **Earth frame** — North-East-Down, origin on the mean free surface. At rest in calm water at the
  design condition, O lies at the earth origin and the two frames coincide.
* Position/attitude η = (x, y, z, φ, θ, ψ) of O in the earth frame, zyx Euler angles
  (roll φ, pitch θ, yaw ψ). Velocities ν = (u, v, w, p, q, r) in the body frame.
  Positive roll: starboard side down. Positive pitch: bow up. Positive heave: downward.

Degrees of freedom
------------------
``DOF_NAMES = ("Surge", "Sway", "Heave", "Roll", "Pitch", "Yaw")`` (capytaine's labels), in that
order everywhere (arrays of shape (..., 6) and (..., 6, 6)).

Waves
-----
Wave heading β = χ − ψ, where χ is the direction the waves travel *to* and ψ the ship heading, both
clockwise from north. β = 0 following seas, β = π head seas, β = π/2 waves travelling toward
starboard (coming from port). An incident regular wave of amplitude a has elevation (positive up)

    ζ(x, y, t) = a cos(ω t − k (x cos β + y sin β) + ε)

in body-aligned horizontal coordinates; complex amplitudes use **capytaine's time convention**
x(t) = Re(X e^{−iωt}), so ζ = Re(a e^{i k (x cos β + y sin β)} e^{−iωt}). The incident crest is at
O at t = 0 for ε = 0.

capytaine works in a z-up frame (x forward, y to port). The change of frame is the rotation by π
about x: (x, y, z)_ours = (x, −y, −z)_capytaine, which flips the signs of sway, heave, pitch and
yaw (:data:`CAPYTAINE_DOF_SIGNS`) and maps capytaine's ``wave_direction`` β_c to β = −β_c. It is
applied once, in :mod:`ship_gym.hydro.frames`.

Units
-----
SI inside (m, s, kg, N, rad). Degrees only at user boundaries, in names ending with ``_deg``.
"""

from __future__ import annotations

from typing import Final, overload

import numpy as np

DOF_NAMES: Final[tuple[str, ...]] = ("Surge", "Sway", "Heave", "Roll", "Pitch", "Yaw")
"""DOF labels and order (capytaine's names)."""

N_DOF: Final[int] = 6

SURGE, SWAY, HEAVE, ROLL, PITCH, YAW = range(6)

RHO_SEAWATER: Final[float] = 1025.0
"""Default water density [kg/m^3]."""

GRAVITY: Final[float] = 9.81
"""Default gravitational acceleration [m/s^2]."""

CAPYTAINE_DOF_SIGNS: Final[np.ndarray] = np.array([1.0, -1.0, -1.0, 1.0, -1.0, -1.0])
"""Sign of each DOF when going from capytaine's z-up frame to ours (rotation by π about x)."""

TIME_CONVENTION: Final[str] = "x(t) = Re(X exp(-i omega t))"
"""Complex-amplitude time convention (capytaine's), recorded in database attributes."""

BODY_FRAME: Final[str] = (
    "body frame: x forward, y starboard, z down; origin amidships (Lpp/2), on the centreline, "
    "at the design waterline"
)
"""Frame description recorded in database attributes."""

WAVE_HEADING: Final[str] = (
    "beta = chi - psi; chi the direction waves travel to, psi the ship heading, clockwise from "
    "north; 0 following seas, pi head seas, pi/2 waves travelling toward starboard"
)
"""Wave-heading convention recorded in database attributes."""


def dof_index(name: str) -> int:
    """Index of a DOF by its capytaine label (case-insensitive).

    Parameters
    ----------
    name : str
        One of :data:`DOF_NAMES`.

    Returns
    -------
    int
        Position of the DOF in every (…, 6) array.
    """
    for i, label in enumerate(DOF_NAMES):
        if label.lower() == name.lower():
            return i
    raise ValueError(f"unknown degree of freedom {name!r}; expected one of {DOF_NAMES}")


@overload
def wrap_angle(angle: float) -> float: ...
@overload
def wrap_angle(angle: np.ndarray) -> np.ndarray: ...
def wrap_angle(angle: np.ndarray | float) -> np.ndarray | float:
    """Wrap an angle [rad] to the interval [−π, π) (arrays elementwise; the scalar form for
    numba kernels is :func:`ship_gym.numerics.angles.wrap_angle_scalar`)."""
    return (np.asarray(angle) + np.pi) % (2.0 * np.pi) - np.pi
