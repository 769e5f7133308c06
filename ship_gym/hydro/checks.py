"""Sanity checks of a hydrodynamic database before it feeds the time-domain model.

:func:`validate_database` gathers every problem it finds and raises one :class:`DatabaseError`
listing them all; on success it returns a report of measured quantities (for the CLI and logs).

What is checked (forward-speed-free, deep-water database in our body frame):

* schema: required variables and their dimensions, the six DOF labels in order, frame attribute;
* finite values (wave forces may be NaN only at ω = 0 and ω = ∞);
* radiation damping: B_ii(ω) ≥ −tol · max_ω B_ii (energy is radiated away, never absorbed);
  B(0) = 0 where present;
* symmetry of A(ω) and B(ω): without forward speed the radiation matrices are symmetric
  (Green's theorem), to BEM accuracy (separate tolerances for A and B: see the Notes of
  :func:`validate_database` for every tolerance and why). Asymmetry of a pair is measured
  relative to the geometric mean of the two diagonal scales,
  |X_ij − X_ji| / sqrt(max|X_ii| max|X_jj|), which is unit-consistent for mixed
  translation/rotation pairs;
* frequency coverage: ω strictly increasing, at least ``min_frequencies`` finite points, A(∞)
  present, and ω_max at least ``min_omega_ratio`` (default 1.5) times the highest heave/roll/
  pitch natural frequency, so that the damping peak and its shoulder are computed; what lies
  beyond ω_max must be extrapolated by the kernel code, and the report gives the tail ratio
  B_ii(ω_max) / max B_ii and ω_max·T_n to judge it. (The S175 with its 1440-panel mesh resolves
  up to 1.67 rad/s ≈ 1.98 × its heave natural frequency, with heave/pitch tail ratios 0.22/0.45.)
* hydrostatics: C33, C44, C55 > 0 (a negative value usually means a z-up frame slipped through or
  the loading condition is unstable); the inertia matrix is symmetric positive definite.
"""

from __future__ import annotations

from typing import Any, Literal

import numpy as np
import xarray as xr

from ship_gym.conventions import BODY_FRAME, DOF_NAMES

HEAVE, ROLL, PITCH = 2, 3, 4


class DatabaseError(ValueError):
    """A hydrodynamic database failed validation; the message lists every problem found."""


_REQUIRED = {
    "added_mass": ("omega", "influenced_dof", "radiating_dof"),
    "radiation_damping": ("omega", "influenced_dof", "radiating_dof"),
    "excitation_force": ("omega", "wave_direction", "influenced_dof"),
    "hydrostatic_stiffness": ("influenced_dof", "radiating_dof"),
    "inertia_matrix": ("influenced_dof", "radiating_dof"),
}
_OPTIONAL = {
    "diffraction_force": ("omega", "wave_direction", "influenced_dof"),
    "Froude_Krylov_force": ("omega", "wave_direction", "influenced_dof"),
}
_DATA_REQUIRED = ("added_mass", "radiation_damping")
"""Variables required at ``level="data"`` (the others are checked only where present)."""

Level = Literal["full", "data"]


NEGLIGIBLE_SAME_KIND = 1e-6
"""A DOF whose diagonal scale is below this fraction of the largest of the same kind is noise."""
NEGLIGIBLE_ROTATIONS = 1e-3
"""All rotations are noise when their largest scale is below this fraction of the largest
translational scale times L² (L the largest radius of gyration about O)."""


def _negligible(diag_scale: np.ndarray, length2: float = float("nan")) -> np.ndarray:
    """DOFs whose diagonal scale is negligible (their entries are numerical noise).

    Translations (0-2) and rotations (3-5) are first compared separately (different units),
    with :data:`NEGLIGIBLE_SAME_KIND`: a body of revolution has, e.g., no yaw added mass or
    damping. When ``length2`` (L² [m²], L a radius of gyration about O) is given, the whole
    rotational block is also compared with the translations, max X_rot < NEGLIGIBLE_ROTATIONS ·
    max X_trans · L²: a hemisphere (or sphere) rotating about its centre O displaces no water, so
    its roll, pitch and yaw entries are all noise and cannot be judged relative to each other.
    Measured max B_rot / (max B_trans L²): 1.1e-6 for the library hemisphere (1.8e-5 on a coarse
    8 × 24 mesh); 0.87, 1.1 and 1.3 for the box barge, the S175 and the Wigley hull (a margin
    of 50 or more on both sides).
    """
    out = np.zeros(6, dtype=bool)
    for block in (slice(0, 3), slice(3, 6)):
        top = float(np.max(diag_scale[block]))
        out[block] = diag_scale[block] <= NEGLIGIBLE_SAME_KIND * top
    top_t = float(np.max(diag_scale[:3]))
    if np.isfinite(length2) and length2 > 0.0 and top_t > 0.0:
        if float(np.max(diag_scale[3:])) < NEGLIGIBLE_ROTATIONS * top_t * length2:
            out[3:] = True
    return out


def _radius_of_gyration2(ds: xr.Dataset) -> float:
    """L² [m²]: the largest rotational inertia about O over the mass, NaN when unavailable."""
    if "inertia_matrix" not in ds:
        return float("nan")
    m = np.asarray(ds["inertia_matrix"].values, dtype=float)
    if m.shape != (6, 6) or not np.all(np.isfinite(m)) or not m[0, 0] > 0.0:
        return float("nan")
    return float(np.max(np.diag(m)[3:]) / m[0, 0])


def _natural_frequency(
    omega: np.ndarray, a_ii: np.ndarray, a_inf: float, m_ii: float, c_ii: float
) -> float:
    """Undamped natural frequency ω_n = sqrt(C / (M + A(ω_n))) by fixed-point iteration."""
    if c_ii <= 0.0 or m_ii + a_inf <= 0.0:
        return float("nan")
    w = np.sqrt(c_ii / (m_ii + a_inf))
    for _ in range(50):
        a = np.interp(w, omega, a_ii, left=a_ii[0], right=a_inf)
        w_new = np.sqrt(c_ii / max(m_ii + a, np.finfo(float).tiny))
        if abs(w_new - w) < 1e-10 * w:
            return float(w_new)
        w = 0.5 * (w + w_new)
    return float(w)


def validate_database(
    ds: xr.Dataset,
    *,
    rtol_symmetry: float = 0.05,
    rtol_symmetry_damping: float = 0.25,
    damping_tolerance: float = 0.01,
    min_frequencies: int = 10,
    min_omega_ratio: float = 1.5,
    require_infinite: bool = True,
    level: Level = "full",
) -> dict[str, Any]:
    """Validate a hydrodynamic database; raise :class:`DatabaseError` listing every problem.

    Parameters
    ----------
    ds : xarray.Dataset
        Database in ship_gym's body frame (schema in :mod:`ship_gym.hydro.database`).
    rtol_symmetry : float
        Largest accepted relative asymmetry of the added mass A (see Tolerances).
    rtol_symmetry_damping : float
        Largest accepted relative asymmetry of the radiation damping B (see Tolerances).
    damping_tolerance : float
        Largest accepted negative diagonal damping, relative to max_ω B_ii of the same DOF
        (see Tolerances).
    min_frequencies : int
        Smallest accepted number of finite frequencies.
    min_omega_ratio : float
        ω_max must reach this multiple of the highest heave/roll/pitch natural frequency.
    require_infinite : bool
        Require the ω = ∞ entry (A(∞)), needed by the retardation kernels.
    level : {"full", "data"}
        ``"full"`` (default): everything above, i.e. a database the time-domain model can use.
        ``"data"``: only that the data present are sound (schema of ``added_mass`` and
        ``radiation_damping`` and of the other variables where present, DOF labels, frame,
        finite values, damping sign, B(0) = 0, symmetry, ω increasing); completeness (wave
        forces, hydrostatics, inertia, A(∞), number and range of frequencies, C33/C44/C55 > 0)
        is not required. :func:`ship_gym.hydro.database.open_database` uses it for foreign
        (capytaine) files, which may hold a partial BEM run.

    Returns
    -------
    dict
        Measured quantities: ``n_frequencies``, ``omega_min``, ``omega_max`` [rad/s],
        ``has_zero_frequency``, ``has_infinite_frequency``, ``wave_directions_deg``,
        ``max_asymmetry_added_mass``, ``max_asymmetry_damping``, ``min_damping_ratio``
        (per DOF), ``natural_periods`` [s] and ``omega_max_times_period`` (heave, roll, pitch),
        ``damping_tail_ratio`` (per DOF), ``C33``, ``C44``, ``C55``, ``GM_T``, ``GM_L`` [m] (from
        C44, C55 and the mass when available).

    Raises
    ------
    DatabaseError
        With one line per problem found.

    Notes
    -----
    Tolerances: what is physics and what is BEM noise. The BEM (constant panels, one
    collocation point each) satisfies the exact relations B_ii ≥ 0 and X_ij = X_ji only to its
    discretisation error, which is largest on coarse meshes and sharp corners; a database is
    refused when a deviation exceeds what that error explains, i.e. when it points to a broken
    database (wrong sign or frame, transposed or mislabelled DOFs, irregular frequencies, a
    failed lid) rather than to a coarse mesh. The numbers quoted are the library hulls with
    their default meshes, 10 frequencies up to the resolved ω_max, lid on (box barge also with
    the CLI's 40 frequencies: 0.032 and 0.173).

    * ``damping_tolerance`` = 0.01: min_ω B_ii ≥ −0.01 · max_ω B_ii. Radiated energy is never
      negative, so a negative diagonal is noise only when it is a small fraction of the DOF's
      own scale (near ω → 0, where B → 0, or at a sharp-cornered box's low-frequency end).
      Measured: no negative diagonal on any library hull (smallest min/max ratios of the
      non-negligible DOFs: box barge sway 2.7e-4, Wigley sway and roll 3e-5, hemisphere
      surge/sway 6e-4, S175 roll 3e-6). The one negative value seen during development,
      −0.030 (box-barge roll), came from a lid that covered only part of the waterplane: an
      irregular frequency, rightly refused. A sign error gives −1.
    * DOFs whose damping or added mass is physically zero (see :func:`_negligible`: below
      1e-6 of the same kind, or all rotations below 1e-3 · max translation · L²) are noise and
      skipped by the sign and symmetry checks: judged against their own tiny scale, their
      noise would look like a large relative error.
    * ``rtol_symmetry`` = 0.05 (added mass) and ``rtol_symmetry_damping`` = 0.25 (radiation
      damping): max_ω |X_ij − X_ji| / sqrt(max_ω |X_ii| · max_ω |X_jj|) ≤ tol, the geometric mean
      of the diagonal scales making translation–rotation pairs unit-consistent. Measured
      (A, B): box barge 0.031, 0.185 (sway–roll); Wigley 0.009, 0.010; S175 0.006, 0.017;
      hemisphere 1e-15 (its rotations are skipped as noise; judged against their own noise
      scale they gave 0.001, 0.004). The sway–roll damping of the box barge converges to symmetry
      with the panel size (first order; a 20 × 10 × 5 m box: 0.090 with 2.5 m panels, 0.034
      with 1.25 m): the flow round its sharp bilges is singular and the library mesh has only
      two panels over the draught, so the roll moment of the sway pressure is poorly resolved.
      B is more sensitive
      than A because its off-diagonal terms pass through zero near the roll-damping minimum,
      where only the absolute error is left. A broken database is far outside both bounds: a
      wrong sign of a coupling term gives 2 max|X_ij| / sqrt(max X_ii max X_jj) (sway–roll
      damping: 1.99 box barge, 1.73 Wigley, 0.52 S175; surge–pitch: 1.95 S175), transposed or
      mislabelled DOFs O(1), an irregular frequency (box barge without a lid) 0.34–0.84.
    * Non-finite values are never noise; B(0) must be 0 to 1e-9 of max|B| (it is set, not
      computed); hydrostatic C33, C44, C55 > 0 and the inertia matrix symmetric to 1e-9 of its
      largest entry (they are not BEM results).
    """
    if not isinstance(ds, xr.Dataset):
        raise DatabaseError(f"expected an xarray.Dataset, got {type(ds).__name__}")
    if level not in ("full", "data"):
        raise ValueError(f"level must be 'full' or 'data', got {level!r}")
    full = level == "full"
    problems: list[str] = []
    report: dict[str, Any] = {}

    # --- schema -----------------------------------------------------------------------------
    for name, dims in {**_REQUIRED, **_OPTIONAL}.items():
        if name not in ds:
            if name in _REQUIRED and (full or name in _DATA_REQUIRED):
                problems.append(f"missing required variable {name!r} with dims {dims}")
            continue
        if set(ds[name].dims) != set(dims):
            problems.append(f"variable {name!r} has dims {ds[name].dims}; expected {dims}")
    for dim in ("influenced_dof", "radiating_dof"):
        if dim in ds.coords:
            labels = tuple(str(v) for v in ds[dim].values)
            if labels != DOF_NAMES:
                problems.append(f"coordinate {dim!r} is {labels}; expected {DOF_NAMES}")
    frame = ds.attrs.get("frame")
    if frame != BODY_FRAME:
        problems.append(
            f"attrs['frame'] is {frame!r}; expected the ship_gym body frame (convert capytaine/"
            "WAMIT data with ship_gym.hydro.frames or open_database)"
        )
    if problems:  # the numeric checks below need a sound schema
        raise DatabaseError("invalid hydrodynamic database:\n  - " + "\n  - ".join(problems))

    dofs = list(DOF_NAMES)
    sel = {"influenced_dof": dofs, "radiating_dof": dofs}
    omega = ds["omega"].values.astype(float)
    a_all = ds["added_mass"].sel(sel).transpose("omega", *sel).values
    b_all = ds["radiation_damping"].sel(sel).transpose("omega", *sel).values
    finite = np.isfinite(omega) & (omega > 0.0)
    has_zero = bool(np.any(omega == 0.0))
    has_inf = bool(np.any(np.isinf(omega)))
    w = omega[finite]
    a, b = a_all[finite], b_all[finite]
    report.update(
        n_frequencies=int(finite.sum()),
        omega_min=float(w.min()) if w.size else float("nan"),
        omega_max=float(w.max()) if w.size else float("nan"),
        has_zero_frequency=has_zero,
        has_infinite_frequency=has_inf,
        wave_directions_deg=(
            np.rad2deg(ds["wave_direction"].values).round(6).tolist()
            if "wave_direction" in ds.coords
            else []
        ),
    )

    # --- frequency axis ---------------------------------------------------------------------
    if np.any(np.isnan(omega)) or np.any(omega < 0.0):
        problems.append(f"omega holds NaN or negative values: {omega}")
    elif np.any(np.diff(omega) <= 0.0):
        problems.append("omega is not strictly increasing")
    if full and finite.sum() < min_frequencies:
        problems.append(
            f"only {int(finite.sum())} finite frequencies; expected at least {min_frequencies}"
        )
    if full and require_infinite and not has_inf:
        problems.append("A(inf) is missing: no omega = inf entry (needed by the kernels)")

    # --- finite values ----------------------------------------------------------------------
    for name, arr in (("added_mass", a_all), ("radiation_damping", b_all)):
        bad = ~np.isfinite(arr)
        if np.any(bad):
            k = np.argwhere(bad)[0]
            problems.append(
                f"{name} has {int(bad.sum())} non-finite value(s), first at omega = "
                f"{omega[k[0]]:.4g} rad/s, ({dofs[k[1]]}, {dofs[k[2]]})"
            )
    for name in ("excitation_force", *_OPTIONAL):
        if name not in ds:
            continue
        f = ds[name].transpose("omega", ...).values[finite]
        bad = ~np.isfinite(f)
        if np.any(bad):
            k = np.argwhere(bad)[0]
            problems.append(
                f"{name} has {int(bad.sum())} non-finite value(s) at finite frequencies, first "
                f"at omega = {w[k[0]]:.4g} rad/s"
            )
    for name in ("hydrostatic_stiffness", "inertia_matrix"):
        if name in ds and not np.all(np.isfinite(ds[name].values)):
            problems.append(f"{name} has non-finite values")

    # --- damping ----------------------------------------------------------------------------
    min_ratio: dict[str, float] = {}
    tail: dict[str, float] = {}
    length2 = _radius_of_gyration2(ds)
    if w.size and np.all(np.isfinite(b)):
        tiny = _negligible(np.max(np.abs(np.einsum("kii->ki", b)), axis=0), length2)
        for i, dof in enumerate(dofs):
            bii = b[:, i, i]
            peak = float(np.max(np.abs(bii)))
            if peak == 0.0 or tiny[i]:
                min_ratio[dof], tail[dof] = 0.0, 0.0
                continue
            min_ratio[dof] = float(bii.min() / peak)
            tail[dof] = float(abs(bii[np.argmax(w)]) / peak)
            if bii.min() < -damping_tolerance * peak:
                k = int(np.argmin(bii))
                problems.append(
                    f"negative radiation damping B[{dof},{dof}] = {bii[k]:.4g} at omega = "
                    f"{w[k]:.4g} rad/s ({bii[k] / peak:.3g} of its maximum; tolerance "
                    f"-{damping_tolerance})"
                )
    if has_zero:
        b0 = b_all[omega == 0.0][0]
        if np.any(np.abs(b0) > 1e-9 * max(float(np.abs(b).max(initial=0.0)), 1e-300)):
            problems.append("radiation damping at omega = 0 is not zero")
    report["min_damping_ratio"] = min_ratio
    report["damping_tail_ratio"] = tail

    # --- symmetry ---------------------------------------------------------------------------
    def asymmetry(x: np.ndarray) -> tuple[float, tuple[str, str]]:
        if not np.all(np.isfinite(x)) or x.size == 0:
            return float("nan"), ("", "")
        d2 = np.max(np.abs(np.einsum("kii->ki", x)), axis=0)
        d = np.sqrt(d2)
        scale = np.maximum(np.outer(d, d), np.finfo(float).tiny)
        r = np.max(np.abs(x - np.swapaxes(x, 1, 2)), axis=0) / scale
        skip = _negligible(d2, length2)
        r[skip, :] = 0.0
        r[:, skip] = 0.0
        i, j = np.unravel_index(np.argmax(r), r.shape)
        return float(r[i, j]), (dofs[i], dofs[j])

    for name, x, tol in (
        ("added_mass", a_all[np.isfinite(omega)], rtol_symmetry),
        ("radiation_damping", b, rtol_symmetry_damping),
    ):
        r, pair = asymmetry(x)
        report[f"max_asymmetry_{'added_mass' if name == 'added_mass' else 'damping'}"] = r
        report[f"max_asymmetry_{'added_mass' if name == 'added_mass' else 'damping'}_pair"] = pair
        if r > tol:
            problems.append(
                f"{name} is not symmetric: |X_ij - X_ji| reaches {r:.3g} of the diagonal scale "
                f"for ({pair[0]}, {pair[1]}) (tolerance {tol}); a zero-speed database "
                "must be symmetric (a coarse mesh gives a few %; refine it if this is close)"
            )

    if not full:
        if problems:
            raise DatabaseError("invalid hydrodynamic database:\n  - " + "\n  - ".join(problems))
        return report

    # --- hydrostatics and inertia -------------------------------------------------------------
    c = ds["hydrostatic_stiffness"].sel(sel).values.astype(float)
    m = ds["inertia_matrix"].sel(sel).values.astype(float)
    for i, label in ((HEAVE, "C33"), (ROLL, "C44"), (PITCH, "C55")):
        report[label] = float(c[i, i])
        if not c[i, i] > 0.0:
            problems.append(
                f"{label} = {c[i, i]:.6g} is not positive (hydrostatic stiffness of "
                f"{dofs[i]}); a z-up frame or an unstable loading condition?"
            )
    if np.all(np.isfinite(m)):
        if not np.allclose(m, m.T, rtol=0.0, atol=1e-9 * np.abs(m).max()):
            problems.append("inertia_matrix is not symmetric")
        elif np.any(np.linalg.eigvalsh(m) <= 0.0):
            problems.append("inertia_matrix is not positive definite")
    mass = float(m[0, 0]) if np.isfinite(m[0, 0]) else float("nan")
    g = float(ds.attrs.get("g", np.nan))
    report["GM_T"] = float(c[ROLL, ROLL] / (mass * g)) if mass > 0 and g > 0 else float("nan")
    report["GM_L"] = float(c[PITCH, PITCH] / (mass * g)) if mass > 0 and g > 0 else float("nan")

    # --- natural periods and coverage ---------------------------------------------------------
    periods: dict[str, float] = {}
    w_times_t: dict[str, float] = {}
    if w.size >= 2 and np.all(np.isfinite(a)):
        a_inf_all = a_all[np.isinf(omega)][0] if has_inf else a[-1]
        w_n_max = 0.0
        for i in (HEAVE, ROLL, PITCH):
            wn = _natural_frequency(w, a[:, i, i], float(a_inf_all[i, i]), m[i, i], c[i, i])
            periods[dofs[i]] = float(2.0 * np.pi / wn) if np.isfinite(wn) else float("nan")
            w_times_t[dofs[i]] = float(w.max() * 2.0 * np.pi / wn) if np.isfinite(wn) else np.nan
            if np.isfinite(wn):
                w_n_max = max(w_n_max, wn)
        if w_n_max > 0.0 and w.max() < min_omega_ratio * w_n_max:
            problems.append(
                f"omega_max = {w.max():.4g} rad/s is below {min_omega_ratio} x the highest "
                f"natural frequency {w_n_max:.4g} rad/s: the retardation kernels would be "
                f"truncated; compute up to {min_omega_ratio * w_n_max:.4g} rad/s (a mesh "
                "resolves up to omega = sqrt(2 pi g / (8 r_max)): panels of radius r_max <= "
                f"{2 * np.pi * g / (8 * (min_omega_ratio * w_n_max) ** 2):.3g} m)"
            )
    report["natural_periods"] = periods
    report["omega_max_times_period"] = w_times_t

    if problems:
        raise DatabaseError("invalid hydrodynamic database:\n  - " + "\n  - ".join(problems))
    return report
