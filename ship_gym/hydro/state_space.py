"""Stable state-space realisation of the radiation memory convolution.

The memory force of Cummins' equation (DESIGN.md §3, Matusiak eq. 15–16)

    μᵢ(t) = Σⱼ ∫₀^t Kᵢⱼ(t − τ) vⱼ(τ) dτ

is replaced by the output of a linear system ẋ = A x + B v, μ = C x (D = 0: K is finite at
t = 0, the transfer function is strictly proper) whose impulse response C e^{At} B fits K(t).
Cost per time step is O(number of states) instead of O(history length).

Method (per DOF pair, SISO, assembled block-diagonally into a MIMO system)
--------------------------------------------------------------------------
1. **Poles by Kung's / ERA realisation.** K is sampled at Δt_s (a stride of the kernel grid,
   by default 2·``hankel_size`` samples over the window). The samples are the Markov parameters
   hₖ = K(kΔt_s) = C A_dᵏ B of a discrete system; the Hankel matrix H₀[i, j] = h_{i+j} is
   factorised by SVD, truncated to order r, and A_d = Σ_r^{−½} U_rᵀ H₁ V_r Σ_r^{−½} with the
   shifted Hankel matrix H₁[i, j] = h_{i+j+1}. The order r is the number of normalised Hankel
   singular values above ``tol`` (raised until the fit error is below ``target_error``, at most
   ``max_order``).
2. **Continuous poles** s = ln(λ)/Δt_s from the eigenvalues λ of A_d (a negative real λ gives a
   complex pair at the Nyquist frequency π/Δt_s). **Stability** is enforced by reflecting any
   pole with Re s ≥ 0 into the left half plane, Re s → −max(|Re s|, 1/(10 T)) with T the kernel
   window.
3. **Residues by linear least squares** of K(t) on the full kernel grid against the modal basis
   e^{st} (real poles) and e^{σt}cos ωt, e^{σt}sin ωt (complex pairs). This fits the continuous
   kernel (not only the ERA samples) and keeps the reflected poles useful.
4. **Real modal realisation**: a real pole gives one state (ẋ = s x + v, μ = c x); a complex
   pair σ ± iω gives two states with A = [[σ, ω], [−ω, σ]], B = [1, 0]ᵀ and
   C = [a, −b] for a e^{σt}cos ωt + b e^{σt}sin ωt.

Pairs whose kernel is negligible (max|Kᵢⱼ| ≤ ``zero_tol``·√(max|Kᵢᵢ|·max|Kⱼⱼ|), e.g.
surge–sway by port–starboard symmetry) get order 0. A ship at zero speed has 18 non-zero pairs of
the 36; at 2–4 states each the total order is ≈ 40–70. Fit kernels computed with
``tail="asymptotic"``, ``"power"`` or ``"taper"`` (:mod:`ship_gym.hydro.retardation`): the 1/t
truncation ringing left by ``tail="none"`` is not a sum of exponentials and costs several extra
states per pair (a synthetic 6×6 case: 54 states with the power tail, 74–100 without).

Layout
------
Kernels are passed as ``K[t, i, j]`` coupling input (velocity) j to output (force) i:
μᵢ = Σⱼ Kᵢⱼ * vⱼ. A capytaine-ordered database has axes (radiating_dof, influenced_dof), i.e.
(input, output): pass ``np.swapaxes(K, 1, 2)`` (identical at zero speed, where K is symmetric).

Discretisation
--------------
:func:`discretize` returns the exact discrete update for piecewise-constant (``hold="zoh"``)
or piecewise-linear (``hold="foh"``, triangle hold) velocity between samples, from one matrix
exponential of an augmented matrix (Van Loan):

    ZOH: x_{k+1} = A_d x_k + Γ₀ v_k,                 Γ₀ = ∫₀^Δt e^{Aτ}dτ B
    FOH: x_{k+1} = A_d x_k + (Γ₀ − Γ₁) v_k + Γ₁ v_{k+1},  Γ₁ = ∫₀^Δt e^{Aτ}(1 − τ/Δt)dτ B

ZOH is O(Δt) accurate in the memory force and explicit; FOH is O(Δt²) and needs v_{k+1}
(available at the end of a step of a time integrator). Inside a Runge–Kutta scheme one can
instead integrate ẋ = A x + B v together with the ship states.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any, Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray
from scipy.linalg import expm

from ship_gym.hydro.retardation import relative_pair_error

__all__ = [
    "DiscreteStateSpace",
    "ModalFit",
    "StateSpaceRadiation",
    "discretize",
    "fit_kernel",
    "fit_state_space",
    "frequency_fit_error",
]

Hold = Literal["zoh", "foh"]
_HOLDS = ("zoh", "foh")


# --------------------------------------------------------------------------------------------
# SISO modal fit
# --------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class ModalFit:
    """Modal (sum-of-exponentials) fit of one kernel entry Kᵢⱼ(t).

    K(t) ≈ Σ_r c_r e^{s_r t} + Σ_c e^{σ_c t}(a_c cos ω_c t + b_c sin ω_c t).

    Attributes
    ----------
    output, input : int
        Indices i (force) and j (velocity) of the pair.
    real_poles : ndarray, shape (n_r,)
        Real poles s_r < 0 [1/s].
    real_residues : ndarray, shape (n_r,)
        c_r [units of K].
    complex_poles : ndarray, shape (n_c,), complex
        σ_c + iω_c with σ_c < 0, ω_c > 0 [1/s, rad/s].
    cos_coefficients, sin_coefficients : ndarray, shape (n_c,)
        a_c, b_c [units of K].
    fit_error : float
        Relative L2 error ‖K_fit − K‖/‖K‖ on the fitting grid [-].
    hankel_singular_values : ndarray
        Normalised Hankel singular values σₖ/σ₁ of the sampled kernel [-].
    """

    output: int
    input: int
    real_poles: NDArray[np.float64]
    real_residues: NDArray[np.float64]
    complex_poles: NDArray[np.complex128]
    cos_coefficients: NDArray[np.float64]
    sin_coefficients: NDArray[np.float64]
    fit_error: float
    hankel_singular_values: NDArray[np.float64]

    def __post_init__(self) -> None:
        rp = np.asarray(self.real_poles, dtype=float).reshape(-1)
        rr = np.asarray(self.real_residues, dtype=float).reshape(-1)
        cp = np.asarray(self.complex_poles, dtype=complex).reshape(-1)
        ca = np.asarray(self.cos_coefficients, dtype=float).reshape(-1)
        cb = np.asarray(self.sin_coefficients, dtype=float).reshape(-1)
        if rr.shape != rp.shape:
            raise ValueError(f"real_residues has shape {rr.shape}; expected {rp.shape}")
        if ca.shape != cp.shape or cb.shape != cp.shape:
            raise ValueError(
                f"cos/sin coefficients have shapes {ca.shape}, {cb.shape}; expected {cp.shape}"
            )
        if np.any(rp >= 0) or np.any(cp.real >= 0):
            raise ValueError(
                f"unstable poles {rp[rp >= 0]}, {cp[cp.real >= 0]}; expected Re(s) < 0 [1/s]"
            )
        if np.any(cp.imag <= 0):
            raise ValueError(
                f"complex_poles {cp}; expected positive imaginary parts (one per pair)"
            )
        for name, value in (
            ("real_poles", rp),
            ("real_residues", rr),
            ("complex_poles", cp),
            ("cos_coefficients", ca),
            ("sin_coefficients", cb),
            ("hankel_singular_values", np.asarray(self.hankel_singular_values, dtype=float)),
        ):
            value.setflags(write=False)
            object.__setattr__(self, name, value)

    @property
    def order(self) -> int:
        """Number of states of the realisation."""
        return int(self.real_poles.size + 2 * self.complex_poles.size)

    def poles(self) -> NDArray[np.complex128]:
        """All poles (complex pairs listed with both signs) [1/s]."""
        cp = self.complex_poles
        return np.concatenate([self.real_poles.astype(complex), cp, cp.conj()])

    def impulse_response(self, t: ArrayLike) -> NDArray[np.float64]:
        """Fitted K(t) at times t [s]; shape (n_t,)."""
        tt = np.asarray(t, dtype=float).reshape(-1)
        return _modal_basis(tt, self.real_poles, self.complex_poles) @ np.concatenate(
            [self.real_residues, self.cos_coefficients, self.sin_coefficients]
        )

    def transfer(self, s: ArrayLike) -> NDArray[np.complex128]:
        """Laplace transform K̂(s) = ∫₀^∞ K(t)e^{−st} dt of the fitted kernel; shape of s."""
        ss = np.asarray(s, dtype=complex)
        out = np.zeros(ss.shape, dtype=complex)
        for p, c in zip(self.real_poles, self.real_residues, strict=True):
            out += c / (ss - p)
        for p, a, b in zip(
            self.complex_poles, self.cos_coefficients, self.sin_coefficients, strict=True
        ):
            d = (ss - p.real) ** 2 + p.imag**2
            out += (a * (ss - p.real) + b * p.imag) / d
        return out

    def matrices(
        self,
    ) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
        """Real modal realisation (A (r, r), b (r,), c (r,)) with K(t) = c·e^{At}b."""
        r = self.order
        a_mat = np.zeros((r, r))
        b_vec = np.zeros(r)
        c_vec = np.zeros(r)
        k = 0
        for p, c in zip(self.real_poles, self.real_residues, strict=True):
            a_mat[k, k] = p
            b_vec[k] = 1.0
            c_vec[k] = c
            k += 1
        for p, a, b in zip(
            self.complex_poles, self.cos_coefficients, self.sin_coefficients, strict=True
        ):
            a_mat[k : k + 2, k : k + 2] = [[p.real, p.imag], [-p.imag, p.real]]
            b_vec[k] = 1.0
            c_vec[k : k + 2] = [a, -b]
            k += 2
        return a_mat, b_vec, c_vec


def _modal_basis(
    t: NDArray[np.float64], real_poles: NDArray[np.float64], complex_poles: NDArray[np.complex128]
) -> NDArray[np.float64]:
    """Columns e^{s t} (real poles), then e^{σt}cos ωt, then e^{σt}sin ωt (complex poles)."""
    er = np.exp(np.outer(t, real_poles))
    decay = np.exp(np.outer(t, complex_poles.real))
    phase = np.outer(t, complex_poles.imag)
    return np.hstack([er, decay * np.cos(phase), decay * np.sin(phase)])


def _continuous_poles(
    lam: NDArray[np.complex128], dt_s: float, sigma_min: float
) -> tuple[NDArray[np.float64], NDArray[np.complex128]]:
    """Map discrete eigenvalues to stable continuous poles (real, and complex with Im > 0)."""
    real: list[float] = []
    cplx: list[complex] = []
    for lm in lam:
        if abs(lm) < 1e-12:
            continue  # a pole at the origin of the z-plane: decays within one sample
        if abs(lm.imag) <= 1e-9 * abs(lm):
            if lm.real > 0:
                real.append(math.log(lm.real) / dt_s)
            else:  # negative real eigenvalue: an oscillation at the Nyquist frequency
                cplx.append(complex(math.log(-lm.real) / dt_s, math.pi / dt_s))
        elif lm.imag > 0:
            cplx.append(complex(np.log(lm)) / dt_s)
    rp = np.array(real, dtype=float)
    cp = np.array(cplx, dtype=complex)
    rp = np.where(rp < -sigma_min, rp, -np.maximum(np.abs(rp), sigma_min))
    cp = np.where(cp.real < -sigma_min, cp, -np.maximum(np.abs(cp.real), sigma_min) + 1j * cp.imag)
    return rp, cp


_DAMPING_OMEGA = np.linspace(0.0, 3.0, 601)[1:]
"""Default grid of the B(ω) ≥ 0 constraint [rad/s]."""


def _transfer_rows(
    s: ArrayLike,
    real_poles: NDArray[np.float64],
    complex_poles: NDArray[np.complex128],
) -> NDArray[np.complex128]:
    """K̂(s) = rows @ [c_r, a_c, b_c]: Laplace transforms of the columns of :func:`_modal_basis`.

    e^{pt} → 1/(s − p); e^{σt}cos ωt → (s − σ)/((s − σ)² + ω²); e^{σt}sin ωt → ω/((s − σ)² + ω²).
    """
    ss = np.asarray(s, dtype=complex).reshape(-1, 1)
    sig, om = complex_poles.real[None, :], complex_poles.imag[None, :]
    den = (ss - sig) ** 2 + om**2
    return np.hstack([1.0 / (ss - real_poles[None, :]), (ss - sig) / den, om / den])


def _damping_rows(
    omega: NDArray[np.float64],
    real_poles: NDArray[np.float64],
    complex_poles: NDArray[np.complex128],
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Rows of B(ω) = ∫₀^∞ K cos ωt dt = Re K̂(iω) and of dB/dω = Re[i K̂'(iω)] (linear in coef)."""
    s = 1j * np.asarray(omega, dtype=float)
    rows = _transfer_rows(s, real_poles, complex_poles)
    ss = s.reshape(-1, 1)
    sig, om = complex_poles.real[None, :], complex_poles.imag[None, :]
    den = (ss - sig) ** 2 + om**2
    d_real = -1.0 / (ss - real_poles[None, :]) ** 2
    d_cos = 1.0 / den - 2.0 * (ss - sig) ** 2 / den**2
    d_sin = -2.0 * om * (ss - sig) / den**2
    d_rows = np.hstack([d_real, d_cos, d_sin])
    return rows.real, (1j * d_rows).real


def _lstsq_residues(
    t: NDArray[np.float64],
    k: NDArray[np.float64],
    rp: NDArray[np.float64],
    cp: NDArray[np.complex128],
    *,
    zero_dc: bool = False,
    damping_omega: NDArray[np.float64] | None = None,
) -> tuple[NDArray[np.float64], float]:
    """Residues by least squares on K(t), optionally constrained (module docstring, step 3).

    ``zero_dc``: equality K̂(0) = ∫₀^∞ K dt = B(0) = 0, i.e. Σ c_r/s_r + Σ (a σ − b ω)/|s|² = 0.
    ``damping_omega``: B(ω) ≥ 0 on that grid, by an active set: while some B(ω_k) < 0, the most
    violated ω_k gets the equalities B(ω_k) = 0 and dB/dω(ω_k) = 0 (the tangency that an active
    interior inequality has at the optimum). Equalities are imposed in the null space of the
    constraint rows (exact to round-off).
    """
    phi = _modal_basis(t, rp, cp)
    norms = np.linalg.norm(phi, axis=0)
    norms[norms == 0] = 1.0
    phin = phi / norms
    n = phin.shape[1]
    eq: list[NDArray[np.float64]] = []
    if zero_dc:
        eq.append(_transfer_rows(np.zeros(1), rp, cp).real[0] / norms)
    b_rows = None
    if damping_omega is not None and damping_omega.size:
        b_rows, db_rows = _damping_rows(damping_omega, rp, cp)
        b_rows = b_rows / norms
        db_rows = db_rows / norms

    def solve(rows: list[NDArray[np.float64]]) -> NDArray[np.float64] | None:
        if not rows:
            z, *_ = np.linalg.lstsq(phin, k, rcond=1e-12)
            return z
        g = np.array(rows)
        g = g / np.linalg.norm(g, axis=1, keepdims=True)
        _, sv, vt = np.linalg.svd(g)
        rank = int(np.count_nonzero(sv > 1e-10 * sv[0]))
        if rank >= n:
            return None
        null = vt[rank:].T
        y, *_ = np.linalg.lstsq(phin @ null, k, rcond=1e-12)
        return null @ y

    z = solve(eq)
    if z is None:
        raise ValueError("the zero-DC constraint leaves no free residue")
    if b_rows is not None:
        for _ in range(3 * n):
            b = b_rows @ z
            scale = float(np.max(np.abs(b)))
            i_min = int(np.argmin(b))
            if scale == 0.0 or b[i_min] >= -1e-9 * scale:
                break
            new = [b_rows[i_min], db_rows[i_min]]
            trial = solve([*eq, *new])
            if trial is None:
                new = new[:1]
                trial = solve([*eq, *new])
            if trial is None:
                break
            eq.extend(new)
            z = trial
    coef = z / norms
    err = float(np.linalg.norm(phi @ coef - k) / np.linalg.norm(k))
    return coef, err


def fit_kernel(
    t: ArrayLike,
    k: ArrayLike,
    *,
    order: int | None = None,
    tol: float = 1e-2,
    target_error: float = 5e-3,
    max_order: int = 12,
    hankel_size: int = 60,
    dt_fit: float | None = None,
    output: int = 0,
    input: int = 0,
    zero_dc: bool = False,
    nonnegative_damping: bool = False,
    damping_omega: ArrayLike | None = None,
) -> ModalFit:
    """Fit one kernel K(t) by ERA poles + least-squares residues (module docstring).

    Parameters
    ----------
    t : array_like, shape (n_t,)
        Uniform times from 0 [s].
    k : array_like, shape (n_t,)
        Kernel samples [any units].
    order : int, optional
        Fixed ERA order (number of discrete poles); automatic when None.
    tol : float
        Automatic order: number of normalised Hankel singular values σₖ/σ₁ > tol [-].
    target_error : float
        Automatic order: raise the order until the relative L2 error is ≤ this [-].
    max_order : int
        Largest ERA order tried.
    hankel_size : int
        Number of rows (= columns) of the Hankel matrix.
    dt_fit : float, optional
        Sampling interval of the ERA samples [s]; default T/(2·hankel_size) rounded to a
        multiple of the grid step.
    output, input : int
        Pair indices recorded in the result.
    zero_dc : bool
        Constrain the zero-frequency damping B_fit(0) = ∫₀^∞ K_fit dt = −Σ rᵢ/λᵢ to zero (exact
        to round-off), as a radiation kernel must (Perez & Fossen 2008).
    nonnegative_damping : bool
        Constrain B_fit(ω) = ∫₀^∞ K_fit cos ωt dt ≥ 0 on ``damping_omega`` (a diagonal pair:
        a passive radiation force) by the active set of :func:`_lstsq_residues`.
    damping_omega : array_like, optional
        Frequency grid of that constraint [rad/s]; default 600 points on (0, 3] rad/s.

    Returns
    -------
    ModalFit
    """
    tt, kk = _check_kernel_grid(t, np.asarray(k, dtype=float)[:, None, None])
    kk = kk[:, 0, 0]
    if not np.any(kk != 0):
        raise ValueError("k is identically zero; a zero pair has order 0 and needs no fit")
    if order is not None and (int(order) != order or order < 1):
        raise ValueError(f"order={order!r}; expected a positive integer or None")
    if not 0 < tol < 1:
        raise ValueError(f"tol={tol!r}; expected 0 < tol < 1")
    if not (isinstance(max_order, int) and max_order >= 1):
        raise ValueError(f"max_order={max_order!r}; expected a positive integer")
    if not (isinstance(hankel_size, int) and hankel_size >= 4):
        raise ValueError(f"hankel_size={hankel_size!r}; expected an integer ≥ 4")
    w_con = None
    if nonnegative_damping:
        w_con = (
            _DAMPING_OMEGA
            if damping_omega is None
            else np.asarray(damping_omega, dtype=float).reshape(-1)
        )
        if not np.all(np.isfinite(w_con)) or np.any(w_con < 0):
            raise ValueError(f"damping_omega must hold finite ω ≥ 0 [rad/s]; got {w_con}")
    dt = tt[1] - tt[0]
    window = tt[-1]
    dt_target = window / (2 * hankel_size) if dt_fit is None else float(dt_fit)
    if not dt_target > 0:
        raise ValueError(f"dt_fit={dt_fit!r}; expected a positive sampling interval [s]")
    stride = max(1, round(dt_target / dt))
    h = kk[::stride]
    dt_s = stride * dt
    n_rows = min(hankel_size, (h.size - 1) // 2)
    if n_rows < 2:
        raise ValueError(
            f"only {h.size} ERA samples at Δt = {dt_s} s; expected ≥ 5 (longer kernel window or "
            "smaller dt_fit)"
        )
    idx = np.arange(n_rows)
    h0 = h[idx[:, None] + idx[None, :]]
    h1 = h[idx[:, None] + idx[None, :] + 1]
    u, sv, vt = np.linalg.svd(h0)
    hsv = sv / sv[0]
    n_valid = int(np.count_nonzero(hsv > 1e-13))
    sigma_min = 1.0 / (10.0 * window)
    if order is not None:
        candidates = [min(int(order), n_valid)]
    else:
        r0 = max(1, int(np.count_nonzero(hsv > tol)))
        candidates = list(range(min(r0, max_order, n_valid), min(max_order, n_valid) + 1))
    best: tuple[float, Any] | None = None
    for r in candidates:
        sr = np.sqrt(sv[:r])
        ad = (u[:, :r].T @ h1 @ vt[:r].T) / sr[:, None] / sr[None, :]
        rp, cp = _continuous_poles(np.linalg.eigvals(ad), dt_s, sigma_min)
        if rp.size + cp.size == 0:
            continue
        coef, err = _lstsq_residues(tt, kk, rp, cp, zero_dc=zero_dc, damping_omega=w_con)
        if best is None or err < best[0]:
            best = (err, (rp, cp, coef))
        if err <= target_error:
            break
    if best is None:
        raise ValueError("ERA found no usable pole; the kernel may be too short or too noisy")
    err, (rp, cp, coef) = best
    nr, nc = rp.size, cp.size
    return ModalFit(
        output=output,
        input=input,
        real_poles=rp,
        real_residues=coef[:nr],
        complex_poles=cp,
        cos_coefficients=coef[nr : nr + nc],
        sin_coefficients=coef[nr + nc :],
        fit_error=err,
        hankel_singular_values=hsv,
    )


def _check_kernel_grid(
    t: ArrayLike, k: NDArray[np.float64]
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    tt = np.asarray(t, dtype=float)
    if tt.ndim != 1 or tt.size < 5 or not np.all(np.isfinite(tt)):
        raise ValueError(f"t must be a finite 1-D time grid with ≥ 5 samples [s]; got {tt.shape}")
    d = np.diff(tt)
    if tt[0] != 0.0 or np.any(d <= 0) or np.max(np.abs(d - d.mean())) > 1e-6 * d.mean():
        raise ValueError("t must be uniform and start at 0 s (K(0) is the first Markov parameter)")
    if k.shape[0] != tt.size or not np.all(np.isfinite(k)):
        raise ValueError(f"K has shape {k.shape}; expected finite values of shape ({tt.size}, ...)")
    return tt, k


# --------------------------------------------------------------------------------------------
# discrete system
# --------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class DiscreteStateSpace:
    """Exact discretisation of ẋ = A x + B v, μ = C x for a fixed step.

    Attributes
    ----------
    Ad : ndarray, shape (n, n)
        e^{AΔt} [-].
    B0, B1 : ndarray, shape (n, m)
        Input matrices for v_k and v_{k+1} (B1 = 0 for ZOH) [s · units of B].
    C : ndarray, shape (p, n)
        Output matrix [units of K].
    dt : float
        Step [s].
    hold : str
        "zoh" or "foh".
    """

    Ad: NDArray[np.float64]
    B0: NDArray[np.float64]
    B1: NDArray[np.float64]
    C: NDArray[np.float64]
    dt: float
    hold: str

    def __post_init__(self) -> None:
        if self.hold not in _HOLDS:
            raise ValueError(f"hold={self.hold!r}; expected one of {_HOLDS}")
        n = self.Ad.shape[0]
        if self.Ad.shape != (n, n) or self.B0.shape[0] != n or self.B1.shape != self.B0.shape:
            raise ValueError(
                f"inconsistent shapes Ad {self.Ad.shape}, B0 {self.B0.shape}, B1 {self.B1.shape}"
            )
        if self.C.shape[1] != n:
            raise ValueError(f"C has shape {self.C.shape}; expected (p, {n})")
        if not self.dt > 0:
            raise ValueError(f"dt={self.dt!r}; expected a positive step [s]")

    def step(
        self, x: NDArray[np.float64], v: ArrayLike, v_next: ArrayLike | None = None
    ) -> NDArray[np.float64]:
        """State after one step from x with velocity v (and v_next for FOH).

        Parameters
        ----------
        x : ndarray, shape (n,)
            State at t_k.
        v : array_like, shape (m,)
            Velocities at t_k [m/s, rad/s].
        v_next : array_like, shape (m,), optional
            Velocities at t_{k+1}; required for FOH, ignored for ZOH.

        Returns
        -------
        ndarray, shape (n,)
            State at t_{k+1}.
        """
        xn = self.Ad @ x + self.B0 @ np.asarray(v, dtype=float)
        if self.hold == "foh":
            if v_next is None:
                raise ValueError("hold='foh' needs v_next (velocity at the end of the step)")
            xn = xn + self.B1 @ np.asarray(v_next, dtype=float)
        return xn

    def output(self, x: NDArray[np.float64]) -> NDArray[np.float64]:
        """Memory force μ = C x [N, N·m]."""
        return self.C @ x


def _discretize_matrices(
    a: NDArray[np.float64], b: NDArray[np.float64], c: NDArray[np.float64], dt: float, hold: str
) -> DiscreteStateSpace:
    n, m = b.shape
    big = np.zeros((n + 2 * m, n + 2 * m))
    big[:n, :n] = a * dt
    big[:n, n : n + m] = b * dt
    big[n : n + m, n + m :] = np.eye(m)
    e = expm(big)
    ad = e[:n, :n]
    g0 = e[:n, n : n + m]  # ∫₀^Δt e^{Aτ} dτ B
    g1 = e[:n, n + m :]  # ∫₀^Δt e^{Aτ}(1 − τ/Δt) dτ B
    if hold == "zoh":
        return DiscreteStateSpace(ad, g0, np.zeros_like(g0), c, dt, hold)
    return DiscreteStateSpace(ad, g0 - g1, g1, c, dt, hold)


# --------------------------------------------------------------------------------------------
# MIMO system
# --------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class StateSpaceRadiation:
    """Fitted stable realisation ẋ = A x + B v, μ = C x + D v of the radiation memory.

    Total order ≈ 40–70 states for a ship (18 non-zero pairs at 2–4 states each).

    Attributes
    ----------
    A : ndarray, shape (n, n)
        Block-diagonal state matrix [1/s]; all eigenvalues have negative real part.
    B : ndarray, shape (n, m)
        Input matrix (velocity inputs) [-].
    C : ndarray, shape (p, n)
        Output matrix (memory force) [units of K].
    D : ndarray, shape (p, m)
        Feed-through, zero (strictly proper kernel transform).
    orders : ndarray of int, shape (p, m)
        States per pair (0 for negligible pairs).
    fit_error : ndarray, shape (p, m)
        Relative L2 error of the fitted K per pair on the fitting grid (0 for zero pairs) [-].
    fits : tuple of ModalFit
        Per-pair fits in state order.
    """

    A: NDArray[np.float64]
    B: NDArray[np.float64]
    C: NDArray[np.float64]
    D: NDArray[np.float64]
    orders: NDArray[np.int64]
    fit_error: NDArray[np.float64]
    fits: tuple[ModalFit, ...]
    _cache: dict[tuple[float, str], DiscreteStateSpace] = field(
        default_factory=dict, init=False, repr=False, compare=False
    )

    def __post_init__(self) -> None:
        a = np.asarray(self.A, dtype=float)
        b = np.asarray(self.B, dtype=float)
        c = np.asarray(self.C, dtype=float)
        d = np.asarray(self.D, dtype=float)
        orders = np.asarray(self.orders, dtype=np.int64)
        err = np.asarray(self.fit_error, dtype=float)
        n = a.shape[0] if a.ndim == 2 else -1
        if a.shape != (n, n):
            raise ValueError(f"A has shape {a.shape}; expected a square matrix")
        if b.ndim != 2 or b.shape[0] != n:
            raise ValueError(f"B has shape {b.shape}; expected ({n}, m)")
        if c.ndim != 2 or c.shape[1] != n:
            raise ValueError(f"C has shape {c.shape}; expected (p, {n})")
        if d.shape != (c.shape[0], b.shape[1]):
            raise ValueError(f"D has shape {d.shape}; expected {(c.shape[0], b.shape[1])}")
        if orders.shape != d.shape or err.shape != d.shape:
            raise ValueError(
                f"orders {orders.shape} and fit_error {err.shape} must have shape {d.shape}"
            )
        if int(orders.sum()) != n:
            raise ValueError(f"orders sum to {orders.sum()}; expected the state count {n}")
        if n and np.max(np.linalg.eigvals(a).real) >= 0:
            raise ValueError("A has eigenvalues with Re ≥ 0; expected a stable system")
        for name, value in (("A", a), ("B", b), ("C", c), ("D", d), ("orders", orders)):
            value.setflags(write=False)
            object.__setattr__(self, name, value)
        err.setflags(write=False)
        object.__setattr__(self, "fit_error", err)
        object.__setattr__(self, "fits", tuple(self.fits))

    @property
    def order(self) -> int:
        """Total number of states."""
        return int(self.A.shape[0])

    @property
    def n_inputs(self) -> int:
        """Number of velocity inputs m."""
        return int(self.B.shape[1])

    @property
    def n_outputs(self) -> int:
        """Number of force outputs p."""
        return int(self.C.shape[0])

    def poles(self) -> NDArray[np.complex128]:
        """Eigenvalues of A [1/s]."""
        if self.order == 0:
            return np.zeros(0, dtype=complex)
        return np.concatenate([f.poles() for f in self.fits])

    def initial_state(self) -> NDArray[np.float64]:
        """Zero state (ship at rest for all t < 0)."""
        return np.zeros(self.order)

    def impulse_response(self, t: ArrayLike) -> NDArray[np.float64]:
        """Fitted K(t) = C e^{At} B, shape (n_t, p, m)."""
        tt = np.asarray(t, dtype=float).reshape(-1)
        out = np.zeros((tt.size, self.n_outputs, self.n_inputs))
        for f in self.fits:
            out[:, f.output, f.input] = f.impulse_response(tt)
        return out

    def frequency_response(
        self, omega: ArrayLike
    ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Added mass and damping implied by the realisation (Ogilvie).

        K̂(iω) = C(iωI − A)⁻¹B = B(ω) + iω[A(ω) − A(∞)].

        Parameters
        ----------
        omega : array_like, shape (n_omega,)
            Frequencies ω > 0 [rad/s].

        Returns
        -------
        added_mass_minus_inf : ndarray, shape (n_omega, p, m)
            A(ω) − A(∞) [units of A].
        damping : ndarray, shape (n_omega, p, m)
            B(ω) [units of B].
        """
        w = np.asarray(omega, dtype=float).reshape(-1)
        if not np.all(np.isfinite(w)) or np.any(w <= 0):
            raise ValueError(f"omega must contain finite ω > 0 [rad/s]; got {w}")
        h = np.zeros((w.size, self.n_outputs, self.n_inputs), dtype=complex)
        for f in self.fits:
            h[:, f.output, f.input] = f.transfer(1j * w)
        return h.imag / w[:, None, None], h.real

    def discretize(self, dt: float, hold: Hold = "zoh") -> DiscreteStateSpace:
        """Exact discrete system for step dt [s] (cached per (dt, hold)); see module docstring."""
        key = (float(dt), str(hold))
        if key not in self._cache:
            self._cache[key] = discretize(self, dt, hold)
        return self._cache[key]

    def step(
        self,
        x: NDArray[np.float64],
        v: ArrayLike,
        dt: float,
        v_next: ArrayLike | None = None,
    ) -> NDArray[np.float64]:
        """Advance the state by dt [s]: ZOH if ``v_next`` is None, FOH otherwise."""
        hold: Hold = "zoh" if v_next is None else "foh"
        return self.discretize(dt, hold).step(x, v, v_next)

    def output(self, x: NDArray[np.float64]) -> NDArray[np.float64]:
        """Memory force μ = C x, shape (p,) [N, N·m]."""
        return self.C @ x

    def simulate(self, t: ArrayLike, v: ArrayLike, hold: Hold = "foh") -> NDArray[np.float64]:
        """Memory force μ(t_k) for a velocity history on a uniform grid, from rest.

        Parameters
        ----------
        t : array_like, shape (n_t,)
            Uniform times [s].
        v : array_like, shape (n_t, m)
            Velocities [m/s, rad/s].
        hold : {"zoh", "foh"}
            Inter-sample assumption on v.

        Returns
        -------
        ndarray, shape (n_t, p)
            μ(t_k) = Σⱼ ∫₀^{t_k} Kᵢⱼ(t_k − τ) vⱼ(τ) dτ [units of K · m].
        """
        tt = np.asarray(t, dtype=float).reshape(-1)
        vv = np.asarray(v, dtype=float)
        if vv.shape != (tt.size, self.n_inputs):
            raise ValueError(f"v has shape {vv.shape}; expected {(tt.size, self.n_inputs)}")
        d = np.diff(tt)
        if tt.size < 2 or np.any(d <= 0) or np.max(np.abs(d - d.mean())) > 1e-9 * d.mean():
            raise ValueError("t must be a uniform, increasing time grid [s]")
        sys = self.discretize(float(d.mean()), hold)
        x = self.initial_state()
        out = np.empty((tt.size, self.n_outputs))
        out[0] = self.C @ x
        for k in range(tt.size - 1):
            x = sys.step(x, vv[k], vv[k + 1])
            out[k + 1] = self.C @ x
        return out


def discretize(ss: StateSpaceRadiation, dt: float, hold: Hold = "zoh") -> DiscreteStateSpace:
    """Exact discretisation of a fitted realisation (one matrix exponential, Van Loan).

    Parameters
    ----------
    ss : StateSpaceRadiation
        Continuous system.
    dt : float
        Step [s].
    hold : {"zoh", "foh"}
        Zero-order hold (v constant over the step) or first-order/triangle hold (v linear
        between samples); see the module docstring.

    Returns
    -------
    DiscreteStateSpace
    """
    if not (np.isfinite(dt) and dt > 0):
        raise ValueError(f"dt={dt!r}; expected a positive step [s]")
    if hold not in _HOLDS:
        raise ValueError(f"hold={hold!r}; expected one of {_HOLDS}")
    return _discretize_matrices(
        np.asarray(ss.A), np.asarray(ss.B), np.asarray(ss.C), float(dt), hold
    )


def fit_state_space(
    t: ArrayLike,
    K: ArrayLike,
    *,
    order: int | None = None,
    tol: float = 1e-2,
    target_error: float = 5e-3,
    max_order: int = 12,
    pairs: Any = None,
    zero_tol: float = 1e-5,
    hankel_size: int = 60,
    dt_fit: float | None = None,
    zero_dc: bool = False,
    nonnegative_damping: bool = False,
    damping_omega: ArrayLike | None = None,
) -> StateSpaceRadiation:
    """Fit a stable state-space realisation to a matrix of kernels K(t).

    Parameters
    ----------
    t : array_like, shape (n_t,)
        Uniform times from 0 [s].
    K : array_like, shape (n_t,) or (n_t, p, m)
        Velocity kernel with axes (t, output, input) [units of K] (see *Layout* in the module
        docstring; for a capytaine-ordered database swap the last two axes).
    order : int, optional
        Fixed ERA order for every non-zero pair; automatic (Hankel singular values > ``tol``,
        raised to meet ``target_error``) when None.
    tol : float
        Threshold on normalised Hankel singular values σₖ/σ₁ [-].
    target_error : float
        Relative L2 error per pair the automatic order aims for [-].
    max_order : int
        Largest ERA order per pair.
    pairs : iterable of (int, int), optional
        Pairs to fit; the others are set to zero. Default: all non-negligible pairs.
    zero_tol : float
        A pair with max|Kᵢⱼ| ≤ zero_tol·√(max|Kᵢᵢ|·max|Kⱼⱼ|) (square K) or ≤ zero_tol·max|K|
        gets order 0 [-].
    hankel_size, dt_fit
        ERA sampling (see :func:`fit_kernel`).
    zero_dc : bool
        B_fit(0) = ∫₀^∞ K_fit dt = 0 for every fitted pair (see :func:`fit_kernel`).
    nonnegative_damping : bool
        B_ii,fit(ω) ≥ 0 on ``damping_omega`` for the diagonal pairs i = j (square K only).
    damping_omega : array_like, optional
        Grid of that constraint [rad/s] (default (0, 3] rad/s, 600 points).

    Returns
    -------
    StateSpaceRadiation
    """
    kk = np.asarray(K, dtype=float)
    if kk.ndim == 1:
        kk = kk[:, None, None]
    if kk.ndim != 3:
        raise ValueError(f"K has shape {kk.shape}; expected (n_t,) or (n_t, p, m)")
    tt, kk = _check_kernel_grid(t, kk)
    if not zero_tol >= 0:
        raise ValueError(f"zero_tol={zero_tol!r}; expected a non-negative ratio")
    _, p, m = kk.shape
    peak = np.max(np.abs(kk), axis=0)
    if p == m:
        d = np.diag(peak)
        scale = np.sqrt(np.outer(d, d))
    else:
        scale = np.full(peak.shape, peak.max())
    active = (peak > zero_tol * scale) & (peak > 1e-12 * peak.max()) & (peak > 0)
    if pairs is not None:
        chosen = np.zeros_like(active)
        for pair in pairs:
            i, j = (int(q) for q in pair)
            if not (0 <= i < p and 0 <= j < m):
                raise ValueError(f"pair {pair!r} is outside the kernel matrix of shape {(p, m)}")
            chosen[i, j] = True
        active &= chosen
    fits: list[ModalFit] = []
    orders = np.zeros((p, m), dtype=np.int64)
    errors = np.zeros((p, m))
    for i in range(p):
        for j in range(m):
            if not active[i, j]:
                continue
            fit = fit_kernel(
                tt,
                kk[:, i, j],
                order=order,
                tol=tol,
                target_error=target_error,
                max_order=max_order,
                hankel_size=hankel_size,
                dt_fit=dt_fit,
                output=i,
                input=j,
                zero_dc=zero_dc,
                nonnegative_damping=nonnegative_damping and p == m and i == j,
                damping_omega=damping_omega,
            )
            fits.append(fit)
            orders[i, j] = fit.order
            errors[i, j] = fit.fit_error
    n = int(orders.sum())
    a = np.zeros((n, n))
    b = np.zeros((n, m))
    c = np.zeros((p, n))
    k0 = 0
    for fit in fits:
        af, bf, cf = fit.matrices()
        r = fit.order
        a[k0 : k0 + r, k0 : k0 + r] = af
        b[k0 : k0 + r, fit.input] = bf
        c[fit.output, k0 : k0 + r] = cf
        k0 += r
    return StateSpaceRadiation(
        A=a, B=b, C=c, D=np.zeros((p, m)), orders=orders, fit_error=errors, fits=tuple(fits)
    )


def frequency_fit_error(
    ss: StateSpaceRadiation,
    omega: ArrayLike,
    added_mass: ArrayLike,
    damping: ArrayLike,
    added_mass_inf: ArrayLike,
    *,
    floor: float = 1e-2,
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Relative RMS error of the realisation's A(ω) − A(∞) and B(ω) against a database.

    Parameters
    ----------
    ss : StateSpaceRadiation
        Fitted system (axes (output, input)).
    omega : array_like, shape (n_omega,)
        Frequencies ω > 0 [rad/s].
    added_mass, damping : array_like, shape (n_omega, p, m)
        Database A(ω) [units of A] and B(ω) [units of B], in the (output, input) layout.
    added_mass_inf : array_like, shape (p, m)
        A(∞).
    floor : float
        Relative floor of the denominator (see
        :func:`ship_gym.hydro.retardation.relative_pair_error`).

    Returns
    -------
    added_mass_error, damping_error : ndarray, shape (p, m)
        Relative RMS errors per pair [-].
    """
    w = np.asarray(omega, dtype=float).reshape(-1)
    a = np.asarray(added_mass, dtype=float)
    b = np.asarray(damping, dtype=float)
    a_inf = np.asarray(added_mass_inf, dtype=float)
    shape = (w.size, ss.n_outputs, ss.n_inputs)
    if a.shape != shape or b.shape != shape or a_inf.shape != shape[1:]:
        raise ValueError(
            f"added_mass {a.shape}, damping {b.shape}, added_mass_inf {a_inf.shape}; expected "
            f"{shape}, {shape}, {shape[1:]}"
        )
    da, bb = ss.frequency_response(w)
    return (
        relative_pair_error(a - a_inf, da, floor=floor),
        relative_pair_error(b, bb, floor=floor),
    )
