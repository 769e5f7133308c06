"""Sea-state value objects and deep-water dispersion helpers.

Deep water only: every wave component obeys k = ω²/g (water depth h ≫ λ/2; the error in k is
< 0.4 % once kh > π). Directions follow :mod:`ship_gym.conventions`: the heading χ of a sea state
is the direction the waves travel **to**, in the earth (NED) frame, clockwise from north [rad];
a ship with heading ψ sees the relative heading β = χ − ψ (0 following seas, π head seas).

:class:`RegularWave` and :class:`IrregularSea` only *describe* a sea; a realisation with phases
(the state) is a :class:`ship_gym.waves.wave_field.WaveField`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ship_gym.conventions import GRAVITY
from ship_gym.kinematics import encounter_frequency
from ship_gym.waves.spectra import frequency_range, jonswap, pierson_moskowitz, spreading_cos2s

__all__ = [
    "DEFAULT_HEADING",
    "MAX_STEEPNESS",
    "IrregularSea",
    "RegularWave",
    "encounter_frequency",
    "heading_is_set",
    "omega_to_wavelength",
    "wavelength_to_omega",
    "wavenumber",
]


class _DefaultHeading(float):
    """The float 0.0 that marks a sea state whose ``heading`` was left at its default.

    It behaves as 0.0 everywhere (arithmetic, comparison, hashing, NumPy); only
    :func:`heading_is_set` tells it apart, so that :func:`ship_gym.engine.ship.wave_field_for`
    can refuse a sea whose explicit heading contradicts its ``wave_heading`` argument.
    """

    def __repr__(self) -> str:
        return "0.0"

    def __reduce__(self) -> tuple:
        return (_DefaultHeading, (0.0,))


DEFAULT_HEADING: float = _DefaultHeading(0.0)
"""Default ``heading`` of :class:`RegularWave` and :class:`IrregularSea` (χ = 0, waves travel
north), distinguishable from an explicit ``heading=0.0`` by :func:`heading_is_set`."""


def heading_is_set(sea: RegularWave | IrregularSea) -> bool:
    """Whether ``sea.heading`` was given explicitly (not left at :data:`DEFAULT_HEADING`)."""
    return not isinstance(sea.heading, _DefaultHeading)


MAX_STEEPNESS = 1.0 / 7.0
"""Largest accepted regular-wave steepness H/λ [-] (Michell's breaking limit ≈ 0.142)."""


def irregular_steepness_limit(tp: float) -> float:
    """Largest average steepness S_p = 2π Hs / (g Tp²) = Hs/λp of a physical sea state (DNV-RP-C205,
    *Environmental conditions and environmental loads*, 2010, §3.5.5.4): 1/15 for Tp ≤ 8 s,
    1/25 for Tp ≥ 15 s, linear in between (seas steeper than this break)."""
    if tp <= 8.0:
        return 1.0 / 15.0
    if tp >= 15.0:
        return 1.0 / 25.0
    return 1.0 / 15.0 + (tp - 8.0) / 7.0 * (1.0 / 25.0 - 1.0 / 15.0)


def steepness_error(
    kind: str, height: float, period: float, height_name: str, period_name: str
) -> str | None:
    """Why a wave of ``height`` [m] at ``period`` [s] cannot exist (None if it can): a regular
    wave steeper than the breaking limit H/λ = MAX_STEEPNESS (Stokes/Michell: 1/7), an irregular
    sea steeper than :func:`irregular_steepness_limit`."""
    wavelength = GRAVITY * period**2 / (2.0 * math.pi)
    steepness = height / wavelength
    if kind == "regular":
        if steepness > MAX_STEEPNESS:
            return (
                f"{height_name} = {height:g} m at {period_name} = {period:g} s "
                f"(λ = {wavelength:.1f} m) exceeds the breaking steepness H/λ = "
                f"{MAX_STEEPNESS:.3f}: H <= {MAX_STEEPNESS * wavelength:.2f} m at that period"
            )
        return None
    limit = irregular_steepness_limit(period)
    if steepness > limit:
        return (
            f"{height_name} = {height:g} m at {period_name} = {period:g} s "
            f"(λp = {wavelength:.1f} m, Hs/λp = {steepness:.3g}) is steeper than a "
            f"physical sea: Hs/λp <= 1/{1.0 / limit:.1f} at that Tp (DNV-RP-C205 §3.5.5.4: 1/15 "
            f"for Tp <= 8 s, 1/25 for Tp >= 15 s), i.e. Hs <= {limit * wavelength:.2f} m"
        )
    return None


def _check_g(g: float) -> None:
    if not (math.isfinite(g) and g > 0.0):
        raise ValueError(f"g must be a finite gravitational acceleration > 0 [m/s^2]; got {g!r}")


def _finite(name: str, value: float) -> float:
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a real number; got {value!r}") from None
    if not math.isfinite(v):
        raise ValueError(f"{name} must be finite; got {value!r}")
    return v


def wavenumber(omega: ArrayLike, g: float = GRAVITY) -> NDArray:
    """Deep-water dispersion relation k = ω²/g.

    Parameters
    ----------
    omega : array_like
        Circular frequency [rad/s].
    g : float, optional
        Gravitational acceleration [m/s²].

    Returns
    -------
    numpy.ndarray
        Wavenumber k [rad/m].
    """
    _check_g(g)
    w = np.asarray(omega, dtype=float)
    return w * w / g


def wavelength_to_omega(wavelength: ArrayLike, g: float = GRAVITY) -> NDArray:
    """Circular frequency of a deep-water wave of given length: ω = √(2π g/λ).

    Parameters
    ----------
    wavelength : array_like
        Wavelength λ > 0 [m].
    g : float, optional
        Gravitational acceleration [m/s²].

    Returns
    -------
    numpy.ndarray
        ω [rad/s].
    """
    _check_g(g)
    lam = np.asarray(wavelength, dtype=float)
    if np.any(~np.isfinite(lam)) or np.any(lam <= 0.0):
        raise ValueError(f"wavelength must be finite and > 0 [m]; got {wavelength!r}")
    return np.sqrt(2.0 * np.pi * g / lam)


def omega_to_wavelength(omega: ArrayLike, g: float = GRAVITY) -> NDArray:
    """Deep-water wavelength λ = 2π g/ω² [m] of circular frequency ω > 0 [rad/s]."""
    _check_g(g)
    w = np.asarray(omega, dtype=float)
    if np.any(~np.isfinite(w)) or np.any(w <= 0.0):
        raise ValueError(f"omega must be finite and > 0 [rad/s]; got {omega!r}")
    return 2.0 * np.pi * g / (w * w)


@dataclass(frozen=True)
class RegularWave:
    """A regular (monochromatic, linear, deep-water) incident wave.

    Elevation in the earth frame (:mod:`ship_gym.conventions`), positive up::

        ζ(X, Y, t) = (H/2) cos(ωt − k(X cos χ + Y sin χ) + ε)

    so for ε = 0 a crest is at the origin at t = 0 and crests travel in direction χ at the phase
    speed c = ω/k = g/ω.

    Give exactly one of ``period`` and ``wavelength``; ``__post_init__`` fills in the other from
    deep-water dispersion (so both read back as floats). To change one with
    :func:`dataclasses.replace`, set the other to ``None``.

    Parameters
    ----------
    height : float
        Wave height H = 2a ≥ 0 [m]; H/λ must not exceed :data:`MAX_STEEPNESS`.
    period : float, optional
        Wave period T > 0 [s].
    wavelength : float, optional
        Wavelength λ > 0 [m].
    heading : float, optional
        χ, the direction the waves travel to, clockwise from north [rad]; default 0 (left
        unset: :func:`ship_gym.engine.ship.wave_field_for` then takes its ``wave_heading``).
    phase : float, optional
        Phase ε [rad].
    ramp_time : float, optional
        Duration T_f ≥ 0 of the start-up ramp (Matusiak eq. 12) [s]; 0 disables it.
    g : float, optional
        Gravitational acceleration [m/s²].
    """

    height: float
    period: float | None = None
    wavelength: float | None = None
    heading: float = DEFAULT_HEADING
    phase: float = 0.0
    ramp_time: float = 50.0
    g: float = GRAVITY

    def __post_init__(self) -> None:
        _check_g(self.g)
        height = _finite("height", self.height)
        if height < 0.0:
            raise ValueError(f"height must be >= 0 [m]; got {self.height!r}")
        _finite("heading", self.heading)
        _finite("phase", self.phase)
        ramp = _finite("ramp_time", self.ramp_time)
        if ramp < 0.0:
            raise ValueError(f"ramp_time must be >= 0 [s]; got {self.ramp_time!r}")
        if self.period is None and self.wavelength is None:
            raise ValueError("give a period [s] or a wavelength [m]; got neither")
        period = None if self.period is None else _finite("period", self.period)
        length = None if self.wavelength is None else _finite("wavelength", self.wavelength)
        if period is not None and period <= 0.0:
            raise ValueError(f"period must be > 0 [s]; got {self.period!r}")
        if length is not None and length <= 0.0:
            raise ValueError(f"wavelength must be > 0 [m]; got {self.wavelength!r}")
        if period is not None and length is not None:
            from_period = self.g * period**2 / (2.0 * math.pi)
            if not math.isclose(length, from_period, rel_tol=1e-9):
                raise ValueError(
                    f"period {period} s and wavelength {length} m disagree with deep-water "
                    f"dispersion (λ = gT²/2π = {from_period:.6g} m); give only one"
                )
        elif period is None:
            assert length is not None  # one of the two was given (checked above)
            period = 2.0 * math.pi / float(wavelength_to_omega(length, self.g))
        else:
            length = self.g * period**2 / (2.0 * math.pi)
        if height / length > MAX_STEEPNESS:
            raise ValueError(
                f"steepness H/λ = {height / length:.4g} exceeds the breaking limit "
                f"{MAX_STEEPNESS:.4g}; expected a smaller height or a longer wave"
            )
        object.__setattr__(self, "height", height)
        object.__setattr__(self, "period", period)
        object.__setattr__(self, "wavelength", length)
        if heading_is_set(self):
            object.__setattr__(self, "heading", float(self.heading))
        object.__setattr__(self, "phase", float(self.phase))
        object.__setattr__(self, "ramp_time", ramp)

    @property
    def amplitude(self) -> float:
        """Amplitude a = H/2 [m]."""
        return 0.5 * self.height

    @property
    def omega(self) -> float:
        """Circular frequency ω = 2π/T [rad/s]."""
        assert self.period is not None  # set by __post_init__
        return 2.0 * math.pi / self.period

    @property
    def wavenumber(self) -> float:
        """Wavenumber k = 2π/λ = ω²/g [rad/m]."""
        assert self.wavelength is not None  # set by __post_init__
        return 2.0 * math.pi / self.wavelength

    @property
    def steepness(self) -> float:
        """Steepness H/λ [-]."""
        assert self.wavelength is not None  # set by __post_init__
        return self.height / self.wavelength

    @property
    def phase_speed(self) -> float:
        """Phase speed c = ω/k = g/ω [m/s]."""
        return self.g / self.omega


SpectrumName = Literal["jonswap", "pm"]
FrequencySampling = Literal["jittered", "equal"]
DirectionSampling = Literal["equal_energy", "random"]


@dataclass(frozen=True)
class IrregularSea:
    """An irregular, deep-water sea state: spectrum, spreading and discretisation choices.

    The one-sided spectrum S(ω) (:func:`ship_gym.waves.spectra.jonswap` or
    :func:`~ship_gym.waves.spectra.pierson_moskowitz`) is split into
    ``n_components × n_directions`` wave components over ``omega_range`` by
    :meth:`ship_gym.waves.wave_field.WaveField.from_sea_state`, which documents the sampling.

    Parameters
    ----------
    hs : float
        Significant wave height Hs = 4√m0 ≥ 0 [m].
    tp : float
        Peak period Tp > 0 [s].
    heading : float, optional
        Mean direction χ̄ the waves travel to, clockwise from north [rad]; default 0 (left
        unset: :func:`ship_gym.engine.ship.wave_field_for` then takes its ``wave_heading``).
    spectrum : {"jonswap", "pm"}, optional
        Spectrum family; "pm" is JONSWAP with γ = 1 (``gamma`` ignored).
    gamma : float, optional
        JONSWAP peak-enhancement factor γ ≥ 1 [-].
    spreading_s : float or None, optional
        Cos-2s spreading exponent s ≥ 0 [-]; ``None`` gives a long-crested sea.
    n_components : int, optional
        Number of equal-width frequency bins ≥ 1.
    n_directions : int, optional
        Components per frequency bin ≥ 1 (each at its own frequency inside the bin, so the sum
        stays a single summation); total components ``n_components × n_directions``.
    omega_min, omega_max : float or None, optional
        Frequency band [rad/s]; ``None`` takes the frequencies where S falls to
        ``cutoff × max S`` (:func:`ship_gym.waves.spectra.frequency_range`).
    cutoff : float, optional
        Relative spectral level defining the default band, 0 < cutoff < 1 [-].
    ramp_time : float, optional
        Duration T_f ≥ 0 of the start-up ramp, Matusiak eq. 12 (T_f = 50 s there) [s].
    frequency_sampling : {"jittered", "equal"}, optional
        Random frequency inside each bin (default, no repeat period) or the bin centre.
    direction_sampling : {"equal_energy", "random"}, optional
        Stratified (equal-probability sectors) or independent sampling of D(θ).
    g : float, optional
        Gravitational acceleration [m/s²].
    """

    hs: float
    tp: float
    heading: float = DEFAULT_HEADING
    spectrum: SpectrumName = "jonswap"
    gamma: float = 3.3
    spreading_s: float | None = None
    n_components: int = 50
    n_directions: int = 1
    omega_min: float | None = None
    omega_max: float | None = None
    cutoff: float = 1e-3
    ramp_time: float = 50.0
    frequency_sampling: FrequencySampling = "jittered"
    direction_sampling: DirectionSampling = "equal_energy"
    g: float = GRAVITY

    def __post_init__(self) -> None:
        _check_g(self.g)
        if _finite("hs", self.hs) < 0.0:
            raise ValueError(f"hs must be >= 0 [m]; got {self.hs!r}")
        if _finite("tp", self.tp) <= 0.0:
            raise ValueError(f"tp must be > 0 [s]; got {self.tp!r}")
        _finite("heading", self.heading)
        if self.spectrum not in ("jonswap", "pm"):
            raise ValueError(f"spectrum must be 'jonswap' or 'pm'; got {self.spectrum!r}")
        if not (_finite("gamma", self.gamma) >= 1.0):
            raise ValueError(f"gamma must be >= 1; got {self.gamma!r}")
        if self.spreading_s is not None and _finite("spreading_s", self.spreading_s) < 0.0:
            raise ValueError(f"spreading_s must be None or >= 0; got {self.spreading_s!r}")
        for name in ("n_components", "n_directions"):
            value = getattr(self, name)
            if isinstance(value, bool) or not isinstance(value, int | np.integer) or value < 1:
                raise ValueError(f"{name} must be an integer >= 1; got {value!r}")
        if not (0.0 < _finite("cutoff", self.cutoff) < 1.0):
            raise ValueError(f"cutoff must be a relative level in (0, 1); got {self.cutoff!r}")
        if _finite("ramp_time", self.ramp_time) < 0.0:
            raise ValueError(f"ramp_time must be >= 0 [s]; got {self.ramp_time!r}")
        for name in ("omega_min", "omega_max"):
            value = getattr(self, name)
            if value is not None and _finite(name, value) <= 0.0:
                raise ValueError(f"{name} must be None or > 0 [rad/s]; got {value!r}")
        if self.frequency_sampling not in ("jittered", "equal"):
            raise ValueError(
                f"frequency_sampling must be 'jittered' or 'equal'; got {self.frequency_sampling!r}"
            )
        if self.direction_sampling not in ("equal_energy", "random"):
            raise ValueError(
                "direction_sampling must be 'equal_energy' or 'random'; "
                f"got {self.direction_sampling!r}"
            )
        lo, hi = self.omega_range
        if not lo < hi:
            raise ValueError(f"omega_min {lo} must be below omega_max {hi} [rad/s]")

    @property
    def effective_gamma(self) -> float:
        """γ actually used: 1 for ``spectrum="pm"`` [-]."""
        return 1.0 if self.spectrum == "pm" else float(self.gamma)

    @property
    def omega_peak(self) -> float:
        """Peak frequency ω_p = 2π/Tp [rad/s]."""
        return 2.0 * math.pi / self.tp

    @property
    def omega_range(self) -> tuple[float, float]:
        """Discretised band (ω_min, ω_max) [rad/s], defaults resolved from ``cutoff``."""
        lo, hi = self.omega_min, self.omega_max
        if lo is None or hi is None:
            d_lo, d_hi = frequency_range(self.tp, self.effective_gamma, self.cutoff)
            lo = d_lo if lo is None else lo
            hi = d_hi if hi is None else hi
        return float(lo), float(hi)

    @property
    def n_total(self) -> int:
        """Total number of wave components ``n_components × n_directions``."""
        return int(self.n_components) * int(self.n_directions)

    @property
    def long_crested(self) -> bool:
        """True when all components travel in the mean direction (``spreading_s is None``)."""
        return self.spreading_s is None

    def spectral_density(self, omega: ArrayLike) -> NDArray:
        """Frequency spectrum S(ω) [m² s/rad] at circular frequencies ω [rad/s]."""
        if self.spectrum == "pm":
            return pierson_moskowitz(omega, self.hs, self.tp)
        return jonswap(omega, self.hs, self.tp, gamma=self.gamma)

    def spreading(self, theta: ArrayLike) -> NDArray:
        """Directional spreading D(θ) [1/rad], θ relative to the mean heading [rad].

        Raises ValueError for a long-crested sea (a Dirac delta has no density).
        """
        if self.spreading_s is None:
            raise ValueError("long-crested sea (spreading_s=None) has no spreading density")
        return spreading_cos2s(theta, float(self.spreading_s))
