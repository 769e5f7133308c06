"""Import WAMIT numeric output (``.1``, ``.3``, ``.hst``) into a ship_gym database.

WAMIT conventions (WAMIT User Manual, chapters 3–5) and how they are converted
--------------------------------------------------------------------------------
* **Frame**: the body axes of the geometry file; for a ship x forward, y to **port**, z **up**,
  origin on the free surface. This is capytaine's frame; it is assumed to coincide with ours at
  O (amidships on the waterline) and is converted by :mod:`ship_gym.hydro.frames`.
* **Time convention**: x(t) = Re(X e^{+iωt}); ship_gym (and capytaine) use Re(X e^{−iωt}), so
  every complex amplitude is **conjugated**. Both place the incident crest at the origin at t = 0.
* **Heading**: BETA [deg] is the direction of propagation, measured from +x toward +y (port), as
  capytaine's ``wave_direction``; ours is β = −BETA (mod 2π).
* **Non-dimensional values**, with ULEN = L [m]:

  - ``.1``:  PER I J Ā_ij B̄_ij with A_ij = ρ L^k Ā_ij and B_ij = ρ ω L^k B̄_ij, k = 3 when i, j
    are both translations (1–3), 4 for mixed pairs, 5 when both are rotations (4–6). Two special
    periods carry added mass only: **PER = −1 is the infinite-period limit (ω = 0)** and
    **PER = 0 the zero-period limit (ω = ∞)**, as written by capytaine's WAMIT exporter and read by
    BEMRosetta.
  - ``.3``:  PER BETA I Mod Pha Re Im with X_i = ρ g A L^m X̄_i, m = 2 for forces, 3 for
    moments, per unit wave amplitude A. Re and Im are used (Mod and Pha are redundant).
  - ``.hst``: I J C̄_ij with C_ij = ρ g L^k C̄_ij, k = 2 + the number of rotational indices
    (C33 ~ ρ g L², C34 ~ ρ g L³, C44 ~ ρ g L⁴: this is what dimensional analysis requires).

* First column: period [s] (WAMIT's default IPEROUT = 1) or angular frequency [rad/s]
  (IPEROUT = 2), chosen with ``period_column``. Only single-body, rigid-body files (I, J ≤ 6) are
  supported.
"""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np
import xarray as xr

from ship_gym.conventions import DOF_NAMES, GRAVITY, RHO_SEAWATER
from ship_gym.hydro import frames

_ROTATION = np.array([False, False, False, True, True, True])

EXPECTED: dict[int, str] = {
    4: "a WAMIT .1 file (text rows 'PER I J A B'; PER = -1 and 0 rows hold A only)",
    7: "a WAMIT .3 file (text rows 'PER BETA I Mod Pha Re Im')",
    3: "a WAMIT .hst file (text rows 'I J C')",
}
"""What each reader expects, by its minimum number of columns (quoted in error messages)."""


class WamitFileError(ValueError):
    """A WAMIT numeric file is empty, binary, truncated or malformed; the message names it."""


def _read_rows(path: Path, min_cols: int) -> list[list[float]]:
    """Numeric rows of a WAMIT text file (Fortran 'D' exponents accepted, headers skipped)."""
    expected = EXPECTED.get(min_cols, f"a WAMIT text file with {min_cols} columns")
    where = f"WAMIT file {str(path)!r}"
    if path.is_dir():
        raise IsADirectoryError(f"{where} is a directory; expected {expected}")
    if not path.is_file():
        raise FileNotFoundError(f"{where} not found; expected {expected}")
    data = path.read_bytes()
    if not data.strip():
        raise WamitFileError(f"{where} is empty; expected {expected}")
    sample = data[:4096]
    printable = sum(32 <= c < 127 or c in (9, 10, 13) for c in sample)
    if b"\x00" in sample or printable < 0.95 * len(sample):
        raise WamitFileError(f"{where} is not a text file (binary content); expected {expected}")
    rows: list[list[float]] = []
    text = data.decode("ascii", errors="replace")
    for number, line in enumerate(text.splitlines(), start=1):
        tokens = line.replace("D", "E").replace("d", "e").split()
        if not tokens:
            continue
        try:
            values = [float(t) for t in tokens]
        except ValueError:
            if rows:
                raise WamitFileError(
                    f"{str(path)!r} line {number}: cannot read numbers from {line.strip()!r}; "
                    f"expected {expected}"
                ) from None
            continue  # a header before the data
        if len(values) < min_cols:
            raise WamitFileError(
                f"{str(path)!r} line {number}: expected at least {min_cols} columns, got "
                f"{len(values)}: {line.strip()!r} (file truncated?); expected {expected}"
            )
        if not all(np.isfinite(values)):
            raise WamitFileError(
                f"{str(path)!r} line {number}: non-finite value in {line.strip()!r}; expected "
                f"{expected}"
            )
        rows.append(values)
    if not rows:
        raise WamitFileError(f"{str(path)!r} holds no numeric data; expected {expected}")
    return rows


def _check_complete(groups: dict, path: Path, what: str, label: str, expected: str) -> None:
    """Every group (frequency, or frequency and heading) must hold the same entries: a file cut
    at a line boundary leaves the last group short."""
    if len(groups) < 2:
        return
    union: set = set().union(*groups.values())
    for key, entries in groups.items():
        if set(entries) != union:
            missing = sorted(union - set(entries))
            first = missing[0]
            shown = tuple(x + 1 for x in first) if isinstance(first, tuple) else first + 1
            raise WamitFileError(
                f"{str(path)!r}: {label} {key} lack {len(missing)} of the {len(union)} {what} "
                f"present elsewhere in the file (first missing: {shown}; file truncated?); "
                f"expected {expected}"
            )


def _dof_index(value: float, path: Path) -> int:
    i = round(value)
    if i != value or not 1 <= i <= 6:
        raise WamitFileError(
            f"{str(path)!r}: mode index {value!r} is not in 1..6; only single rigid bodies are "
            "supported"
        )
    return i - 1


def _exponent(i: int, j: int, base: int) -> int:
    return base + int(_ROTATION[i]) + int(_ROTATION[j])


def _omega_from_first_column(x: float, period_column: str, path: Path) -> float:
    """Angular frequency [rad/s] from the first column; −1 → 0 and 0 → inf for periods."""
    if period_column == "period":
        if x < 0.0:
            if x != -1.0:
                raise WamitFileError(f"{str(path)!r}: negative period {x!r}; only -1 (omega = 0)")
            return 0.0
        return np.inf if x == 0.0 else 2.0 * np.pi / x
    if not (np.isfinite(x) and x > 0.0):
        raise WamitFileError(
            f"{str(path)!r}: frequency {x!r} rad/s must be > 0 with period_column='omega' (the "
            "zero/infinite limits are only recognised as PER = -1 / 0 with period_column="
            "'period')"
        )
    return float(x)


def _check_period_column(period_column: str) -> None:
    if period_column not in ("period", "omega"):
        raise ValueError(f"period_column must be 'period' or 'omega', got {period_column!r}")


def read_wamit_1(
    path: str | os.PathLike, *, rho: float, ulen: float = 1.0, period_column: str = "period"
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Dimensional added mass and damping from a WAMIT ``.1`` file, in WAMIT's frame.

    Parameters
    ----------
    path : str or os.PathLike
        The ``.1`` file.
    rho : float
        Water density [kg/m³].
    ulen : float
        WAMIT length scale ULEN [m].
    period_column : {"period", "omega"}
        Meaning of the first column.

    Returns
    -------
    omega : numpy.ndarray
        (n,) sorted frequencies [rad/s], 0 and inf included when present.
    added_mass, radiation_damping : numpy.ndarray
        (n, 6, 6) [SI]; entries absent from the file are 0; damping is 0 at ω = 0 and ∞.
    """
    path = Path(path)
    _check_period_column(period_column)
    rows = _read_rows(path, 4)
    entries: dict[float, dict[tuple[int, int], tuple[float, float]]] = {}
    for r in rows:
        w = _omega_from_first_column(r[0], period_column, path)
        i, j = _dof_index(r[1], path), _dof_index(r[2], path)
        if np.isfinite(w) and w > 0.0:
            if len(r) < 5:
                raise WamitFileError(
                    f"{str(path)!r}: finite period {r[0]!r} without damping column"
                )
            b = r[4]
        else:
            b = 0.0
        entries.setdefault(w, {})[(i, j)] = (r[3], b)
    finite_entries = {
        f"omega = {w:.6g} rad/s": e for w, e in entries.items() if np.isfinite(w) and w > 0.0
    }
    _check_complete(finite_entries, path, "(I, J) entries", "the rows at", EXPECTED[4])
    omega = np.array(sorted(entries))
    a = np.zeros((len(omega), 6, 6))
    bb = np.zeros_like(a)
    for n, w in enumerate(omega):
        for (i, j), (a_nd, b_nd) in entries[w].items():
            scale = rho * ulen ** _exponent(i, j, 3)
            a[n, i, j] = a_nd * scale
            bb[n, i, j] = b_nd * scale * w if np.isfinite(w) else 0.0
    return omega, a, bb


def read_wamit_3(
    path: str | os.PathLike,
    *,
    rho: float,
    g: float,
    ulen: float = 1.0,
    period_column: str = "period",
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Dimensional excitation from a WAMIT ``.3`` (or ``.3fk``/``.3sc``) file, WAMIT conventions.

    Returns
    -------
    omega : numpy.ndarray
        (n,) sorted frequencies [rad/s].
    beta_deg : numpy.ndarray
        (m,) sorted WAMIT headings [deg] (direction of propagation from +x toward +y).
    force : numpy.ndarray
        (n, m, 6) complex amplitudes per unit wave amplitude [N/m, N·m/m], **WAMIT's time
        convention** Re(X e^{iωt}); NaN where the file has no entry.
    """
    path = Path(path)
    _check_period_column(period_column)
    rows = _read_rows(path, 7)
    data = []
    for r in rows:
        w = _omega_from_first_column(r[0], period_column, path)
        if not (np.isfinite(w) and w > 0.0):
            raise WamitFileError(f"{str(path)!r}: excitation at period {r[0]!r} is not defined")
        data.append((w, r[1], _dof_index(r[2], path), complex(r[5], r[6])))
    groups: dict[str, set] = {}
    for w, beta_value, i, _ in data:
        groups.setdefault(f"omega = {w:.6g} rad/s, BETA = {beta_value:.6g} deg", set()).add(i)
    _check_complete(groups, path, "modes I", "the rows at", EXPECTED[7])
    omega = np.array(sorted({d[0] for d in data}))
    beta = np.array(sorted({d[1] for d in data}))
    force = np.full((len(omega), len(beta), 6), np.nan + 0j)
    w_index = {w: n for n, w in enumerate(omega)}
    b_index = {b: n for n, b in enumerate(beta)}
    for w, b, i, x in data:
        m_exp = 3 if _ROTATION[i] else 2
        force[w_index[w], b_index[b], i] = x * rho * g * ulen**m_exp
    return omega, beta, force


def read_wamit_hst(
    path: str | os.PathLike, *, rho: float, g: float, ulen: float = 1.0
) -> np.ndarray:
    """Dimensional 6×6 hydrostatic stiffness [N/m, N, N·m] from a ``.hst`` file, WAMIT frame."""
    path = Path(path)
    c = np.zeros((6, 6))
    for r in _read_rows(path, 3):
        i, j = _dof_index(r[0], path), _dof_index(r[1], path)
        c[i, j] = r[2] * rho * g * ulen ** _exponent(i, j, 2)
    return c


def _union_axis(*axes: np.ndarray | None) -> np.ndarray:
    """Sorted union of frequency axes, merging values equal to 1e-9 relative."""
    values = np.sort(np.concatenate([np.asarray(a, dtype=float) for a in axes if a is not None]))
    out: list[float] = []
    for v in values:
        if out and (v == out[-1] or (np.isfinite(v) and abs(v - out[-1]) <= 1e-9 * abs(v))):
            continue
        out.append(float(v))
    return np.array(out)


def _positions(axis: np.ndarray, values: np.ndarray) -> np.ndarray:
    idx = []
    for v in values:
        hit = np.flatnonzero((axis == v) | np.isclose(axis, v, rtol=1e-9, atol=0.0))
        idx.append(int(hit[0]))
    return np.array(idx, dtype=int)


def read_wamit(
    prefix: str | os.PathLike | None = None,
    *,
    rho: float = RHO_SEAWATER,
    g: float = GRAVITY,
    ulen: float = 1.0,
    file_1: str | os.PathLike | None = None,
    file_3: str | os.PathLike | None = None,
    file_hst: str | os.PathLike | None = None,
    inertia_matrix: np.ndarray | None = None,
    period_column: str = "period",
    name: str | None = None,
) -> xr.Dataset:
    """Build a ship_gym database (our body frame) from WAMIT ``.1``, ``.3`` and ``.hst`` files.

    Parameters
    ----------
    prefix : str or os.PathLike, optional
        Common path without extension: reads ``prefix.1``, ``prefix.3`` and ``prefix.hst`` (the
        last two only if they exist). Explicit ``file_*`` arguments override it.
    rho : float
        Water density used by the WAMIT run [kg/m³].
    g : float
        Gravitational acceleration used by the WAMIT run [m/s²].
    ulen : float
        WAMIT length scale ULEN [m].
    file_1, file_3, file_hst : str or os.PathLike, optional
        Individual files (``.1`` is required, the others optional).
    inertia_matrix : numpy.ndarray, optional
        (6, 6) rigid-body mass matrix about O **in our frame** [kg, kg·m, kg·m²] (WAMIT's numeric
        files do not hold it); stored as ``inertia_matrix``.
    period_column : {"period", "omega"}
        Meaning of the first column (WAMIT's IPEROUT = 1 or 2).
    name : str, optional
        Label stored in ``attrs["mesh_name"]``.

    Returns
    -------
    xarray.Dataset
        The database in our frame (schema of :mod:`ship_gym.hydro.database`): complex amplitudes
        conjugated to Re(X e^{−iωt}), headings β = −BETA (mod 2π), DOF signs flipped for sway,
        heave, pitch and yaw.

    Raises
    ------
    ValueError
        For bad parameters; :class:`WamitFileError` (a ValueError naming the file and the
        format expected) for empty, binary, truncated or malformed files.
    FileNotFoundError
        If a requested file does not exist (:class:`IsADirectoryError` for a directory).
    """
    for label, value in (("rho", rho), ("g", g), ("ulen", ulen)):
        if not (np.isfinite(value) and value > 0.0):
            raise ValueError(f"{label} must be a positive finite number, got {value!r}")
    if prefix is not None:
        base = os.fspath(prefix)
        file_1 = file_1 if file_1 is not None else f"{base}.1"
        if file_3 is None and Path(f"{base}.3").is_file():
            file_3 = f"{base}.3"
        if file_hst is None and Path(f"{base}.hst").is_file():
            file_hst = f"{base}.hst"
    if file_1 is None:
        raise ValueError("read_wamit needs a prefix or file_1 (the .1 added-mass/damping file)")
    for f, minimum in ((file_1, 4), (file_3, 7), (file_hst, 3)):
        if f is not None and Path(f).is_dir():
            raise IsADirectoryError(
                f"WAMIT file {os.fspath(f)!r} is a directory; expected {EXPECTED[minimum]}"
            )
        if f is not None and not Path(f).is_file():
            raise FileNotFoundError(
                f"WAMIT file {os.fspath(f)!r} not found; expected {EXPECTED[minimum]}"
            )

    w1, a, b = read_wamit_1(file_1, rho=rho, ulen=ulen, period_column=period_column)
    if file_3 is not None:
        w3, beta_deg, x_wamit = read_wamit_3(
            file_3, rho=rho, g=g, ulen=ulen, period_column=period_column
        )
    else:
        w3, beta_deg, x_wamit = None, np.array([]), None
    omega = _union_axis(w1, w3)
    dof3 = ("omega", "influenced_dof", "radiating_dof")
    n = len(omega)
    a_full = np.full((n, 6, 6), np.nan)
    b_full = np.full((n, 6, 6), np.nan)
    a_full[_positions(omega, w1)] = a
    b_full[_positions(omega, w1)] = b
    coords = {
        "omega": omega,
        "influenced_dof": list(DOF_NAMES),
        "radiating_dof": list(DOF_NAMES),
    }
    ds_w = xr.Dataset(
        {"added_mass": (dof3, a_full), "radiation_damping": (dof3, b_full)}, coords=coords
    )
    if x_wamit is not None:
        assert w3 is not None  # read together with x_wamit
        x_full = np.full((n, len(beta_deg), 6), np.nan + 0j)
        x_full[_positions(omega, w3)] = np.conj(x_wamit)  # to Re(X e^{-iωt})
        ds_w["excitation_force"] = xr.DataArray(
            x_full,
            dims=("omega", "wave_direction", "influenced_dof"),
            coords={"wave_direction": np.deg2rad(beta_deg)},
        )
    if file_hst is not None:
        c = read_wamit_hst(file_hst, rho=rho, g=g, ulen=ulen)
        ds_w["hydrostatic_stiffness"] = (("influenced_dof", "radiating_dof"), c)
    with np.errstate(divide="ignore"):
        ds_w = ds_w.assign_coords(period=("omega", 2.0 * np.pi / omega))  # inf at 0, 0 at inf
    ds = frames.dataset_from_capytaine(ds_w)
    if inertia_matrix is not None:
        m6 = np.asarray(inertia_matrix, dtype=float)
        if m6.shape != (6, 6) or not np.all(np.isfinite(m6)):
            raise ValueError(f"inertia_matrix must be a finite (6, 6) array, got {m6.shape}")
        ds["inertia_matrix"] = (("influenced_dof", "radiating_dof"), m6)
    files = [os.fspath(f) for f in (file_1, file_3, file_hst) if f is not None]
    ds.attrs.update(
        rho=float(rho),
        g=float(g),
        wamit_ulen=float(ulen),
        water_depth="as in the WAMIT run",
        forward_speed=0.0,
        mesh_name=str(name) if name is not None else Path(file_1).stem,
        source="WAMIT numeric output: " + ", ".join(Path(f).name for f in files),
        wamit_conversion=(
            "complex amplitudes conjugated (WAMIT Re(X exp(+i omega t))); beta = -BETA mod 2pi; "
            "y, z, sway, heave, pitch, yaw sign-flipped; PER=-1 -> omega=0, PER=0 -> omega=inf"
        ),
    )
    return ds
