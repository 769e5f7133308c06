"""Frequency-domain linear response: response amplitude operators (RAOs) from a BEM database.

This is the reference against which the time-domain simulator is checked in its linear limit
(DESIGN.md §6): same database, same mass and restoring, solved exactly in the frequency domain.

Equation solved
---------------
For a regular incident wave of unit amplitude, wave frequency ω and heading β (our conventions,
:mod:`ship_gym.conventions`), a ship advancing at the steady speed U meets the wave at the
encounter frequency (deep water)

    ω_e = ω − k U cos β = ω − ω² U cos β / g                                    (1)

(:func:`ship_gym.kinematics.encounter_frequency`, shared by every stage). The linear equations of
motion about O, M ẍ + A ẍ + B ẋ + C x = Re(F a e^{−iω_e t}), with x(t) = Re(ξ a e^{−iω_e t})
(capytaine's time convention, x(t) = Re(X e^{−iωt})), become, with s = −iω_e,

    [s² M + C + C_extra + R(ω_e, U) + s B_extra] ξ = F_exc(ω, β),                         (2)

    R(ω_e, U) = (s I − U Lᵀ) [A(ω_c) + B(ω_c)/s] (s I + U L)

the radiation impedance of :mod:`ship_gym.hydro.forward_speed` (its eq. 3: the zero-speed
coefficients taken to speed by the body-axis kinematics L and the Kirchhoff moment Lᵀ, which is
Salvesen–Tuck–Faltinsen's forward-speed correction without end terms, and exactly what the
time-domain engine integrates). At U = 0, R = s² A + s B. ξ is the complex RAO per unit wave
amplitude [m/m for surge, sway, heave; rad/m for roll, pitch, yaw] and ω_c = |ω_e|
(``frequency="encounter"``, default) or ω_c = ω (``"wave"``, see below). Its phase is relative
to the incident crest at O: the wave at O is ζ(O, t) = Re(a e^{−iω_e t}), so ζ(O, 0) = a.

Why these frequencies. The radiated waves oscillate at ω_e, so A and B are read at |ω_e| (they
are even in ω). The excitation per unit amplitude F_exc(ω, β) = F_FK + F_D is taken at the wave
frequency ω: the Froude–Krylov part is the incident pressure over the hull, whose spatial
pattern e^{ik(x cos β + y sin β)} (k = ω²/g) is the same whatever the speed, and the diffraction
part is the zero-speed value for that pattern — the time domain does the same
(:mod:`ship_gym.forces.diffraction`, ``frequency="wave"``). ``frequency="wave"`` evaluates A
and B at ω instead of |ω_e| (the crude "constant coefficients at the wave frequency" model);
it changes nothing at U = 0. ``speed_terms`` selects the planes of the outer factor (``"all"``,
``"vertical"`` — what the engine uses with the manoeuvring model on — or ``"none"``).

Interpolation
-------------
The database is exact at its own frequencies and headings; between them:

* in ω: piecewise linear (``interpolation="linear"``, default) or cubic (not-a-knot) splines of
  A, B and of the real and imaginary parts of F. A(0) (stored at ω = 0) extends the radiation
  grid down to 0 with B(0) = 0; frequencies above the highest finite database frequency, and wave
  frequencies below the lowest finite one (F is not defined at ω = 0), raise ValueError. Use a
  database frequency for quantitative comparisons: the excitation phase turns by k L/2 along the
  hull and linear interpolation of its real and imaginary parts loses amplitude between coarse
  grid points.
* in β: linear in real and imaginary parts between neighbouring headings, periodic in 2π. A
  database holding 0 ≤ β ≤ π only (port/starboard symmetric hull) is completed to the full circle
  with :func:`ship_gym.hydro.database.mirror_headings` when a heading outside its range is asked.

Constrained degrees of freedom
------------------------------
Surge, sway and yaw have no hydrostatic restoring, so their response grows like 1/ω_e² at low
frequency (the ship drifts with the orbital motion). ``restoring_extra`` adds soft springs;
``free_dofs`` solves only the given DOFs, the others being held at zero (their rows and columns
are removed from (2), exactly what a simulator that constrains those DOFs computes).

References
----------
Newman, J. N. (1977), *Marine Hydrodynamics*, MIT Press, §6.16–6.19 (linear ship motions).
Faltinsen, O. M. (1990), *Sea Loads on Ships and Offshore Structures*, Cambridge University
Press, ch. 3 and 7 (encounter frequency, equations of motion in regular waves).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Literal, NamedTuple

import numpy as np
import xarray as xr
from numpy.typing import ArrayLike
from scipy.interpolate import make_interp_spline
from scipy.optimize import brentq

from ship_gym.conventions import DOF_NAMES, GRAVITY, N_DOF, dof_index
from ship_gym.hydro.database import HydroArrays, as_arrays, mirror_headings
from ship_gym.hydro.forward_speed import (
    SpeedTerms,
    check_speed_cutoff,
    check_speed_terms,
    complex_mass_table,
    diffraction_at_speed,
    radiation_impedance,
)
from ship_gym.kinematics import encounter_frequency

Frequency = Literal["encounter", "wave"]
Interpolation = Literal["linear", "cubic"]

_TWO_PI = 2.0 * np.pi
_REL_TOL = 1e-9


# ------------------------------------------------------------------------------ validation
def _matrix(name: str, value: ArrayLike | None, default: np.ndarray | None) -> np.ndarray:
    """A finite (6, 6) float matrix: ``value`` if given, else ``default`` (zeros if both None)."""
    if value is None:
        return np.zeros((N_DOF, N_DOF)) if default is None else np.asarray(default, float)
    arr = np.asarray(value, dtype=float)
    if arr.shape != (N_DOF, N_DOF) or not np.all(np.isfinite(arr)):
        raise ValueError(
            f"{name} must be a finite (6, 6) matrix in DOF order {DOF_NAMES}; got shape {arr.shape}"
        )
    return arr


def dof_mask(free_dofs: Sequence[bool] | Sequence[int | str] | None) -> np.ndarray:
    """Boolean mask (6,) of the degrees of freedom left free.

    Parameters
    ----------
    free_dofs : sequence or None
        None (all six free), six booleans, or DOF indices / capytaine labels (e.g.
        ``("Heave", "Pitch")`` or ``(2, 4)``).

    Returns
    -------
    numpy.ndarray
        (6,) bool, True for a free DOF.

    Raises
    ------
    ValueError
        For an unknown label, an index outside 0..5, or an empty selection.
    """
    if free_dofs is None:
        return np.ones(N_DOF, dtype=bool)
    items = list(free_dofs)
    if len(items) == N_DOF and all(isinstance(v, bool | np.bool_) for v in items):
        mask = np.array(items, dtype=bool)
    else:
        mask = np.zeros(N_DOF, dtype=bool)
        for item in items:
            if isinstance(item, str):
                mask[dof_index(item)] = True
            elif isinstance(item, int | np.integer) and not isinstance(item, bool | np.bool_):
                if not 0 <= int(item) < N_DOF:
                    raise ValueError(f"free_dofs index {item!r} outside 0..5 ({DOF_NAMES})")
                mask[int(item)] = True
            else:
                raise ValueError(
                    f"free_dofs entries must be DOF labels {DOF_NAMES} or indices 0..5, or six "
                    f"booleans; got {item!r}"
                )
    if not mask.any():
        raise ValueError(f"free_dofs selects no degree of freedom: {free_dofs!r}")
    return mask


def _frequencies(omega: ArrayLike) -> np.ndarray:
    w = np.atleast_1d(np.asarray(omega, dtype=float))
    if w.ndim != 1 or w.size == 0:
        raise ValueError(f"omega must be a scalar or a 1-D array of frequencies [rad/s]; got {w}")
    if not np.all(np.isfinite(w)) or np.any(w <= 0.0):
        raise ValueError(f"omega must be finite wave frequencies > 0 [rad/s]; got {omega!r}")
    return w


def _scalar(name: str, value: float, unit: str) -> float:
    try:
        out = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{name} must be a real number [{unit}]; got {value!r}") from None
    if not np.isfinite(out):
        raise ValueError(f"{name} must be finite [{unit}]; got {value!r}")
    return out


def _spline(x: np.ndarray, y: np.ndarray, method: Interpolation):
    k = 1 if method == "linear" or len(x) < 4 else 3
    return make_interp_spline(x, y, k=k, axis=0)


def _heading_weights(grid: np.ndarray, beta: float) -> tuple[int, int, float]:
    """Indices (i, j) and weight w of ``beta`` between grid[i] (1 − w) and grid[j] (w)."""
    m = len(grid)
    if m == 1:
        return 0, 0, 0.0
    lo, hi = grid[0], grid[-1]
    tol = 1e-9
    if lo - tol <= beta <= hi + tol:
        b = min(max(beta, lo), hi)
        j = int(np.clip(np.searchsorted(grid, b, side="right"), 1, m - 1))
        i = j - 1
        return i, j, float((b - grid[i]) / (grid[j] - grid[i]))
    # periodic wrap between the last and the first heading
    gap = lo + _TWO_PI - hi
    b = beta if beta > hi else beta + _TWO_PI
    return m - 1, 0, float((b - hi) / gap)


def _headings_for(ds: xr.Dataset, beta: float) -> xr.Dataset:
    """The database, completed by mirroring when β lies outside its heading range."""
    grid = np.mod(ds["wave_direction"].values.astype(float), _TWO_PI)
    if grid.min() - 1e-9 <= beta <= grid.max() + 1e-9:
        return ds
    full = mirror_headings(ds)
    grid = np.sort(np.mod(full["wave_direction"].values.astype(float), _TWO_PI))
    if not grid.min() - 1e-9 <= beta <= grid.max() + 1e-9:
        spacing = np.diff(grid).max(initial=0.0)
        gap = grid.min() + _TWO_PI - grid.max()
        if len(grid) < 2 or gap > 1.01 * spacing:
            raise ValueError(
                f"heading {np.degrees(beta):.6g}° is not covered by the database headings "
                f"{np.round(np.degrees(grid), 6).tolist()} (even after mirroring); expected a "
                "heading between two stored ones"
            )
    return full


def _excitation_at(
    arrays: HydroArrays,
    beta: float,
    omega: np.ndarray,
    method: Interpolation,
    force: np.ndarray | None = None,
):
    """``force`` (default the excitation force) (n_ω, n_β, 6) interpolated to (ω, β)."""
    grid = np.mod(arrays.wave_direction, _TWO_PI)
    order = np.argsort(grid)
    exc = arrays.excitation_force if force is None else force
    grid, exc = grid[order], exc[:, order, :]
    i, j, w = _heading_weights(grid, beta)
    f_beta = (1.0 - w) * exc[:, i, :] + w * exc[:, j, :]  # (n_omega, 6)
    w_grid = arrays.omega
    lo, hi = w_grid[0], w_grid[-1]
    if np.any(omega < lo * (1 - _REL_TOL)) or np.any(omega > hi * (1 + _REL_TOL)):
        raise ValueError(
            f"wave frequencies {omega.min():.6g}..{omega.max():.6g} rad/s outside the "
            f"database's finite frequencies {lo:.6g}..{hi:.6g} rad/s (excitation is not "
            "extrapolated)"
        )
    if not np.all(np.isfinite(f_beta)):
        raise ValueError("database excitation_force holds NaN/inf at finite frequencies")
    w_eval = np.clip(omega, lo, hi)
    re = _spline(w_grid, f_beta.real, method)(w_eval)
    im = _spline(w_grid, f_beta.imag, method)(w_eval)
    return re + 1j * im


def _excitation_at_speed(
    arrays: HydroArrays,
    beta: float,
    omega: np.ndarray,
    omega_e: np.ndarray,
    speed: float,
    terms: SpeedTerms,
    cutoff: float,
    method: Interpolation,
) -> np.ndarray:
    """F_FK + F_D at speed (n, 6): the diffraction taken to speed with its Kirchhoff moment
    (:mod:`ship_gym.hydro.forward_speed` eq. 4 and 6); the zero-speed excitation at U = 0 or
    ``terms="none"``."""
    f_exc = _excitation_at(arrays, beta, omega, method)  # (n, 6)
    if speed == 0.0 or terms == "none":
        return f_exc
    if arrays.diffraction_force is None:
        raise ValueError(
            "database has no 'diffraction_force': the forward-speed terms of the scattered flow "
            "need it (or pass speed_terms='none')"
        )
    f_d = _excitation_at(arrays, beta, omega, method, arrays.diffraction_force)
    table = complex_mass_table(
        arrays.omega, arrays.added_mass, arrays.radiation_damping, arrays.added_mass_zero
    )
    return f_exc - f_d + diffraction_at_speed(f_d, omega, omega_e, speed, table, terms, cutoff)


def _radiation_at(arrays: HydroArrays, omega_c: np.ndarray, method: Interpolation):
    w_grid = arrays.omega
    a, b = arrays.added_mass, arrays.radiation_damping
    if arrays.added_mass_zero is not None:
        w_grid = np.concatenate([[0.0], w_grid])
        a = np.concatenate([arrays.added_mass_zero[None], a])
        b = np.concatenate([np.zeros((1, N_DOF, N_DOF)), b])
    lo, hi = w_grid[0], w_grid[-1]
    if np.any(omega_c < lo * (1 - _REL_TOL)) or np.any(omega_c > hi * (1 + _REL_TOL)):
        note = "" if arrays.added_mass_zero is not None else "; the database has no A(0) entry"
        raise ValueError(
            f"radiation frequencies {omega_c.min():.6g}..{omega_c.max():.6g} rad/s outside the "
            f"database's range {lo:.6g}..{hi:.6g} rad/s (no extrapolation{note})"
        )
    w_eval = np.clip(omega_c, lo, hi)
    return _spline(w_grid, a, method)(w_eval), _spline(w_grid, b, method)(w_eval)


class _WaveCase(NamedTuple):
    """The checked arguments of one regular-wave problem at speed."""

    omega: np.ndarray
    beta: float
    speed: float
    terms: SpeedTerms
    cutoff: float
    omega_e: np.ndarray
    arrays: HydroArrays


def _wave_case(
    database: xr.Dataset,
    omega: ArrayLike,
    heading: float,
    forward_speed: float,
    speed_terms: SpeedTerms,
    speed_cutoff: float,
    interpolation: Interpolation,
    frequency: Frequency | None = None,
) -> _WaveCase:
    """Check the arguments shared by :func:`response_amplitude_operator` and
    :func:`excitation_force` (``frequency`` only where given) and read the database's arrays
    at the heading; ValueError naming the bad one."""
    if not isinstance(database, xr.Dataset):
        raise ValueError(f"database must be an xarray.Dataset; got {type(database).__name__}")
    if frequency is not None and frequency not in ("encounter", "wave"):
        raise ValueError(f"frequency must be 'encounter' or 'wave'; got {frequency!r}")
    if interpolation not in ("linear", "cubic"):
        raise ValueError(f"interpolation must be 'linear' or 'cubic'; got {interpolation!r}")
    terms = check_speed_terms(speed_terms)
    if "excitation_force" not in database:
        raise ValueError("database has no 'excitation_force'; expected a diffraction database")
    w = _frequencies(omega)
    beta = float(np.mod(_scalar("heading", heading, "rad"), _TWO_PI))
    speed = _scalar("forward_speed", forward_speed, "m/s")
    cutoff = check_speed_cutoff(speed_cutoff)
    g = float(database.attrs.get("g", GRAVITY))
    arrays = as_arrays(_headings_for(database, beta))
    w_e = encounter_frequency(w, speed, beta, g)
    return _WaveCase(w, beta, speed, terms, cutoff, w_e, arrays)


# ------------------------------------------------------------------------------ public API
def response_amplitude_operator(
    database: xr.Dataset,
    *,
    omega: ArrayLike,
    heading: float,
    forward_speed: float = 0.0,
    extra_damping: ArrayLike | None = None,
    hull_hydrostatic_stiffness: ArrayLike | None = None,
    mass_matrix: ArrayLike | None = None,
    restoring_extra: ArrayLike | None = None,
    free_dofs: Sequence[bool] | Sequence[int | str] | None = None,
    frequency: Frequency = "encounter",
    interpolation: Interpolation = "linear",
    speed_terms: SpeedTerms = "all",
    speed_cutoff: float = 0.0,
) -> np.ndarray:
    """Complex RAOs per unit wave amplitude, solving eq. (2) of the module docstring.

    Parameters
    ----------
    database : xarray.Dataset
        Hydrodynamic database in our body frame (:mod:`ship_gym.hydro.database` schema), zero
        forward speed, with ``excitation_force``.
    omega : array_like
        Wave (absolute) frequencies ω > 0 [rad/s], scalar or (n,).
    heading : float
        Wave heading β [rad] (π head seas, π/2 waves travelling toward starboard).
    forward_speed : float, optional
        Ship speed U [m/s]; the response oscillates at ω_e (eq. 1).
    extra_damping : array_like, optional
        (6, 6) additional linear damping B_extra [SI], e.g. an equivalent-linear viscous roll
        damping (:meth:`ship_gym.forces.viscous.RollDampingCoefficients.equivalent_linear`).
    hull_hydrostatic_stiffness : array_like, optional
        (6, 6) restoring matrix C about O [N/m, N, N·m/rad]; default the database's
        ``hydrostatic_stiffness``.
    mass_matrix : array_like, optional
        (6, 6) rigid-body mass matrix M about O [kg, kg·m, kg·m²]; default the database's
        ``inertia_matrix``.
    restoring_extra : array_like, optional
        (6, 6) additional springs C_extra (e.g. soft surge/sway/yaw moorings) [SI].
    free_dofs : sequence, optional
        DOFs solved for (labels, indices or six booleans, :func:`dof_mask`); the others are held
        at zero. Default: all six.
    frequency : {"encounter", "wave"}, optional
        Frequency at which A and B are read: |ω_e| (default) or ω.
    interpolation : {"linear", "cubic"}, optional
        Interpolation of the database along ω (see the module docstring).
    speed_terms : {"all", "vertical", "none"}, optional
        Planes of the forward-speed Kirchhoff moment (:mod:`ship_gym.hydro.forward_speed`), on
        the radiated and on the scattered flow's momentum (its eq. 4; the database's
        ``diffraction_force`` is needed at speed unless ``"none"``).
    speed_cutoff : float, optional
        ω_c [rad/s] of the moment's high-pass (:mod:`ship_gym.hydro.forward_speed` eq. 5;
        :func:`~ship_gym.hydro.forward_speed.default_speed_cutoff` gives the engine's default);
        0: Salvesen–Tuck–Faltinsen's terms at every encounter frequency.

    Returns
    -------
    numpy.ndarray
        (n, 6) complex RAO ξ: [m/m] for surge, sway, heave and [rad/m] for roll, pitch, yaw, in
        capytaine's convention x(t) = Re(ξ a e^{−iω_e t}) with the wave crest at O at t = 0; held
        DOFs are exactly 0.

    Raises
    ------
    ValueError
        Bad arguments, frequencies or headings outside the database, a missing mass or stiffness
        matrix, or a singular system (e.g. ω_e = 0 with a free DOF that has no restoring).
    """
    case = _wave_case(
        database, omega, heading, forward_speed, speed_terms, speed_cutoff, interpolation,
        frequency,
    )  # fmt: skip
    w, beta, speed, terms, cutoff, w_e, arrays = case
    mask = dof_mask(free_dofs)
    if mass_matrix is None and arrays.inertia_matrix is None:
        raise ValueError("database has no 'inertia_matrix'; pass mass_matrix (6, 6) [SI]")
    if hull_hydrostatic_stiffness is None and arrays.hydrostatic_stiffness is None:
        raise ValueError(
            "database has no 'hydrostatic_stiffness'; pass hull_hydrostatic_stiffness (6, 6)"
        )
    m = _matrix("mass_matrix", mass_matrix, arrays.inertia_matrix)
    c = _matrix(
        "hull_hydrostatic_stiffness", hull_hydrostatic_stiffness, arrays.hydrostatic_stiffness
    )
    c = c + _matrix("restoring_extra", restoring_extra, None)
    b_extra = _matrix("extra_damping", extra_damping, None)

    w_c = np.abs(w_e) if frequency == "encounter" else w
    f_exc = _excitation_at_speed(arrays, beta, w, w_e, speed, terms, cutoff, interpolation)
    a, b = _radiation_at(arrays, w_c, interpolation)  # (n, 6, 6)

    s = (-1j * w_e)[:, None, None]
    k = s * s * m + c + s * b_extra + radiation_impedance(a, b, w_e, speed, terms, cutoff)
    idx = np.flatnonzero(mask)
    k_ff = k[:, idx[:, None], idx[None, :]]
    rao = np.zeros((len(w), N_DOF), dtype=complex)
    try:
        rao[:, idx] = np.linalg.solve(k_ff, f_exc[:, idx, None])[..., 0]
    except np.linalg.LinAlgError:
        raise ValueError(
            "singular equations of motion: some free DOF has neither restoring nor inertia at "
            f"the encounter frequencies {w_e.tolist()} rad/s (omega_e = 0 with a free surge, "
            "sway or yaw?); add restoring_extra or hold it with free_dofs"
        ) from None
    if not np.all(np.isfinite(rao)):
        raise ValueError("non-finite response: the equations of motion are singular")
    return rao


def excitation_force(
    database: xr.Dataset,
    *,
    omega: ArrayLike,
    heading: float,
    forward_speed: float = 0.0,
    speed_terms: SpeedTerms = "all",
    speed_cutoff: float = 0.0,
    interpolation: Interpolation = "linear",
) -> np.ndarray:
    """Wave excitation on the restrained ship at speed, per unit wave amplitude: F_FK + F_D with
    the diffraction in relative-motion form and the scattered flow's Kirchhoff moment
    (:mod:`ship_gym.hydro.forward_speed` eq. 4 and 6) — the right-hand side of eq. (2).

    Parameters
    ----------
    database : xarray.Dataset
        Zero-speed database with ``excitation_force`` and ``diffraction_force``.
    omega : array_like
        Wave frequencies ω > 0 [rad/s].
    heading : float
        Wave heading β [rad].
    forward_speed, speed_terms, speed_cutoff, interpolation
        As :func:`response_amplitude_operator`.

    Returns
    -------
    numpy.ndarray
        (n, 6) complex [N/m, N·m/m], capytaine's time convention, the crest at O at t = 0.
    """
    w, beta, speed, terms, cutoff, w_e, arrays = _wave_case(
        database, omega, heading, forward_speed, speed_terms, speed_cutoff, interpolation
    )
    return _excitation_at_speed(arrays, beta, w, w_e, speed, terms, cutoff, interpolation)


def natural_frequency(
    database: xr.Dataset,
    dof: int | str,
    *,
    hull_hydrostatic_stiffness: ArrayLike | None = None,
    mass_matrix: ArrayLike | None = None,
    restoring_extra: ArrayLike | None = None,
) -> float:
    """Uncoupled natural frequency ω_n of one DOF: root of ω² (M_ii + A_ii(ω)) = C_ii.

    The added mass is interpolated linearly in ω (with A(0) at ω = 0 when stored); couplings with
    the other DOFs are ignored, so for roll this is the period of a ship whose sway is held.

    Parameters
    ----------
    database : xarray.Dataset
        Hydrodynamic database (our frame).
    dof : int or str
        DOF index 0..5 or label (e.g. ``"Heave"``).
    hull_hydrostatic_stiffness, mass_matrix, restoring_extra : array_like, optional
        As in :func:`response_amplitude_operator`.

    Returns
    -------
    float
        ω_n [rad/s].

    Raises
    ------
    ValueError
        If the DOF has no positive restoring or no root lies in the database's frequency range.
    """
    i = dof_index(dof) if isinstance(dof, str) else int(dof)
    if not 0 <= i < N_DOF:
        raise ValueError(f"dof must be a label {DOF_NAMES} or an index 0..5; got {dof!r}")
    if not isinstance(database, xr.Dataset):
        raise ValueError(f"database must be an xarray.Dataset; got {type(database).__name__}")
    arrays = as_arrays(database)
    if mass_matrix is None and arrays.inertia_matrix is None:
        raise ValueError("database has no 'inertia_matrix'; pass mass_matrix (6, 6) [SI]")
    m = _matrix("mass_matrix", mass_matrix, arrays.inertia_matrix)
    c = _matrix(
        "hull_hydrostatic_stiffness", hull_hydrostatic_stiffness, arrays.hydrostatic_stiffness
    )
    c = c + _matrix("restoring_extra", restoring_extra, None)
    if not c[i, i] > 0.0:
        raise ValueError(f"{DOF_NAMES[i]} has no positive restoring (C_ii = {c[i, i]:.6g})")
    w_grid = arrays.omega
    a_ii = arrays.added_mass[:, i, i]
    if arrays.added_mass_zero is not None:
        w_grid = np.concatenate([[0.0], w_grid])
        a_ii = np.concatenate([[arrays.added_mass_zero[i, i]], a_ii])

    def residual(w: float) -> float:
        return w * w * (m[i, i] + np.interp(w, w_grid, a_ii)) - c[i, i]

    lo, hi = max(w_grid[0], 1e-9), w_grid[-1]
    if residual(lo) * residual(hi) > 0.0:
        raise ValueError(
            f"no {DOF_NAMES[i]} natural frequency in the database range {lo:.6g}..{hi:.6g} rad/s"
        )
    return float(brentq(residual, lo, hi, xtol=1e-12, rtol=1e-12))


def rao_time_series(
    rao: ArrayLike,
    omega: ArrayLike,
    amplitude: ArrayLike,
    t: ArrayLike,
    phase: ArrayLike = 0.0,
) -> np.ndarray:
    """Steady-state linear response in time, superposing one or more regular components.

    x(t) = Σ_j Re(ξ_j a_j e^{−iε_j} e^{−iω_j t})  (capytaine's convention).

    Mapping to ship_gym's wave phasors: a wave component is c(t) = a e^{i(ω t + ε)} with
    ζ(O, t) = Re(c(t)) = a cos(ω t + ε) (:mod:`ship_gym.conventions`); since
    Re(z) = Re(z̄), this is Re(a e^{−iε} e^{−iωt}), i.e. the capytaine complex amplitude of the
    wave at O is a e^{−iε}, and the response is Re(ξ a e^{−iε} e^{−iωt}). With forward speed the
    wave at O (which passes the earth origin at t = 0) oscillates at the encounter frequency, so
    pass ω_e as ``omega`` (:func:`ship_gym.kinematics.encounter_frequency`).

    Parameters
    ----------
    rao : array_like
        (6,) or (n, 6) complex RAOs per unit amplitude (:func:`response_amplitude_operator`).
    omega : array_like
        Frequency of oscillation of each component [rad/s]: the encounter frequency ω_e (equal
        to the wave frequency at zero speed); scalar or (n,).
    amplitude : array_like
        Wave amplitude a of each component [m]; scalar or (n,).
    t : array_like
        Times [s], (n_t,).
    phase : array_like, optional
        Phase ε of each component [rad] (ζ(O, t) = a cos(ω t + ε)); scalar or (n,).

    Returns
    -------
    numpy.ndarray
        (n_t, 6) real motions [m, rad].
    """
    xi = np.asarray(rao, dtype=complex)
    if xi.ndim == 1:
        xi = xi[None, :]
    if xi.ndim != 2 or xi.shape[1] != N_DOF:
        raise ValueError(f"rao must have shape (6,) or (n, 6); got {np.shape(rao)}")
    n = xi.shape[0]
    try:
        w, a, eps = (
            np.broadcast_to(np.asarray(v, dtype=float), (n,)) for v in (omega, amplitude, phase)
        )
    except ValueError:
        raise ValueError(
            f"omega, amplitude and phase must be scalars or arrays of the {n} components; got "
            f"shapes {np.shape(omega)}, {np.shape(amplitude)}, {np.shape(phase)}"
        ) from None
    tt = np.atleast_1d(np.asarray(t, dtype=float))
    if tt.ndim != 1:
        raise ValueError(f"t must be a 1-D array of times [s]; got shape {tt.shape}")
    for name, v in (("omega", w), ("amplitude", a), ("phase", eps), ("t", tt)):
        if not np.all(np.isfinite(v)):
            raise ValueError(f"{name} must be finite; got {v!r}")
    if np.any(a < 0.0):
        raise ValueError(f"amplitude must be >= 0 [m]; got {amplitude!r}")
    if not np.all(np.isfinite(xi)):
        raise ValueError("rao must be finite")
    phasor = np.exp(-1j * (np.outer(tt, w) + eps[None, :]))  # (n_t, n)
    return np.real(phasor @ (xi * a[:, None]))
