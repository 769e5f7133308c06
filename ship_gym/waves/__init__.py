"""Incident waves, deep water only: spectra, sea states and the seeded wave field.

Data flow (DESIGN.md §2): this stage imports only the base layer (:mod:`ship_gym.conventions`);
it never imports forces, dynamics or envs.

* :mod:`~ship_gym.waves.spectra` — S(ω) [m² s/rad] (PM, JONSWAP), cos-2s spreading, moments.
* :mod:`~ship_gym.waves.sea_state` — :class:`RegularWave`, :class:`IrregularSea`, dispersion
  k = ω²/g, encounter frequency.
* :mod:`~ship_gym.waves.wave_field` — :class:`WaveField` (elevation, pressure, velocity, phasors),
  Matusiak's ramp (eq. 12), :class:`PhasorClock`, :func:`stack_fields`.
"""

from ship_gym.waves.sea_state import (
    MAX_STEEPNESS,
    IrregularSea,
    RegularWave,
    encounter_frequency,
    omega_to_wavelength,
    wavelength_to_omega,
    wavenumber,
)
from ship_gym.waves.spectra import (
    frequency_range,
    jonswap,
    jonswap_normalisation,
    pierson_moskowitz,
    spectral_moments,
    spreading_cos2s,
    spreading_cos2s_ppf,
)
from ship_gym.waves.wave_field import (
    PhasorClock,
    WaveField,
    WaveFieldStack,
    ramp_factor,
    stack_fields,
)

__all__ = [
    "MAX_STEEPNESS",
    "IrregularSea",
    "PhasorClock",
    "RegularWave",
    "WaveField",
    "WaveFieldStack",
    "encounter_frequency",
    "frequency_range",
    "jonswap",
    "jonswap_normalisation",
    "omega_to_wavelength",
    "pierson_moskowitz",
    "ramp_factor",
    "spectral_moments",
    "spreading_cos2s",
    "spreading_cos2s_ppf",
    "stack_fields",
    "wavelength_to_omega",
    "wavenumber",
]
