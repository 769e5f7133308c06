"""Incident wave field: a seeded sum of linear deep-water components (ζ, pressure, velocity).

Conventions (:mod:`ship_gym.conventions`, quoted)
-------------------------------------------------
Earth frame NED (X north, Y east, Z down, origin on the mean free surface); the elevation ζ is
positive **up**, so the instantaneous free surface is at Z = −ζ. Component j has amplitude a_j
[m], circular frequency ω_j [rad/s], deep-water wavenumber k_j = ω_j²/g [rad/m], direction χ_j
[rad] (the direction it travels *to*, clockwise from north) and phase ε_j [rad]::

    θ_j(X, Y, t) = ω_j t − k_j (X cos χ_j + Y sin χ_j) + ε_j
    ζ(X, Y, t)   = r(t) Σ_j a_j cos θ_j

which is the body-frame form ζ = a cos(ωt − k(x cos β + y sin β) + ε) of the conventions with
β = χ − ψ. r(t) is Matusiak's start-up ramp (eq. 12, :func:`ramp_factor`).

Phasors (for the fast Froude–Krylov kernel)
-------------------------------------------
c_j(t) = r(t) a_j e^{i(ω_j t + ε_j)}  and  ζ = Re Σ_j c_j(t) e^{−i k_j (X cos χ_j + Y sin χ_j)}.

This is the complex conjugate of capytaine's time convention x(t) = Re(X e^{−iωt}): in that
convention the complex elevation amplitude of component j is conj(c_j(0)) e^{+i k_j (…)}. The
time factor e^{iω_j t} is advanced without trig by :class:`PhasorClock`.

Deep water only: the vertical decay is e^{−k d} (d depth below the surface), valid for kh > π.
"""

from __future__ import annotations

import math
from collections.abc import Iterator, Sequence
from dataclasses import dataclass, field
from typing import Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from ship_gym.conventions import GRAVITY, RHO_SEAWATER, wrap_angle
from ship_gym.waves.sea_state import IrregularSea, RegularWave
from ship_gym.waves.spectra import spreading_cos2s_ppf

__all__ = [
    "PhasorClock",
    "WaveField",
    "WaveFieldStack",
    "ramp_factor",
    "stack_fields",
]

PressureMethod = Literal["wheeler", "linear"]

_CHUNK_ELEMENTS = 1 << 20
"""Points × components evaluated per chunk (bounds temporary memory to ≈ 8 MB per array)."""


def ramp_factor(t: ArrayLike, ramp_time: ArrayLike) -> NDArray:
    """Start-up ramp of the wave amplitude, Matusiak eq. 12.

    A(t) = A_final [1 − cos²(πt/(2T_f))] for t < T_f, i.e.

        r(t) = sin²(πt/(2T_f))  for 0 ≤ t < T_f,   r = 1 for t ≥ T_f,   r = 0 for t < 0,

    which rises from 0 to 1 with zero slope at both ends (r' = (π/2T_f) sin(πt/T_f)) and
    r(T_f/2) = ½. T_f = 0 disables the ramp (r ≡ 1 for all t).

    Parameters
    ----------
    t : array_like
        Time [s].
    ramp_time : array_like
        Ramp duration T_f ≥ 0 [s]; broadcasts with ``t``.

    Returns
    -------
    numpy.ndarray
        r(t) [-], shape ``broadcast(t, ramp_time)``.
    """
    tt = np.asarray(t, dtype=float)
    tf = np.asarray(ramp_time, dtype=float)
    if np.any(~np.isfinite(tf)) or np.any(tf < 0.0):
        raise ValueError(f"ramp_time must be finite and >= 0 [s]; got {ramp_time!r}")
    tt, tf = np.broadcast_arrays(tt, tf)
    safe = np.where(tf > 0.0, tf, 1.0)
    r = np.sin(0.5 * np.pi * np.clip(tt / safe, 0.0, 1.0)) ** 2
    r = np.where(tt >= tf, 1.0, r)
    return np.where(tf > 0.0, r, 1.0)


def _as_component_array(name: str, value: ArrayLike) -> NDArray:
    arr = np.array(value, dtype=float, copy=True, ndmin=1)
    if arr.ndim != 1:
        raise ValueError(f"{name} must be a 1-D array of components; got shape {arr.shape}")
    if not np.all(np.isfinite(arr)):
        raise ValueError(f"{name} must be finite")
    arr.setflags(write=False)
    return arr


def _broadcast_points(*arrays: ArrayLike) -> tuple[tuple[int, ...], list[NDArray]]:
    arrs = [np.asarray(a, dtype=float) for a in arrays]
    try:
        b = np.broadcast_arrays(*arrs)
    except ValueError:
        shapes = [a.shape for a in arrs]
        raise ValueError(f"positions and times must broadcast together; got {shapes}") from None
    for a in b:
        if not np.all(np.isfinite(a)):
            raise ValueError("positions and times must be finite")
    return b[0].shape, [np.ravel(a) for a in b]


def _chunks(n_points: int, n_comp: int) -> Iterator[slice]:
    step = max(1, _CHUNK_ELEMENTS // max(1, n_comp))
    for start in range(0, n_points, step):
        yield slice(start, min(start + step, n_points))


@dataclass(frozen=True, eq=False, repr=False)
class WaveField:
    """One realisation of the incident wave field: component arrays and the ramp.

    A value object: the arrays are copied and made read-only on construction. Equality is
    identity (arrays do not compare as booleans). All randomness enters through
    :meth:`from_sea_state`, so one ``numpy.random.Generator`` seed gives one sea.

    Parameters
    ----------
    amplitude : array_like
        a_j ≥ 0 [m], shape (n,).
    omega : array_like
        ω_j ≥ 0 [rad/s], shape (n,).
    wavenumber : array_like
        k_j ≥ 0 [rad/m], shape (n,) (deep water: ω_j²/g; see :meth:`from_components`).
    direction : array_like
        χ_j, direction each component travels to, clockwise from north [rad], shape (n,).
    phase : array_like
        ε_j [rad], shape (n,).
    ramp_time : float, optional
        Start-up ramp duration T_f ≥ 0 [s] (Matusiak eq. 12); 0 disables it.
    g : float, optional
        Gravitational acceleration [m/s²].
    """

    amplitude: NDArray
    omega: NDArray
    wavenumber: NDArray
    direction: NDArray
    phase: NDArray
    ramp_time: float = 50.0
    g: float = GRAVITY
    kx: NDArray = field(init=False, repr=False)
    """k_j cos χ_j [rad/m] (north component of the wavenumber vector)."""
    ky: NDArray = field(init=False, repr=False)
    """k_j sin χ_j [rad/m] (east component of the wavenumber vector)."""

    def __post_init__(self) -> None:
        names = ("amplitude", "omega", "wavenumber", "direction", "phase")
        arrays = {name: _as_component_array(name, getattr(self, name)) for name in names}
        n = arrays["amplitude"].size
        for name, arr in arrays.items():
            if arr.size != n:
                raise ValueError(f"{name} has {arr.size} components; expected {n} like amplitude")
        for name in ("amplitude", "omega", "wavenumber"):
            if np.any(arrays[name] < 0.0):
                raise ValueError(f"{name} must be >= 0 for every component")
        if not (math.isfinite(self.ramp_time) and self.ramp_time >= 0.0):
            raise ValueError(f"ramp_time must be finite and >= 0 [s]; got {self.ramp_time!r}")
        if not (math.isfinite(self.g) and self.g > 0.0):
            raise ValueError(f"g must be finite and > 0 [m/s^2]; got {self.g!r}")
        for name, arr in arrays.items():
            object.__setattr__(self, name, arr)
        object.__setattr__(self, "ramp_time", float(self.ramp_time))
        object.__setattr__(self, "g", float(self.g))
        k, chi = arrays["wavenumber"], arrays["direction"]
        kx, ky = k * np.cos(chi), k * np.sin(chi)
        kx.setflags(write=False)
        ky.setflags(write=False)
        object.__setattr__(self, "kx", kx)
        object.__setattr__(self, "ky", ky)

    def __repr__(self) -> str:
        w = self.omega
        band = f", omega=[{w.min():.4g}, {w.max():.4g}] rad/s" if w.size else ""
        return (
            f"WaveField(n_components={self.n_components}, "
            f"significant_height={self.significant_height:.4g} m{band}, "
            f"ramp_time={self.ramp_time:g} s, g={self.g:g})"
        )

    # ------------------------------------------------------------------ constructors
    @classmethod
    def from_components(
        cls,
        amplitude: ArrayLike,
        omega: ArrayLike,
        direction: ArrayLike,
        phase: ArrayLike,
        ramp_time: float = 50.0,
        g: float = GRAVITY,
    ) -> WaveField:
        """Build a field from components, with deep-water wavenumbers k_j = ω_j²/g."""
        w = np.asarray(omega, dtype=float)
        return cls(
            np.asarray(amplitude, dtype=float),
            w,
            w * w / g,
            np.asarray(direction, dtype=float),
            np.asarray(phase, dtype=float),
            ramp_time=ramp_time,
            g=g,
        )

    @classmethod
    def calm(cls, g: float = GRAVITY) -> WaveField:
        """Calm water: a field with no components (ζ ≡ 0, hydrostatic pressure)."""
        empty = np.zeros(0)
        return cls(empty, empty, empty, empty, empty, ramp_time=0.0, g=g)

    @classmethod
    def regular(cls, wave: RegularWave, ramp_time: float | None = None) -> WaveField:
        """One-component field of a :class:`~ship_gym.waves.sea_state.RegularWave`.

        Parameters
        ----------
        wave : RegularWave
            The wave (height, period/wavelength, heading χ, phase ε, ramp time, g).
        ramp_time : float, optional
            Overrides ``wave.ramp_time`` [s].

        Returns
        -------
        WaveField
            a = H/2, ω = 2π/T, k = 2π/λ, χ = ``wave.heading``, ε = ``wave.phase``.
        """
        if not isinstance(wave, RegularWave):
            raise ValueError(f"wave must be a RegularWave; got {type(wave).__name__}")
        return cls(
            np.array([wave.amplitude]),
            np.array([wave.omega]),
            np.array([wave.wavenumber]),
            np.array([wave.heading]),
            np.array([wave.phase]),
            ramp_time=wave.ramp_time if ramp_time is None else ramp_time,
            g=wave.g,
        )

    @classmethod
    def from_sea_state(cls, sea: IrregularSea, rng: np.random.Generator) -> WaveField:
        """Draw one realisation of an :class:`~ship_gym.waves.sea_state.IrregularSea`.

        Every random number comes from ``rng`` (in this order: frequency jitter, phases,
        direction sectors and positions), so one seed gives one sea.

        * **Frequencies.** The band (ω_min, ω_max) is cut into M = ``n_components ×
          n_directions`` equal bins of width Δω. With ``frequency_sampling="equal"`` each
          component sits at its bin centre; the sum is then periodic in time — a realisation
          repeats after T_r = 2π/Δω (exactly when the ω_j are integer multiples of Δω;
          otherwise its envelope repeats and every component is rotated by the same phase).
          With ``"jittered"`` (default) each component sits at a uniform random frequency
          inside its bin: the ω_j are incommensurate, so there is no repeat period and the
          correlation at lag T_r is ≈ Σ a_j² cos(ω_j T_r)/Σ a_j² ~ O(1/√M) instead of ≈ 1.
        * **Amplitudes.** a_j = √(2 S(ω_j) Δω), unbiased for m0 with jittered bins. Energy
          outside the band is not redistributed (≈ 0.2–0.3 % of m0 for the default cutoff).
        * **Phases.** ε_j uniform in [0, 2π).
        * **Directions.** Long-crested (``spreading_s=None``): χ_j = χ̄. Short-crested: one
          direction per component (single summation: every component keeps its own frequency,
          so the field stays ergodic and the component count does not grow), θ_j = χ_j − χ̄
          from the cos-2s law by inverse-CDF sampling
          (:func:`~ship_gym.waves.spectra.spreading_cos2s_ppf`):
          ``"equal_energy"`` (stratified sampling) cuts D into N equal-probability
          (equal-energy) sectors and uses each sector exactly once, at u = (m + U)/N with U
          uniform — unbiased for any N, unlike sector midpoints, which narrow the spreading
          (5 midpoints with s = 3 give E[cos θ] = 0.79 instead of s/(s+1) = 0.75); sectors are
          randomly assigned to components, N = M over the whole band when
          ``n_directions == 1``, else N = ``n_directions`` within each frequency bin of width
          n_directions·Δω, so every bin carries the whole spreading. ``"random"`` draws every
          u_j independently and uniformly. Directions are wrapped to [−π, π).

        Parameters
        ----------
        sea : IrregularSea
            The sea state.
        rng : numpy.random.Generator
            Source of all randomness.

        Returns
        -------
        WaveField
            M components, ramp time and g of ``sea``.
        """
        if not isinstance(sea, IrregularSea):
            raise ValueError(f"sea must be an IrregularSea; got {type(sea).__name__}")
        if not isinstance(rng, np.random.Generator):
            raise ValueError(
                f"rng must be a numpy.random.Generator (np.random.default_rng(seed)); "
                f"got {type(rng).__name__}"
            )
        m = sea.n_total
        lo, hi = sea.omega_range
        d_omega = (hi - lo) / m
        if sea.frequency_sampling == "jittered":
            offset = rng.random(m)
        else:
            offset = np.full(m, 0.5)
        omega = lo + (np.arange(m) + offset) * d_omega
        amplitude = np.sqrt(2.0 * sea.spectral_density(omega) * d_omega)
        phase = 2.0 * np.pi * rng.random(m)
        if sea.spreading_s is None:
            direction = np.full(m, float(sea.heading))
        else:
            if sea.direction_sampling == "random":
                u = rng.random(m)
            elif sea.n_directions == 1:
                u = (rng.permutation(m) + rng.random(m)) / m
            else:
                nd = sea.n_directions
                sectors = np.tile(np.arange(nd), (sea.n_components, 1))
                u = (rng.permuted(sectors, axis=1).ravel() + rng.random(m)) / nd
            theta = spreading_cos2s_ppf(u, float(sea.spreading_s))
            direction = np.asarray(wrap_angle(sea.heading + theta), dtype=float)
        return cls.from_components(
            amplitude, omega, direction, phase, ramp_time=sea.ramp_time, g=sea.g
        )

    @classmethod
    def build(
        cls, sea: RegularWave | IrregularSea | None, rng: np.random.Generator | None = None
    ) -> WaveField:
        """Field of any sea description: ``None`` → calm, regular, or irregular (needs rng)."""
        if sea is None:
            return cls.calm()
        if isinstance(sea, RegularWave):
            return cls.regular(sea)
        if rng is None:
            raise ValueError("an IrregularSea needs rng, a numpy.random.Generator; got None")
        return cls.from_sea_state(sea, rng)

    # ------------------------------------------------------------------ properties
    @property
    def n_components(self) -> int:
        """Number of wave components n."""
        return int(self.amplitude.size)

    @property
    def variance(self) -> float:
        """Elevation variance after the ramp, Σ a_j²/2 [m²] (= m0 of the realisation)."""
        return float(0.5 * np.sum(self.amplitude**2))

    @property
    def significant_height(self) -> float:
        """Significant wave height of the realisation 4√(Σ a_j²/2) [m]."""
        return 4.0 * math.sqrt(self.variance)

    # ------------------------------------------------------------------ evaluation
    def ramp(self, t: ArrayLike) -> NDArray:
        """Ramp factor r(t) [-] of Matusiak eq. 12 (:func:`ramp_factor`) at times t [s]."""
        return ramp_factor(t, self.ramp_time)

    def _theta(self, x: NDArray, y: NDArray, t: NDArray) -> NDArray:
        return (
            np.multiply.outer(t, self.omega)
            - np.multiply.outer(x, self.kx)
            - np.multiply.outer(y, self.ky)
            + self.phase
        )

    def elevation(self, X: ArrayLike, Y: ArrayLike, t: ArrayLike) -> NDArray:
        """Free-surface elevation ζ = r(t) Σ a_j cos θ_j [m], positive up.

        Parameters
        ----------
        X, Y : array_like
            Earth-frame north / east positions [m].
        t : array_like
            Time [s]. ``X``, ``Y`` and ``t`` broadcast together.

        Returns
        -------
        numpy.ndarray
            ζ [m], shape ``broadcast(X, Y, t)``.
        """
        shape, (x, y, tt) = _broadcast_points(X, Y, t)
        out = np.empty(x.size)
        for sl in _chunks(x.size, self.n_components):
            out[sl] = np.cos(self._theta(x[sl], y[sl], tt[sl])) @ self.amplitude
        return (out * self.ramp(tt)).reshape(shape)

    def _decay(self, z: NDArray, d: NDArray, method: PressureMethod) -> tuple[NDArray, NDArray]:
        """Vertical decay e^{−k s} (s = d for Wheeler, Z for linear; clipped at 0) and wet mask."""
        if method == "wheeler":
            depth = np.maximum(d, 0.0)
        elif method == "linear":
            depth = np.maximum(z, 0.0)
        else:
            raise ValueError(f"method must be 'wheeler' or 'linear'; got {method!r}")
        return np.exp(-np.multiply.outer(depth, self.wavenumber)), d >= 0.0

    def pressure(
        self,
        X: ArrayLike,
        Y: ArrayLike,
        Z: ArrayLike,
        t: ArrayLike,
        rho: float = RHO_SEAWATER,
        method: PressureMethod = "wheeler",
    ) -> NDArray:
        """Total (hydrostatic + incident-wave) gauge pressure, deep water.

        With d = Z + ζ the depth below the instantaneous surface:

        ``"wheeler"`` (default; Wheeler stretching)
            p = ρ g (Z + r(t) Σ a_j e^{−k_j d} cos θ_j) for d ≥ 0: the decay is evaluated at
            the depth below the instantaneous surface, so p = 0 exactly on it (Z = −ζ gives
            ρg(−ζ + ζ)) and the hydrostatic ρgZ is recovered for d ≫ λ.
        ``"linear"`` (Airy, small-amplitude)
            p = ρ g (Z + r(t) Σ a_j e^{−k_j Z} cos θ_j) for Z ≥ 0, and the hydrostatic
            extrapolation p = ρ g (Z + ζ) in a crest above the mean surface (Z < 0).

        In both, p = 0 above the instantaneous surface (d < 0, dry points). The two agree to
        O(ρ g k a²) below the surface.

        Parameters
        ----------
        X, Y, Z : array_like
            Earth-frame positions [m], Z positive down.
        t : array_like
            Time [s]. All four broadcast.
        rho : float, optional
            Water density [kg/m³].
        method : {"wheeler", "linear"}, optional
            Kinematic stretching, see above.

        Returns
        -------
        numpy.ndarray
            p [Pa], shape ``broadcast(X, Y, Z, t)``.
        """
        if not (math.isfinite(rho) and rho > 0.0):
            raise ValueError(f"rho must be finite and > 0 [kg/m^3]; got {rho!r}")
        shape, (x, y, z, tt) = _broadcast_points(X, Y, Z, t)
        r = self.ramp(tt)
        out = np.empty(x.size)
        for sl in _chunks(x.size, self.n_components):
            cos = np.cos(self._theta(x[sl], y[sl], tt[sl]))
            zeta = r[sl] * (cos @ self.amplitude)
            d = z[sl] + zeta
            decay, wet = self._decay(z[sl], d, method)
            dyn = r[sl] * ((decay * cos) @ self.amplitude)
            p = z[sl] + dyn
            if method == "linear":
                p = np.where(z[sl] >= 0.0, p, d)
            out[sl] = np.where(wet, p, 0.0)
        return (rho * self.g * out).reshape(shape)

    def velocity(
        self,
        X: ArrayLike,
        Y: ArrayLike,
        Z: ArrayLike,
        t: ArrayLike,
        method: PressureMethod = "wheeler",
    ) -> NDArray:
        """Orbital velocity of the incident wave in the earth frame (deep water).

        From the potential of each component::

            u_N = r Σ a_j ω_j E_j cos θ_j cos χ_j,   u_E = r Σ a_j ω_j E_j cos θ_j sin χ_j,
            u_D = r Σ a_j ω_j E_j sin θ_j

        (forward under a crest; u_D = −∂ζ/∂t at the surface since ζ is positive up), with
        E_j = e^{−k_j d} for ``"wheeler"`` and e^{−k_j max(Z, 0)} for ``"linear"`` (constant
        extrapolation above Z = 0). Zero above the instantaneous surface (d = Z + ζ < 0).

        Parameters
        ----------
        X, Y, Z : array_like
            Earth-frame positions [m], Z positive down.
        t : array_like
            Time [s]. All four broadcast.
        method : {"wheeler", "linear"}, optional
            Stretching, as in :meth:`pressure`.

        Returns
        -------
        numpy.ndarray
            (u_N, u_E, u_D) [m/s], shape ``broadcast(X, Y, Z, t) + (3,)``.
        """
        shape, (x, y, z, tt) = _broadcast_points(X, Y, Z, t)
        r = self.ramp(tt)
        out = np.empty((x.size, 3))
        aw = self.amplitude * self.omega
        cx, cy = np.cos(self.direction), np.sin(self.direction)
        for sl in _chunks(x.size, self.n_components):
            theta = self._theta(x[sl], y[sl], tt[sl])
            cos, sin = np.cos(theta), np.sin(theta)
            zeta = r[sl] * (cos @ self.amplitude)
            decay, wet = self._decay(z[sl], z[sl] + zeta, method)
            scale = np.where(wet, r[sl], 0.0)[:, None]
            horiz = decay * cos * aw
            out[sl, 0] = horiz @ cx
            out[sl, 1] = horiz @ cy
            out[sl, 2] = (decay * sin) @ aw
            out[sl] *= scale
        return out.reshape(*shape, 3)

    # ------------------------------------------------------------------ phasors
    def phasor(self, t: ArrayLike) -> NDArray:
        """Complex component phasors c_j(t) = r(t) a_j e^{i(ω_j t + ε_j)} [m].

        ζ(X, Y, t) = Re Σ_j c_j(t) e^{−i k_j (X cos χ_j + Y sin χ_j)}; see
        :meth:`elevation_from_phasor` and :class:`PhasorClock` for the trig-free time update.

        Parameters
        ----------
        t : array_like
            Time [s].

        Returns
        -------
        numpy.ndarray
            Complex array, shape ``t.shape + (n,)``.
        """
        tt = np.asarray(t, dtype=float)
        arg = np.multiply.outer(tt, self.omega) + self.phase
        return (self.ramp(tt)[..., None] * self.amplitude) * np.exp(1j * arg)

    def elevation_from_phasor(self, c: ArrayLike, X: ArrayLike, Y: ArrayLike) -> NDArray:
        """ζ = Re Σ_j c_j e^{−i(k_x,j X + k_y,j Y)} [m] from phasors ``c`` of shape (n,).

        ``X`` and ``Y`` [m] broadcast; the result has their broadcast shape.
        """
        cc = np.asarray(c)
        if cc.shape != (self.n_components,):
            raise ValueError(f"c must have shape ({self.n_components},); got {cc.shape}")
        shape, (x, y) = _broadcast_points(X, Y)
        spatial = np.exp(-1j * (np.multiply.outer(x, self.kx) + np.multiply.outer(y, self.ky)))
        return (spatial @ cc).real.reshape(shape)

    def clock(self, dt: float, t0: float = 0.0, reanchor_every: int | None = 4096) -> PhasorClock:
        """A :class:`PhasorClock` for this field starting at ``t0`` [s] with step ``dt`` [s]."""
        return PhasorClock(
            self.omega,
            self.amplitude,
            self.phase,
            dt,
            t0=t0,
            ramp_time=self.ramp_time,
            reanchor_every=reanchor_every,
        )


class PhasorClock:
    """Advance the component phasors c_j(t) = r(t) a_j e^{i(ω_j t + ε_j)} with no trig per step.

    The unit time factors z_j = e^{iω_j t_n}, t_n = t0 + n Δt, are updated by one complex
    multiplication z_j ← z_j e^{iω_j Δt}. Rounding makes |z_j| and arg z_j drift by
    O(n ε_machine) after n steps (≈ 1e-11 after 10⁵ steps); every ``reanchor_every`` steps
    z_j is recomputed exactly as e^{iω_j t_n} from the integer step count (one exp per
    component, amortised to nothing), which removes the drift. Works for any leading batch
    shape of the component arrays, e.g. (n_ships, n_comp) from :func:`stack_fields`.

    Parameters
    ----------
    omega : array_like
        ω_j [rad/s], shape (..., n).
    amplitude : array_like
        a_j [m], broadcastable to ``omega``.
    phase : array_like
        ε_j [rad], broadcastable to ``omega``.
    dt : float
        Time step Δt > 0 [s].
    t0 : float, optional
        Start time [s].
    ramp_time : array_like, optional
        Ramp duration(s) T_f [s], broadcastable to ``omega.shape[:-1]``.
    reanchor_every : int or None, optional
        Steps between exact re-evaluations; ``None`` never re-anchors.
    """

    def __init__(
        self,
        omega: ArrayLike,
        amplitude: ArrayLike,
        phase: ArrayLike,
        dt: float,
        t0: float = 0.0,
        ramp_time: ArrayLike = 0.0,
        reanchor_every: int | None = 4096,
    ) -> None:
        if not (math.isfinite(dt) and dt > 0.0):
            raise ValueError(f"dt must be finite and > 0 [s]; got {dt!r}")
        if not math.isfinite(t0):
            raise ValueError(f"t0 must be finite [s]; got {t0!r}")
        if reanchor_every is not None and (
            not isinstance(reanchor_every, int | np.integer) or reanchor_every < 1
        ):
            raise ValueError(
                f"reanchor_every must be None or an integer >= 1; got {reanchor_every!r}"
            )
        self._omega = np.asarray(omega, dtype=float)
        self._base = np.broadcast_to(
            np.asarray(amplitude, dtype=float) * np.exp(1j * np.asarray(phase, dtype=float)),
            self._omega.shape,
        ).copy()
        self._ramp_time = np.asarray(ramp_time, dtype=float)
        ramp_factor(0.0, self._ramp_time)  # validates
        self._dt = float(dt)
        self._t0 = float(t0)
        self._reanchor = reanchor_every
        self._rotation = np.exp(1j * self._omega * self._dt)
        self.reset(t0)

    @property
    def t(self) -> float:
        """Current time t_n = t0 + n Δt [s]."""
        return self._t0 + self._n * self._dt

    @property
    def steps(self) -> int:
        """Number of steps n taken since the last reset."""
        return self._n

    @property
    def dt(self) -> float:
        """Time step Δt [s]."""
        return self._dt

    @property
    def time_factor(self) -> NDArray:
        """Current unit phasors z_j = e^{iω_j t_n} (read-only view)."""
        view = self._z.view()
        view.setflags(write=False)
        return view

    def reset(self, t0: float | None = None) -> None:
        """Restart at ``t0`` [s] (default: the original start time), step count 0."""
        if t0 is not None:
            if not math.isfinite(t0):
                raise ValueError(f"t0 must be finite [s]; got {t0!r}")
            self._t0 = float(t0)
        self._n = 0
        self._z = np.exp(1j * self._omega * self._t0)

    def step(self, n_steps: int = 1) -> None:
        """Advance by ``n_steps`` ≥ 0 steps of Δt (one complex multiply per component each)."""
        if n_steps < 0:
            raise ValueError(f"n_steps must be >= 0; got {n_steps!r}")
        for _ in range(n_steps):
            np.multiply(self._z, self._rotation, out=self._z)
            self._n += 1
            if self._reanchor is not None and self._n % self._reanchor == 0:
                self._z[...] = np.exp(1j * self._omega * self.t)

    def phasor(self, out: NDArray | None = None) -> NDArray:
        """c_j(t_n) = r(t_n) a_j e^{iε_j} z_j [m], shape of ``omega`` (written to ``out``)."""
        r = ramp_factor(self.t, self._ramp_time)[..., None]
        out = np.multiply(self._base, self._z, out=out)
        out *= r
        return out


@dataclass(frozen=True, eq=False)
class WaveFieldStack:
    """Component arrays of several wave fields, padded to a common length, for a vector env.

    Arrays have shape (n_fields, n_comp); padding components have a = ω = k = 0 and contribute
    nothing. Per-field ``ramp_time`` and ``g`` have shape (n_fields,). Built by
    :func:`stack_fields`.
    """

    amplitude: NDArray
    omega: NDArray
    wavenumber: NDArray
    direction: NDArray
    phase: NDArray
    kx: NDArray
    ky: NDArray
    ramp_time: NDArray
    g: NDArray

    @property
    def n_fields(self) -> int:
        """Number of stacked fields (ships)."""
        return int(self.amplitude.shape[0])

    @property
    def n_components(self) -> int:
        """Common (padded) number of components."""
        return int(self.amplitude.shape[1])

    def _times(self, t: ArrayLike) -> NDArray:
        tt = np.asarray(t, dtype=float)
        try:
            return np.broadcast_to(tt, (self.n_fields,))
        except ValueError:
            raise ValueError(
                f"t must be a scalar or have shape ({self.n_fields},); got {tt.shape}"
            ) from None

    def ramp(self, t: ArrayLike) -> NDArray:
        """Ramp factors r(t) [-], shape (n_fields,); t [s] scalar or (n_fields,)."""
        return ramp_factor(self._times(t), self.ramp_time)

    def phasor(self, t: ArrayLike) -> NDArray:
        """c_{s,j}(t_s) = r_s(t_s) a_{s,j} e^{i(ω_{s,j} t_s + ε_{s,j})} [m], (n_fields, n_comp)."""
        tt = self._times(t)
        arg = self.omega * tt[:, None] + self.phase
        return (self.ramp(tt)[:, None] * self.amplitude) * np.exp(1j * arg)

    def elevation(self, X: ArrayLike, Y: ArrayLike, t: ArrayLike) -> NDArray:
        """ζ [m] of field s at its own points and time.

        Parameters
        ----------
        X, Y : array_like
            Positions [m], shape (n_fields, ...) (broadcast together).
        t : array_like
            Times [s], scalar or (n_fields,).

        Returns
        -------
        numpy.ndarray
            ζ [m], shape ``broadcast(X, Y)``.
        """
        xx, yy = np.broadcast_arrays(np.asarray(X, dtype=float), np.asarray(Y, dtype=float))
        if xx.ndim < 1 or xx.shape[0] != self.n_fields:
            raise ValueError(f"X, Y must have leading axis {self.n_fields}; got {xx.shape}")
        tt = self._times(t)
        x = xx.reshape(self.n_fields, -1, 1)
        y = yy.reshape(self.n_fields, -1, 1)
        theta = (
            (self.omega * tt[:, None])[:, None, :]
            - x * self.kx[:, None, :]
            - y * self.ky[:, None, :]
            + self.phase[:, None, :]
        )
        zeta = np.einsum("spj,sj->sp", np.cos(theta), self.amplitude)
        return (zeta * self.ramp(tt)[:, None]).reshape(xx.shape)

    def clock(self, dt: float, t0: float = 0.0, reanchor_every: int | None = 4096) -> PhasorClock:
        """A :class:`PhasorClock` advancing all fields together (phasors (n_fields, n_comp))."""
        return PhasorClock(
            self.omega,
            self.amplitude,
            self.phase,
            dt,
            t0=t0,
            ramp_time=self.ramp_time,
            reanchor_every=reanchor_every,
        )


def stack_fields(fields: Sequence[WaveField]) -> WaveFieldStack:
    """Stack wave fields into (n_fields, n_comp) arrays, zero-padding shorter fields.

    Parameters
    ----------
    fields : sequence of WaveField
        One field per ship (at least one).

    Returns
    -------
    WaveFieldStack
        Read-only arrays; ``n_comp`` is the largest component count.
    """
    fields = list(fields)
    if not fields:
        raise ValueError("fields must hold at least one WaveField; got an empty sequence")
    for i, f in enumerate(fields):
        if not isinstance(f, WaveField):
            raise ValueError(f"fields[{i}] must be a WaveField; got {type(f).__name__}")
    n = max(f.n_components for f in fields)

    def pad(name: str) -> NDArray:
        arr = np.zeros((len(fields), n))
        for i, f in enumerate(fields):
            vals = getattr(f, name)
            arr[i, : vals.size] = vals
        arr.setflags(write=False)
        return arr

    per_field = {
        "ramp_time": np.array([f.ramp_time for f in fields]),
        "g": np.array([f.g for f in fields]),
    }
    for arr in per_field.values():
        arr.setflags(write=False)
    names = ("amplitude", "omega", "wavenumber", "direction", "phase", "kx", "ky")
    return WaveFieldStack(**{name: pad(name) for name in names}, **per_field)
