"""Radiation retardation (memory) kernels from frequency-domain added mass and damping.

Conventions (DESIGN.md §3, quoted)
----------------------------------
* Velocity kernel (Cummins; Matusiak eq. 16)::

      K(t) = (2/π) ∫₀^∞ B(ω) cos ωt dω

* Acceleration kernel, *sine form* (Gourlay eq. 3, preferred) and *cosine form* (Gourlay eq. 2)::

      L(t) = (2/π) ∫₀^∞ B(ω)/ω sin ωt dω = (2/π) ∫₀^∞ [A(ω) − A(∞)] cos ωt dω,   K = dL/dt

  For a physical body B(0) = 0, so L(t) = ∫₀^t K(τ) dτ and L(0) = L(∞) = 0.
* Ogilvie's relations, used to check a kernel against the frequency-domain data::

      A(ω) = A(∞) − (1/ω) ∫₀^∞ K(t) sin ωt dt,     B(ω) = ∫₀^∞ K(t) cos ωt dt

  Equivalently the one-sided Laplace transform of K at s = iω is K̂(iω) = B(ω) + iω[A(ω) − A(∞)].

Array layout
------------
Every transform is vectorised over all DOF pairs: coefficient arrays have shape
``(n_omega, ...)`` with any trailing shape (typically ``(n_omega, 6, 6)`` with axes
``(omega, radiating_dof, influenced_dof)`` of a capytaine-style database) and kernels come back
with shape ``(n_t, ...)`` and the same trailing axes. Units: K carries the units of B times
[rad/s] (e.g. [kg/s²] for a force per velocity), L the units of B, i.e. of A times [rad/s]
(e.g. [kg/s] for a force per acceleration).

Quadratures
-----------
``"filon"``
    Filon (1930) quadrature in Gourlay's complex form (eq. 4–10): ∫ f(ω) e^{iωt} dω ≈
    Δω Σ Wₙ f(ωₙ) e^{iωₙt} over 2N intervals; the real part gives the cosine integral, the
    imaginary part the sine integral. f is replaced by a parabola on each double interval and
    the product with e^{iωt} is integrated exactly, so the rule stays accurate for θ = tΔω ≫ 1
    where Simpson's rule aliases. Error O(Δω⁴) at fixed t. The closed-form weights (eq. 7–9)
    cancel catastrophically for small θ (α loses ≈ log10(22/θ⁴) digits); below
    :data:`FILON_SERIES_THRESHOLD` = 0.4 their Taylor series to θ¹³ are used instead. At θ = 0.4
    the closed forms are accurate to ≈ 3e-14 relative and the truncated series to ≈ 4e-14
    (checked against 50-digit arithmetic), so the switch is seamless at the 1e-13 level. At
    θ = 0 the rule reduces exactly to Simpson's.
``"simpson"``
    Composite Simpson's rule applied to f(ω) e^{iωt} (the integrand is sampled, so the rule
    aliases once θ = tΔω is of order 1 — Gourlay §3, Fig. 2).
``"trapezoid"``
    Trapezoidal rule on f(ω) e^{iωt}; works on non-uniform grids without resampling.
``"fft"``
    Matusiak eq. 17–18: the integrand is interpolated (cubic spline) onto ωₙ = nΔω_F,
    n = 0…N/2, and the trapezoidal sum is evaluated for all tₖ = kΔt, Δt = 2π/(NΔω_F), by one
    FFT. For the cosine integral this is exactly eq. 17 with the double-sided (even) extension
    of eq. 18 and a 1/N-normalised FFT. See :func:`_fft_transform` for the choice of N and Δt.

Grids
-----
The data grid must be strictly increasing with ω ≥ 0 and finite (drop ω = 0 / ω = ∞ entries of
a database yourself if they carry limits rather than data; ω = 0 is accepted). If it does not
start at ω = 0 the integrand is extended to 0 linearly from the value at 0 (B(0) = 0 and
B/ω → 0 for a body in deep water — B vanishes faster than ω there; for the cosine form
A(0) := A(ω₀), a flat extension). Filon and Simpson need a uniform grid with an even number of
intervals (odd number of points): any other grid (non-uniform, or an even number of points) is
resampled by a not-a-knot cubic spline onto the coarsest uniform grid with an even number of
intervals whose spacing does not exceed the finest input spacing; the spline's O(h⁴) error
matches the order of both rules. The trapezoidal rule uses the grid as given.

High-frequency tail
-------------------
Databases stop at a finite ω_max; the integrals are truncated there unless a tail is chosen:

``"none"``
    Integrate up to ω_max only (Gourlay and WAMIT F2T practice). The jump f(ω_max) ≠ 0 makes
    K ring at frequency ω_max with an envelope ≈ (2/π)|f(ω_max)|/t and biases K(0).
``"power"``
    Extend B(ω) = B(ω_max)(ω_max/ω)ⁿ beyond ω_max and integrate the extension analytically:
    ∫_{ω_m}^∞ (ω_m/ω)^p e^{iωt} dω = ω_m E_p(−iω_m t) with E_p the generalised exponential
    integral (p = n for K, p = n + 1 for B/ω in the sine form). The default n = 4 follows from the
    initial-value expansion K̂(iω) = K(0)/(iω) + K'(0⁺)/(iω)² + K''(0⁺)/(iω)³ + K'''(0⁺)/(iω)⁴…
    whose real part is B(ω) = −K'(0⁺)/ω² + K'''(0⁺)/ω⁴ + …: radiation kernels leave t = 0 with
    zero slope (K'(0⁺) = −(2/π)·lim ∫ ωB sin ωt dω = 0 whenever ∫ωB dω converges), so the
    leading term is ω⁻⁴. n = 4 also keeps K(0), K'(0) and K''(0) finite. The tail adds
    (2/π)B(ω_max)ω_max/(n − 1) to K(0) and cancels most of the truncation ringing at large t.
    ``tail_exponent="fit"`` fits n per DOF pair (least squares on log|B| over the last 20 % of
    the grid, rounded to an integer in [2, 8]; pairs where the fit is not possible keep 4). For
    the cosine form the tail of A(ω) − A(∞) is always ∝ ω⁻² (from the same expansion: A − A(∞) ≈
    −K(0)/ω²). A single power pinned at B(ω_max) ignores the next term of the series: for
    B = ω²/(1 + ω²)² (∝ ω⁻² − 2ω⁻⁴ + …) cut at ω_max = 4 rad/s it leaves 2.4e-2 of K(0) even
    with the right n = 2 (error O(ω_max⁻³)).
``"asymptotic"``
    Two terms of that series: B(ω) = B(ω_max)[a(ω_max/ω)ⁿ + (1 − a)(ω_max/ω)ⁿ⁺²] beyond ω_max,
    n = ``tail_exponent`` (integer or ``"fit"``), a fitted by one-parameter least squares on the
    last :data:`ASYMPTOTIC_TAIL_POINTS` = 5 grid points (value at ω_max matched exactly, so
    the extension is continuous; a clipped to [0, 2], which keeps the sign of B(ω_max)), and
    integrated analytically like ``"power"``. The same B extension (same a) gives the
    sine-form L; the cosine form applies it to A − A(∞) with n = 2. Exact for B = c_nω⁻ⁿ +
    c_{n+2}ω⁻ⁿ⁻²; the K(0) error is O(ω_max⁻⁵): ω²/(1+ω²)² cut at 4 rad/s, 1.8e-3 of K(0)
    (6.1e-5 at 8 rad/s); ω²/(1+ω²)³ (∝ ω⁻⁴), 1.2e-4 (1.1e-6). This is the tail recommended
    for ship databases (``tail="asymptotic"``, ``tail_exponent="fit"``; docs/kernel_tails.md):
    on the bundled S175 (ω_max = 1.67 rad/s, B(ω_max) still 22–73 % of its peak) the tail
    carries 17–59 % of K(0), and of all options it has the smallest worst-pair error of the
    database A(ω) − A(∞) reproduced through Ogilvie's relation (relative RMS error per pair
    0.4–3.2 %, sway–roll 14 %; single power with fitted n: 0.5–4.6 %, 15 %; none: 5–26 %).
    Measured truncation uncertainty of the S175 kernels (spread between the two best tails):
    K(0) ±14 %, kernel L2 norm ±11 % (heave–pitch; heave ±1 %).
``"taper"``
    Multiply the integrand by a Hann (raised-cosine) taper over the last ``taper_fraction`` of
    [0, ω_max], so it goes smoothly to zero at ω_max. This suppresses the truncation ringing at
    large t but removes part of the integral (lowers |K| at small t).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any, Literal, TypeVar

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.interpolate import CubicSpline
from scipy.special import exp1, roots_laguerre

from ship_gym.conventions import DOF_NAMES, dof_index

__all__ = [
    "ASYMPTOTIC_TAIL_POINTS",
    "ASYMPTOTIC_WEIGHT_RANGE",
    "DEFAULT_N_FFT",
    "DEFAULT_TAIL_EXPONENT",
    "FILON_SERIES_THRESHOLD",
    "FORMS",
    "METHODS",
    "TAILS",
    "KernelDecay",
    "ReconstructionError",
    "RetardationKernels",
    "acceleration_kernel",
    "compute_kernels",
    "filon_weights",
    "kernel_decay",
    "oscillatory_integral",
    "plot_kernels",
    "plot_reconstruction",
    "reconstruct_coefficients",
    "reconstruction_error",
    "relative_pair_error",
    "velocity_kernel",
]

Method = Literal["filon", "simpson", "trapezoid", "fft"]
Form = Literal["sine", "cosine"]
Tail = Literal["none", "power", "asymptotic", "taper"]

METHODS: tuple[Method, ...] = ("filon", "simpson", "trapezoid", "fft")
FORMS: tuple[Form, ...] = ("sine", "cosine")
TAILS: tuple[Tail, ...] = ("none", "power", "asymptotic", "taper")
_Choice = TypeVar("_Choice", bound=str)

FILON_SERIES_THRESHOLD: float = 0.4
"""θ = tΔω below which Filon's α, β, γ come from their Taylor series (see module docstring)."""

DEFAULT_TAIL_EXPONENT: int = 4
"""Exponent n of the B(ω) ∝ ω⁻ⁿ high-frequency extension (see module docstring)."""

COSINE_TAIL_EXPONENT: int = 2
"""Exponent of the A(ω) − A(∞) ∝ ω⁻² extension used by the cosine form."""

DEFAULT_N_FFT: int = 2048
"""Matusiak's FFT length (§3.1: 2048 points, 1024 kernel values)."""

ASYMPTOTIC_TAIL_POINTS: int = 5
"""Number of last grid points on which the ``"asymptotic"`` tail's mixing weight is fitted."""

ASYMPTOTIC_WEIGHT_RANGE: tuple[float, float] = (0.0, 2.0)
"""Bounds of the ``"asymptotic"`` tail's weight a on ω⁻ⁿ (a ≥ 0 keeps the tail's sign)."""

_UNIFORM_RTOL = 1e-6
_CHUNK_ELEMENTS = 2_000_000
_MAX_FFT = 2**22
_LAGUERRE_SWITCH = 8.0
_LAGUERRE_X, _LAGUERRE_W = roots_laguerre(60)

# Taylor coefficients (in θ²) of Filon's weights, from sympy series of eq. 7–9.
_ALPHA_SERIES = (2 / 45, -2 / 315, 2 / 4725, -8 / 467775, 4 / 8513505, -2 / 212837625)
_BETA_SERIES = (2 / 3, 2 / 15, -4 / 105, 2 / 567, -4 / 22275, 4 / 675675, -8 / 58046625)
_GAMMA_SERIES = (4 / 3, -2 / 15, 1 / 210, -1 / 11340, 1 / 997920, -1 / 129729600, 1 / 23351328000)


# --------------------------------------------------------------------------------------------
# validation helpers
# --------------------------------------------------------------------------------------------
def _check_choice(value: Any, name: str, allowed: tuple[_Choice, ...]) -> _Choice:
    if not isinstance(value, str) or value not in allowed:
        raise ValueError(f"{name}={value!r} is not supported; expected one of {allowed}")
    return value


def _as_frequency_grid(omega: ArrayLike, name: str = "omega") -> NDArray[np.float64]:
    w = np.asarray(omega, dtype=float)
    if w.ndim != 1 or w.size < 2:
        raise ValueError(
            f"{name} must be a 1-D array of at least 2 frequencies, got shape {w.shape}"
        )
    if not np.all(np.isfinite(w)):
        raise ValueError(
            f"{name} contains non-finite values {w[~np.isfinite(w)]}; expected finite ω ≥ 0 "
            "(drop the ω = ∞ entry of a database and pass it as added_mass_inf)"
        )
    if w[0] < 0:
        raise ValueError(f"{name}[0] = {w[0]} is negative; expected ω ≥ 0 [rad/s]")
    if np.any(np.diff(w) <= 0):
        raise ValueError(f"{name} must be strictly increasing; got {w}")
    return w


def _as_samples(values: ArrayLike, n: int, name: str, axis_name: str) -> NDArray[np.float64]:
    v = np.asarray(values)
    if np.iscomplexobj(v):
        raise ValueError(f"{name} must be real, got dtype {v.dtype}")
    v = v.astype(float)
    if v.ndim < 1 or v.shape[0] != n:
        raise ValueError(
            f"{name} has shape {v.shape}; expected ({n}, ...) with the first axis along {axis_name}"
        )
    if not np.all(np.isfinite(v)):
        raise ValueError(f"{name} contains non-finite values; expected finite numbers")
    return v


def _as_times(t: ArrayLike, name: str = "t") -> NDArray[np.float64]:
    tt = np.asarray(t, dtype=float)
    if tt.ndim != 1 or tt.size < 1:
        raise ValueError(f"{name} must be a non-empty 1-D array of times [s], got shape {tt.shape}")
    if not np.all(np.isfinite(tt)) or np.any(tt < 0):
        raise ValueError(f"{name} must contain finite times t ≥ 0 [s]; got min {np.min(tt)}")
    return tt


def _check_exponent(tail_exponent: int | str) -> int | str:
    if isinstance(tail_exponent, str):
        if tail_exponent != "fit":
            raise ValueError(f"tail_exponent={tail_exponent!r}; expected an integer ≥ 2 or 'fit'")
        return tail_exponent
    if isinstance(tail_exponent, bool) or int(tail_exponent) != tail_exponent:
        raise ValueError(f"tail_exponent={tail_exponent!r}; expected an integer ≥ 2 or 'fit'")
    n = int(tail_exponent)
    if not 2 <= n <= 12:
        raise ValueError(f"tail_exponent={n}; expected 2 ≤ n ≤ 12 (B ∝ ω⁻ⁿ must be integrable)")
    return n


# --------------------------------------------------------------------------------------------
# Filon weights and quadrature kernels
# --------------------------------------------------------------------------------------------
def filon_weights(
    theta: ArrayLike,
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """Filon's weight constants α, β, γ (Gourlay eq. 7–9) as functions of θ = tΔω (eq. 10).

    Parameters
    ----------
    theta : array_like
        θ = tΔω [rad], any shape.

    Returns
    -------
    alpha, beta, gamma : ndarray
        Same shape as ``theta`` [-]. For |θ| < :data:`FILON_SERIES_THRESHOLD` the Taylor series
        α = 2θ³/45 − 2θ⁵/315 + 2θ⁷/4725 − …, β = 2/3 + 2θ²/15 − 4θ⁴/105 + …,
        γ = 4/3 − 2θ²/15 + θ⁴/210 − … (7 terms each, to θ¹³) replace the closed forms, which
        lose ≈ log10(22/θ⁴) digits to cancellation.
    """
    th = np.asarray(theta, dtype=float)
    small = np.abs(th) < FILON_SERIES_THRESHOLD
    x = np.where(small, 1.0, th)  # dummy argument where the series is used
    s, c = np.sin(x), np.cos(x)
    s2 = np.sin(2.0 * x)
    alpha_c = 1.0 / x + s2 / (2.0 * x**2) - 2.0 * s * s / x**3
    beta_c = 2.0 * (1.0 / x**2 + c * c / x**2 - s2 / x**3)
    gamma_c = 4.0 * (s / x**3 - c / x**2)
    t2 = th * th
    alpha_s = th**3 * np.polynomial.polynomial.polyval(t2, _ALPHA_SERIES)
    beta_s = np.polynomial.polynomial.polyval(t2, _BETA_SERIES)
    gamma_s = np.polynomial.polynomial.polyval(t2, _GAMMA_SERIES)
    return (
        np.where(small, alpha_s, alpha_c),
        np.where(small, beta_s, beta_c),
        np.where(small, gamma_s, gamma_c),
    )


def _is_uniform(x: NDArray[np.float64]) -> bool:
    d = np.diff(x)
    return bool(np.all(np.abs(d - d.mean()) <= _UNIFORM_RTOL * d.mean()))


def _uniform_odd_grid(
    x: NDArray[np.float64], f: NDArray[np.float64]
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Return (x, f) on a uniform grid with an even number of intervals (resample if needed)."""
    if x.size >= 3 and (x.size - 1) % 2 == 0 and _is_uniform(x):
        return x, f
    if x.size < 3:
        raise ValueError(f"need at least 3 grid points for Filon/Simpson quadrature, got {x.size}")
    h = float(np.min(np.diff(x)))
    n_int = max(2, math.ceil((x[-1] - x[0]) / h - 1e-9))
    n_int += n_int % 2
    xu = np.linspace(x[0], x[-1], n_int + 1)
    return xu, CubicSpline(x, f, axis=0)(xu)


def _transform(
    x: NDArray[np.float64],
    f: NDArray[np.float64],
    t: NDArray[np.float64],
    weights: Any,
) -> NDArray[np.complex128]:
    """Σₙ wₙ(t) f(xₙ) e^{ixₙt} for all t, chunked over t; ``weights(tt)`` → (n_tt, n_x) complex."""
    out = np.empty((t.size, f.shape[1]), dtype=complex)
    step = max(1, _CHUNK_ELEMENTS // x.size)
    for s in range(0, t.size, step):
        tt = t[s : s + step]
        w = weights(tt) * np.exp(1j * np.outer(tt, x))
        out[s : s + step] = w.real @ f + 1j * (w.imag @ f)
    return out


def _filon(x: NDArray[np.float64], f: NDArray[np.float64], t: NDArray[np.float64]) -> NDArray:
    x, f = _uniform_odd_grid(x, f)
    h = x[1] - x[0]
    n = x.size

    def weights(tt: NDArray[np.float64]) -> NDArray[np.complex128]:
        a, b, g = filon_weights(tt * h)  # eq. 10
        w = np.empty((tt.size, n), dtype=complex)
        w[:, 1::2] = g[:, None]  # eq. 6, odd n
        w[:, 2:-1:2] = b[:, None]  # eq. 6, even interior n
        w[:, 0] = b / 2 + 1j * a
        w[:, -1] = b / 2 - 1j * a
        return h * w

    return _transform(x, f, t, weights)


def _simpson(x: NDArray[np.float64], f: NDArray[np.float64], t: NDArray[np.float64]) -> NDArray:
    x, f = _uniform_odd_grid(x, f)
    h = x[1] - x[0]
    s = np.full(x.size, 2.0)
    s[1::2] = 4.0
    s[0] = s[-1] = 1.0
    s *= h / 3.0
    return _transform(x, f, t, lambda tt: np.broadcast_to(s, (tt.size, s.size)))


def _trapezoid(x: NDArray[np.float64], f: NDArray[np.float64], t: NDArray[np.float64]) -> NDArray:
    d = np.diff(x)
    s = np.zeros(x.size)
    s[:-1] += d / 2
    s[1:] += d / 2
    return _transform(x, f, t, lambda tt: np.broadcast_to(s, (tt.size, s.size)))


def _fft_transform(
    x: NDArray[np.float64],
    f: NDArray[np.float64],
    t: NDArray[np.float64],
    n_fft: int,
    oversample: float,
) -> NDArray[np.complex128]:
    """∫₀^{x_end} f e^{iωt} dω by Matusiak's FFT (eq. 17–18), evaluated at the requested t.

    Choice of the FFT grid: Δt is the smallest spacing of the requested times, divided by the
    smallest integer m that puts the data's ω_max at or below the Nyquist frequency π/Δt (so
    requested uniform times fall exactly on FFT samples). N is the smallest power of two
    ≥ max(n_fft, 2·oversample·(t_max/Δt + 1)): the trapezoidal sum in ω is periodic in t with
    period NΔt, so its images of the kernel start beyond (2·oversample − 1)·t_max. With
    Matusiak's N = 2048, Δt = 0.1 s one gets his 1024 values over 102.4 s (``oversample=1``).
    f is interpolated onto ωₙ = nΔω_F by a cubic spline; the last partial interval up to
    ω_max is added by a trapezoid. Times off the FFT grid are interpolated by a cubic spline in
    t.
    """
    x_end = float(x[-1])
    t_max = float(np.max(t))
    ts = np.unique(t)
    dts = np.diff(ts)
    dt_req = float(dts.min()) if dts.size else math.pi / (4.0 * x_end)
    if t_max == 0.0:
        dt_req = math.pi / (4.0 * x_end)
    m = max(1, math.ceil(dt_req * x_end / math.pi - 1e-12))
    dt = dt_req / m
    n_min = max(int(n_fft), math.ceil(2.0 * oversample * (t_max / dt + 1.0)))
    n = 1 << max(1, math.ceil(math.log2(n_min)))
    if n > _MAX_FFT:
        raise ValueError(
            f"the FFT grid would need N = {n} > {_MAX_FFT} points (t_max = {t_max} s, Δt = {dt} s);"
            " request fewer or more widely spaced times, or use method='filon'"
        )
    dw = 2.0 * math.pi / (n * dt)
    n_last = min(n // 2, math.floor(x_end / dw + 1e-9))
    w_grid = np.arange(n_last + 1) * dw
    g = np.zeros((n, f.shape[1]))
    g[: n_last + 1] = CubicSpline(x, f, axis=0)(w_grid)
    f_nl = g[n_last].copy()
    g[0] *= 0.5
    g[n_last] *= 0.5
    spectrum = (n * dw) * np.fft.ifft(g, axis=0)[: n // 2]  # Σ gₙ e^{+i ωₙ tₖ} Δω
    t_nat = np.arange(n // 2) * dt
    k = t / dt
    k_int = np.rint(k)
    if np.all(np.abs(k - k_int) < 1e-6):
        out = spectrum[k_int.astype(int)]
    else:
        out = CubicSpline(t_nat, spectrum, axis=0)(t)
    partial = x_end - w_grid[-1]
    if partial > 1e-12 * dw:
        f_end = f[-1]
        out = out + 0.5 * partial * (
            np.exp(1j * w_grid[-1] * t)[:, None] * f_nl[None, :]
            + np.exp(1j * x_end * t)[:, None] * f_end[None, :]
        )
    return out


def oscillatory_integral(
    x: ArrayLike,
    f: ArrayLike,
    t: ArrayLike,
    method: Method = "filon",
    *,
    n_fft: int = DEFAULT_N_FFT,
    fft_oversample: float = 2.0,
) -> NDArray[np.complex128]:
    """Finite Fourier integral I(t) = ∫_{x₀}^{x_end} f(x) e^{ixt} dx for many t and columns.

    Parameters
    ----------
    x : array_like, shape (n,)
        Strictly increasing abscissae (e.g. ω [rad/s] or t [s]).
    f : array_like, shape (n, ...)
        Samples of f; trailing axes are independent columns.
    t : array_like, shape (n_t,)
        Conjugate variable (t [s] or ω [rad/s]), ≥ 0.
    method : {"filon", "simpson", "trapezoid", "fft"}
        Quadrature (module docstring). Filon: Gourlay eq. 4–10.
    n_fft, fft_oversample : int, float
        FFT length lower bound and oversampling (method "fft" only; see :func:`_fft_transform`).

    Returns
    -------
    ndarray, shape (n_t, ...), complex
        Real part: ∫ f cos xt dx; imaginary part: ∫ f sin xt dx.
    """
    method = _check_choice(method, "method", METHODS)
    xx = np.asarray(x, dtype=float)
    if xx.ndim != 1 or xx.size < 2 or not np.all(np.isfinite(xx)) or np.any(np.diff(xx) <= 0):
        raise ValueError(f"x must be a finite, strictly increasing 1-D array; got {xx}")
    ff = _as_samples(f, xx.size, "f", "x")
    tt = _as_times(t)
    trailing = ff.shape[1:]
    f2 = ff.reshape(xx.size, -1)
    if method == "fft":
        if xx[0] != 0.0:
            raise ValueError(f"method='fft' needs a grid starting at 0, got x[0] = {xx[0]}")
        if not (isinstance(n_fft, int | np.integer) and n_fft >= 8):
            raise ValueError(f"n_fft={n_fft!r}; expected an integer ≥ 8")
        if not fft_oversample >= 1.0:
            raise ValueError(f"fft_oversample={fft_oversample!r}; expected a number ≥ 1")
    out = _quadrature(method, xx, f2, tt, n_fft, fft_oversample)
    return out.reshape((tt.size, *trailing))


def _quadrature(
    method: str, x: np.ndarray, f: np.ndarray, t: np.ndarray, n_fft: int, fft_oversample: float
) -> np.ndarray:
    """∫ f(x) e^{ixt} dx on the samples (n_x, m) by the named rule → (n_t, m) complex."""
    if method == "filon":
        return _filon(x, f, t)
    if method == "simpson":
        return _simpson(x, f, t)
    if method == "trapezoid":
        return _trapezoid(x, f, t)
    if x.size < 3:
        raise ValueError(f"method='fft' needs at least 3 samples, got {x.size}")
    return _fft_transform(x, f, t, int(n_fft), float(fft_oversample))


# --------------------------------------------------------------------------------------------
# high-frequency tail
# --------------------------------------------------------------------------------------------
def _expint_neg_imag(p: int, tau: NDArray[np.float64]) -> NDArray[np.complex128]:
    """Generalised exponential integral E_p(−iτ) = ∫₁^∞ e^{iτs} s^{−p} ds, integer p ≥ 2, τ ≥ 0.

    τ < 8: upward recurrence E_{k+1}(z) = (e^{−z} − z E_k(z))/k from scipy's complex E₁ (stable
    for small |z|). τ ≥ 8: the contour is rotated to s = 1 + iu, E_p(−iτ) =
    i e^{iτ} ∫₀^∞ e^{−τu} (1 + iu)^{−p} du, evaluated by 60-point Gauss–Laguerre. Both branches
    agree with 40-digit mpmath values to < 2e-13 relative for 2 ≤ p ≤ 9.
    """
    out = np.empty(tau.shape, dtype=complex)
    zero = tau == 0.0
    out[zero] = 1.0 / (p - 1)
    small = (~zero) & (tau < _LAGUERRE_SWITCH)
    if np.any(small):
        z = -1j * tau[small]
        e = exp1(z)
        ez = np.exp(-z)
        for k in range(1, p):
            e = (ez - z * e) / k
        out[small] = e
    large = tau >= _LAGUERRE_SWITCH
    if np.any(large):
        tl = tau[large][:, None]
        s = np.sum(_LAGUERRE_W * (1.0 + 1j * _LAGUERRE_X / tl) ** (-p), axis=1)
        out[large] = 1j * np.exp(1j * tl[:, 0]) / tl[:, 0] * s
    return out


def _fit_tail_exponents(x: NDArray[np.float64], f: NDArray[np.float64]) -> NDArray[np.int64]:
    """Per-column integer n of |f| ∝ x⁻ⁿ over the last 20 % of the grid (fallback 4)."""
    n_fit = max(4, math.ceil(0.2 * x.size))
    xs = x[-n_fit:]
    out = np.full(f.shape[1], DEFAULT_TAIL_EXPONENT, dtype=np.int64)
    if xs[0] <= 0:
        return out
    fs = f[-n_fit:]
    for j in range(f.shape[1]):
        col = fs[:, j]
        if np.all(col > 0) or np.all(col < 0):
            slope = np.polyfit(np.log(xs), np.log(np.abs(col)), 1)[0]
            out[j] = int(np.clip(np.rint(-slope), 2, 8))
    return out


def _power_tail(
    x_end: float,
    f_end: NDArray[np.float64],
    p: NDArray[np.int64],
    t: NDArray[np.float64],
    weight: NDArray[np.float64] | None = None,
) -> NDArray[np.complex128]:
    """∫_{x_end}^∞ f_end [a (x_end/ω)^p + (1 − a)(x_end/ω)^{p+2}] e^{iωt} dω, all t and columns.

    = f_end x_end [a E_p(−i x_end t) + (1 − a) E_{p+2}(−i x_end t)]; ``weight`` = a per column
    (None: a = 1, the pure power tail).
    """
    out = np.zeros((t.size, f_end.size), dtype=complex)
    a = np.ones(f_end.size) if weight is None else weight
    cache: dict[int, NDArray[np.complex128]] = {}

    def expint(q: int) -> NDArray[np.complex128]:
        if q not in cache:
            cache[q] = _expint_neg_imag(q, x_end * t)
        return cache[q]

    for pk in np.unique(p):
        cols = p == pk
        e = expint(int(pk))[:, None] * a[None, cols]
        if np.any(a[cols] != 1.0):
            e = e + expint(int(pk) + 2)[:, None] * (1.0 - a[None, cols])
        out[:, cols] = x_end * e * f_end[None, cols]
    return out


def _asymptotic_weights(
    x: NDArray[np.float64], f: NDArray[np.float64], p: NDArray[np.int64]
) -> NDArray[np.float64]:
    """Weight a of f ≈ f_end[a (x_end/ω)^p + (1 − a)(x_end/ω)^{p+2}] on the last grid points.

    One-parameter least squares on the last :data:`ASYMPTOTIC_TAIL_POINTS` points (the value at
    x_end is matched exactly, so the extension is continuous), clipped to
    :data:`ASYMPTOTIC_WEIGHT_RANGE`; a = 1 (pure power) where f_end = 0 or x ≤ 0 in the window.
    """
    m = min(ASYMPTOTIC_TAIL_POINTS, x.size)
    xs = x[-m:]
    a = np.ones(f.shape[1])
    if m < 2 or xs[0] <= 0.0:
        return a
    r = x[-1] / xs
    lo, hi = ASYMPTOTIC_WEIGHT_RANGE
    for j in range(f.shape[1]):
        f_end = f[-1, j]
        if f_end == 0.0:
            continue
        g = r ** p[j] - r ** (p[j] + 2)
        y = f[-m:, j] / f_end - r ** (p[j] + 2)
        den = float(np.dot(g, g))
        if den > 0.0:
            a[j] = float(np.clip(np.dot(g, y) / den, lo, hi))
    return a


def _hann_taper(x: NDArray[np.float64], fraction: float) -> NDArray[np.float64]:
    """1 on [x₀, x_s], raised cosine to 0 on [x_s, x_end], x_s = x_end − fraction·(x_end − x₀)."""
    x_s = x[-1] - fraction * (x[-1] - x[0])
    w = np.ones_like(x)
    m = x > x_s
    w[m] = 0.5 * (1.0 + np.cos(np.pi * (x[m] - x_s) / (x[-1] - x_s)))
    return w


def _kernel_transform(
    omega: NDArray[np.float64],
    f: NDArray[np.float64],
    t: NDArray[np.float64],
    *,
    low_value: NDArray[np.float64],
    part: Literal["real", "imag"],
    method: str,
    tail: str,
    exponents: NDArray[np.int64],
    taper_fraction: float,
    n_fft: int,
    fft_oversample: float,
    weight: NDArray[np.float64] | None = None,
) -> NDArray[np.float64]:
    """(2/π) Re/Im ∫₀^∞ f(ω) e^{iωt} dω with the grid extension and tail rules of this module.

    ``weight``: the ``"asymptotic"`` tail's a per column (from :func:`_asymptotic_weights` of B,
    so that the K and sine-form L tails extend the same B).
    """
    x = omega
    if x[0] > 0.0:
        x = np.concatenate([[0.0], x])
        f = np.concatenate([low_value[None, :], f], axis=0)
    if tail == "taper":
        f = f * _hann_taper(x, taper_fraction)[:, None]
    out = _quadrature(method, x, f, t, n_fft, fft_oversample)
    if tail == "power":
        out = out + _power_tail(float(x[-1]), f[-1], exponents, t)
    elif tail == "asymptotic":
        out = out + _power_tail(float(x[-1]), f[-1], exponents, t, weight)
    res = out.real if part == "real" else out.imag
    return (2.0 / np.pi) * res


def _tail_exponents(
    tail_exponent: int | str, omega: NDArray[np.float64], b: NDArray[np.float64], shift: int
) -> NDArray[np.int64]:
    if tail_exponent == "fit":
        return _fit_tail_exponents(omega, b) + shift
    return np.full(b.shape[1], int(tail_exponent) + shift, dtype=np.int64)


def _check_common(
    method: str, tail: str, tail_exponent: int | str, taper_fraction: float
) -> int | str:
    _check_choice(method, "method", METHODS)
    _check_choice(tail, "tail", TAILS)
    if not 0.0 < taper_fraction <= 1.0:
        raise ValueError(f"taper_fraction={taper_fraction!r}; expected 0 < fraction ≤ 1")
    return _check_exponent(tail_exponent)


# --------------------------------------------------------------------------------------------
# public kernels
# --------------------------------------------------------------------------------------------
def velocity_kernel(
    omega: ArrayLike,
    damping: ArrayLike,
    t: ArrayLike,
    method: Method = "filon",
    tail: Tail = "none",
    *,
    tail_exponent: int | Literal["fit"] = DEFAULT_TAIL_EXPONENT,
    taper_fraction: float = 0.1,
    n_fft: int = DEFAULT_N_FFT,
    fft_oversample: float = 2.0,
) -> NDArray[np.float64]:
    """Velocity retardation kernel K(t) = (2/π)∫₀^∞ B(ω) cos ωt dω (Matusiak eq. 16).

    Parameters
    ----------
    omega : array_like, shape (n_omega,)
        Finite, strictly increasing wave frequencies ω ≥ 0 [rad/s].
    damping : array_like, shape (n_omega, ...)
        Radiation damping B(ω) [e.g. kg/s, kg·m/s, kg·m²/s], any trailing shape.
    t : array_like, shape (n_t,)
        Times t ≥ 0 [s].
    method : {"filon", "simpson", "trapezoid", "fft"}
        Quadrature (module docstring; Filon: Gourlay eq. 4–10; FFT: Matusiak eq. 17–18).
    tail : {"none", "power", "asymptotic", "taper"}
        High-frequency treatment beyond ω_max (module docstring).
    tail_exponent : int or "fit"
        Leading n of B ∝ ω⁻ⁿ for ``tail="power"`` and ``tail="asymptotic"`` [-].
    taper_fraction : float
        Fraction of [0, ω_max] covered by the Hann taper for ``tail="taper"`` [-].
    n_fft, fft_oversample : int, float
        FFT parameters (method "fft" only).

    Returns
    -------
    ndarray, shape (n_t, ...)
        K(t) [units of B · rad/s].
    """
    exponent = _check_common(method, tail, tail_exponent, taper_fraction)
    w = _as_frequency_grid(omega)
    b = _as_samples(damping, w.size, "damping", "omega")
    tt = _as_times(t)
    b2 = b.reshape(w.size, -1)
    exps = _tail_exponents(exponent, w, b2, 0)
    k = _kernel_transform(
        w,
        b2,
        tt,
        low_value=np.zeros(b2.shape[1]),
        part="real",
        method=method,
        tail=tail,
        exponents=exps,
        taper_fraction=taper_fraction,
        n_fft=n_fft,
        fft_oversample=fft_oversample,
        weight=_asymptotic_weights(w, b2, exps) if tail == "asymptotic" else None,
    )
    return k.reshape((tt.size, *b.shape[1:]))


def acceleration_kernel(
    omega: ArrayLike,
    t: ArrayLike,
    *,
    damping: ArrayLike | None = None,
    added_mass: ArrayLike | None = None,
    added_mass_inf: ArrayLike | None = None,
    form: Form = "sine",
    method: Method = "filon",
    tail: Tail = "none",
    tail_exponent: int | Literal["fit"] = DEFAULT_TAIL_EXPONENT,
    taper_fraction: float = 0.1,
    n_fft: int = DEFAULT_N_FFT,
    fft_oversample: float = 2.0,
) -> NDArray[np.float64]:
    """Acceleration retardation kernel L(t), with K = dL/dt.

    ``form="sine"`` (Gourlay eq. 3, f = (2/π)B/ω, eq. 12; preferred — it tends to zero as
    t → ∞ and gives L(0) = 0 exactly)::

        L(t) = (2/π) ∫₀^∞ B(ω)/ω sin ωt dω

    ``form="cosine"`` (Gourlay eq. 2, f = (2/π)[A − A(∞)], eq. 11; L(0) and the large-t
    behaviour depend on A(ω) averaging exactly to A(∞) over the finite grid)::

        L(t) = (2/π) ∫₀^∞ [A(ω) − A(∞)] cos ωt dω

    Parameters
    ----------
    omega : array_like, shape (n_omega,)
        Finite, strictly increasing frequencies ω ≥ 0 [rad/s]. At ω = 0 the sine form needs
        B(0) = 0 (B/ω is then taken as 0).
    t : array_like, shape (n_t,)
        Times t ≥ 0 [s].
    damping : array_like, shape (n_omega, ...), optional
        B(ω) [e.g. kg/s]; required for ``form="sine"``.
    added_mass : array_like, shape (n_omega, ...), optional
        A(ω) [e.g. kg]; required for ``form="cosine"``.
    added_mass_inf : array_like, shape (...), optional
        A(∞) [e.g. kg]; required for ``form="cosine"``.
    form : {"sine", "cosine"}
        Which of Gourlay's eq. 2/3 to evaluate.
    method, tail, tail_exponent, taper_fraction, n_fft, fft_oversample
        As in :func:`velocity_kernel` (for the sine form the tail of B/ω is ∝ ω^{−(n+1)}, and
        ``"asymptotic"`` adds ω^{−(n+3)} with the weight a fitted to B, as for K; for the
        cosine form the tail of A − A(∞) is ∝ ω⁻² (``"asymptotic"``: ω⁻² and ω⁻⁴ with a fitted
        to A − A(∞)), ``tail_exponent`` only matters with ``"fit"``, which then fits A − A(∞)
        itself).

    Returns
    -------
    ndarray, shape (n_t, ...)
        L(t) [units of B = units of A · rad/s, e.g. kg/s].
    """
    form = _check_choice(form, "form", FORMS)
    exponent = _check_common(method, tail, tail_exponent, taper_fraction)
    w = _as_frequency_grid(omega)
    tt = _as_times(t)
    if form == "sine":
        if damping is None:
            raise ValueError("form='sine' needs damping=B(ω); got damping=None")
        b = _as_samples(damping, w.size, "damping", "omega")
        trailing = b.shape[1:]
        b2 = b.reshape(w.size, -1)
        f = np.empty_like(b2)
        pos = w > 0
        f[pos] = b2[pos] / w[pos, None]
        if not pos[0]:
            scale = np.max(np.abs(b2), axis=0)
            bad = np.abs(b2[0]) > 1e-9 * np.where(scale > 0, scale, 1.0)
            if np.any(bad):
                raise ValueError(
                    f"damping at ω = 0 is {b2[0][bad]}, expected 0: B/ω is singular there; "
                    "drop the ω = 0 entry or use form='cosine'"
                )
            f[0] = 0.0
        exps = _tail_exponents(exponent, w, b2, 1)
        weight = _asymptotic_weights(w, b2, exps - 1) if tail == "asymptotic" else None
        low = np.zeros(f.shape[1])
        part: Literal["real", "imag"] = "imag"
    else:
        if added_mass is None or added_mass_inf is None:
            raise ValueError(
                "form='cosine' needs added_mass=A(ω) and added_mass_inf=A(∞); "
                f"got added_mass={'None' if added_mass is None else 'array'}, "
                f"added_mass_inf={'None' if added_mass_inf is None else 'array'}"
            )
        a = _as_samples(added_mass, w.size, "added_mass", "omega")
        trailing = a.shape[1:]
        a_inf = np.asarray(added_mass_inf, dtype=float)
        if a_inf.shape != trailing or not np.all(np.isfinite(a_inf)):
            raise ValueError(
                f"added_mass_inf has shape {a_inf.shape}; expected finite values of shape "
                f"{trailing} (added_mass without its frequency axis)"
            )
        f = (a - a_inf[None]).reshape(w.size, -1)
        if exponent == "fit":
            exps = _fit_tail_exponents(w, f)
        else:
            exps = np.full(f.shape[1], COSINE_TAIL_EXPONENT, dtype=np.int64)
        weight = _asymptotic_weights(w, f, exps) if tail == "asymptotic" else None
        low = f[0].copy()
        part = "real"
    out = _kernel_transform(
        w,
        f,
        tt,
        low_value=low,
        part=part,
        method=method,
        tail=tail,
        exponents=exps,
        taper_fraction=taper_fraction,
        n_fft=n_fft,
        fft_oversample=fft_oversample,
        weight=weight,
    )
    return out.reshape((tt.size, *trailing))


# --------------------------------------------------------------------------------------------
# kernels of a database
# --------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class RetardationKernels:
    """Retardation kernels of a hydrodynamic database on a uniform time grid.

    Attributes
    ----------
    t : ndarray, shape (n_t,)
        Uniform times from 0 [s].
    K : ndarray, shape (n_t, ...)
        Velocity kernel K(t) (Matusiak eq. 16) [units of B · rad/s, e.g. kg/s²]; trailing axes
        as in the database, e.g. (radiating_dof, influenced_dof) — i.e. (input, output); swap
        the last two axes for the (output, input) layout of
        :func:`ship_gym.hydro.state_space.fit_state_space` (no-op at zero speed, K symmetric).
    L : ndarray, shape (n_t, ...)
        Acceleration kernel L(t) (Gourlay eq. 2 or 3) [units of B, e.g. kg/s].
    A_inf : ndarray, shape (...)
        Infinite-frequency added mass A(∞) [e.g. kg].
    method : str
        Quadrature used (one of :data:`METHODS`).
    form : str
        Form used for L (one of :data:`FORMS`).
    tail : str
        High-frequency tail treatment (one of :data:`TAILS`).
    """

    t: NDArray[np.float64]
    K: NDArray[np.float64]
    L: NDArray[np.float64]
    A_inf: NDArray[np.float64]
    method: str
    form: str
    tail: str

    def __post_init__(self) -> None:
        t = _as_times(self.t)
        if t.size < 2 or t[0] != 0.0 or not _is_uniform(t):
            raise ValueError(f"t must be a uniform grid starting at 0 s with ≥ 2 points; got {t}")
        k = _as_samples(self.K, t.size, "K", "t")
        lk = _as_samples(self.L, t.size, "L", "t")
        if lk.shape != k.shape:
            raise ValueError(f"L has shape {lk.shape}; expected the shape of K, {k.shape}")
        a_inf = np.asarray(self.A_inf, dtype=float)
        if a_inf.shape != k.shape[1:] or not np.all(np.isfinite(a_inf)):
            raise ValueError(f"A_inf has shape {a_inf.shape}; expected finite {k.shape[1:]}")
        _check_choice(self.method, "method", METHODS)
        _check_choice(self.form, "form", FORMS)
        _check_choice(self.tail, "tail", TAILS)
        for name, value in (("t", t), ("K", k), ("L", lk), ("A_inf", a_inf)):
            value.setflags(write=False)
            object.__setattr__(self, name, value)

    @property
    def dt(self) -> float:
        """Time step of the grid [s]."""
        return float(self.t[1] - self.t[0])

    @property
    def t_max(self) -> float:
        """Truncation time of the kernels [s]."""
        return float(self.t[-1])


def compute_kernels(
    omega: ArrayLike,
    added_mass: ArrayLike,
    damping: ArrayLike,
    added_mass_inf: ArrayLike,
    *,
    t_max: float = 60.0,
    dt: float = 0.05,
    method: Method = "filon",
    form: Form = "sine",
    tail: Tail = "none",
    tail_exponent: int | Literal["fit"] = DEFAULT_TAIL_EXPONENT,
    taper_fraction: float = 0.1,
) -> RetardationKernels:
    """K(t) and L(t) for all DOF pairs of a database on t = 0, dt, …, t_max.

    Parameters
    ----------
    omega : array_like, shape (n_omega,)
        Finite frequencies [rad/s] (drop ω = ∞; its added mass is ``added_mass_inf``).
    added_mass, damping : array_like, shape (n_omega, ...)
        A(ω) [kg, kg·m, kg·m²] and B(ω) [kg/s, …], e.g. (n_omega, 6, 6).
    added_mass_inf : array_like, shape (...)
        A(∞) [kg, …].
    t_max : float
        Truncation time of the kernels [s]; default 60 s (ship kernels decay within 20–40 s;
        check with :func:`kernel_decay`).
    dt : float
        Time step [s]; default 0.05 s.
    method, form, tail, tail_exponent, taper_fraction
        See :func:`velocity_kernel` and :func:`acceleration_kernel`.

    Returns
    -------
    RetardationKernels
    """
    if not (np.isfinite(dt) and dt > 0):
        raise ValueError(f"dt={dt!r}; expected a positive time step [s]")
    if not (np.isfinite(t_max) and t_max >= 2 * dt):
        raise ValueError(f"t_max={t_max!r}; expected a finite time ≥ 2·dt = {2 * dt} [s]")
    n = round(t_max / dt)
    t = dt * np.arange(n + 1, dtype=np.float64)
    k = velocity_kernel(
        omega,
        damping,
        t,
        method=method,
        tail=tail,
        tail_exponent=tail_exponent,
        taper_fraction=taper_fraction,
    )
    lk = acceleration_kernel(
        omega,
        t,
        damping=damping,
        added_mass=added_mass,
        added_mass_inf=added_mass_inf,
        form=form,
        method=method,
        tail=tail,
        tail_exponent=tail_exponent,
        taper_fraction=taper_fraction,
    )
    return RetardationKernels(
        t=t,
        K=k,
        L=lk,
        A_inf=np.asarray(added_mass_inf, dtype=float),
        method=method,
        form=form,
        tail=tail,
    )


# --------------------------------------------------------------------------------------------
# diagnostics
# --------------------------------------------------------------------------------------------
def reconstruct_coefficients(
    t: ArrayLike,
    K: ArrayLike,
    omega: ArrayLike,
    added_mass_inf: ArrayLike,
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """A(ω) and B(ω) from a truncated kernel by Ogilvie's relations.

    A(ω) = A(∞) − (1/ω)∫₀^T K(t) sin ωt dt and B(ω) = ∫₀^T K(t) cos ωt dt, evaluated by Filon
    quadrature in t (Gourlay eq. 4–10 with the roles of t and ω swapped; a non-uniform t grid
    or an even number of samples is resampled as described in the module docstring). At ω = 0
    the limit A(0) = A(∞) − ∫₀^T t K(t) dt is used.

    Parameters
    ----------
    t : array_like, shape (n_t,)
        Increasing times from 0 [s]; T = t[-1] is the truncation time.
    K : array_like, shape (n_t, ...)
        Velocity kernel [units of B · rad/s].
    omega : array_like, shape (n_omega,)
        Finite frequencies ω ≥ 0 [rad/s] (any order).
    added_mass_inf : array_like, shape (...)
        A(∞) [units of A].

    Returns
    -------
    added_mass, damping : ndarray, shape (n_omega, ...)
        Reconstructed A(ω) [units of A] and B(ω) [units of B].
    """
    tt = _as_times(t)
    if tt.size < 3 or tt[0] != 0.0 or np.any(np.diff(tt) <= 0):
        raise ValueError(f"t must be strictly increasing from 0 s with ≥ 3 samples; got {tt}")
    k = _as_samples(K, tt.size, "K", "t")
    w = np.asarray(omega, dtype=float)
    if w.ndim != 1 or not np.all(np.isfinite(w)) or np.any(w < 0):
        raise ValueError(f"omega must be a 1-D array of finite ω ≥ 0 [rad/s]; got {w}")
    a_inf = np.asarray(added_mass_inf, dtype=float)
    if a_inf.shape != k.shape[1:]:
        raise ValueError(f"added_mass_inf has shape {a_inf.shape}; expected {k.shape[1:]}")
    k2 = k.reshape(tt.size, -1)
    s = _filon(tt, k2, w)
    b = s.real
    a = np.empty_like(b)
    pos = w > 0
    a[pos] = -s.imag[pos] / w[pos, None]
    if np.any(~pos):
        m0 = _filon(tt, tt[:, None] * k2, np.zeros(1)).real
        a[~pos] = -m0
    a = a + a_inf.reshape(1, -1)
    shape = (w.size, *k.shape[1:])
    return a.reshape(shape), b.reshape(shape)


def relative_pair_error(
    reference: ArrayLike, estimate: ArrayLike, *, floor: float = 1e-2
) -> NDArray[np.float64]:
    """RMS error over the first axis, relative to the RMS of the reference, per DOF pair.

    For square trailing shapes (n, n) the denominator of pair (i, j) is
    max(rms(ref_ij), floor·√(rms(ref_ii)·rms(ref_jj))), so couplings that are negligible
    compared with the diagonal terms they couple (e.g. surge–sway by symmetry) are judged on the
    diagonal scale instead of their own round-off. For other shapes the floor is relative to the
    largest RMS.

    Parameters
    ----------
    reference, estimate : array_like, shape (n, ...)
        Reference and estimated samples [any units, same for both].
    floor : float
        Relative floor of the denominator [-].

    Returns
    -------
    ndarray, shape (...)
        Relative RMS errors [-].
    """
    ref = np.asarray(reference, dtype=float)
    est = np.asarray(estimate, dtype=float)
    if ref.shape != est.shape or ref.ndim < 1:
        raise ValueError(
            f"estimate has shape {est.shape}; expected the reference shape {ref.shape}"
        )
    rms_ref = np.sqrt(np.mean(ref**2, axis=0))
    rms_err = np.sqrt(np.mean((est - ref) ** 2, axis=0))
    if rms_ref.ndim == 2 and rms_ref.shape[0] == rms_ref.shape[1]:
        d = np.diag(rms_ref)
        scale = np.sqrt(np.outer(d, d))
    else:
        scale = np.full(rms_ref.shape, np.max(rms_ref) if rms_ref.size else 0.0)
    denom = np.maximum(rms_ref, floor * scale)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.where(denom > 0, rms_err / np.where(denom > 0, denom, 1.0), 0.0)


def fit_added_mass_infinite(
    t: ArrayLike,
    K: ArrayLike,
    omega: ArrayLike,
    added_mass: ArrayLike,
    *,
    omega_min: float | None = None,
    omega_max: float | None = None,
) -> NDArray[np.float64]:
    """A(∞) that makes the kernel reproduce the database A(ω) best over the resolved band.

    With a database truncated at ω_max, the kernel K knows B(ω) only up to ω_max (plus any tail
    model), and Ogilvie's A(ω) = A(∞) − (1/ω)∫K sin ωt dt then sits a nearly constant offset away
    from the database A(ω) when the BEM's own A(∞) is used. The least-squares constant over the
    band, A(∞)_fit = mean_ω [A(ω) + (1/ω)∫₀^T K sin ωt dt], removes that offset; a time-domain
    model built from (A(∞)_fit, K) matches the frequency-domain added mass in the wave band,
    which matters more for motions than the exact infinite-frequency limit (Perez & Fossen 2008
    discuss the same trade-off).

    Parameters
    ----------
    t, K : array_like
        Kernel samples, shapes (n_t,) and (n_t, ...).
    omega, added_mass : array_like
        Database frequencies (n,) [rad/s] and A(ω) (n, ...).
    omega_min, omega_max : float, optional
        Band used [rad/s]; default 2π/T … the largest database frequency.

    Returns
    -------
    ndarray, shape (...)
        Fitted A(∞) [units of A].
    """
    w = np.asarray(omega, dtype=float)
    a = np.asarray(added_mass, dtype=float)
    tt = _as_times(t)
    lo = 2.0 * np.pi / tt[-1] if omega_min is None else float(omega_min)
    hi = float(np.max(w)) if omega_max is None else float(omega_max)
    sel = (w >= lo) & (w <= hi) & (w > 0.0)
    if np.count_nonzero(sel) < 2:
        raise ValueError(
            f"need at least 2 database frequencies in [{lo:.4g}, {hi:.4g}] rad/s to fit A(inf)"
        )
    a_memory, _ = reconstruct_coefficients(tt, K, w[sel], np.zeros(a.shape[1:]))
    return np.mean(a[sel] - a_memory, axis=0)


@dataclass(frozen=True)
class ReconstructionError:
    """Errors of Ogilvie-reconstructed coefficients against a database.

    Attributes
    ----------
    omega : ndarray, shape (n,)
        Frequencies used in the comparison [rad/s].
    added_mass : ndarray, shape (...)
        Relative RMS error of A(ω) − A(∞) per DOF pair [-] (see :func:`relative_pair_error`).
    damping : ndarray, shape (...)
        Relative RMS error of B(ω) per DOF pair [-].
    added_mass_reconstructed, damping_reconstructed : ndarray, shape (n, ...)
        The reconstructed coefficients at ``omega`` [units of A and B].
    """

    omega: NDArray[np.float64]
    added_mass: NDArray[np.float64]
    damping: NDArray[np.float64]
    added_mass_reconstructed: NDArray[np.float64]
    damping_reconstructed: NDArray[np.float64]

    @property
    def max_error(self) -> float:
        """Largest relative error over all pairs and both coefficients [-]."""
        return float(max(np.max(self.added_mass), np.max(self.damping)))


def reconstruction_error(
    t: ArrayLike,
    K: ArrayLike,
    omega: ArrayLike,
    added_mass: ArrayLike,
    damping: ArrayLike,
    added_mass_inf: ArrayLike,
    *,
    omega_min: float | None = None,
    omega_max: float | None = None,
    floor: float = 1e-2,
) -> ReconstructionError:
    """Compare Ogilvie's reconstruction from K(t) with the database, per DOF pair.

    Only frequencies the truncated, sampled kernel resolves are compared: by default
    ω_min = 2π/T (a period longer than the kernel window T = t[-1] is not resolved) and
    ω_max = π/Δt (Nyquist frequency of the time grid).

    Parameters
    ----------
    t : array_like, shape (n_t,)
        Times from 0 [s].
    K : array_like, shape (n_t, ...)
        Velocity kernel.
    omega : array_like, shape (n_omega,)
        Database frequencies (finite) [rad/s].
    added_mass, damping : array_like, shape (n_omega, ...)
        Database A(ω) and B(ω).
    added_mass_inf : array_like, shape (...)
        A(∞).
    omega_min, omega_max : float, optional
        Frequency band of the comparison [rad/s].
    floor : float
        Relative floor of the error denominator (:func:`relative_pair_error`).

    Returns
    -------
    ReconstructionError
    """
    tt = _as_times(t)
    w = _as_frequency_grid(omega)
    a = _as_samples(added_mass, w.size, "added_mass", "omega")
    b = _as_samples(damping, w.size, "damping", "omega")
    a_inf = np.asarray(added_mass_inf, dtype=float)
    lo = 2.0 * np.pi / tt[-1] if omega_min is None else float(omega_min)
    hi = np.pi / float(np.min(np.diff(tt))) if omega_max is None else float(omega_max)
    sel = (w >= lo) & (w <= hi)
    if np.count_nonzero(sel) < 1:
        raise ValueError(
            f"no database frequency lies in the resolved band [{lo:.4g}, {hi:.4g}] rad/s; "
            f"omega spans [{w[0]:.4g}, {w[-1]:.4g}]"
        )
    a_rec, b_rec = reconstruct_coefficients(tt, K, w[sel], a_inf)
    err_a = relative_pair_error(a[sel] - a_inf, a_rec - a_inf, floor=floor)
    err_b = relative_pair_error(b[sel], b_rec, floor=floor)
    return ReconstructionError(
        omega=w[sel],
        added_mass=err_a,
        damping=err_b,
        added_mass_reconstructed=a_rec,
        damping_reconstructed=b_rec,
    )


@dataclass(frozen=True)
class KernelDecay:
    """Whether kernels have decayed at the truncation time.

    Attributes
    ----------
    ratio : ndarray, shape (...)
        max|K| over the last ``tail_fraction`` of the window / max|K| over the window [-]
        (0 for identically zero pairs).
    decayed : ndarray of bool, shape (...)
        ``ratio <= threshold``.
    threshold : float
        Threshold used [-].
    """

    ratio: NDArray[np.float64]
    decayed: NDArray[np.bool_]
    threshold: float

    @property
    def all_decayed(self) -> bool:
        """True when every pair has decayed."""
        return bool(np.all(self.decayed))


def kernel_decay(
    t: ArrayLike, K: ArrayLike, *, tail_fraction: float = 0.05, threshold: float = 0.01
) -> KernelDecay:
    """Report whether |K| has decayed at the truncation time relative to its maximum.

    Parameters
    ----------
    t : array_like, shape (n_t,)
        Increasing times [s].
    K : array_like, shape (n_t, ...)
        Kernel (K or L).
    tail_fraction : float
        Final fraction of the time window inspected [-].
    threshold : float
        Largest acceptable ratio [-].

    Returns
    -------
    KernelDecay
    """
    tt = _as_times(t)
    k = _as_samples(K, tt.size, "K", "t")
    if not 0.0 < tail_fraction < 1.0:
        raise ValueError(f"tail_fraction={tail_fraction!r}; expected 0 < fraction < 1")
    if not threshold > 0.0:
        raise ValueError(f"threshold={threshold!r}; expected a positive ratio")
    t_start = tt[-1] - tail_fraction * (tt[-1] - tt[0])
    late = tt >= t_start
    peak = np.max(np.abs(k), axis=0)
    late_peak = np.max(np.abs(k[late]), axis=0)
    ratio = np.where(peak > 0, late_peak / np.where(peak > 0, peak, 1.0), 0.0)
    return KernelDecay(ratio=ratio, decayed=ratio <= threshold, threshold=float(threshold))


# --------------------------------------------------------------------------------------------
# plots (matplotlib imported lazily)
# --------------------------------------------------------------------------------------------
def _pair_index(pair: tuple[int | str, int | str]) -> tuple[int, int]:
    i, j = pair
    return (
        i if isinstance(i, int | np.integer) else dof_index(i),
        j if isinstance(j, int | np.integer) else dof_index(j),
    )


def _pair_label(i: int, j: int) -> str:
    if i < len(DOF_NAMES) and j < len(DOF_NAMES):
        return f"{DOF_NAMES[i]}–{DOF_NAMES[j]} ({i + 1}{j + 1})"
    return f"({i}, {j})"


def plot_kernels(
    kernels: RetardationKernels,
    pairs: tuple[tuple[int | str, int | str], ...] = ((2, 2), (1, 1), (3, 3)),
    *,
    axes: Any = None,
) -> Any:
    """Plot K(t) and L(t) of selected DOF pairs.

    Parameters
    ----------
    kernels : RetardationKernels
        Kernels with (…, 6, 6) trailing axes.
    pairs : tuple of (int or str, int or str)
        DOF pairs by index or label (e.g. ``("Sway", "Sway")``).
    axes : sequence of 2 matplotlib Axes, optional
        Where to draw (a new figure otherwise).

    Returns
    -------
    matplotlib.figure.Figure
    """
    import matplotlib.pyplot as plt

    if axes is None:
        fig, axes = plt.subplots(2, 1, sharex=True, figsize=(8, 6))
    else:
        fig = axes[0].figure
    for pair in pairs:
        i, j = _pair_index(pair)
        lab = _pair_label(i, j)
        # DOF pairs differ by orders of magnitude (kg vs kg·m²): plot each on its own scale
        k_ij, l_ij = kernels.K[:, i, j], kernels.L[:, i, j]
        k_max = float(np.max(np.abs(k_ij))) or 1.0
        l_max = float(np.max(np.abs(l_ij))) or 1.0
        axes[0].plot(kernels.t, k_ij / k_max, label=f"{lab} (max {k_max:.3g})")
        axes[1].plot(kernels.t, l_ij / l_max, label=f"{lab} (max {l_max:.3g})")
    axes[0].set_ylabel("K(t) / max|K|  [-]")
    axes[1].set_ylabel(f"L(t) / max|L|  [-], {kernels.form} form")
    axes[1].set_xlabel("t [s]")
    axes[0].set_title(f"Retardation kernels ({kernels.method}, tail={kernels.tail})")
    for ax in axes:
        ax.grid(True, alpha=0.3)
        ax.legend()
    return fig


def plot_reconstruction(
    omega: ArrayLike,
    added_mass: ArrayLike,
    damping: ArrayLike,
    added_mass_reconstructed: ArrayLike,
    damping_reconstructed: ArrayLike,
    pair: tuple[int | str, int | str] = (2, 2),
    *,
    omega_reconstructed: ArrayLike | None = None,
    axes: Any = None,
) -> Any:
    """Plot database A(ω), B(ω) of one DOF pair against a reconstruction (Ogilvie or fit).

    Parameters
    ----------
    omega : array_like, shape (n,)
        Database frequencies [rad/s].
    added_mass, damping : array_like, shape (n, ...)
        Database A(ω) [units of A] and B(ω) [units of B].
    added_mass_reconstructed, damping_reconstructed : array_like, shape (m, ...)
        Reconstructed coefficients.
    pair : (int or str, int or str)
        DOF pair.
    omega_reconstructed : array_like, shape (m,), optional
        Frequencies of the reconstruction (default ``omega``) [rad/s].
    axes : sequence of 2 matplotlib Axes, optional

    Returns
    -------
    matplotlib.figure.Figure
    """
    import matplotlib.pyplot as plt

    i, j = _pair_index(pair)
    w = np.asarray(omega, dtype=float)
    wr = w if omega_reconstructed is None else np.asarray(omega_reconstructed, dtype=float)
    if axes is None:
        fig, axes = plt.subplots(2, 1, sharex=True, figsize=(8, 6))
    else:
        fig = axes[0].figure
    axes[0].plot(w, np.asarray(added_mass)[:, i, j], "o", ms=3, label="database")
    axes[0].plot(wr, np.asarray(added_mass_reconstructed)[:, i, j], "-", label="reconstructed")
    axes[1].plot(w, np.asarray(damping)[:, i, j], "o", ms=3, label="database")
    axes[1].plot(wr, np.asarray(damping_reconstructed)[:, i, j], "-", label="reconstructed")
    axes[0].set_ylabel("A(ω)")
    axes[1].set_ylabel("B(ω)")
    axes[1].set_xlabel("ω [rad/s]")
    axes[0].set_title(_pair_label(i, j))
    for ax in axes:
        ax.grid(True, alpha=0.3)
        ax.legend()
    return fig
