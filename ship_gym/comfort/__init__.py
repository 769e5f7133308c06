"""Passenger comfort and motion sickness from the ship's motions (:mod:`ship_gym.comfort.metrics`):
acceleration and specific force at a point, lateral force estimator, ISO 2631-1 W_f weighting,
motion-sickness dose value and incidence.
"""

from ship_gym.comfort.metrics import (
    ISO_MSI_CONSTANT,
    WF,
    ComfortSample,
    ExponentialRMS,
    FrequencyWeighting,
    PassengerComfort,
    RunningDose,
    RunningWeighting,
    lateral_force_estimator,
    motion_sickness_dose_value,
    msi_iso,
    msi_ohanlon_mccauley,
    point_acceleration,
    specific_force,
    vertical_acceleration,
    weighted_acceleration,
)

__all__ = [
    "ISO_MSI_CONSTANT",
    "WF",
    "ComfortSample",
    "ExponentialRMS",
    "FrequencyWeighting",
    "PassengerComfort",
    "RunningDose",
    "RunningWeighting",
    "lateral_force_estimator",
    "motion_sickness_dose_value",
    "msi_iso",
    "msi_ohanlon_mccauley",
    "point_acceleration",
    "specific_force",
    "vertical_acceleration",
    "weighted_acceleration",
]
