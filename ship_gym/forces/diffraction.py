"""Linear wave diffraction force from a zero-speed frequency-domain database.

Phase mapping between our wave phasors and capytaine's complex amplitudes
------------------------------------------------------------------------
The wave field (:mod:`ship_gym.waves.wave_field`) gives phasors cⱼ(t) = r(t) aⱼ e^{i(ωⱼt + εⱼ)}
with the elevation, in earth axes (X north, Y east),

    ζ(X, Y, t) = Re Σⱼ cⱼ(t) e^{−i kⱼ (X cos χⱼ + Y sin χⱼ)}.

Fold the phasor to the ship's origin O = (X_O, Y_O):

    c'ⱼ(t) = cⱼ(t) e^{−i kⱼ (X_O cos χⱼ + Y_O sin χⱼ)},     ζ(O, t) = Re Σⱼ c'ⱼ(t).

A body point at horizontal body coordinates (x, y) lies at X = X_O + x cos ψ − y sin ψ,
Y = Y_O + x sin ψ + y cos ψ (roll and pitch neglected), so X cos χ + Y sin χ = X_O cos χ +
Y_O sin χ + x cos β + y sin β with β = χ − ψ, and

    ζ(x, y, t) = Re Σⱼ c'ⱼ(t) e^{−i kⱼ (x cos βⱼ + y sin βⱼ)}
               = Re Σⱼ conj(c'ⱼ(t)) e^{+i kⱼ (x cos βⱼ + y sin βⱼ)}.

capytaine's incident wave (time convention x(t) = Re(X e^{−iωt}), database ``attrs``) is
ζ = Re(a_c e^{ik(x cos β + y sin β)} e^{−iωt}) with the diffraction force Re(X_D a_c e^{−iωt}).
Matching the two term by term: **a_c e^{−iωt} ≡ conj(c'(t))**, i.e. the complex amplitude at O
is a_c = conj(c'(0)) for a fixed O, and

    F_D(t) = Re Σⱼ X_D(ω'ⱼ, βⱼ) conj(c'ⱼ(t))     (body axes, about O).

Check: one regular wave, ε = 0, ship at rest at the origin: c' = a e^{iωt},
conj(c') = a e^{−iωt}, F_D = Re(X_D a e^{−iωt}) (tested).

Frequency of the transfer function
----------------------------------
With the ship moving, X_O(t) advances and c'ⱼ(t) rotates at the encounter frequency
ω_e = ω − kU cos β (U = ``ctx.forward_speed``): the time dependence comes out of the folding
exactly. The transfer function is the **zero-speed** X_D, looked up at

* ``frequency="wave"`` (default): ω' = ω. The zero-speed transfer function of the incident
  wave's own pattern k(ω) (exact at zero speed); the force oscillates at ω_e through the folding.
  This is the linearisation of :mod:`ship_gym.hydro.forward_speed`, which the frequency-domain
  solver (:mod:`ship_gym.hydro.rao`) shares; with ``speed_terms`` other than ``"none"`` the
  force is then taken to speed in relative-motion form (its eq. 6; below).
* ``frequency="encounter"``: ω' = ω_e, the older approximation "the hull responds to the
  encountered wave as it would at zero speed to a wave of that frequency": it imposes the
  pattern k(ω_e) = ω_e²/g on the hull, a factor (ω_e/ω)² off (2.6 in head seas at Fn 0.25 near
  the S175's heave resonance). Kept for comparison.

Forward-speed moment of the scattered flow
-------------------------------------------
With ``speed_terms`` other than ``"none"`` the model adds Kirchhoff's moment of the scattered
flow's momentum, u H(ω_e) Lᵀ P_D with P_D(t) = Re Σⱼ conj(c'ⱼ(t)) X_D,ⱼ/(iωⱼ) (eq. 4–5 of
:mod:`ship_gym.hydro.forward_speed`: +u P_D,heave on pitch, −u P_D,sway on yaw, u the ship's own
surge velocity as in the radiation model). It pairs with the radiation model's moment of the
radiated momentum (same ``speed_terms`` and ``speed_cutoff``): together they act on the motion
relative to the incident flow. The per-component factors X_D/(iω) H(ω_e) are cached beside X_D
(two more columns of the cache, with their heading derivative).

Negative encounter frequency (following seas, ship overtaking the waves, U cos β > g/ω), with
``frequency="encounter"``: the folded phasor turns backwards, conj(c'(t)) ∝ e^{+i|ω_e|t}. A
real linear system with the transfer function H(ω) in the e^{−iωt} convention has
H(−ω) = conj(H(ω)), so X_D is taken as
conj(X_D(|ω_e|, β)): the force is that of the same transfer function applied to the encountered
signal written with a positive frequency, Re(conj(X_D) conj(c')) = Re(X_D c') (continuous
through ω_e = 0, where X_D → 0).

Outside the database frequency range (ω_min, ω_max):

* 0 ≤ |ω'| < ω_min: X_D(ω') = X_D(ω_min, β)(ω'/ω_min)². Diffraction vanishes in long waves
  (the scattered potential is O(ω²); the S175 data follow the ω² law at the lowest frequencies).
* |ω'| > ω_max: X_D = 0 (``above_range="zero"``, default), or an error (``"raise"``). The
  attribute :attr:`n_above_range` counts such components. Short waves are weakly felt by a long
  hull but the force does not vanish physically (reflection in beam seas); with the S175
  database (ω_max = 1.67 rad/s) and the default wave-frequency look-up this drops waves shorter
  than 22 m (0.13 L) at any speed (with ``frequency="encounter"``: waves shorter than ≈ 0.5 L
  in head seas at Fn 0.2).

Interpolation and caching
-------------------------
The database headings are completed to the full circle by
:func:`ship_gym.hydro.database.mirror_headings` (port–starboard symmetry) and extended
periodically; X_D is interpolated bilinearly in (ω, β) on the real and imaginary parts (exact at
database nodes). The per-component values X_D(ω'ⱼ, βⱼ) (taken to the ship's speed U_s,
:mod:`ship_gym.hydro.forward_speed` eq. 6) and their heading derivatives are cached and
recomputed only when the heading ψ has moved by more than ``heading_tolerance_deg`` (default
0.5°) since the last update; in between, X_D + (ψ − ψ_ref) ∂X_D/∂ψ is used, so the force is
continuous in ψ and a refresh changes it only by the O(Δψ²) curvature term (a plain cache
would jump by O(Δψ) and cap time-integration accuracy, as the convergence study showed).

U_s, the speed of the linearisation, is the ship's surge velocity at its reset (the engine's U
unless the ship was reset at another speed): the steady speed of the linear theory. The
instantaneous surge velocity oscillates at the encounter frequency in steep waves; a
correction taken at it would multiply two wave-frequency signals and create mean forces the
theory does not have (measured: a mean heel that capsized the S175 in bow seas at Fn 0.4).
Kirchhoff's moment itself takes the instantaneous u, as the radiation model's does. The
folding of the phasors to O is exact at every evaluation (n complex exponentials).

Heading coverage
----------------
The bilinear look-up wraps around the circle, so a database with only, e.g., 135° and 180°
(mirrored to 225° for a symmetric hull) would silently interpolate a following sea from the
head-sea data. The covered headings are the arcs between consecutive database headings (after
mirroring) no wider than ``max_heading_gap_deg`` (default 90°). At construction, the relative
headings βⱼ = χⱼ of the wave components (the ship starts heading north, ψ = 0) are checked
against them: a component within ``heading_extrapolation_tolerance_deg`` (default 5°) of the
covered arcs only warns; beyond it ``heading_extrapolation="raise"`` (default) refuses with a
:class:`ValueError` naming the requested heading and the covered range, ``"warn"`` warns
(:class:`UserWarning`) and ``"allow"`` accepts silently. A port–starboard symmetric database
with 0–180° covers 180–360° by mirroring and is never flagged. The check cannot follow the
ship's later heading changes (a course change in a partial database is the user's
responsibility).

Frame
-----
The force is in body axes about O, as in the database; the heading enters through β. The rotation
of the force by roll and pitch is second order (amplitude × angle) in the linear theory and is not
applied.
"""

from __future__ import annotations

import math
import warnings
from typing import Literal, NamedTuple

import numba as nb
import numpy as np
import xarray as xr
from numpy.typing import ArrayLike, NDArray

from ship_gym.conventions import DOF_NAMES, N_DOF, PITCH, SURGE, YAW
from ship_gym.forces.base import ForceContext, ForceModel
from ship_gym.hydro.database import as_arrays, mirror_headings, split_frequencies
from ship_gym.hydro.forward_speed import (
    SpeedTerms,
    check_speed_cutoff,
    check_speed_terms,
    complex_mass_table,
    momentum_coefficients,
    speed_correct_element,
)
from ship_gym.numerics.angles import wrap_angle_scalar
from ship_gym.waves.wave_field import WaveField

__all__ = ["Diffraction"]

Frequency = Literal["encounter", "wave"]
AboveRange = Literal["zero", "raise"]
HeadingExtrapolation = Literal["raise", "warn", "allow"]

_TWO_PI = 2.0 * math.pi

CACHE_COLUMNS = N_DOF + 2
"""Columns of the per-component cache: X_D (6) and the scattered momentum's pitch and yaw
moment factors (module docstring, *Forward-speed moment of the scattered flow*)."""


def kirchhoff_parameters(
    speed_terms: SpeedTerms, speed_cutoff: float, enabled: bool = True
) -> NDArray[np.float64]:
    """(Lᵀ[pitch, heave], Lᵀ[yaw, sway], ω_c [rad/s], enabled): the speed correction's
    parameters as the row kernels take them (enabled 0: the zero-speed force, no moment)."""
    pitch, yaw = momentum_coefficients(check_speed_terms(speed_terms))
    on = bool(enabled) and speed_terms != "none"
    return np.array([pitch, yaw, check_speed_cutoff(speed_cutoff), 1.0 if on else 0.0])


@nb.njit(cache=True, nogil=True)
def _speed_correct_columns(w_wave, w_enc, kirchhoff, grid, table, out):  # pragma: no cover
    """:func:`~ship_gym.hydro.forward_speed.speed_correct_element` for every row of ``out``
    (n, 8)."""
    for j in range(out.shape[0]):
        speed_correct_element(w_wave[j], w_enc[j], kirchhoff, grid, table, out, j)


@nb.njit(cache=True, nogil=True)
def transfer_element(w, b, table, beta_ext, omega_db, out, j):  # pragma: no cover - compiled
    """out[j, :] = X_D(ω', β) by the model's rule; returns True if |ω'| > ω_max.

    ``w`` signed ω' [rad/s], ``b`` β in [0, 2π) [rad]; ``table`` (n_ω, n_β + 2, 6) and
    ``beta_ext`` are :meth:`Diffraction.interpolation_table`, ``omega_db`` :attr:`omega`.
    Bilinear in (|ω'|, β), the ω_min row scaled by (|ω'|/ω_min)² below ω_min, zero above
    ω_max, conjugated for ω' < 0. The one implementation of the look-up: the model's
    :meth:`~Diffraction.diffraction_transfer` loops over it, and so does the compiled
    single-ship stepper (:mod:`ship_gym.engine.compiled`) when it refreshes its cache.
    """
    n_beta = beta_ext.shape[0]
    n_omega = omega_db.shape[0]
    w_min, w_max = omega_db[0], omega_db[n_omega - 1]
    aw = abs(w)
    ib = min(max(np.searchsorted(beta_ext, b, side="right") - 1, 0), n_beta - 2)
    fb = (b - beta_ext[ib]) / (beta_ext[ib + 1] - beta_ext[ib])
    wc = min(max(aw, w_min), w_max)
    iw = min(max(np.searchsorted(omega_db, wc, side="right") - 1, 0), n_omega - 2)
    fw = (wc - omega_db[iw]) / (omega_db[iw + 1] - omega_db[iw])
    c00, c01 = (1.0 - fw) * (1.0 - fb), (1.0 - fw) * fb
    c10, c11 = fw * (1.0 - fb), fw * fb
    above = aw > w_max * (1.0 + 1e-12)
    scale = (aw / w_min) ** 2
    for o in range(table.shape[2]):
        x = (
            c00 * table[iw, ib, o]
            + c01 * table[iw, ib + 1, o]
            + c10 * table[iw + 1, ib, o]
            + c11 * table[iw + 1, ib + 1, o]
        )
        if aw < w_min:
            x = x * scale
        if above:
            x = 0.0j
        out[j, o] = x.conjugate() if w < 0.0 else x
    return above


@nb.njit(cache=True, nogil=True)
def _transfer_elements(w, b, table, beta_ext, omega_db, out):  # pragma: no cover - compiled
    """:func:`transfer_element` for every element of the 1-D arrays w, b."""
    for j in range(w.shape[0]):
        transfer_element(w[j], b[j], table, beta_ext, omega_db, out, j)


class Diffraction(ForceModel):
    """Linear diffraction force F_D(t) = Re Σⱼ X_D(ω'ⱼ, βⱼ) conj(c'ⱼ(t)) (module docstring).

    Parameters
    ----------
    database : xarray.Dataset
        Zero-speed database with ``diffraction_force`` (omega, wave_direction, influenced_dof),
        complex per unit amplitude [N/m, N·m/m], capytaine's time convention, headings in
        ship_gym's convention.
    wave_field : WaveField
        The incident field (components ωⱼ [rad/s], kⱼ [rad/m], χⱼ [rad]).
    frequency : {"wave", "encounter"}
        Frequency at which X_D is looked up: the wave frequency (default, the hull sees the
        wave pattern k(ω); :mod:`ship_gym.hydro.forward_speed`) or the encounter frequency.
    interpolation : {"linear"}
        Bilinear interpolation in (ω, β).
    heading_tolerance_deg : float
        Heading change [deg] that triggers a recomputation of the cached X_D per component.
    above_range : {"zero", "raise"}
        Treatment of |ω'| > ω_max.
    heading_extrapolation : {"raise", "warn", "allow"}
        What to do when a wave component's relative heading lies outside the headings the
        database covers by more than ``heading_extrapolation_tolerance_deg`` (module notes,
        *Heading coverage*); within the tolerance it warns unless ``"allow"``.
    heading_extrapolation_tolerance_deg : float
        Angle [deg] outside the covered headings accepted with a warning.
    max_heading_gap_deg : float
        Widest gap [deg] between consecutive database headings that is still interpolated.
    speed_terms : {"all", "vertical", "none"}
        Planes of the scattered flow's forward-speed moment (module docstring); give the
        radiation model's.
    speed_cutoff : float
        ω_c [rad/s] of that moment's high-pass (:mod:`ship_gym.hydro.forward_speed` eq. 5);
        give the radiation model's.

    Attributes
    ----------
    omega : numpy.ndarray
        (n_ω,) database frequencies [rad/s].
    wave_direction : numpy.ndarray
        (n_β,) headings after mirroring, in [0, 2π) [rad].
    n_above_range : int
        Components with |ω'| > ω_max at the last cache update.
    omega_lookup, beta_lookup : numpy.ndarray
        (n,) signed ω' [rad/s] and β [rad] of the last cache update.
    """

    name = "diffraction"

    def __init__(
        self,
        database: xr.Dataset,
        wave_field: WaveField,
        *,
        frequency: Frequency = "wave",
        interpolation: str = "linear",
        heading_tolerance_deg: float = 0.5,
        above_range: AboveRange = "zero",
        heading_extrapolation: HeadingExtrapolation = "raise",
        heading_extrapolation_tolerance_deg: float = 5.0,
        max_heading_gap_deg: float = 90.0,
        speed_terms: SpeedTerms = "all",
        speed_cutoff: float = 0.0,
    ) -> None:
        self.speed_terms: SpeedTerms = check_speed_terms(speed_terms)
        self.speed_cutoff: float = check_speed_cutoff(speed_cutoff)
        self.kirchhoff: NDArray[np.float64] = kirchhoff_parameters(
            speed_terms, speed_cutoff, enabled=frequency == "wave"
        )
        """The speed correction's parameters (:func:`kirchhoff_parameters`)."""
        if not isinstance(database, xr.Dataset):
            raise ValueError(
                f"database must be an xarray.Dataset (ship_gym.hydro.load_database); got "
                f"{type(database).__name__}"
            )
        if "diffraction_force" not in database:
            raise ValueError(
                "database has no 'diffraction_force' variable; expected (omega, "
                "wave_direction, influenced_dof) complex amplitudes per unit wave amplitude"
            )
        if not isinstance(wave_field, WaveField):
            raise ValueError(f"wave_field must be a WaveField; got {type(wave_field).__name__}")
        if frequency not in ("encounter", "wave"):
            raise ValueError(f"frequency={frequency!r}; expected 'encounter' or 'wave'")
        if interpolation != "linear":
            raise ValueError(f"interpolation={interpolation!r}; expected 'linear' (bilinear)")
        if above_range not in ("zero", "raise"):
            raise ValueError(f"above_range={above_range!r}; expected 'zero' or 'raise'")
        tol = float(heading_tolerance_deg)
        if not (math.isfinite(tol) and tol >= 0.0):
            raise ValueError(
                f"heading_tolerance_deg={heading_tolerance_deg!r}; expected a finite angle ≥ 0 "
                "[deg]"
            )
        if heading_extrapolation not in ("raise", "warn", "allow"):
            raise ValueError(
                f"heading_extrapolation={heading_extrapolation!r}; expected 'raise', 'warn' or "
                "'allow'"
            )
        for label, value, top in (
            ("heading_extrapolation_tolerance_deg", heading_extrapolation_tolerance_deg, 360.0),
            ("max_heading_gap_deg", max_heading_gap_deg, 360.0),
        ):
            v = float(value)
            if not (math.isfinite(v) and 0.0 <= v <= top):
                raise ValueError(f"{label}={value!r}; expected an angle in [0, {top:g}] [deg]")
        self.frequency: str = frequency
        self.above_range: str = above_range
        self.wave_field: WaveField = wave_field
        self._heading_tol = math.radians(tol)

        ds = self._full_circle(database)
        finite, _, _ = split_frequencies(ds)
        x = (
            finite["diffraction_force"]
            .sel(influenced_dof=list(DOF_NAMES))
            .transpose("omega", "wave_direction", "influenced_dof")
            .values.astype(complex)
        )
        omega = finite["omega"].values.astype(float)
        beta = np.mod(finite["wave_direction"].values.astype(float), _TWO_PI)
        if omega.size < 2:
            raise ValueError(f"database has {omega.size} finite frequencies; expected ≥ 2")
        if not np.all(np.isfinite(x)):
            raise ValueError("diffraction_force contains non-finite values at finite frequencies")
        order = np.argsort(beta)
        beta, x = beta[order], x[:, order]
        if beta.size < 2 or np.any(np.diff(beta) <= 0):
            raise ValueError(f"wave_direction {beta} must hold ≥ 2 distinct headings")
        self.omega: NDArray[np.float64] = omega
        self.wave_direction: NDArray[np.float64] = beta
        self.complex_mass = self._complex_mass(ds)
        """(grid (m,) [rad/s], Z₃₃ and Z₂₂ (2, m) [kg]) of the speed correction
        (:func:`ship_gym.hydro.forward_speed.complex_mass_table`)."""
        self.covered_headings: list[tuple[float, float]] = covered_heading_arcs(
            beta, math.radians(float(max_heading_gap_deg))
        )
        self._check_heading_coverage(
            wave_field,
            heading_extrapolation,
            math.radians(float(heading_extrapolation_tolerance_deg)),
            database,
        )
        # periodic extension in β: one heading below 0 and one above 2π
        self._beta = np.concatenate([[beta[-1] - _TWO_PI], beta, [beta[0] + _TWO_PI]])
        self._table = np.concatenate([x[:, -1:], x, x[:, :1]], axis=1)

        w = wave_field
        self._kx = np.asarray(w.kx, dtype=float)
        self._ky = np.asarray(w.ky, dtype=float)
        self._n = w.n_components
        self._xd = np.zeros((self._n, CACHE_COLUMNS), dtype=complex)
        self._dxd = np.zeros((self._n, CACHE_COLUMNS), dtype=complex)
        self._psi_ref: float | None = None
        self._u_ref: float | None = None
        self.n_above_range: int = 0
        self.omega_lookup: NDArray[np.float64] = np.zeros(self._n)
        self.beta_lookup: NDArray[np.float64] = np.zeros(self._n)

    def _check_heading_coverage(
        self, wave_field: WaveField, mode: str, tolerance: float, database: xr.Dataset
    ) -> None:
        """Refuse or warn when the field's relative headings (ψ = 0) leave the covered arcs."""
        if mode == "allow" or wave_field.n_components == 0:
            return
        amplitude = np.asarray(wave_field.amplitude, dtype=float)
        chi = np.mod(np.asarray(wave_field.direction, dtype=float), _TWO_PI)[amplitude > 0.0]
        if chi.size == 0:
            return
        distance = heading_distance_to_arcs(chi, self.covered_headings)
        worst = int(np.argmax(distance))
        if distance[worst] <= 1e-9:
            return
        requested = math.degrees(float(chi[worst]))
        covered = describe_arcs(self.covered_headings)
        own = np.mod(database["wave_direction"].values.astype(float), _TWO_PI)
        given = ", ".join(f"{math.degrees(float(b)):.6g}" for b in own)
        mirrored = ", mirrored port-starboard" if self.wave_direction.size > own.size else ""
        message = (
            f"wave heading {requested:.6g} deg (relative to the ship heading north) lies "
            f"{math.degrees(float(distance[worst])):.3g} deg outside the headings the "
            f"diffraction database covers ({covered}; database headings {given} deg"
            f"{mirrored}): its diffraction force would be extrapolated"
        )
        if mode == "raise" and distance[worst] > tolerance:
            raise ValueError(
                f"{message} beyond the tolerance of {math.degrees(tolerance):.3g} deg. Use a "
                "database computed at this heading, or pass heading_extrapolation='warn' or "
                "'allow' to accept the extrapolation"
            )
        warnings.warn(message, UserWarning, stacklevel=3)

    def _complex_mass(self, ds: xr.Dataset) -> tuple[NDArray[np.float64], NDArray[np.complex128]]:
        if self.kirchhoff[3] == 0.0 or not {"added_mass", "radiation_damping"} <= set(ds):
            if self.kirchhoff[3] != 0.0:
                raise ValueError(
                    "the diffraction force at speed needs the database's added_mass and "
                    "radiation_damping (forward_speed eq. 6), or speed_terms='none'"
                )
            return np.array([0.0, 1.0]), np.ones((2, 2), dtype=complex)
        arrays = as_arrays(ds)
        return complex_mass_table(
            arrays.omega, arrays.added_mass, arrays.radiation_damping, arrays.added_mass_zero
        )

    @staticmethod
    def _full_circle(ds: xr.Dataset) -> xr.Dataset:
        beta = np.mod(ds["wave_direction"].values.astype(float), _TWO_PI)
        mirror = np.mod(_TWO_PI - beta, _TWO_PI)
        have = np.isclose(mirror[:, None], beta[None, :], rtol=0.0, atol=1e-9).any(axis=1)
        if np.all(have):
            return ds
        return mirror_headings(ds)

    # ------------------------------------------------------------------ interpolation
    def diffraction_transfer(self, omega: ArrayLike, beta: ArrayLike) -> NDArray[np.complex128]:
        """X_D(ω', β) with the conventions of this model (module docstring).

        Parameters
        ----------
        omega : array_like
            Signed lookup frequencies ω' [rad/s] (negative: conjugated transfer function).
        beta : array_like
            Relative headings β [rad], any value (wrapped to [0, 2π)).

        Returns
        -------
        numpy.ndarray
            Complex (…, 6) [N/m, N·m/m], broadcast shape of ``omega`` and ``beta``.

        Raises
        ------
        ValueError
            If ``above_range="raise"`` and some |ω'| > ω_max.
        """
        w, b = np.broadcast_arrays(np.asarray(omega, dtype=float), np.asarray(beta, dtype=float))
        shape = w.shape
        w, b = w.ravel(), np.mod(b.ravel(), _TWO_PI)
        if not (np.all(np.isfinite(w)) and np.all(np.isfinite(b))):
            raise ValueError("omega and beta must be finite")
        aw = np.abs(w)
        w_max = self.omega[-1]
        above = aw > w_max * (1.0 + 1e-12)
        if np.any(above) and self.above_range == "raise":
            raise ValueError(
                f"lookup frequencies {aw[above]} rad/s exceed the database maximum "
                f"ω_max = {w_max:.6g} rad/s (above_range='raise')"
            )
        out = np.empty((w.size, N_DOF), dtype=complex)
        _transfer_elements(w, b, self._table, self._beta, self.omega, out)
        return out.reshape(*shape, N_DOF)

    @property
    def heading_step(self) -> float:
        """Half-width h [rad] of the central difference ∂X_D/∂ψ ≈ (X_D(ψ + h) − X_D(ψ − h))/2h:
        the heading tolerance, at least 1e-4 rad."""
        return max(self._heading_tol, 1e-4)

    @property
    def heading_tolerance(self) -> float:
        """Heading change [rad] beyond which the cached X_D is recomputed."""
        return self._heading_tol

    def interpolation_table(self) -> tuple[NDArray[np.complex128], NDArray[np.float64]]:
        """The bilinear look-up's data: X_D (n_ω, n_β + 2, 6) on (:attr:`omega`, β) with the
        headings extended periodically by one below 0 and one above 2π, and those headings
        (n_β + 2,) [rad] (copies)."""
        return self._table.copy(), self._beta.copy()

    def heading_expansion(
        self,
        direction: np.ndarray,
        omega: np.ndarray,
        wavenumber: np.ndarray,
        psi: np.ndarray | float,
        speed: float,
    ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """X_D(ω'ⱼ, βⱼ) at heading ψ and speed U and its heading derivative, for any leading
        shape.

        Parameters
        ----------
        direction, omega, wavenumber : numpy.ndarray
            (..., n) component directions χⱼ [rad], frequencies [rad/s], wavenumbers [rad/m].
        psi : numpy.ndarray or float
            Heading(s) ψ [rad], broadcast against the leading shape (e.g. (n_ships, 1)).
        speed : float
            Forward speed U [m/s].

        Returns
        -------
        x, dx : numpy.ndarray
            (..., n, 8) X_D with the scattered momentum's moment factors (:data:`CACHE_COLUMNS`)
            and their ∂/∂ψ (central difference over :attr:`heading_step`).
        omega_lookup, beta : numpy.ndarray
            (..., n) the frequencies and relative headings used.
        """

        def at(heading: np.ndarray | float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
            beta = np.mod(np.asarray(direction, dtype=float) - heading, _TWO_PI)
            wave = np.broadcast_to(np.asarray(omega, dtype=float), beta.shape)
            w_enc = wave - np.asarray(wavenumber, dtype=float) * speed * np.cos(beta)
            w = w_enc if self.frequency == "encounter" else wave
            xd = self.diffraction_transfer(w, beta)
            table = np.zeros((*xd.shape[:-1], CACHE_COLUMNS), dtype=complex)
            table[..., :N_DOF] = xd
            flat = table.reshape(-1, CACHE_COLUMNS)
            _speed_correct_columns(
                np.ascontiguousarray(wave.ravel()), np.ascontiguousarray(w_enc.ravel()),
                self.kirchhoff, *self.complex_mass, flat,
            )  # fmt: skip
            return flat.reshape(table.shape), w, beta

        x, w, beta = at(psi)
        h = self.heading_step
        dx = (at(np.asarray(psi) + h)[0] - at(np.asarray(psi) - h)[0]) / (2.0 * h)
        return x, dx, w, beta

    def _update(self, psi: float, speed: float) -> None:
        # X_D at the reference heading and its heading derivative: between refreshes the force
        # follows X_D + (ψ − ψ_ref) ∂X_D/∂ψ, so it is continuous in ψ; a refresh changes it only
        # by the O(Δψ²) curvature of the interpolated transfer functions (instead of an O(Δψ)
        # jump that would cap the integrators' accuracy)
        w = self.wave_field
        self._xd, self._dxd, omega, beta = self.heading_expansion(
            w.direction, w.omega, w.wavenumber, psi, speed
        )
        self.omega_lookup = omega
        self.beta_lookup = beta
        self.n_above_range = int(np.count_nonzero(np.abs(omega) > self.omega[-1] * (1 + 1e-12)))
        self._psi_ref = psi
        self._u_ref = speed

    # ------------------------------------------------------------------ protocol
    def reset(self, t0: float, ctx: ForceContext) -> None:
        """Drop the cached per-component transfer functions; the ship's surge velocity in
        ``ctx`` becomes the speed U_s of the correction (module docstring)."""
        self._psi_ref = None
        self._u_ref = float(np.asarray(ctx.nu, dtype=float)[SURGE])

    def evaluate(
        self, ctx: ForceContext, states: NDArray[np.float64]
    ) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """Diffraction force at ``ctx`` (body axes, about O).

        Parameters
        ----------
        ctx : ForceContext
            Uses ``eta`` (X_O, Y_O [m], ψ [rad]), ``forward_speed`` U [m/s] and
            ``wave_phasor`` cⱼ(t) [m] (ramp included); when ``wave_phasor`` is None the phasors
            are taken from :meth:`WaveField.phasor` at ``ctx.t``.
        states : numpy.ndarray
            Unused (no states).

        Returns
        -------
        force : numpy.ndarray
            (6,) [N, N·m].
        states_dot : numpy.ndarray
            Empty.
        """
        empty = np.zeros(0)
        if self._n == 0:
            return np.zeros(N_DOF), empty
        c = ctx.wave_phasor
        c = self.wave_field.phasor(ctx.t) if c is None else np.asarray(c)
        if c.shape != (self._n,):
            raise ValueError(
                f"ctx.wave_phasor has shape {c.shape}; expected ({self._n},), one phasor per "
                "component of the wave field"
            )
        eta = np.asarray(ctx.eta, dtype=float)
        if eta.shape != (N_DOF,):
            raise ValueError(f"ctx.eta has shape {eta.shape}; expected (6,)")
        psi = float(eta[YAW])
        u = float(np.asarray(ctx.nu, dtype=float)[SURGE])
        speed = u if self._u_ref is None else self._u_ref  # U_s: the speed at reset
        if self._psi_ref is None or abs(wrap_angle_scalar(psi - self._psi_ref)) > self._heading_tol:
            self._update(psi, speed)
        assert self._psi_ref is not None  # set by _update
        folded = c * np.exp(-1j * (self._kx * eta[0] + self._ky * eta[1]))
        dpsi = wrap_angle_scalar(psi - self._psi_ref)
        columns = (folded.conj() @ (self._xd + dpsi * self._dxd)).real
        force = columns[:N_DOF].copy()
        force[PITCH] += u * columns[N_DOF]
        force[YAW] += u * columns[N_DOF + 1]
        return force, empty


def covered_heading_arcs(beta: np.ndarray, max_gap: float) -> list[tuple[float, float]]:
    """Arcs (start, end) [rad], start in [0, 2π), end > start, of the headings a database covers.

    ``beta``: sorted distinct headings in [0, 2π) [rad]. Consecutive headings (cyclically) whose
    gap is at most ``max_gap`` [rad] are joined; a lone heading is a zero-width arc. The whole
    circle is ``[(0, 2π)]``.
    """
    b = np.sort(np.mod(np.asarray(beta, dtype=float), _TWO_PI))
    n = b.size
    if n == 0:
        return []
    gaps = np.diff(np.concatenate([b, [b[0] + _TWO_PI]]))  # gap after heading i
    open_gaps = np.flatnonzero(gaps > max_gap * (1.0 + 1e-9) + 1e-12)
    if open_gaps.size == 0:
        return [(0.0, _TWO_PI)]
    arcs: list[tuple[float, float]] = []
    for k in range(open_gaps.size):
        first = (open_gaps[k - 1] + 1) % n  # heading after the previous open gap
        last = open_gaps[k]
        start = float(b[first])
        end = float(b[last]) if last >= first else float(b[last]) + _TWO_PI
        arcs.append((start, end))
    return arcs


def heading_distance_to_arcs(beta: np.ndarray, arcs: list[tuple[float, float]]) -> np.ndarray:
    """Angular distance [rad] of each heading ``beta`` [rad] to the nearest of ``arcs``."""
    b = np.mod(np.asarray(beta, dtype=float), _TWO_PI)
    if not arcs:
        return np.full(b.shape, math.pi)
    out = np.full(b.shape, np.inf)
    for start, end in arcs:
        rel = np.mod(b - start, _TWO_PI)  # position after the arc's start
        inside = rel <= (end - start) + 1e-12
        to_end = rel - (end - start)
        to_start = _TWO_PI - rel
        d = np.where(inside, 0.0, np.minimum(to_end, to_start))
        out = np.minimum(out, d)
    return out


def describe_arcs(arcs: list[tuple[float, float]]) -> str:
    """Human-readable covered headings, e.g. ``'135-225 deg'``."""
    if arcs == [(0.0, _TWO_PI)]:
        return "all headings"
    parts = []
    for start, end in arcs:
        a, b = math.degrees(start), math.degrees(end) % 360.0
        parts.append(f"{a:.6g} deg" if end - start <= 1e-12 else f"{a:.6g}-{b:.6g} deg")
    return "covered: " + ", ".join(parts)


# =============================================================================================
# row kernels (numba; the engine's numpy path and its compiled loop call these)
# =============================================================================================
@nb.njit(cache=True, nogil=True)
def transfer_at_heading(heading, speed, diff, out):  # pragma: no cover - compiled
    """out[j] = X_D(ω'ⱼ, βⱼ) at ship heading ψ = ``heading`` [rad] for every component; returns
    the number of components above the table's ω_max.

    As :meth:`Diffraction.heading_expansion`: β = (χⱼ − ψ) mod 2π and, at encounter
    frequency, ω' = ωⱼ − kⱼ U cos β, then the model's own element look-up
    (:func:`ship_gym.forces.diffraction.transfer_element`) and the scattered momentum's moment
    correction at speed (:func:`ship_gym.hydro.forward_speed.speed_correct_element`: X_D to
    speed and the scattered momentum's moment factors in out[j, 6:8]).
    """
    table, beta_ext, omega_db, direction, omega_c, wavenumber, encounter = diff[:7]
    kirchhoff, grid, mass = diff[7:10]
    n_above = 0
    for j in range(direction.shape[0]):
        b = np.mod(direction[j] - heading, _TWO_PI)
        w_enc = omega_c[j] - wavenumber[j] * speed * math.cos(b)
        w = w_enc if encounter else omega_c[j]
        n_above += transfer_element(w, b, table, beta_ext, omega_db, out, j)
        speed_correct_element(omega_c[j], w_enc, kirchhoff, grid, mass, out, j)
    return n_above


@nb.njit(cache=True, nogil=True)
def refresh_diffraction_cache(psi, speed, diff, xd, dxd, diff_ref):  # pragma: no cover
    """Cache X_D and ∂X_D/∂ψ (central difference over ±h) at heading ψ and the ship's speed U_s
    ``speed``, as :meth:`Diffraction.heading_expansion`; returns False, leaving the cache as it
    was, when the model must raise (``above_range="raise"`` and a component above ω_max)."""
    h, must_raise, work, count = diff[10:]
    above = transfer_at_heading(psi, speed, diff, work[0])
    if above > 0 and must_raise:
        return False
    transfer_at_heading(psi + h, speed, diff, work[1])
    transfer_at_heading(psi - h, speed, diff, work[2])
    for j in range(xd.shape[0]):
        for o in range(xd.shape[1]):
            xd[j, o] = work[0, j, o]
            dxd[j, o] = (work[1, j, o] - work[2, j, o]) / (2.0 * h)
    diff_ref[0] = psi
    diff_ref[1] = speed
    count[0] += 1
    return True


@nb.njit(cache=True, nogil=True)
def diffraction_force(psi, u, local, xd, dxd, diff_ref, total):  # pragma: no cover - compiled
    """F_D = Re Σⱼ conj(c'ⱼ)(X_D,ⱼ + Δψ ∂X_D,ⱼ/∂ψ), X_D cached at heading diff_ref[0] (and the
    ship's speed diff_ref[1]), and the scattered momentum's moment u Lᵀ H P_D from the cache's
    columns 6–7 (u the surge velocity [m/s])."""
    dpsi = wrap_angle_scalar(psi - diff_ref[0])
    for o in range(xd.shape[1]):
        s = 0.0
        for j in range(local.shape[0]):
            c = local[j]
            x = xd[j, o] + dpsi * dxd[j, o]
            s += c.real * x.real + c.imag * x.imag
        if o < N_DOF:
            total[o] += s
        elif o == N_DOF:
            total[PITCH] += u * s
        else:
            total[YAW] += u * s


class DiffractionRecord(NamedTuple):
    """The diffraction table, the seas of the ships (N, n_c) and the per-ship caches.

    ``table, beta_ext, omega_db`` the look-up (:func:`transfer_element`); ``direction, omega,
    wavenumber`` χⱼ [rad], ωⱼ [rad/s], kⱼ [rad/m] per ship; ``kirchhoff, mass_grid,
    complex_mass`` the speed correction; ``step`` h [rad] of ∂X_D/∂ψ; ``tolerance`` [rad] of the
    heading cache; ``speed`` U [m/s] for a cache without a reset speed; ``xd, dxd`` (N, n_c, 8)
    and ``ref`` (N, 2) the caches; ``work`` (N, 3, n_c, 8) and ``refresh_count`` (N,) per ship
    (ships refresh concurrently in the parallel loop)."""

    table: NDArray
    beta_ext: NDArray
    omega_db: NDArray
    direction: NDArray
    omega: NDArray
    wavenumber: NDArray
    encounter: bool
    kirchhoff: NDArray
    mass_grid: NDArray
    complex_mass: NDArray
    step: float
    tolerance: float
    speed: float
    xd: NDArray
    dxd: NDArray
    ref: NDArray
    work: NDArray
    refresh_count: NDArray


@nb.njit(cache=True, nogil=True)
def diffraction_row(s, t, q, v, z, zdot, ctx, rec, out):  # pragma: no cover - compiled
    """Row kernel: refresh ship s's heading cache when ψ moved more than the tolerance from
    its reference (:func:`refresh_diffraction_cache`, at the ship's speed at its reset, U
    without one), then add :func:`diffraction_force` with the component phasors at O."""
    psi = q[5]
    ref = rec.ref[s, 0]
    if np.isnan(ref) or abs(wrap_angle_scalar(psi - ref)) > rec.tolerance:
        dtab = (
            rec.table, rec.beta_ext, rec.omega_db, rec.direction[s], rec.omega[s],
            rec.wavenumber[s], rec.encounter, rec.kirchhoff, rec.mass_grid, rec.complex_mass,
            rec.step, False, rec.work[s], rec.refresh_count[s : s + 1],
        )  # fmt: skip
        speed = rec.ref[s, 1]  # U_s: the ship's speed at its reset
        if np.isnan(speed):
            speed = rec.speed
        refresh_diffraction_cache(psi, speed, dtab, rec.xd[s], rec.dxd[s], rec.ref[s])
    diffraction_force(psi, v[0], ctx.local, rec.xd[s], rec.dxd[s], rec.ref[s], out)
