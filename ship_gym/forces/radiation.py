"""Linear radiation forces from a zero-speed frequency-domain database (Cummins form).

Perturbation velocity
---------------------
Radiation is linearised about steady straight-ahead motion at the forward speed U
(``ForceContext.forward_speed``): the models act on the perturbation velocity

    ν_p = ν − (U, 0, 0, 0, 0, 0)                [m/s, rad/s], body axes.

The database is a **zero-speed** BEM database (``attrs["forward_speed"] = 0``). The memory model
takes it to speed by the linearisation of :mod:`ship_gym.hydro.forward_speed`: body-axis ν_p
(the relative normal velocity, ν_p = ẋ + U L x) and Kirchhoff's moment u Lᵀ(A(∞) E ν_p + λ) of
the radiated momentum — Salvesen–Tuck–Faltinsen's forward-speed terms without end terms, with
the zero-speed kernels (no speed-dependent kernels or fits), high-passed below ω_c
(``speed_cutoff``, its eq. 5: two more states) so that the steady momentum has no moment; the
diffraction model adds the same moment of the scattered flow's momentum (its eq. 4). The
constant-coefficient model (Matusiak's case 2) keeps its zero-speed coefficients at the
encounter frequency, without that moment.

Sign conventions (DESIGN.md §3, :mod:`ship_gym.hydro.retardation`)
-----------------------------------------------------------------
Arrays from :func:`ship_gym.hydro.database.as_arrays` are used in the layout
``added_mass[ω, i, j]``, ``radiation_damping[ω, i, j]``: i the *influenced* DOF (force, output),
j the *radiating* DOF (velocity, input), i.e. dims (omega, influenced_dof, radiating_dof). The
kernels K[t, i, j] = (2/π)∫₀^∞ B_ij(ω) cos ωt dω (Matusiak eq. 16) then have the (t, output,
input) layout of :func:`ship_gym.hydro.state_space.fit_state_space` without any swap.

Cummins / Matusiak eq. 15 with Kring–Huang–Sclavounos' split (their eq. 3):

    F_rad(t) = −A(∞) ν̇(t) − μ(t),      μ(t) = ∫₀^t K(t − τ) ν_p(τ) dτ,

A(∞) going to the left-hand side (:attr:`ForceModel.added_mass`). For a harmonic motion
ν_p = Re(V̂ e^{−iωt}) (capytaine's time convention) the steady state of μ is

    μ(t) = Re{ ∫₀^∞ K(s) e^{iωs} ds · V̂ e^{−iωt} } = Re{ [B(ω) − iω(A(ω) − A(∞))] V̂ e^{−iωt} }

by Ogilvie's relations B(ω) = ∫₀^∞ K cos ωs ds, ω[A(∞) − A(ω)] = ∫₀^∞ K sin ωs ds; then
F_rad = Re{(iωA(ω) − B(ω)) V̂ e^{−iωt}} = −A(ω) ν̇ − B(ω) ν, the frequency-domain force.

Models
------
:class:`RadiationMemory`
    Matusiak's case 1 (memory). ``method="convolution"`` is the reference path (trapezoidal
    convolution over a stored velocity history); ``method="state_space"`` (default) replaces
    the convolution by a fitted stable linear system integrated with the ship. A(∞) goes to the
    left-hand side (:attr:`RadiationMemory.added_mass`; Holloway's alternative of lumping it into
    the force, his eq. 10, is studied on his oscillator in :mod:`ship_gym.analysis.holloway`).
:class:`ConstantCoefficientRadiation`
    Matusiak's case 2 (his eq. 13–14): constant A and B, no memory.
"""

from __future__ import annotations

import hashlib
import math
import warnings
from collections.abc import Mapping
from typing import Any, Literal, NamedTuple

import numba as nb
import numpy as np
import xarray as xr
from numpy.typing import ArrayLike, NDArray
from scipy.interpolate import CubicSpline

from ship_gym.conventions import GRAVITY, HEAVE, N_DOF, PITCH, ROLL, SURGE, SWAY, YAW
from ship_gym.forces.base import ForceContext, ForceModel
from ship_gym.hydro.database import HydroArrays, as_arrays
from ship_gym.hydro.forward_speed import (
    MOMENT_ROWS,
    SURGE_FREE,
    SpeedTerms,
    check_speed_cutoff,
    check_speed_terms,
    momentum_rows,
)
from ship_gym.hydro.retardation import (
    KernelDecay,
    Method,
    ReconstructionError,
    RetardationKernels,
    Tail,
    compute_kernels,
    kernel_decay,
    reconstruction_error,
)
from ship_gym.hydro.state_space import StateSpaceRadiation, fit_state_space, frequency_fit_error
from ship_gym.waves.sea_state import encounter_frequency as _encounter_frequency

__all__ = [
    "DEFAULT_FIT_OPTIONS",
    "ConstantCoefficientRadiation",
    "RadiationMemory",
    "perturbation_velocity",
    "roll_natural_frequency",
    "speed_momentum_rows",
]

MemoryMethod = Literal["state_space", "convolution"]
Case = Literal["2a", "2b"]
Interpolation = Literal["cubic", "linear"]

DEFAULT_FIT_OPTIONS: dict[str, Any] = {
    "target_error": 5e-3,
    "max_order": 12,
    "tol": 1e-2,
    "zero_tol": 1e-3,
    "zero_dc": True,
    "nonnegative_damping": True,
}
"""Default options of :func:`ship_gym.hydro.state_space.fit_state_space` used here.

``zero_tol = 1e-3`` drops the pairs that vanish by port–starboard symmetry but carry BEM
round-off (≈ 2e-5 of the diagonal scale for the S175), which would otherwise get 8–12 states
each. ``zero_dc`` imposes B_fit(0) = ∫K_fit dt = 0 and ``nonnegative_damping`` B_ii,fit(ω) ≥ 0
on 0–3 rad/s. ``target_error = 5e-3`` (relative L2 error of K per pair, ≤ 12 states per pair)
gives 124 states for the S175 with the default asymptotic kernel tail (the fit's A(ω) − A(∞)
within 0.7 % heave, 0.9 % roll, 1.1 % pitch and 1.8 % heave–pitch of the database, relative
RMS; 140 states with the single-power tail). With the power tail, ``max_order = 6`` gave 102
states with similar memory errors but moved the 135° pitch RAO of the linear-limit test from
1.9 % to 2.4 %, and 4 per pair (72 states) lost the roll memory (31 %).
"""

_FIT_DT = 0.05
"""Kernel grid [s] of the state-space fit."""

_CACHE: dict[tuple, Any] = {}
_CACHE_SIZE = 16


def _cached(key: tuple, build: Any) -> Any:
    """Kernels / state-space fits, built once per process.

    Built with one BLAS thread: a multithreaded SVD or least-squares solve rounds differently,
    and a fit that depended on the thread count of the process that first built it would make
    otherwise identical runs (a serial and a joblib-parallel capsize map, a subprocess) differ
    in the last bits, which a long nonlinear run amplifies.
    """
    if key not in _CACHE:
        from threadpoolctl import threadpool_limits

        if len(_CACHE) >= _CACHE_SIZE:
            _CACHE.pop(next(iter(_CACHE)))
        with threadpool_limits(limits=1, user_api="blas"):
            _CACHE[key] = build()
    return _CACHE[key]


def _digest(*arrays: NDArray) -> str:
    h = hashlib.sha1()
    for a in arrays:
        h.update(np.ascontiguousarray(a, dtype=float).tobytes())
    return h.hexdigest()


def _hydro_arrays(database: xr.Dataset | HydroArrays) -> HydroArrays:
    if isinstance(database, HydroArrays):
        return database
    if isinstance(database, xr.Dataset):
        speed = float(database.attrs.get("forward_speed", 0.0))
        if speed != 0.0:
            warnings.warn(
                f"database attrs['forward_speed'] = {speed} m/s; the radiation models assume a "
                "zero-speed database and add the forward-speed terms themselves (they would be "
                "counted twice)",
                RuntimeWarning,
                stacklevel=3,
            )
        return as_arrays(database)
    raise ValueError(
        f"database must be an xarray.Dataset (ship_gym.hydro.load_database) or HydroArrays; "
        f"got {type(database).__name__}"
    )


def _check_positive(name: str, value: float) -> float:
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name}={value!r}; expected a positive number") from None
    if not (math.isfinite(v) and v > 0.0):
        raise ValueError(f"{name}={value!r}; expected a finite positive number")
    return v


def _vector6(name: str, value: ArrayLike | None) -> NDArray[np.float64]:
    if value is None:
        raise ValueError(f"{name} is None; expected a (6,) array")
    v = np.asarray(value, dtype=float)
    if v.shape != (N_DOF,):
        raise ValueError(f"{name} has shape {v.shape}; expected (6,)")
    return v


def perturbation_velocity(ctx: ForceContext) -> NDArray[np.float64]:
    """ν_p = ν − (U, 0, 0, 0, 0, 0) [m/s, rad/s] with U = ``ctx.forward_speed`` [m/s]."""
    v = _vector6("ctx.nu", ctx.nu).copy()
    v[SURGE] -= float(ctx.forward_speed)
    return v


def speed_momentum_rows(
    a_inf: ArrayLike, a: ArrayLike, b: ArrayLike, c: ArrayLike, speed_terms: SpeedTerms = "all"
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Pitch and yaw rows of Lᵀ A(∞) (2, 6) and of Lᵀ C A⁻¹ (2, n) for a state-space memory.

    With ż = A z + B ν_p, μ = C z and z(0) = 0, λ = C A⁻¹ z has λ̇ = μ + C A⁻¹ B ν_p = μ − K̂(0)
    ν_p, K̂(0) = ∫K dt = B_fit(0) (zero when the fit imposes it): the momentum of eq. (2) of
    :mod:`ship_gym.hydro.forward_speed` without states of its own; the surge input's share of
    the momentum is left out (its E).
    """
    a_mat = np.asarray(a, dtype=float)
    b_mat = np.asarray(b, dtype=float)
    c_mat = np.asarray(c, dtype=float)
    lam = np.linalg.solve(a_mat.T, c_mat.T).T if a_mat.size else np.zeros((N_DOF, 0))
    # leave out the momentum of the surge input (the E of ship_gym.hydro.forward_speed): A is
    # block-diagonal, so λ of the states of blocks driven by surge is λ's surge part
    lam = lam * (state_inputs(a_mat, b_mat) != SURGE)[None, :]
    return momentum_rows(np.asarray(a_inf) * SURGE_FREE, speed_terms), momentum_rows(
        lam, speed_terms
    )


def state_inputs(a: ArrayLike, b: ArrayLike) -> NDArray[np.int64]:
    """Input (velocity component) driving each state of a block-diagonal realisation (n,).

    States coupled through A form a block; a block's input is the one column of B that is
    non-zero on it (−1 for a block without input).

    Raises
    ------
    ValueError
        If a block is driven by more than one input (not a per-pair realisation).
    """
    a_mat, b_mat = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
    n = a_mat.shape[0]
    out = np.full(n, -1, dtype=np.int64)
    seen = np.zeros(n, dtype=bool)
    coupled = (a_mat != 0.0) | (a_mat.T != 0.0)
    for start in range(n):
        if seen[start]:
            continue
        block, stack = [], [start]
        seen[start] = True
        while stack:
            k = stack.pop()
            block.append(k)
            for m in np.flatnonzero(coupled[k] & ~seen):
                seen[m] = True
                stack.append(int(m))
        inputs = np.flatnonzero(np.any(b_mat[block] != 0.0, axis=0))
        if inputs.size > 1:
            raise ValueError(f"states {sorted(block)} are driven by inputs {inputs.tolist()}")
        out[block] = inputs[0] if inputs.size else -1
    return out


# ============================================================================================
# memory model (Matusiak case 1)
# ============================================================================================
class RadiationMemory(ForceModel):
    """Radiation memory force of Cummins' equation (Matusiak eq. 15–16), Kring–Sclavounos form.

    ``added_mass`` = A(∞) is moved to the left-hand side (Kring–Huang–Sclavounos eq. 3) and
    the force is −μ(t), μ(t) = ∫₀^t K(t − τ) ν_p(τ) dτ (Matusiak eq. 15), ν_p the perturbation
    velocity (module docstring). The motion is taken to start at the reset time t₀ (ν_p = 0
    before), for both methods.

    Kernels come from :func:`ship_gym.hydro.retardation.compute_kernels` (Filon quadrature,
    Gourlay eq. 4–10) up to ``t_max`` and are truncated there; :attr:`decay` reports how far
    they have decayed (a ``RuntimeWarning`` is issued when a pair keeps more than 1 % of its
    peak in the last 5 % of the window) and :attr:`ogilvie_error` how well the kernels
    reproduce the database A(ω), B(ω) (Ogilvie's relations).

    High-frequency tail: ``tail="asymptotic"`` with ``tail_exponent="fit"`` (default) extends
    B(ω) beyond ω_max by the first two terms of its inverse-power series,
    B(ω_max)[a(ω_max/ω)ⁿ + (1 − a)(ω_max/ω)ⁿ⁺²], n fitted per pair (2 for all S175 pairs but
    sway–roll) and a on the last grid points (:mod:`ship_gym.hydro.retardation`). Chosen from the
    S175's own kernels (docs/kernel_tails.md): the reconstructed A(ω) − A(∞) is within 0.4–3.2 %
    of the database per pair (sway–roll 14 %), against 0.5–4.6 % (15 %) with the single power
    ``tail="power"``; for a B with such a series the K(0) truncation error is O(ω_max⁻ⁿ⁻³) instead
    of O(ω_max⁻³). The S175 grid stops at 1.67 rad/s, where B is still 22–73 % of its peak, so
    its kernels carry a truncation uncertainty of ±14 % in K(0) at heave–pitch (heave ±1 %, roll
    ±2 %, pitch ±8 %), which only a database run to higher frequency removes.

    Methods
    -------
    ``"convolution"`` (reference)
        ν_p is stored on accepted steps (:meth:`commit`, uniform spacing ``dt``; anything else
        raises) in a ring buffer of the last N = t_max/dt + 1 samples. At t = t_n + h,
        0 ≤ h ≤ dt (a Runge–Kutta stage time, with the *current* stage velocity ``ctx.nu``),
        the trapezoidal rule is applied on the committed nodes and on the partial interval
        [t_n, t]::

            μ(t) ≈ Σ_{k<n} (dt/2)[K(t − t_k) v_k + K(t − t_{k+1}) v_{k+1}]
                   + (h/2)[K(h) v_n + K(0) v(t)],

        truncated where t − t_k > t_max (at h = 0 the newest node takes the current velocity,
        equal to v_n for any integrator that evaluates at the committed state). The kernel is
        needed at the shifted offsets s_j = h + j·dt: it is computed by Filon on the grid
        dt/``kernel_refinement`` (default dt/2) and interpolated by a cubic spline, so h = 0,
        dt/2 and dt fall on exact kernel nodes (no interpolation error) and any other h is
        spline-accurate (O(Δt⁴)). The weighted shifted kernels are cached per h (an RK4 step
        uses three: 0, dt/2, dt), and an evaluation is one (6 × 6N) matrix–vector product over
        the ring buffer: O(36 N).
        The evaluation at h = dt before a commit equals the one at h = 0 after committing the
        same velocity, to rounding.
    ``"state_space"`` (fast, default)
        A stable realisation ż = A z + B ν_p, μ = C z + D ν_p (D = 0) fitted once to K by
        :func:`ship_gym.hydro.state_space.fit_state_space` (options
        :data:`DEFAULT_FIT_OPTIONS`, kernel grid 0.05 s) and cached per database and options.
        The model has :attr:`n_states` = order states; :meth:`evaluate` returns
        (−(C z + D ν_p), A z + B ν_p). The caller integrates the states (initial value
        :meth:`initial_states` = 0) and resets them.

    Parameters
    ----------
    database : xarray.Dataset or HydroArrays
        Zero-speed database with A(ω), B(ω) and A(∞) (``ship_gym.hydro.load_database``).
    method : {"state_space", "convolution"}
        Evaluation path.
    dt : float, optional
        Time step of the committed history [s]; required for ``"convolution"``, unused by
        ``"state_space"``.
    t_max : float
        Kernel truncation time [s]; for the convolution it is rounded to a multiple of dt.
    tail : {"asymptotic", "power", "none", "taper"}
        High-frequency treatment of B(ω) (:mod:`ship_gym.hydro.retardation`).
    tail_exponent : int or "fit"
        Exponent n of the leading tail term B ∝ ω⁻ⁿ.
    quadrature : {"filon", "simpson", "trapezoid", "fft"}
        Kernel quadrature (default Filon, Gourlay eq. 4–10).
    kernel_refinement : int
        Kernel grid = dt / kernel_refinement for the convolution (≥ 1; 2 makes h = dt/2 exact).
    fit_options : mapping, optional
        Overrides of :data:`DEFAULT_FIT_OPTIONS` (state-space path).
    commit_tolerance : float
        Allowed deviation of commit and evaluation times from the uniform grid, as a fraction
        of dt [-].
    speed_terms : {"all", "vertical", "none"}
        Planes of the forward-speed Kirchhoff moment (:mod:`ship_gym.hydro.forward_speed`).
    speed_cutoff : float
        ω_c [rad/s] of that moment's high-pass (:mod:`ship_gym.hydro.forward_speed` eq. 5); > 0
        adds two states after the memory's (:attr:`n_filter_states`); 0: no high-pass.

    Attributes
    ----------
    A_inf : numpy.ndarray
        (6, 6) infinite-frequency added mass [kg, kg·m, kg·m²].
    kernels : RetardationKernels
        Kernels K[t, i, j] (output i, input j) on the kernel grid.
    decay : KernelDecay
        Truncation report of K at t_max.
    ogilvie_error : ReconstructionError
        Relative RMS errors per pair of A(ω) − A(∞) and B(ω) reconstructed from K.
    state_space : StateSpaceRadiation or None
        The fitted system (``"state_space"`` only).
    order : int
        Number of states (0 for the convolution).
    fit_error : numpy.ndarray or None
        (6, 6) relative L2 error of the fitted K per pair (time domain) [-].
    frequency_error : tuple of numpy.ndarray or None
        (6, 6) relative RMS errors of the fit's A(ω) − A(∞) and B(ω) against the database [-].
    momentum_added_mass, momentum_memory : numpy.ndarray
        (2, 6) and (2, n_memory): the pitch and yaw rows of Kirchhoff's moment per unit surge
        velocity, on ν_p and on the states (:func:`speed_momentum_rows`;
        :mod:`ship_gym.hydro.forward_speed` eq. 2).
    """

    name = "radiation"

    def __init__(
        self,
        database: xr.Dataset | HydroArrays,
        *,
        method: MemoryMethod = "state_space",
        dt: float | None = None,
        t_max: float = 60.0,
        tail: Tail = "asymptotic",
        tail_exponent: int | Literal["fit"] = "fit",
        quadrature: Method = "filon",
        kernel_refinement: int = 2,
        fit_options: Mapping[str, Any] | None = None,
        commit_tolerance: float = 1e-6,
        speed_terms: SpeedTerms = "all",
        speed_cutoff: float = 0.0,
    ) -> None:
        if method not in ("state_space", "convolution"):
            raise ValueError(f"method={method!r}; expected 'state_space' or 'convolution'")
        self.speed_terms: SpeedTerms = check_speed_terms(speed_terms)
        self.speed_cutoff: float = check_speed_cutoff(speed_cutoff)
        self.n_filter_states: int = 2 if self.speed_cutoff > 0.0 else 0
        """States of the Kirchhoff moment's high-pass (the last ones; 0 without it)."""
        h = _hydro_arrays(database)
        if h.added_mass_infinite is None:
            raise ValueError(
                "database has no infinite-frequency added mass A(∞) (omega = inf entry); the "
                "memory model needs it on the left-hand side"
            )
        self.method: str = method
        self.A_inf: NDArray[np.float64] = np.array(h.added_mass_infinite, dtype=float)
        self.added_mass = self.A_inf
        t_max = _check_positive("t_max", t_max)
        self._tol = _check_positive("commit_tolerance", commit_tolerance)
        key_base = (
            _digest(h.omega, h.added_mass, h.radiation_damping, self.A_inf),
            str(tail),
            str(tail_exponent),
            str(quadrature),
        )

        def kernels_on(grid: float, window: float) -> RetardationKernels:
            return _cached(
                ("kernels", *key_base, grid, window),
                lambda: compute_kernels(
                    h.omega,
                    h.added_mass,
                    h.radiation_damping,
                    self.A_inf,
                    t_max=window,
                    dt=grid,
                    method=quadrature,
                    tail=tail,
                    tail_exponent=tail_exponent,
                ),
            )

        self.state_space: StateSpaceRadiation | None = None
        self.fit_error: NDArray[np.float64] | None = None
        self.frequency_error: tuple[NDArray[np.float64], NDArray[np.float64]] | None = None
        self.order: int = 0
        self.dt: float | None = None
        if method == "convolution":
            if dt is None:
                raise ValueError("method='convolution' needs dt, the committed time step [s]")
            self.dt = self._dt = _check_positive("dt", dt)
            if int(kernel_refinement) != kernel_refinement or kernel_refinement < 1:
                raise ValueError(
                    f"kernel_refinement={kernel_refinement!r}; expected an integer ≥ 1"
                )
            self._refine = int(kernel_refinement)
            n_steps = max(2, round(t_max / self.dt))
            self.kernels = kernels_on(self.dt / self._refine, n_steps * self.dt)
            self._setup_convolution(n_steps)
            # λ (heave and sway components) integrated as two states: λ̇ = μ
            self.n_states = 2 + self.n_filter_states
            select = np.zeros((N_DOF, 2))
            select[HEAVE, 0] = select[SWAY, 1] = 1.0
            self.momentum_added_mass = momentum_rows(self.A_inf * SURGE_FREE, speed_terms)
            self.momentum_memory = momentum_rows(select, speed_terms)
        else:
            self.kernels = kernels_on(_FIT_DT, t_max)
            opts = dict(DEFAULT_FIT_OPTIONS)
            if fit_options is not None:
                opts.update(fit_options)
            key = ("fit", *key_base, _FIT_DT, t_max, tuple(sorted(opts.items())))
            self.state_space = _cached(
                key, lambda: fit_state_space(self.kernels.t, self.kernels.K, **opts)
            )
            ss = self.state_space
            self.order = ss.order
            self.n_states = ss.order + self.n_filter_states
            self.fit_error = np.asarray(ss.fit_error)
            self.frequency_error = frequency_fit_error(
                ss, h.omega, h.added_mass, h.radiation_damping, self.A_inf
            )
            self._A = np.ascontiguousarray(ss.A)
            self._B = np.ascontiguousarray(ss.B)
            self._C = np.ascontiguousarray(ss.C)
            self._D = np.ascontiguousarray(ss.D)
            self._has_d = bool(np.any(self._D != 0.0))
            self.momentum_added_mass, self.momentum_memory = speed_momentum_rows(
                self.A_inf, ss.A, ss.B, ss.C, speed_terms
            )
        self.decay: KernelDecay = kernel_decay(self.kernels.t, self.kernels.K)
        if not self.decay.all_decayed:
            worst = float(np.max(self.decay.ratio))
            warnings.warn(
                f"radiation kernels have not decayed at t_max = {self.kernels.t[-1]:g} s: "
                f"the last 5 % of the window still holds {worst:.3g} of the peak |K| "
                f"(> {self.decay.threshold}); increase t_max",
                RuntimeWarning,
                stacklevel=2,
            )
        self.ogilvie_error: ReconstructionError = reconstruction_error(
            self.kernels.t,
            self.kernels.K,
            h.omega,
            h.added_mass,
            h.radiation_damping,
            self.A_inf,
        )
        self._empty = np.zeros(0)

    # ------------------------------------------------------------------ convolution set-up
    def _setup_convolution(self, n_steps: int) -> None:
        kern = self.kernels
        self._n_kernel = n_steps + 1  # nodes s = 0, dt, …, t_max
        self.t_max: float = n_steps * self._dt
        self._k_fine = np.ascontiguousarray(kern.K)
        self._spline = CubicSpline(kern.t, kern.K, axis=0)
        self._k0 = self._k_fine[0].copy()
        self._shift_cache: dict[int, tuple[NDArray, NDArray, int]] = {}
        self._buffer = np.zeros((2 * self._n_kernel, N_DOF))
        self._count = -1  # number of committed intervals; −1 before reset
        self._t0 = 0.0
        self._v_first = np.zeros(N_DOF)

    def kernel_at(self, s: ArrayLike) -> NDArray[np.float64]:
        """K(s) [kg/s², …] at offsets s [s] (cubic spline of the kernel grid, 0 beyond t_max).

        Returns an array of shape ``s.shape + (6, 6)`` with axes (output i, input j).
        """
        ss = np.asarray(s, dtype=float)
        if not hasattr(self, "_spline"):
            raise ValueError("kernel_at is available for method='convolution' only")
        out = self._spline(np.clip(ss, 0.0, self.t_max))
        return np.where(((ss >= 0) & (ss <= self.t_max * (1 + 1e-12)))[..., None, None], out, 0.0)

    def _shifted(self, h: float) -> tuple[NDArray, NDArray, int]:
        """(flattened weighted kernel (6, 6N), shifted kernel (N, 6, 6), last used node J)."""
        dt = self._dt
        key = round(h / dt * 1e9)
        hit = self._shift_cache.get(key)
        if hit is not None:
            return hit
        n = self._n_kernel
        r = self._refine
        fine = h / dt * r
        m = round(fine)
        if abs(fine - m) < 1e-9:  # h on a kernel node: exact samples, no interpolation
            ks = np.zeros((n, N_DOF, N_DOF))
            nodes = self._k_fine[m::r]
            ks[: nodes.shape[0]] = nodes[:n]
        else:
            ks = self.kernel_at(h + dt * np.arange(n))
        last = n - 1 if h == 0.0 else n - 2  # last node with s = h + j·dt ≤ t_max
        ks[last + 1 :] = 0.0
        w = np.full(n, dt)
        w[0] = 0.5 * dt + 0.5 * h
        w[last] = 0.5 * dt
        w[last + 1 :] = 0.0
        weighted = (w[:, None, None] * ks)[::-1]  # chronological: oldest first
        flat = np.ascontiguousarray(weighted.transpose(1, 0, 2).reshape(N_DOF, -1))
        if len(self._shift_cache) >= 16:
            self._shift_cache.clear()
        self._shift_cache[key] = (flat, ks, last)
        return flat, ks, last

    # ------------------------------------------------------------------ protocol
    def initial_states(self) -> NDArray[np.float64]:
        """Zero memory states (ship at rest relative to U before t₀), length :attr:`n_states`."""
        return np.zeros(self.n_states)

    def reset(self, t0: float, ctx: ForceContext) -> None:
        """Forget the history; the convolution stores ν_p(t₀) of ``ctx`` as its first sample.

        The state-space states are reset by the caller (:meth:`initial_states`).
        """
        if self.method != "convolution":
            return
        if not math.isfinite(float(t0)):
            raise ValueError(f"t0={t0!r}; expected a finite time [s]")
        self._buffer[:] = 0.0
        self._count = 0
        self._t0 = float(t0)
        v = perturbation_velocity(ctx)
        self._write(0, v)
        self._v_first = v

    def _write(self, count: int, v: NDArray[np.float64]) -> None:
        p = count % self._n_kernel
        self._buffer[p] = v
        self._buffer[p + self._n_kernel] = v

    def commit(self, ctx: ForceContext, states: NDArray[np.float64]) -> None:
        """Store ν_p at the end of an accepted step (convolution only).

        Commits must be spaced by exactly ``dt`` (to ``commit_tolerance``·dt); a commit at the
        time of the last sample replaces it.

        Raises
        ------
        ValueError
            If the model was not reset, or ``ctx.t`` is neither t_n nor t_n + dt.
        """
        if self.method != "convolution":
            return
        self._require_reset()
        dt = self._dt
        t_last = self._t0 + self._count * dt
        t = float(ctx.t)
        if abs(t - t_last) <= self._tol * dt:
            count = self._count
        elif abs(t - (t_last + dt)) <= self._tol * dt:
            count = self._count + 1
        else:
            raise ValueError(
                f"commit at t = {t!r} s, but the convolution history needs uniform steps of "
                f"dt = {dt} s: expected t = {t_last + dt!r} s (last sample at {t_last!r} s)"
            )
        v = perturbation_velocity(ctx)
        self._write(count, v)
        self._count = count
        if count == 0:
            self._v_first = v

    def _require_reset(self) -> None:
        if self._count < 0:
            raise ValueError("the convolution history is empty: call reset(t0, ctx) first")

    def _memory_convolution(
        self, ctx: ForceContext, v: NDArray[np.float64]
    ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """μ at ``ctx.t`` and the share of μ due to the surge input (both (6,))."""
        self._require_reset()
        dt = self._dt
        t_n = self._t0 + self._count * dt
        h = float(ctx.t) - t_n
        if h < -self._tol * dt or h > dt * (1.0 + self._tol):
            raise ValueError(
                f"evaluation at t = {ctx.t!r} s is outside the step [t_n, t_n + dt] = "
                f"[{t_n!r}, {t_n + dt!r}] s after the last commit; the convolution evaluates "
                "only within one step of its history"
            )
        h = min(max(h, 0.0), dt)
        if self._count == 0 and h == 0.0:
            return np.zeros(N_DOF), np.zeros(N_DOF)  # empty integral at t = t₀
        flat, ks, last = self._shifted(h)
        n = self._n_kernel
        p = self._count % n
        window = self._buffer[p + 1 : p + 1 + n].reshape(-1)
        v_n = self._buffer[p]
        # μ, and the share of the surge input (column SURGE of every kernel sample, the
        # window's surge entries): the same quadrature on one input
        parts = []
        for columns in (slice(None), slice(SURGE, None, N_DOF)):
            mu = flat[:, columns] @ window[columns]
            pick = slice(None) if columns == slice(None) else slice(SURGE, SURGE + 1)
            k0, vv, vn, vf = self._k0[:, pick], v[pick], v_n[pick], self._v_first[pick]
            if h == 0.0:
                if self._count > 0:  # use the current velocity at the newest node
                    mu = mu + (0.5 * dt) * (k0 @ (vv - vn))
            else:
                mu = mu + (0.5 * h) * (k0 @ vv)
            if self._count < last:  # the first sample is an end node of the trapezoid
                mu = mu - (0.5 * dt) * (ks[self._count][:, pick] @ vf)
            parts.append(mu)
        return parts[0], parts[1]

    def evaluate(
        self, ctx: ForceContext, states: NDArray[np.float64]
    ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Memory force −μ and the state derivatives.

        Parameters
        ----------
        ctx : ForceContext
            Uses ``t`` [s], ``nu`` [m/s, rad/s] and ``forward_speed`` [m/s].
        states : numpy.ndarray
            (n_states,) memory states z (state-space path; ignored by the convolution).

        Returns
        -------
        force : numpy.ndarray
            (6,) [N, N·m], body axes, about O.
        states_dot : numpy.ndarray
            (n_states,) ż = A z + B ν_p (empty for the convolution).
        """
        v = perturbation_velocity(ctx)
        z_all = np.asarray(states, dtype=float)
        if z_all.shape != (self.n_states,):
            raise ValueError(f"states has shape {z_all.shape}; expected ({self.n_states},)")
        n_memory = self.n_states - self.n_filter_states
        z, z_filter = z_all[:n_memory], z_all[n_memory:]
        if self.method == "convolution":
            mu, mu_surge = self._memory_convolution(ctx, v)
            force = -mu
            memory_dot = (mu - mu_surge)[[HEAVE, SWAY]]  # λ̇: the memory of all but surge
        else:
            force = -(self._C @ z)
            memory_dot = self._A @ z + self._B @ v
            if self._has_d:
                force -= self._D @ v
        # Kirchhoff's moment of the radiated momentum, high-passed when a cut-off is set
        # (ship_gym.hydro.forward_speed eq. 2 and 5)
        moment = self.momentum_added_mass @ v + self.momentum_memory @ z
        if self.n_filter_states:
            moment = moment - z_filter
            memory_dot = np.concatenate([memory_dot, self.speed_cutoff * moment])
        u = float(ctx.nu[SURGE])  # the ship's own surge velocity (= U to first order)
        if u != 0.0:
            force[list(MOMENT_ROWS)] += u * moment
        return force, memory_dot


# ============================================================================================
# constant coefficients (Matusiak case 2)
# ============================================================================================
def _interpolator(omega: NDArray[np.float64], values: NDArray[np.float64], kind: str) -> Any:
    if kind == "cubic":
        return CubicSpline(omega, values, axis=0)
    if kind == "linear":

        def lin(w: float) -> NDArray[np.float64]:
            flat = values.reshape(omega.size, -1)
            return np.array([np.interp(w, omega, col) for col in flat.T]).reshape(values.shape[1:])

        return lin
    raise ValueError(f"interpolation={kind!r}; expected 'cubic' or 'linear'")


def roll_natural_frequency(
    database: xr.Dataset | HydroArrays,
    *,
    interpolation: Interpolation = "cubic",
    tol: float = 1e-10,
    max_iter: int = 200,
) -> float:
    """Undamped roll natural frequency ω_φ = √(C44 / (I44 + A44(ω_φ))) by fixed-point iteration.

    Starts from ω = √(C44/(I44 + A44(∞))) (or the middle of the frequency range when A(∞) is
    missing) and iterates ω ← √(C44/(I44 + A44(ω))) with A44 interpolated in ω.

    Parameters
    ----------
    database : xarray.Dataset or HydroArrays
        Needs ``hydrostatic_stiffness`` (C44 [N·m/rad], including the weight term) and
        ``inertia_matrix`` (I44 about O [kg·m²]).
    interpolation : {"cubic", "linear"}
        Interpolation of A44(ω).
    tol : float
        Convergence tolerance on ω [rad/s].
    max_iter : int
        Iteration limit.

    Returns
    -------
    float
        ω_φ [rad/s].

    Raises
    ------
    ValueError
        If C44 or I44 is missing or non-positive, the iteration leaves the database range, or it
        does not converge.
    """
    h = _hydro_arrays(database)
    if h.hydrostatic_stiffness is None or h.inertia_matrix is None:
        raise ValueError(
            "roll natural frequency needs hydrostatic_stiffness and inertia_matrix in the "
            "database; pass roll_natural_frequency explicitly instead"
        )
    c44 = float(h.hydrostatic_stiffness[ROLL, ROLL])
    i44 = float(h.inertia_matrix[ROLL, ROLL])
    if not (c44 > 0.0 and i44 > 0.0):
        raise ValueError(
            f"C44 = {c44} N·m/rad and I44 = {i44} kg·m² must be positive (stable upright ship)"
        )
    a44 = _interpolator(h.omega, h.added_mass[:, ROLL, ROLL], interpolation)
    if h.added_mass_infinite is not None:
        w = math.sqrt(c44 / (i44 + float(h.added_mass_infinite[ROLL, ROLL])))
    else:
        w = 0.5 * (h.omega[0] + h.omega[-1])
    for _ in range(max_iter):
        if not h.omega[0] <= w <= h.omega[-1]:
            raise ValueError(
                f"roll natural frequency iterate {w:.5g} rad/s is outside the database range "
                f"[{h.omega[0]:.5g}, {h.omega[-1]:.5g}] rad/s"
            )
        w_new = math.sqrt(c44 / (i44 + float(a44(w))))
        if abs(w_new - w) <= tol:
            return w_new
        w = w_new
    raise ValueError(f"roll natural frequency did not converge in {max_iter} iterations")


_roll_frequency = roll_natural_frequency  # the class below has a parameter of the same name


class ConstantCoefficientRadiation(ForceModel):
    """Frequency-independent radiation force, Matusiak case 2 (his eq. 13–14).

    F = −A_c ν̇ − B_c ν_p with ``added_mass`` = A_c on the left-hand side and force −B_c ν_p
    (no memory). The full 6 × 6 matrices are used (Matusiak's eq. 14 lists the couplings that
    survive port–starboard symmetry and also drops surge–heave; for the S175 A13 is ≈ 1 % of
    √(A11 A33)).

    * case ``"2b"``: A_c = A(ω_c), B_c = B(ω_c) with ω_c = |ω_e|, the encounter frequency.
    * case ``"2a"``: as 2b, except the roll row and column (index 3: roll and its couplings
      with every other DOF) taken at the roll natural frequency ω_φ (given, or from
      :func:`roll_natural_frequency`).

    A negative encounter frequency (ship overtaking the waves, following seas) is used by its
    magnitude: the motion oscillates at |ω_e|. A(ω), B(ω) are interpolated in ω by a cubic
    spline (not-a-knot, exact at database frequencies) or linearly; frequencies outside the
    database range [ω_min, ω_max] raise.

    Parameters
    ----------
    database : xarray.Dataset or HydroArrays
        Zero-speed database.
    case : {"2a", "2b"}
        Matusiak's case.
    encounter_frequency : float
        ω_e [rad/s] (see :meth:`from_wave` and :func:`ship_gym.waves.encounter_frequency`).
    roll_natural_frequency : float, optional
        ω_φ [rad/s] for case 2a; computed by fixed-point iteration when None.
    interpolation : {"cubic", "linear"}
        Interpolation of the coefficients in ω.

    Attributes
    ----------
    omega_c : float
        |ω_e| [rad/s].
    omega_roll : float or None
        ω_φ [rad/s] (case 2a).
    added_mass : numpy.ndarray
        (6, 6) A_c [kg, kg·m, kg·m²].
    damping : numpy.ndarray
        (6, 6) B_c [kg/s, kg·m/s, kg·m²/s].
    """

    name = "radiation"

    def __init__(
        self,
        database: xr.Dataset | HydroArrays,
        *,
        case: Case = "2b",
        encounter_frequency: float,
        roll_natural_frequency: float | None = None,
        interpolation: Interpolation = "cubic",
    ) -> None:
        if case not in ("2a", "2b"):
            raise ValueError(f"case={case!r}; expected '2a' or '2b' (Matusiak case 2)")
        h = _hydro_arrays(database)
        try:
            w_e = float(encounter_frequency)
        except (TypeError, ValueError):
            raise ValueError(
                f"encounter_frequency={encounter_frequency!r}; expected a number [rad/s]"
            ) from None
        if not math.isfinite(w_e):
            raise ValueError(f"encounter_frequency={encounter_frequency!r}; expected finite")
        self.case: str = case
        self.omega_c: float = abs(w_e)
        added = _interpolator(h.omega, h.added_mass, interpolation)
        damping = _interpolator(h.omega, h.radiation_damping, interpolation)
        self._check_range(h.omega, self.omega_c, "encounter frequency |ω_e|")
        a = np.array(added(self.omega_c), dtype=float)
        b = np.array(damping(self.omega_c), dtype=float)
        self.omega_roll: float | None = None
        if case == "2a":
            if roll_natural_frequency is None:
                w_r = _roll_frequency(h, interpolation=interpolation)
            else:
                w_r = _check_positive("roll_natural_frequency", roll_natural_frequency)
            self._check_range(h.omega, w_r, "roll natural frequency ω_φ")
            self.omega_roll = w_r
            a_r = np.asarray(added(w_r), dtype=float)
            b_r = np.asarray(damping(w_r), dtype=float)
            a[ROLL, :], a[:, ROLL] = a_r[ROLL, :], a_r[:, ROLL]
            b[ROLL, :], b[:, ROLL] = b_r[ROLL, :], b_r[:, ROLL]
        self.added_mass: NDArray[np.float64] = a
        self.damping: NDArray[np.float64] = b
        self._empty = np.zeros(0)

    @staticmethod
    def _check_range(omega: NDArray[np.float64], w: float, what: str) -> None:
        if not omega[0] <= w <= omega[-1]:
            raise ValueError(
                f"{what} = {w:.6g} rad/s is outside the database range "
                f"[{omega[0]:.6g}, {omega[-1]:.6g}] rad/s"
            )

    @classmethod
    def from_wave(
        cls,
        database: xr.Dataset | HydroArrays,
        *,
        wave_omega: float,
        speed: float,
        beta: float,
        case: Case = "2b",
        g: float = GRAVITY,
        roll_natural_frequency: float | None = None,
        interpolation: Interpolation = "cubic",
    ) -> ConstantCoefficientRadiation:
        """Model at the encounter frequency of a regular wave.

        ω_e = ω − ω²U cos β / g (:func:`ship_gym.waves.sea_state.encounter_frequency`).

        Parameters
        ----------
        database : xarray.Dataset or HydroArrays
            Zero-speed database.
        wave_omega : float
            Wave frequency ω [rad/s].
        speed : float
            Forward speed U [m/s].
        beta : float
            Relative heading β [rad] (0 following, π head seas).
        case, roll_natural_frequency, interpolation
            As in the constructor.
        g : float
            Gravitational acceleration [m/s²].
        """
        w_e = float(_encounter_frequency(wave_omega, speed, beta, g))
        return cls(
            database,
            case=case,
            encounter_frequency=w_e,
            roll_natural_frequency=roll_natural_frequency,
            interpolation=interpolation,
        )

    def evaluate(
        self, ctx: ForceContext, states: NDArray[np.float64]
    ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Force −B_c ν_p [N, N·m] (body axes, about O) and no state derivatives."""
        return -(self.damping @ perturbation_velocity(ctx)), self._empty


# =============================================================================================
# row kernels (numba; the engine's numpy path and its compiled loop call these)
# =============================================================================================
@nb.njit(cache=True, nogil=True)
def state_space_radiation(
    v, z, speed, a_ptr, a_idx, a_val, b_ptr, b_idx, b_val, c_ptr, c_idx, c_val, d_mat, has_d,
    p_inf, p_mem, cutoff, total, zdot,
):  # fmt: skip  # pragma: no cover - compiled
    """Radiation memory: ż = A z + B ν_p into zdot, −(C z + D ν_p) + u Lᵀ H(A(∞) ν_p + λ) added
    to total (:mod:`ship_gym.hydro.forward_speed` eq. 2 and 5 with the surge velocity u for U,
    λ = C A⁻¹ z); A, B, C in CSR form (A
    block-diagonal, B one non-zero per state: O(n_states)); ``p_inf`` (2, 6) and ``p_mem``
    (2, n) the pitch and yaw rows of Lᵀ A(∞) and Lᵀ C A⁻¹. With ``cutoff`` ω_c > 0 the two
    states after the fit's n hold the momentum's low-pass m̄ (ṁ̄ = ω_c (m − m̄)) and the moment
    acts on m − m̄ (the high-pass H of eq. 5)."""
    vp = np.empty(6)
    for i in range(6):
        vp[i] = v[i]
    vp[SURGE] -= speed
    u = v[SURGE]  # the Kirchhoff moment takes the ship's own surge velocity (= U to first order)
    n_fit = a_ptr.shape[0] - 1
    if u != 0.0 or cutoff > 0.0:
        for r in range(2):
            s = 0.0
            for j in range(6):
                s += p_inf[r, j] * vp[j]
            for k in range(p_mem.shape[1]):
                s += p_mem[r, k] * z[k]
            if cutoff > 0.0:
                s -= z[n_fit + r]
                zdot[n_fit + r] = cutoff * s
            total[PITCH if r == 0 else YAW] += u * s
    for i in range(n_fit):
        s = 0.0
        for p in range(a_ptr[i], a_ptr[i + 1]):
            s += a_val[p] * z[a_idx[p]]
        for p in range(b_ptr[i], b_ptr[i + 1]):
            s += b_val[p] * vp[b_idx[p]]
        zdot[i] = s
    for o in range(6):
        s = 0.0
        for p in range(c_ptr[o], c_ptr[o + 1]):
            s += c_val[p] * z[c_idx[p]]
        f = -s
        if has_d:
            for j in range(6):
                f -= vp[j] * d_mat[o, j]
        total[o] += f


class RadiationRecord(NamedTuple):
    """:func:`state_space_radiation`'s parameters: U [m/s], A, B, C in CSR form, D (6, 6) (the
    constant coefficients B_c of 2a/2b: no states), the momentum rows and ω_c [rad/s]."""

    speed: float
    a_ptr: NDArray
    a_idx: NDArray
    a_val: NDArray
    b_ptr: NDArray
    b_idx: NDArray
    b_val: NDArray
    c_ptr: NDArray
    c_idx: NDArray
    c_val: NDArray
    d_mat: NDArray
    has_d: bool
    p_inf: NDArray
    p_mem: NDArray
    cutoff: float


def _csr_arrays(matrix: NDArray) -> tuple[NDArray, NDArray, NDArray]:
    m = np.asarray(matrix, dtype=float)
    rows, cols = np.nonzero(m)
    ptr = np.zeros(m.shape[0] + 1, dtype=np.int64)
    np.add.at(ptr, rows + 1, 1)
    c = np.ascontiguousarray
    return c(np.cumsum(ptr), np.int64), c(cols, np.int64), c(m[rows, cols], float)


def radiation_record(
    speed: float,
    matrices: tuple[NDArray, NDArray, NDArray] | None,
    feedthrough: NDArray | None,
    momentum: tuple[NDArray, NDArray] | None = None,
    cutoff: float = 0.0,
) -> RadiationRecord:
    """The record of :func:`radiation_row`.

    Parameters
    ----------
    speed : float
        U [m/s].
    matrices : (A, B, C) or None
        The state-space realisation (None: constant coefficients, no states).
    feedthrough : numpy.ndarray or None
        (6, 6) D (or B_c of 2a/2b) [N·s/m, …].
    momentum : (p_inf, p_mem), optional
        (2, 6) and (2, n) pitch and yaw rows of Lᵀ A(∞) and Lᵀ C A⁻¹.
    cutoff : float
        ω_c [rad/s] of the momentum's high-pass (0: none).
    """
    if matrices is None:
        matrices = (np.zeros((0, 0)), np.zeros((0, 6)), np.zeros((6, 0)))
    d = np.zeros((6, 6)) if feedthrough is None else np.asarray(feedthrough, dtype=float)
    if momentum is None:
        momentum = (np.zeros((2, 6)), np.zeros((2, 0)))
    c = np.ascontiguousarray
    return RadiationRecord(
        float(speed), *_csr_arrays(matrices[0]), *_csr_arrays(matrices[1]),
        *_csr_arrays(matrices[2]), c(d, float), bool(np.any(d != 0.0)), c(momentum[0], float),
        c(momentum[1], float), float(cutoff),
    )  # fmt: skip


@nb.njit(cache=True, nogil=True)
def radiation_row(s, t, q, v, z, zdot, ctx, rec, out):  # pragma: no cover - compiled
    """Row kernel: :func:`state_space_radiation` with the record's parameters."""
    state_space_radiation(
        v, z, rec.speed, rec.a_ptr, rec.a_idx, rec.a_val, rec.b_ptr, rec.b_idx, rec.b_val,
        rec.c_ptr, rec.c_idx, rec.c_val, rec.d_mat, rec.has_d, rec.p_inf, rec.p_mem, rec.cutoff,
        out, zdot,
    )  # fmt: skip
