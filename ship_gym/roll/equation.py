"""Single-degree-of-freedom nonlinear roll equation (McCue & Campbell eq. 1 and eq. 2).

The model, per unit roll inertia (virtual mass moment of inertia included), is

    φ̈ + b₁φ̇ + b₂|φ̇|φ̇ + b₃φ̇³ + c₁φ + c₂|φ|φ + c₃φ³ + c₄|φ|φ³ + c₅φ⁵ = F sin(ωₑt + ε) + m(t)

with roll φ [rad], roll rate φ̇ [rad/s], damping coefficients b₁ [1/s], b₂ [1/rad],
b₃ [s/rad²], restoring coefficients c₁ [1/s²], c₂ [1/(rad s²)], c₃ [1/(rad² s²)],
c₄ [1/(rad³ s²)], c₅ [1/(rad⁴ s²)], forcing amplitude F [rad/s²], encounter frequency ωₑ
[rad/s], phase ε [rad] and an external (control) moment per unit inertia m [rad/s²].

* McCue & Campbell eq. 1 — the *Edith Terkol* of Soliman & Thompson (1991): b₁ = 0.0043,
  b₂ = 0.0225, c₁ = 0.384, c₂ = 0.1296, c₃ = 1.0368, c₄ = −4.059, c₅ = 2.4052,
  ωₑ = 0.85 ωₙ = 0.85 × 0.62, ωₙ = √c₁ (:meth:`RollEquation.edith_terkol`). The converted paper
  prints the c₄ term as |φ|φ⁴, an *even* function that would make the restoring asymmetric; the
  odd reading |φ|φ³ is used (see /work/shared/SEEDS.md). With it the restoring vanishes at
  φᵥ ≈ 0.86 rad (49°).
* McCue & Campbell eq. 2 — the fitted model ÿ + b_u1 ẏ + b_u3 ẏ³ + c_u1 y + c_u3 y³ =
  F_u sin(ωₑt) (:meth:`RollEquation.mccue_campbell`).

Every restoring and damping term is odd, so the restoring moment, the damping and the vanishing
angle are symmetric to port and starboard.

Integration
-----------
:meth:`RollEquation.integrate` advances a *batch* of initial conditions (any broadcast shape)
with the classical fixed-step Runge–Kutta scheme (RK4, 4th order). With a constant moment (None,
a scalar, or an array broadcast with the batch) it runs a compiled numba kernel that loops over
the trajectories; with a callable moment ``m(t, phi, phidot)`` it runs the same scheme in numpy
over the whole batch (the reference path; the two agree to rounding, tested). ``stop_at`` sets a
roll limit: a trajectory whose |φ| exceeds it is flagged as capsized, its capsize time is
interpolated linearly between the two steps that straddle the limit, and it is no longer
integrated (its state is held at the first step beyond the limit — so a capsized trajectory
never overflows). :meth:`RollEquation.advance` is the lean form used by the environments: a
number of steps from the current time, final states only, no checks beyond the shapes.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, fields

import numba as nb
import numpy as np
import numpy.typing as npt
from numpy.typing import NDArray

from ship_gym.typing import FloatArray

__all__ = [
    "EDITH_TERKOL_NATURAL_FREQUENCY",
    "MomentFn",
    "RollEquation",
    "RollTrajectory",
]

#: Natural roll frequency ωₙ of the Edith Terkol [rad/s] (McCue & Campbell: ωₑ = 0.85 · 0.62).
EDITH_TERKOL_NATURAL_FREQUENCY = 0.62

#: A time-varying moment per unit inertia: ``m(t [s], phi [rad], phidot [rad/s]) -> [rad/s²]``.
MomentFn = Callable[[float, FloatArray, FloatArray], npt.ArrayLike]


@dataclass(frozen=True)
class RollTrajectory:
    """Result of :meth:`RollEquation.integrate` for a batch of initial conditions.

    Attributes
    ----------
    time : ndarray, shape (n_rec,)
        Recorded instants [s] (every ``record_every`` steps from t0; or t0 and t_end only).
    phi : ndarray, shape (n_rec, *batch)
        Roll [rad]. After a capsize the state is held at the first step beyond the limit.
    phidot : ndarray, shape (n_rec, *batch)
        Roll rate [rad/s], held likewise.
    capsized : ndarray of bool, shape batch
        |φ| exceeded ``stop_at`` at some step (always False without ``stop_at``).
    capsize_time : ndarray, shape batch
        Instant [s] at which |φ| crossed ``stop_at`` (linear interpolation between the two steps
        that straddle it); NaN where the trajectory did not capsize.
    stop_at : float or None
        The roll limit used [rad].
    dt : float
        Integration step [s].
    """

    time: FloatArray
    phi: FloatArray
    phidot: FloatArray
    capsized: NDArray[np.bool_]
    capsize_time: FloatArray
    stop_at: float | None
    dt: float

    @property
    def final_phi(self) -> FloatArray:
        """Roll at the last recorded instant [rad], shape batch."""
        return self.phi[-1]

    @property
    def final_phidot(self) -> FloatArray:
        """Roll rate at the last recorded instant [rad/s], shape batch."""
        return self.phidot[-1]


# ----------------------------------------------------------------------------------- kernels
@nb.njit(cache=True, fastmath=False, inline="always")
def _accel(b1, b2, b3, c1, c2, c3, c4, c5, x, v, f):  # pragma: no cover - compiled
    ax = abs(x)
    x2 = x * x
    return f - (
        b1 * v
        + b2 * abs(v) * v
        + b3 * v * v * v
        + x * (c1 + c2 * ax + c3 * x2 + c4 * ax * x2 + c5 * x2 * x2)
    )


@nb.njit(cache=True, fastmath=False)
def _rk4_kernel(
    coef,
    amplitude,
    omega,
    phase,
    moment,
    phi0,
    phidot0,
    t0,
    dt,
    n_steps,
    record_every,
    limit,
    phi_hist,
    phidot_hist,
    capsized,
    capsize_time,
):  # pragma: no cover - compiled
    """RK4 over ``n_steps`` for each trajectory i; records every ``record_every`` steps.

    ``phi_hist``/``phidot_hist`` have shape (n_rec, N); row 0 is the initial state and, when
    ``record_every`` is 0, row 1 is the final state (only). ``limit`` = inf disables capsizing.
    """
    b1, b2, b3, c1, c2, c3, c4, c5 = (
        coef[0], coef[1], coef[2], coef[3], coef[4], coef[5], coef[6], coef[7],
    )  # fmt: skip
    n = phi0.shape[0]
    n_rec = phi_hist.shape[0]
    h = dt
    h2 = 0.5 * dt
    for i in range(n):
        x = phi0[i]
        v = phidot0[i]
        amp = amplitude[i]
        ph = phase[i]
        mom = moment[i]
        phi_hist[0, i] = x
        phidot_hist[0, i] = v
        capsized[i] = False
        capsize_time[i] = np.nan
        done = abs(x) > limit
        if done:
            capsized[i] = True
            capsize_time[i] = t0
        rec = 1
        for k in range(n_steps):
            if not done:
                t = t0 + k * h
                f0 = amp * math.sin(omega * t + ph) + mom
                fh = amp * math.sin(omega * (t + h2) + ph) + mom
                f1 = amp * math.sin(omega * (t + h) + ph) + mom
                k1x = v
                k1v = _accel(b1, b2, b3, c1, c2, c3, c4, c5, x, v, f0)
                k2x = v + h2 * k1v
                k2v = _accel(b1, b2, b3, c1, c2, c3, c4, c5, x + h2 * k1x, k2x, fh)
                k3x = v + h2 * k2v
                k3v = _accel(b1, b2, b3, c1, c2, c3, c4, c5, x + h2 * k2x, k3x, fh)
                k4x = v + h * k3v
                k4v = _accel(b1, b2, b3, c1, c2, c3, c4, c5, x + h * k3x, k4x, f1)
                x_new = x + (h / 6.0) * (k1x + 2.0 * k2x + 2.0 * k3x + k4x)
                v = v + (h / 6.0) * (k1v + 2.0 * k2v + 2.0 * k3v + k4v)
                if abs(x_new) > limit:
                    done = True
                    capsized[i] = True
                    ax0 = abs(x)
                    frac = (limit - ax0) / (abs(x_new) - ax0)
                    capsize_time[i] = t + h * min(max(frac, 0.0), 1.0)
                x = x_new
            if record_every > 0 and (k + 1) % record_every == 0:
                phi_hist[rec, i] = x
                phidot_hist[rec, i] = v
                rec += 1
        if record_every == 0:
            phi_hist[n_rec - 1, i] = x
            phidot_hist[n_rec - 1, i] = v


# ------------------------------------------------------------------------------------ model
def _roll_powers(phi: npt.ArrayLike) -> tuple[FloatArray, FloatArray, FloatArray]:
    """(φ, |φ|, φ²) as float64 arrays: the terms of the polynomial restoring [rad, rad, rad²]."""
    x = np.asarray(phi, dtype=np.float64)
    return x, np.abs(x), x * x


def _finite(value: float, name: str) -> float:
    v = float(value)
    if not math.isfinite(v):
        raise ValueError(f"{name} must be finite, got {value!r}")
    return v


@dataclass(frozen=True)
class RollEquation:
    """φ̈ + b₁φ̇ + b₂|φ̇|φ̇ + b₃φ̇³ + c₁φ + c₂|φ|φ + c₃φ³ + c₄|φ|φ³ + c₅φ⁵ = F sin(ωₑt + ε) + m(t).

    McCue & Campbell eq. 1 (b₃ = 0) and eq. 2 (b₂ = c₂ = c₄ = c₅ = 0) are special cases; see the
    module docstring for the units. All terms are per unit roll inertia.

    Parameters
    ----------
    b1 : float
        Linear damping [1/s].
    b2 : float
        Quadratic damping |φ̇|φ̇ [1/rad].
    b3 : float
        Cubic damping φ̇³ [s/rad²].
    c1, c2, c3, c4, c5 : float
        Restoring c₁φ + c₂|φ|φ + c₃φ³ + c₄|φ|φ³ + c₅φ⁵ [1/s², 1/(rad s²), 1/(rad² s²),
        1/(rad³ s²), 1/(rad⁴ s²)]; c₁ = ωₙ² for small angles.
    forcing_amplitude : float
        F [rad/s²].
    forcing_frequency : float
        ωₑ [rad/s].
    forcing_phase : float
        ε [rad].
    """

    b1: float = 0.0
    b2: float = 0.0
    b3: float = 0.0
    c1: float = 0.0
    c2: float = 0.0
    c3: float = 0.0
    c4: float = 0.0
    c5: float = 0.0
    forcing_amplitude: float = 0.0
    forcing_frequency: float = 0.0
    forcing_phase: float = 0.0

    def __post_init__(self) -> None:
        for f in fields(self):
            object.__setattr__(self, f.name, _finite(getattr(self, f.name), f.name))

    # ---------------------------------------------------------------- constructors
    @classmethod
    def edith_terkol(
        cls,
        forcing_amplitude: float = 0.0,
        forcing_frequency: float = 0.85 * EDITH_TERKOL_NATURAL_FREQUENCY,
        forcing_phase: float = 0.0,
    ) -> RollEquation:
        """The Edith Terkol (Soliman & Thompson 1991; McCue & Campbell eq. 1).

        Parameters
        ----------
        forcing_amplitude : float
            F [rad/s²] (McCue & Campbell's runs: 0.0195).
        forcing_frequency : float
            ωₑ [rad/s], default 0.85 ωₙ = 0.527.
        forcing_phase : float
            ε [rad].
        """
        return cls(
            b1=0.0043,
            b2=0.0225,
            c1=0.384,
            c2=0.1296,
            c3=1.0368,
            c4=-4.059,
            c5=2.4052,
            forcing_amplitude=forcing_amplitude,
            forcing_frequency=forcing_frequency,
            forcing_phase=forcing_phase,
        )

    @classmethod
    def mccue_campbell(
        cls,
        b_u1: float,
        b_u3: float,
        c_u1: float,
        c_u3: float,
        forcing_amplitude: float,
        forcing_frequency: float = 0.85 * EDITH_TERKOL_NATURAL_FREQUENCY,
        forcing_phase: float = 0.0,
    ) -> RollEquation:
        """The fitted form of McCue & Campbell eq. 2: ÿ + b_u1 ẏ + b_u3 ẏ³ + c_u1 y + c_u3 y³
        = F_u sin(ωₑt + ε).

        Parameters
        ----------
        b_u1, b_u3 : float
            Linear [1/s] and cubic [s/rad²] damping.
        c_u1, c_u3 : float
            Linear [1/s²] and cubic [1/(rad² s²)] restoring.
        forcing_amplitude : float
            F_u [rad/s²].
        forcing_frequency : float
            ωₑ [rad/s] (known, not fitted, in the paper).
        forcing_phase : float
            ε [rad].
        """
        return cls(
            b1=b_u1,
            b3=b_u3,
            c1=c_u1,
            c3=c_u3,
            forcing_amplitude=forcing_amplitude,
            forcing_frequency=forcing_frequency,
            forcing_phase=forcing_phase,
        )

    # ---------------------------------------------------------------- terms
    @property
    def coefficients(self) -> FloatArray:
        """(b1, b2, b3, c1, c2, c3, c4, c5) as a float64 array (the kernel's layout)."""
        return np.array(
            [self.b1, self.b2, self.b3, self.c1, self.c2, self.c3, self.c4, self.c5],
            dtype=np.float64,
        )

    @property
    def natural_frequency(self) -> float:
        """Small-angle natural frequency ωₙ = √c₁ [rad/s] (NaN if c₁ ≤ 0)."""
        return math.sqrt(self.c1) if self.c1 > 0 else math.nan

    def restoring(self, phi: npt.ArrayLike) -> FloatArray:
        """Restoring moment per unit inertia c₁φ + c₂|φ|φ + c₃φ³ + c₄|φ|φ³ + c₅φ⁵ [rad/s²].

        Parameters
        ----------
        phi : array_like
            Roll [rad].
        """
        x, ax, x2 = _roll_powers(phi)
        return x * (self.c1 + self.c2 * ax + self.c3 * x2 + self.c4 * ax * x2 + self.c5 * x2 * x2)

    def damping(self, phidot: npt.ArrayLike) -> FloatArray:
        """Damping moment per unit inertia b₁φ̇ + b₂|φ̇|φ̇ + b₃φ̇³ [rad/s²].

        Parameters
        ----------
        phidot : array_like
            Roll rate [rad/s].
        """
        v = np.asarray(phidot, dtype=np.float64)
        return v * (self.b1 + self.b2 * np.abs(v) + self.b3 * v * v)

    def forcing(self, t: npt.ArrayLike) -> FloatArray:
        """Wave forcing F sin(ωₑt + ε) [rad/s²] at times t [s]."""
        tt = np.asarray(t, dtype=np.float64)
        return self.forcing_amplitude * np.sin(self.forcing_frequency * tt + self.forcing_phase)

    def acceleration(
        self,
        t: npt.ArrayLike,
        phi: npt.ArrayLike,
        phidot: npt.ArrayLike,
        moment: npt.ArrayLike = 0.0,
    ) -> FloatArray:
        """Roll acceleration φ̈ [rad/s²] (vectorised; arguments broadcast).

        Parameters
        ----------
        t : array_like
            Time [s].
        phi : array_like
            Roll [rad].
        phidot : array_like
            Roll rate [rad/s].
        moment : array_like
            External moment per unit inertia m [rad/s²].
        """
        return (
            self.forcing(t)
            + np.asarray(moment, dtype=np.float64)
            - self.damping(phidot)
            - self.restoring(phi)
        )

    def potential_energy(self, phi: npt.ArrayLike) -> FloatArray:
        """V(φ) = ∫₀^φ restoring = c₁φ²/2 + c₂|φ|³/3 + c₃φ⁴/4 + c₄|φ|⁵/5 + c₅φ⁶/6 [rad²/s²].

        Per unit inertia, so the energy of the free undamped oscillator is ½φ̇² + V(φ).

        Parameters
        ----------
        phi : array_like
            Roll [rad].
        """
        _, ax, x2 = _roll_powers(phi)
        return x2 * (
            self.c1 / 2.0
            + self.c2 * ax / 3.0
            + self.c3 * x2 / 4.0
            + self.c4 * ax * x2 / 5.0
            + self.c5 * x2 * x2 / 6.0
        )

    def energy(self, phi: npt.ArrayLike, phidot: npt.ArrayLike) -> FloatArray:
        """Mechanical energy per unit inertia ½φ̇² + V(φ) [rad²/s²]."""
        v = np.asarray(phidot, dtype=np.float64)
        return 0.5 * v * v + self.potential_energy(phi)

    def vanishing_angle(self) -> float:
        """First positive zero of the restoring moment φᵥ [rad] (inf if none; 0 if c₁ ≤ 0).

        The restoring is φ·P(|φ|) with P(x) = c₁ + c₂x + c₃x² + c₄x³ + c₅x⁴; φᵥ is the smallest
        positive real root of P (the same to port, the restoring being odd). The root of the
        quartic from :func:`numpy.roots` is polished by a few Newton steps.
        """
        if self.c1 <= 0.0:
            return 0.0
        poly = [self.c5, self.c4, self.c3, self.c2, self.c1]  # highest power first
        while poly and poly[0] == 0.0:
            poly.pop(0)
        if len(poly) < 2:
            return math.inf
        roots = np.roots(poly)
        scale = max(1.0, float(np.max(np.abs(roots))))
        real = roots[(np.abs(roots.imag) <= 1e-7 * scale) & (roots.real > 0.0)].real
        if real.size == 0:
            return math.inf
        x = float(np.min(real))
        p = np.poly1d(poly)
        dp = p.deriv()
        for _ in range(3):
            d = float(dp(x))
            if d == 0.0:
                break
            x -= float(p(x)) / d
        return x

    # ---------------------------------------------------------------- integration
    def integrate(
        self,
        phi0: npt.ArrayLike,
        phidot0: npt.ArrayLike,
        t_end: float,
        dt: float,
        *,
        moment: npt.ArrayLike | MomentFn | None = None,
        t0: float = 0.0,
        stop_at: float | None = None,
        record_every: int | None = 1,
        forcing_amplitude: npt.ArrayLike | None = None,
        forcing_phase: npt.ArrayLike | None = None,
    ) -> RollTrajectory:
        """Integrate a batch of initial conditions from t0 to t_end with fixed-step RK4.

        Parameters
        ----------
        phi0, phidot0 : array_like
            Initial roll [rad] and roll rate [rad/s]; broadcast together (with ``moment``,
            ``forcing_amplitude`` and ``forcing_phase`` when those are arrays) to the batch shape.
        t_end : float
            Final time [s]; (t_end − t0)/dt must be a whole number of steps (to 1e-9 relative).
        dt : float
            Step [s], > 0.
        moment : array_like, callable or None
            External moment per unit inertia [rad/s²]: None (zero), a constant broadcast with the
            batch (compiled kernel), or ``m(t, phi, phidot)`` returning an array broadcast with the
            batch (numpy path).
        t0 : float
            Initial time [s] (the forcing is F sin(ωₑt + ε) in absolute time).
        stop_at : float or None
            Capsize roll limit [rad], > 0, e.g. :meth:`vanishing_angle`; None integrates all
            trajectories to the end.
        record_every : int or None
            Record the state every this many steps (must divide the number of steps); None
            records only the initial and final states (cheap, for large batches).
        forcing_amplitude, forcing_phase : array_like or None
            Per-trajectory overrides of F [rad/s²] and ε [rad] (broadcast with the batch);
            None uses the equation's own.

        Returns
        -------
        RollTrajectory
        """
        dt = _finite(dt, "dt")
        if dt <= 0.0:
            raise ValueError(f"dt must be > 0 [s], got {dt!r}")
        t0 = _finite(t0, "t0")
        t_end = _finite(t_end, "t_end")
        span = (t_end - t0) / dt
        n_steps = round(span)
        if n_steps < 0 or abs(span - n_steps) > 1e-9 * max(1.0, span):
            raise ValueError(
                f"t_end - t0 = {t_end - t0!r} s must be a non-negative whole number of steps "
                f"dt = {dt!r} s (got {span!r} steps)"
            )
        if record_every is None:
            rec_every = 0
            n_rec = 2
        else:
            rec_every = int(record_every)
            if rec_every != record_every or rec_every < 1 or n_steps % rec_every:
                raise ValueError(
                    f"record_every must be None or a positive divisor of the {n_steps} steps, "
                    f"got {record_every!r}"
                )
            n_rec = n_steps // rec_every + 1
        if stop_at is None:
            limit = math.inf
        else:
            limit = _finite(stop_at, "stop_at")
            if limit <= 0.0:
                raise ValueError(f"stop_at must be a positive roll limit [rad], got {stop_at!r}")

        amp = self.forcing_amplitude if forcing_amplitude is None else forcing_amplitude
        phase = self.forcing_phase if forcing_phase is None else forcing_phase
        const_moment = 0.0 if moment is None or callable(moment) else moment
        arrays = [np.asarray(a, dtype=np.float64) for a in (phi0, phidot0, amp, phase)]
        arrays.append(np.asarray(const_moment, dtype=np.float64))
        for name, a in zip(("phi0", "phidot0", "forcing_amplitude", "forcing_phase", "moment"),
                           arrays, strict=True):  # fmt: skip
            if not np.all(np.isfinite(a)):
                raise ValueError(f"{name} must be finite, got {a!r}")
        try:
            bcast = np.broadcast_arrays(*arrays)
        except ValueError as exc:
            raise ValueError(
                "phi0, phidot0, moment, forcing_amplitude and forcing_phase must broadcast "
                f"together; shapes {[a.shape for a in arrays]}"
            ) from exc
        shape = bcast[0].shape
        x0, v0, a_, p_, m_ = (np.ascontiguousarray(b.reshape(-1)) for b in bcast)

        if callable(moment):
            phi_h, phidot_h, caps, tcap = self._integrate_numpy(
                x0, v0, a_, p_, moment, shape, t0, dt, n_steps, rec_every, n_rec, limit
            )
        else:
            n = x0.size
            phi_h = np.empty((n_rec, n))
            phidot_h = np.empty((n_rec, n))
            caps = np.empty(n, dtype=np.bool_)
            tcap = np.empty(n)
            _rk4_kernel(
                self.coefficients, a_, self.forcing_frequency, p_, m_, x0, v0, t0, dt,
                n_steps, rec_every, limit, phi_h, phidot_h, caps, tcap,
            )  # fmt: skip
        if rec_every == 0:
            time = np.array([t0, t0 + n_steps * dt])
        else:
            time = t0 + dt * np.arange(0, n_steps + 1, rec_every, dtype=np.float64)
        return RollTrajectory(
            time=time,
            phi=phi_h.reshape((n_rec, *shape)),
            phidot=phidot_h.reshape((n_rec, *shape)),
            capsized=caps.reshape(shape),
            capsize_time=tcap.reshape(shape),
            stop_at=None if stop_at is None else limit,
            dt=dt,
        )

    def _integrate_numpy(
        self,
        x: FloatArray,
        v: FloatArray,
        amp: FloatArray,
        phase: FloatArray,
        moment: MomentFn,
        shape: tuple[int, ...],
        t0: float,
        dt: float,
        n_steps: int,
        rec_every: int,
        n_rec: int,
        limit: float,
    ) -> tuple[FloatArray, FloatArray, NDArray[np.bool_], FloatArray]:
        """Reference RK4 in numpy over the whole batch with a callable moment."""
        n = x.size
        omega = self.forcing_frequency
        phi_h = np.empty((n_rec, n))
        phidot_h = np.empty((n_rec, n))
        x = x.copy()
        v = v.copy()
        phi_h[0] = x
        phidot_h[0] = v
        done = np.abs(x) > limit
        caps = done.copy()
        tcap = np.where(done, t0, np.nan)

        def acc(t: float, xx: FloatArray, vv: FloatArray) -> FloatArray:
            m = np.asarray(moment(t, xx.reshape(shape), vv.reshape(shape)), dtype=np.float64)
            m = np.broadcast_to(m, shape).reshape(-1)
            return amp * np.sin(omega * t + phase) + m - self.damping(vv) - self.restoring(xx)

        h, h2 = dt, 0.5 * dt
        rec = 1
        for k in range(n_steps):
            t = t0 + k * h
            k1x = v
            k1v = acc(t, x, v)
            k2x = v + h2 * k1v
            k2v = acc(t + h2, x + h2 * k1x, k2x)
            k3x = v + h2 * k2v
            k3v = acc(t + h2, x + h2 * k2x, k3x)
            k4x = v + h * k3v
            k4v = acc(t + h, x + h * k3x, k4x)
            x_new = x + (h / 6.0) * (k1x + 2.0 * k2x + 2.0 * k3x + k4x)
            v_new = v + (h / 6.0) * (k1v + 2.0 * k2v + 2.0 * k3v + k4v)
            crossing = ~done & (np.abs(x_new) > limit)
            if np.any(crossing):
                ax0 = np.abs(x[crossing])
                frac = (limit - ax0) / (np.abs(x_new[crossing]) - ax0)
                tcap[crossing] = t + h * np.clip(frac, 0.0, 1.0)
                caps |= crossing
            x = np.where(done, x, x_new)
            v = np.where(done, v, v_new)
            done |= crossing
            if rec_every > 0 and (k + 1) % rec_every == 0:
                phi_h[rec] = x
                phidot_h[rec] = v
                rec += 1
        if rec_every == 0:
            phi_h[-1] = x
            phidot_h[-1] = v
        return phi_h, phidot_h, caps, tcap

    def advance(
        self,
        t0: float,
        phi: FloatArray,
        phidot: FloatArray,
        n_steps: int,
        dt: float,
        moment: FloatArray,
        forcing_amplitude: FloatArray,
        forcing_phase: FloatArray,
        stop_at: float = math.inf,
    ) -> tuple[FloatArray, FloatArray, NDArray[np.bool_]]:
        """Advance 1-D float64 arrays (N,) by ``n_steps`` RK4 steps of ``dt`` [s] from t0 [s].

        The lean per-control-step path of the environments: no history, no validation beyond
        numpy's (all arrays must be contiguous float64 of the same length N; ``moment``
        [rad/s²], ``forcing_amplitude`` [rad/s²] and ``forcing_phase`` [rad] are per
        trajectory). A trajectory whose |φ| exceeds ``stop_at`` [rad] is held there, as in
        :meth:`integrate`. Returns new arrays (phi [rad], phidot [rad/s], capsized [bool]);
        ``capsized`` is True where |φ| exceeded ``stop_at`` during these steps (or at t0).
        """
        n = phi.shape[0]
        phi_h = np.empty((2, n))
        phidot_h = np.empty((2, n))
        caps = np.empty(n, dtype=np.bool_)
        tcap = np.empty(n)
        _rk4_kernel(
            self.coefficients, forcing_amplitude, self.forcing_frequency, forcing_phase, moment,
            phi, phidot, float(t0), float(dt), int(n_steps), 0, float(stop_at), phi_h, phidot_h,
            caps, tcap,
        )  # fmt: skip
        return phi_h[1], phidot_h[1], caps
