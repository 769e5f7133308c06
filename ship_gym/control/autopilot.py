"""PID heading autopilot with anti-windup, tuned by pole placement on a Nomoto model.

Nomoto's first-order steering model (Nomoto et al. 1957; Fossen 2011, ch. 7)

    T ṙ + r = K δ,   ψ̇ = r,

with the PID law (heading error e = wrap(ψ_ref − ψ); positive rudder turns to starboard)

    δ_c = K_p e − K_d r + K_i ∫ e dt

gives the closed loop T ψ̈ + (1 + K K_d) ψ̇ + K K_p ψ = K K_p ψ_ref. Placing its poles at natural
frequency ω_n and damping ζ (Fossen 2011, PID design for the Nomoto model):

    K_p = T ω_n² / K,   K_d = (2 ζ ω_n T − 1) / K,   K_i = K_p ω_n / 10.

The integral of the error is a state of the ODE system (Matusiak's autopilot equation) with
back-calculation anti-windup (Åström & Hägglund 2006, §3.5): when the rudder saturates, the
integral is driven back at rate (δ_applied − δ_c)/(K_i T_t) so it does not wind up.
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import ClassVar

import numba as nb
import numpy as np

from ship_gym.numerics.angles import wrap_angle_scalar
from ship_gym.typing import FloatArray


@dataclass(frozen=True)
class NomotoModel:
    """First-order Nomoto steering model T ṙ + r = K δ.

    Parameters
    ----------
    gain : float
        K [1/s] (yaw rate per radian of rudder at steady state).
    time_constant : float
        T [s].
    """

    gain: float
    time_constant: float

    def __post_init__(self) -> None:
        if not (np.isfinite(self.gain) and self.gain > 0.0):
            raise ValueError(f"Nomoto gain K must be positive [1/s], got {self.gain!r}")
        if not (np.isfinite(self.time_constant) and self.time_constant > 0.0):
            raise ValueError(
                f"Nomoto time constant T must be positive [s], got {self.time_constant!r}"
            )

    @classmethod
    def identify(cls, t: np.ndarray, r: np.ndarray, rudder: float) -> NomotoModel:
        """Fit K, T to a yaw-rate step response r(t) = K δ (1 − e^{−t/T}) (least squares).

        Parameters
        ----------
        t : numpy.ndarray
            Times since the rudder step [s].
        r : numpy.ndarray
            Yaw rate [rad/s].
        rudder : float
            The constant rudder angle δ [rad] (non-zero).
        """
        from scipy.optimize import curve_fit

        if rudder == 0.0:
            raise ValueError("the rudder step must be non-zero to identify a Nomoto model")
        t = np.asarray(t, float)
        r = np.asarray(r, float)
        r_inf = float(np.mean(r[-max(3, len(r) // 10) :]))
        guess_t = float(t[np.argmax(np.abs(r) >= 0.632 * abs(r_inf))]) if r_inf else 10.0
        (k, tc), _ = curve_fit(
            lambda tt, k, tc: k * rudder * (1.0 - np.exp(-tt / tc)),
            t,
            r,
            p0=(r_inf / rudder, max(guess_t, 1.0)),
            bounds=([1e-9, 1e-3], [np.inf, 1e4]),
        )
        return cls(float(k), float(tc))


@dataclass(frozen=True)
class HeadingAutopilot:
    """PID heading controller with back-calculation anti-windup.

    Parameters
    ----------
    kp : float
        Proportional gain [rad rudder / rad error].
    kd : float
        Derivative gain on the yaw rate [s].
    ki : float
        Integral gain [1/s].
    tracking_time : float
        Anti-windup tracking time constant T_t [s].
    heading_key : str
        Command key holding the heading set-point ψ_ref [rad].
    """

    kp: float
    kd: float
    ki: float
    tracking_time: float = 10.0
    heading_key: str = "heading"

    kind: ClassVar[int] = 1
    """Law index of :func:`ship_gym.control.actuators.control_law`."""

    def __post_init__(self) -> None:
        for name in ("kp", "kd", "ki"):
            if not (np.isfinite(getattr(self, name)) and getattr(self, name) >= 0.0):
                raise ValueError(f"{name} must be a non-negative gain, got {getattr(self, name)!r}")
        if not self.tracking_time > 0.0:
            raise ValueError(f"tracking_time must be positive [s], got {self.tracking_time!r}")

    @classmethod
    def from_nomoto(
        cls, model: NomotoModel, *, natural_frequency: float = 0.06, damping: float = 0.9
    ) -> HeadingAutopilot:
        """Gains by pole placement (see the module docstring).

        Parameters
        ----------
        model : NomotoModel
            Identified K, T of the ship at its speed.
        natural_frequency : float
            Closed-loop ω_n [rad/s] (default 0.06: a period of ~100 s, below the wave band, as
            usual for large ships).
        damping : float
            Closed-loop ζ [-].
        """
        k, t = model.gain, model.time_constant
        kp = t * natural_frequency**2 / k
        kd = max((2.0 * damping * natural_frequency * t - 1.0) / k, 0.0)
        return cls(kp=kp, kd=kd, ki=kp * natural_frequency / 10.0)

    def gains(self) -> FloatArray:
        """(K_p, K_d, K_i, T_t): the parameters of :func:`heading_autopilot_law`."""
        return np.array([self.kp, self.kd, self.ki, self.tracking_time], dtype=float)


@nb.njit(cache=True, nogil=True)
def heading_autopilot_law(gains, eta, nu, integral, reference, limit):  # pragma: no cover
    """PID on the heading error with back-calculation anti-windup.

    δ_c = K_p e − K_d r + K_i ∫e with e = wrap(ψ_ref − ψ), and
    d/dt ∫e = e + (sat(δ_c) − δ_c)/(K_i T_t) (0 when K_i = 0).

    Parameters
    ----------
    gains : numpy.ndarray
        (K_p [-], K_d [s], K_i [1/s], T_t [s]) (:meth:`HeadingAutopilot.gains`).
    eta, nu : numpy.ndarray
        (6,) state sampled at the step start.
    integral : float
        ∫e [rad·s].
    reference : float
        ψ_ref [rad].
    limit : float
        Saturation of the command δ_max [rad].

    Returns
    -------
    (float, float)
        δ_c [rad] before saturation and d/dt ∫e [rad].
    """
    kp, kd, ki, tracking = gains[0], gains[1], gains[2], gains[3]
    e = wrap_angle_scalar(reference - eta[5])
    command = kp * e - kd * nu[5] + ki * integral
    if ki == 0.0:
        return command, 0.0
    achievable = min(max(command, -limit), limit)
    return command, e + (achievable - command) / (ki * tracking)
