"""Classical roll-fin and ride-control (T-foil) controllers: the baselines RL must beat.

Fin stabiliser (sign of :class:`~ship_gym.forces.fins.RollFins`: a positive command gives a
positive, starboard-down roll moment), PID on roll angle and rate:

    δ_c = −(k_φ φ + k_p p + k_i ∫φ dt).

Sized like a classical analogue stabiliser: the rate gain adds a chosen fraction ζ_add of
critical roll damping, k_p = 2 ζ_add √(C₄₄ (I₄₄ + A₄₄)) / K_δ, and the angle gain a fraction of
the hydrostatic stiffness, k_φ = c_add C₄₄ / K_δ, with K_δ = ∂K/∂δ of the fins at the ship's speed
(linearised from the fin model itself, so the tuning follows the fin size and speed).

Ride control (T-foil: positive command gives an upward force, F_z < 0, and a bow-up moment):
damp heave velocity and pitch rate,

    δ_c = k_w w − k_q q,

with k_w = 2 ζ_w √(C₃₃ (m + A₃₃)) / |∂F_z/∂δ| and k_q = 2 ζ_q √(C₅₅ (I₅₅ + A₅₅)) / |∂M/∂δ|.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

import numba as nb
import numpy as np

from ship_gym.forces.base import ForceContext, ForceModel
from ship_gym.kinematics import rotation_matrix
from ship_gym.typing import FloatArray


def control_derivative(model: ForceModel, key: str, dof: int, speed: float) -> float:
    """∂(force in ``dof``)/∂(angle) of a surface model at a straight run at ``speed`` [per rad].

    Central difference over ±1° about zero angle (linear range of every surface).
    """
    h = np.radians(1.0)
    values = []
    for angle in (-h, h):
        ctx = ForceContext(
            t=0.0,
            eta=np.zeros(6),
            nu=np.array([speed, 0.0, 0.0, 0.0, 0.0, 0.0]),
            rotation=rotation_matrix(0.0, 0.0, 0.0),
            forward_speed=speed,
            commands={key: angle},
        )
        values.append(model.evaluate(ctx, np.zeros(0))[0][dof])
    return float((values[1] - values[0]) / (2 * h))


@dataclass(frozen=True)
class FinController:
    """PID roll stabiliser δ_c = −(k_φ φ + k_p p + k_i ∫φ).

    Parameters
    ----------
    k_roll : float
        Angle gain k_φ [rad/rad].
    k_rate : float
        Rate gain k_p [rad·s/rad].
    k_integral : float
        Integral gain k_i [rad/(rad·s)] (0: PD, the usual choice — roll has no steady error
        to remove except under a steady heeling moment).
    """

    k_roll: float
    k_rate: float
    k_integral: float = 0.0

    kind: ClassVar[int] = 2
    """Law index of :func:`ship_gym.control.actuators.control_law`."""

    @classmethod
    def tuned(
        cls,
        fin_moment_per_rad: float,
        c44: float,
        i44_total: float,
        *,
        added_damping: float = 0.3,
        added_stiffness: float = 0.2,
    ) -> FinController:
        """Gains from the roll model (see the module docstring).

        Parameters
        ----------
        fin_moment_per_rad : float
            K_δ = ∂K/∂δ of the fin pair at speed [N·m/rad] (> 0).
        c44 : float
            Roll restoring C₄₄ [N·m/rad].
        i44_total : float
            I₄₄ + A₄₄ [kg·m²].
        added_damping, added_stiffness : float
            ζ_add [-] and c_add [-] (fractions of critical damping and of C₄₄).
        """
        if not fin_moment_per_rad > 0.0:
            raise ValueError(
                f"fin_moment_per_rad must be positive (fins at speed), got {fin_moment_per_rad!r}"
            )
        k_rate = 2.0 * added_damping * np.sqrt(c44 * i44_total) / fin_moment_per_rad
        return cls(k_roll=added_stiffness * c44 / fin_moment_per_rad, k_rate=k_rate)

    def gains(self) -> FloatArray:
        """(k_φ, k_p, k_i, 0): the parameters of :func:`fin_law`."""
        return np.array([self.k_roll, self.k_rate, self.k_integral, 0.0], dtype=float)


@nb.njit(cache=True, nogil=True)
def fin_law(gains, eta, nu, integral, limit):  # pragma: no cover - compiled
    """δ_c = −(k_φ φ + k_p p + k_i ∫φ); d/dt ∫φ = φ, frozen (0) while the fins saturate
    (conditional integration). Returns (δ_c [rad], d/dt ∫φ [rad])."""
    command = -(gains[0] * eta[3] + gains[1] * nu[3] + gains[2] * integral)
    achievable = min(max(command, -limit), limit)
    return command, (0.0 if achievable != command else eta[3])


@dataclass(frozen=True)
class RideController:
    """T-foil ride control δ_c = k_w w − k_q q (heave-velocity and pitch-rate damping).

    Parameters
    ----------
    k_heave : float
        Gain on the heave velocity w [rad/(m/s)].
    k_pitch : float
        Gain on the pitch rate q [rad/(rad/s)].
    """

    k_heave: float
    k_pitch: float

    kind: ClassVar[int] = 3
    """Law index of :func:`ship_gym.control.actuators.control_law`."""

    @classmethod
    def tuned(
        cls,
        heave_force_per_rad: float,
        pitch_moment_per_rad: float,
        c33: float,
        m33_total: float,
        c55: float,
        i55_total: float,
        *,
        heave_damping: float = 0.2,
        pitch_damping: float = 0.2,
    ) -> RideController:
        """Gains adding ``heave_damping`` of critical damping in heave and ``pitch_damping`` in
        pitch, each as if the foil acted on that mode alone: k_w = 2 ζ_3 √(C₃₃ (m + A₃₃)) / Z_δ,
        k_q = 2 ζ_5 √(C₅₅ (I₅₅ + A₅₅)) / M_δ (Z_δ, M_δ the foil's heave force and pitch moment
        per radian of foil angle [N/rad, N·m/rad])."""
        k_w = 2 * heave_damping * np.sqrt(c33 * m33_total) / abs(heave_force_per_rad)
        k_q = 2 * pitch_damping * np.sqrt(c55 * i55_total) / abs(pitch_moment_per_rad)
        return cls(k_heave=float(k_w), k_pitch=float(k_q))

    def gains(self) -> FloatArray:
        """(k_w, k_q, 0, 0): the parameters of :func:`ride_law`."""
        return np.array([self.k_heave, self.k_pitch, 0.0, 0.0], dtype=float)


@nb.njit(cache=True, nogil=True)
def ride_law(gains, nu):  # pragma: no cover - compiled
    """δ_c = k_w w − k_q q [rad] (no states)."""
    return gains[0] * nu[2] - gains[1] * nu[4]
