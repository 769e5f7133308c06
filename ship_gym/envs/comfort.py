"""Comfort bookkeeping of a ship task as one component: :class:`ComfortTracker`.

A task that pays for (or observes) the motions felt at a passenger point holds a
:class:`ComfortTracker`: it owns the accelerations estimator
(:class:`ship_gym.comfort.metrics.PassengerComfort`), the sample of the last control step
(zeros after a reset), resets episodes and gives the comfort step info. The task calls
:meth:`ComfortTracker.reset` from its reset and :meth:`ComfortTracker.update` once per step
(before its reward terms and observations read :attr:`ComfortTracker.sample`).
"""

from __future__ import annotations

from collections.abc import Sequence

import numpy as np
from numpy.typing import NDArray

from ship_gym.comfort.metrics import ComfortSample, PassengerComfort

__all__ = ["COMFORT_INFO_KEYS", "ComfortTracker"]

COMFORT_INFO_KEYS: tuple[str, ...] = (
    "lateral_acceleration_mps2",
    "vertical_acceleration_mps2",
    "lateral_acceleration_rms_mps2",
    "vertical_acceleration_rms_mps2",
    "msdv_z",
    "msi_percent",
)
"""The step-info keys of :meth:`ComfortTracker.info`."""


def zero_sample(n: int) -> ComfortSample:
    """The sample of N episodes just reset: every acceleration, RMS and dose zero."""
    z = np.zeros(n)
    return ComfortSample(z, z, z, z, z, z)


class ComfortTracker:
    """Accelerations, their running RMS and the motion-sickness dose at a passenger point.

    Parameters
    ----------
    num_envs : int
        N episodes.
    control_dt : float
        Control step [s] (ν̇ from the backward difference of ν over it).
    passenger_point : NDArray
        (3,) body-frame position [m] (z down).
    time_constant : float
        τ of the running RMS [s].
    g : float
        Gravity [m/s²].
    """

    def __init__(
        self,
        num_envs: int,
        control_dt: float,
        passenger_point: NDArray,
        time_constant: float,
        g: float,
    ) -> None:
        self.num_envs = int(num_envs)
        self.meter = PassengerComfort(
            self.num_envs, control_dt, passenger_point, rms_time_constant=time_constant, g=g
        )
        self.sample = zero_sample(self.num_envs)
        """The last control step's :class:`ComfortSample` (zeros of an episode just reset)."""

    def reset(self, ids: Sequence[int], nu: NDArray) -> None:
        """Restart episodes ``ids`` from body velocities ``nu`` ((k, 6) [m/s, rad/s]); their
        sample entries (accelerations, RMS) become 0 (the dose array is the meter's own)."""
        self.meter.reset(ids, nu)
        s = self.sample
        for arr in (s.lateral, s.vertical, s.weighted_vertical, s.lateral_rms, s.vertical_rms):
            arr[list(ids)] = 0.0

    def update(self, eta: NDArray, nu: NDArray) -> ComfortSample:
        """The sample after a control step ending at (η, ν) ((N, 6) each); kept in
        :attr:`sample`."""
        self.sample = self.meter.update(eta, nu)
        return self.sample

    def info(self) -> dict[str, NDArray]:
        """The comfort step info (:data:`COMFORT_INFO_KEYS`): accelerations [m/s²], their RMS
        [m/s²], MSDV_z [m/s^1.5] and MSI = MSDV_z/3 [%]."""
        s = self.sample
        return {
            "lateral_acceleration_mps2": s.lateral.copy(),
            "vertical_acceleration_mps2": s.vertical.copy(),
            "lateral_acceleration_rms_mps2": s.lateral_rms.copy(),
            "vertical_acceleration_rms_mps2": s.vertical_rms.copy(),
            "msdv_z": s.msdv.copy(),
            "msi_percent": s.msdv / 3.0,
        }
