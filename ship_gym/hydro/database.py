"""Hydrodynamic databases: schema, NetCDF storage, loading, and small accessors.

Schema (every database built by :mod:`ship_gym.hydro.bem`, imported by
:mod:`ship_gym.hydro.wamit` or read by :func:`open_database`)
-------------------------------------------------------------------------------------------
An :class:`xarray.Dataset` in ship_gym's **body frame** (:mod:`ship_gym.conventions`: x forward,
y starboard, z down, origin O amidships on the design waterline) with capytaine's names and axes:

=========================  ==========================================  ======================
variable                   dims                                        units
=========================  ==========================================  ======================
``added_mass``             (omega, influenced_dof, radiating_dof)      kg, kg·m, kg·m²
``radiation_damping``      (omega, influenced_dof, radiating_dof)      kg/s, kg·m/s, kg·m²/s
``excitation_force``       (omega, wave_direction, influenced_dof)     N/m, N·m/m (complex)
``diffraction_force``      (omega, wave_direction, influenced_dof)     (complex, optional)
``Froude_Krylov_force``    (omega, wave_direction, influenced_dof)     (complex, optional)
``hydrostatic_stiffness``  (influenced_dof, radiating_dof)             N/m, N, N·m
``inertia_matrix``         (influenced_dof, radiating_dof)             kg, kg·m, kg·m²
=========================  ==========================================  ======================

* ``influenced_dof`` / ``radiating_dof``: the strings ``DOF_NAMES`` = Surge, Sway, Heave, Roll,
  Pitch, Yaw, in that order. A_ij is the force in DOF i due to the acceleration of DOF j.
* ``omega`` [rad/s], increasing. The zero- and infinite-frequency limits are stored **on the same
  axis**, as ``omega[0] = 0`` and ``omega[-1] = inf`` (NetCDF stores IEEE inf): there only
  ``added_mass`` (A(0), A(∞)) and ``radiation_damping`` (0) are defined and the wave forces are
  NaN. :func:`split_frequencies` separates them. Optional coordinates along ``omega``:
  ``period`` [s], ``wavenumber`` [rad/m].
* ``wave_direction`` β [rad] in [0, 2π), ship_gym's heading convention (0 following seas, π head
  seas, π/2 waves travelling toward starboard). Wave forces are complex amplitudes per unit
  wave amplitude [N/m, N·m/m], time convention x(t) = Re(X e^{−iωt}), phase referred to a crest
  at O at t = 0.
* Moments and rotations are about O. Forward speed zero, deep water.
* ``attrs``: ``frame`` (= :data:`~ship_gym.conventions.BODY_FRAME`, the marker that the data
  are in our frame), ``time_convention``, ``wave_heading``, ``rho`` [kg/m³], ``g`` [m/s²],
  ``source``, ``created``, and where known ``mesh_name``, ``n_panels``, ``symmetry``, ``lid_z``,
  ``mass``, ``cog``, ``omega_limits``.

File format
-----------
NetCDF-4 (HDF5; written with h5netcdf when h5py is installed, otherwise with netCDF4). Complex
variables are split into two real variables ``<name>_real`` and ``<name>_imag`` (tagged with the
attribute ``complex_part``), so the file opens in any NetCDF reader. Files are written atomically
(temporary file in the same directory, then :func:`os.replace`): a failed save never corrupts an
existing file. :func:`open_database`
also reads capytaine's own NetCDF export (``export_dataset`` / ``separate_complex_values``, with a
``complex`` dimension holding ``re``/``im``), which is in capytaine's z-up frame and is converted
with :mod:`ship_gym.hydro.frames`.
"""

from __future__ import annotations

import importlib.util
import os
import warnings
from importlib import resources
from pathlib import Path
from typing import Any, Literal, NamedTuple

import numpy as np
import xarray as xr

from ship_gym.conventions import BODY_FRAME, DOF_NAMES
from ship_gym.hydro import frames
from ship_gym.hydro.checks import DatabaseError, validate_database
from ship_gym.io_utils import atomic_write

FORMAT_VERSION: int = 1
"""Value of ``attrs["ship_gym_format"]`` written by :func:`save_database`."""

_COMPLEX_TAG = "complex_part"
_DOF_DIMS = ("influenced_dof", "radiating_dof")
_ATTR_SCALARS = (str, int, float, np.integer, np.floating)


EXPECTED_DATABASE: str = (
    "a hydrodynamic database written by ship-gym hydro / save_database or a capytaine NetCDF "
    "export: variables added_mass, radiation_damping (omega, influenced_dof, radiating_dof), "
    "excitation_force (omega, wave_direction, influenced_dof), hydrostatic_stiffness and "
    "inertia_matrix (influenced_dof, radiating_dof)"
)
"""What :func:`open_database` expects, quoted in its error messages."""

_NETCDF_MAGIC = (b"\x89HDF\r\n\x1a\n", b"CDF\x01", b"CDF\x02", b"CDF\x05")

ValidateLevel = Literal["auto", "full", "data", "none"]


class DatabaseFileError(DatabaseError):
    """A database file cannot be read or is not a sound hydrodynamic database.

    A :class:`ValueError` (via :class:`~ship_gym.hydro.checks.DatabaseError`); the message names
    the file, the problem and what was expected.
    """


# (resolved path, mtime_ns, size, level, options) of files that passed validation
_VALIDATED: set[tuple[Any, ...]] = set()


# ------------------------------------------------------------------------------ save / open
def netcdf_engine() -> Literal["h5netcdf", "netcdf4"]:
    """xarray engine used to write NetCDF-4: ``"h5netcdf"`` (needs h5py) or ``"netcdf4"``."""
    if importlib.util.find_spec("h5netcdf") and importlib.util.find_spec("h5py"):
        return "h5netcdf"
    if importlib.util.find_spec("netCDF4"):
        return "netcdf4"
    raise ValueError(
        "no NetCDF-4 writer available: install netCDF4, or h5netcdf together with h5py"
    )


def _check_attrs(attrs: dict, where: str) -> None:
    for key, value in attrs.items():
        ok = isinstance(value, _ATTR_SCALARS) and not isinstance(value, bool | np.bool_)
        if isinstance(value, np.ndarray | list | tuple):
            arr = np.asarray(value)
            ok = arr.ndim == 1 and arr.dtype.kind in "iufU"
        if not ok:
            raise ValueError(
                f"cannot store attribute {key!r} of {where} in NetCDF: value {value!r} of type "
                f"{type(value).__name__}; expected a string, a number or a 1-D array of numbers"
            )


def _split_complex(ds: xr.Dataset) -> xr.Dataset:
    out = ds.copy()
    for name in list(ds.data_vars):
        da = ds[name]
        if np.iscomplexobj(da.values):
            for part, values in (("real", da.real), ("imag", da.imag)):
                new = xr.DataArray(values.values, dims=da.dims, attrs=dict(da.attrs))
                new.attrs[_COMPLEX_TAG] = part
                out[f"{name}_{part}"] = new
            out = out.drop_vars([name])
    return out


def save_database(ds: xr.Dataset, path: str | os.PathLike) -> Path:
    """Write a database to NetCDF-4, atomically.

    Complex variables become ``<name>_real`` / ``<name>_imag``; string coordinates are stored as
    strings; ``inf`` frequencies are stored as IEEE inf.

    Parameters
    ----------
    ds : xarray.Dataset
        Database (any frame; :func:`open_database` relies on ``attrs["frame"]``).
    path : str or os.PathLike
        Output file (conventionally ``*.nc``); its directory must exist.

    Returns
    -------
    pathlib.Path
        The path written.

    Raises
    ------
    ValueError
        If ``ds`` is not a Dataset or has attributes NetCDF cannot store. Any error leaves an
        existing file at ``path`` untouched and removes the temporary file.
    """
    if not isinstance(ds, xr.Dataset):
        raise ValueError(f"expected an xarray.Dataset to save, got {type(ds).__name__}")
    path = Path(path)
    if not path.parent.is_dir():
        raise FileNotFoundError(f"directory {str(path.parent)!r} does not exist")
    _check_attrs(ds.attrs, "the dataset")
    for name, var in ds.variables.items():
        _check_attrs(var.attrs, f"variable {name!r}")
    out = _split_complex(ds)
    for name in list(out.coords):
        if out[name].dtype.kind in "OU":
            out = out.assign_coords({name: out[name].astype(str)})
    out.attrs["ship_gym_format"] = FORMAT_VERSION
    return atomic_write(
        path,
        lambda tmp: out.to_netcdf(tmp, engine=netcdf_engine(), format="NETCDF4"),
        make_parents=False,
    )


def _merge_ours(ds: xr.Dataset) -> xr.Dataset:
    out = ds.copy()
    for name in list(ds.data_vars):
        if not (isinstance(name, str) and name.endswith("_real")):
            continue
        base = name[: -len("_real")]
        imag = f"{base}_imag"
        tagged = ds[name].attrs.get(_COMPLEX_TAG) == "real"
        if imag not in ds or (not tagged and base in ds):
            continue
        re, im = ds[name], ds[imag]
        attrs = {k: v for k, v in re.attrs.items() if k != _COMPLEX_TAG}
        out = out.drop_vars([name, imag])
        out[base] = xr.DataArray(re.values + 1j * im.values, dims=re.dims, attrs=attrs)
    return out


def _merge_capytaine(ds: xr.Dataset) -> xr.Dataset:
    """capytaine's ``merge_complex_values``: a ``complex`` dimension with labels re/im."""
    out = ds.copy()
    labels = [str(v) for v in ds["complex"].values]
    if sorted(labels) != ["im", "re"]:
        raise ValueError(f"unexpected 'complex' coordinate {labels}; expected ['re', 'im']")
    for name in list(ds.data_vars):
        da = ds[name]
        if "complex" in da.dims:
            dims = tuple(d for d in da.dims if d != "complex")
            values = da.sel(complex="re").values + 1j * da.sel(complex="im").values
            out[name] = xr.DataArray(values, dims=dims, attrs=dict(da.attrs))
    return out.drop_vars("complex")


def _read_netcdf(path: Path) -> xr.Dataset:
    """The file's raw Dataset, loaded and closed; :class:`DatabaseFileError` for anything that
    is not a readable NetCDF file."""
    where = f"hydrodynamic database file {str(path)!r}"
    size = path.stat().st_size
    if size == 0:
        raise DatabaseFileError(f"{where} is empty (0 bytes); expected {EXPECTED_DATABASE}")
    with open(path, "rb") as fh:
        head = fh.read(8)
    if not head.startswith(_NETCDF_MAGIC):
        text = head.decode("ascii", errors="replace")
        raise DatabaseFileError(
            f"{where} is not a NetCDF file (it starts with {text!r}, not the HDF5/NetCDF "
            f"signature); expected {EXPECTED_DATABASE}"
        )
    try:
        with xr.open_dataset(path) as f:
            return f.load()
    except Exception as exc:  # any backend (netCDF4, h5netcdf, scipy) failure
        reason = " ".join(str(exc).split()) or type(exc).__name__
        raise DatabaseFileError(
            f"{where} cannot be read ({size} bytes; truncated or corrupted?): "
            f"{type(exc).__name__}: {reason}; expected {EXPECTED_DATABASE}"
        ) from exc


def _check_layout(ds: xr.Dataset, path: Path) -> None:
    """Refuse a NetCDF file that is not a database at all (e.g. a simulation output)."""
    names = {str(v) for v in ds.variables}
    merged = {n[: -len("_real")] if n.endswith("_real") else n for n in names}
    missing = [v for v in ("added_mass", "radiation_damping") if v not in merged]
    if missing:
        found = sorted(str(v) for v in ds.data_vars)
        shown = ", ".join(found[:12]) + (", …" if len(found) > 12 else "") or "none"
        hint = ""
        if "eta" in names or "time" in ds.dims or "t" in ds.dims:
            hint = " (this looks like a simulation output, e.g. from ship-gym simulate --output)"
        raise DatabaseFileError(
            f"hydrodynamic database file {str(path)!r} has no variable "
            f"{' or '.join(repr(m) for m in missing)}{hint}; its variables are: {shown}. "
            f"Expected {EXPECTED_DATABASE}"
        )


def _validate_opened(
    ds: xr.Dataset, path: Path, level: str, ours: bool, checks: dict[str, Any]
) -> None:
    if level == "none":
        return
    chosen = ("full" if ours else "data") if level == "auto" else level
    st = path.stat()
    key = (
        str(path.resolve()),
        st.st_mtime_ns,
        st.st_size,
        chosen,
        tuple(sorted(checks.items())),
    )
    if key in _VALIDATED:
        return
    # frequency coverage (how many frequencies, ω_max against the natural frequencies) is a
    # recommendation, not a defect of the data: it warns unless the caller set its limits
    relaxed = {"min_frequencies": 2, "min_omega_ratio": 0.0, **checks}
    try:
        validate_database(ds, level=chosen, **relaxed)  # type: ignore[arg-type]
    except DatabaseError as exc:
        detail = str(exc).split(":", 1)[-1]
        raise DatabaseFileError(
            f"hydrodynamic database file {str(path)!r} is invalid:{detail}\n"
            "(open_database(..., validate='none') skips this check)"
        ) from exc
    if chosen == "full" or (level == "auto" and not ours):
        try:
            validate_database(ds, level="full", **checks)
        except DatabaseError as exc:
            detail = str(exc).split(":", 1)[-1]
            what = (
                "is usable but below the recommended frequency coverage"
                if chosen == "full"
                else "(not written by ship_gym) is sound but incomplete for the time-domain model"
            )
            warnings.warn(
                f"hydrodynamic database file {str(path)!r} {what}:{detail}",
                UserWarning,
                stacklevel=3,
            )
    _VALIDATED.add(key)


def open_database(
    path: str | os.PathLike, *, validate: ValidateLevel = "auto", **checks: Any
) -> xr.Dataset:
    """Read and validate a database written by :func:`save_database`, or a capytaine export.

    The file is read into memory and closed. capytaine-format files (split along a ``complex``
    dimension) are merged back to complex values and, unless ``attrs["frame"]`` says they are
    already in ship_gym's body frame, converted from capytaine's z-up frame with
    :func:`ship_gym.hydro.frames.dataset_from_capytaine`.

    The database is then checked by :func:`ship_gym.hydro.checks.validate_database` (once per
    file version: the result is cached by path, modification time and size), so that NaN or
    negative damping, asymmetric radiation matrices, a missing A(∞)… are reported here, naming
    the file, instead of as a diverging simulation later. The frequency coverage (at least
    ``min_frequencies`` frequencies, ω_max ≥ ``min_omega_ratio`` × the natural frequencies) is
    a recommendation: falling short of it warns (:class:`UserWarning`), unless these limits are
    passed explicitly, which makes them binding; fewer than 2 finite frequencies is refused.

    Parameters
    ----------
    path : str or os.PathLike
        NetCDF file.
    validate : {"auto", "full", "data", "none"}
        ``"full"``: the database must be usable by the time-domain model (every check of
        :func:`~ship_gym.hydro.checks.validate_database`); ``"data"``: the data present must be
        sound (NaN, damping sign, symmetry…), completeness is not required; ``"auto"``
        (default): ``"full"`` for files written by :func:`save_database` (``ship-gym hydro``),
        ``"data"`` for foreign (capytaine) files, with a :class:`UserWarning` listing what the
        time-domain model would miss; ``"none"``: no check.
    **checks
        Tolerances passed to :func:`~ship_gym.hydro.checks.validate_database`
        (``rtol_symmetry``, ``rtol_symmetry_damping``, ``damping_tolerance``,
        ``min_frequencies``, ``min_omega_ratio``, ``require_infinite``).

    Returns
    -------
    xarray.Dataset
        The database in our body frame, with complex wave forces and string DOF coordinates.

    Raises
    ------
    FileNotFoundError
        If ``path`` does not exist.
    IsADirectoryError
        If ``path`` is a directory.
    DatabaseFileError
        A :class:`ValueError`: the file is empty, not NetCDF, truncated or corrupted, not a
        hydrodynamic database (e.g. a simulation output), declares a frame that is neither
        ours nor capytaine's, or fails validation. The message names the file and the problem.
    """
    if validate not in ("auto", "full", "data", "none"):
        raise ValueError(f"validate must be 'auto', 'full', 'data' or 'none', got {validate!r}")
    unknown = set(checks) - {
        "rtol_symmetry",
        "rtol_symmetry_damping",
        "damping_tolerance",
        "min_frequencies",
        "min_omega_ratio",
        "require_infinite",
    }
    if unknown:
        raise TypeError(f"open_database() got unexpected keyword argument(s) {sorted(unknown)}")
    path = Path(path)
    if path.is_dir():
        raise IsADirectoryError(
            f"hydrodynamic database path {str(path)!r} is a directory; expected a NetCDF file "
            f"(.nc): {EXPECTED_DATABASE}"
        )
    if not path.is_file():
        raise FileNotFoundError(
            f"hydrodynamic database file {str(path)!r} not found; expected {EXPECTED_DATABASE}"
        )
    ds = _read_netcdf(path)
    _check_layout(ds, path)
    ours = "ship_gym_format" in ds.attrs
    ds.attrs.pop("ship_gym_format", None)
    try:
        ds = _merge_capytaine(ds) if "complex" in ds.dims else _merge_ours(ds)
        for name in list(ds.coords):
            if ds[name].dtype.kind in "OSU":
                ds = ds.assign_coords({name: np.asarray(ds[name].values, dtype=str)})
        frame = ds.attrs.get("frame")
        if frame not in (BODY_FRAME, None, frames.CAPYTAINE_FRAME):
            raise DatabaseFileError(
                f"{str(path)!r}: attrs['frame'] = {frame!r} is neither the ship_gym body frame "
                "nor capytaine's frame; cannot tell how to convert it"
            )
        if frame != BODY_FRAME:
            ds = frames.dataset_from_capytaine(ds)
    except DatabaseFileError:
        raise
    except (ValueError, KeyError, TypeError, IndexError) as exc:
        raise DatabaseFileError(
            f"hydrodynamic database file {str(path)!r} has an unexpected layout "
            f"({type(exc).__name__}: {exc}); expected {EXPECTED_DATABASE}"
        ) from exc
    _validate_opened(ds, path, validate, ours, checks)
    return ds


def bundled_database_path(name: str) -> Path:
    """Path of a database bundled with ship_gym: ``ship_gym/data/<name>/<name>_hydro.nc``."""
    return Path(str(resources.files("ship_gym").joinpath("data", name, f"{name}_hydro.nc")))


def load_database(
    name_or_path: str | os.PathLike, *, validate: ValidateLevel = "auto", **checks: Any
) -> xr.Dataset:
    """Load a bundled database by name (e.g. ``"s175"``) or any database file by path.

    A bundled database of a port/starboard symmetric hull (every library hull) is returned
    :func:`symmetrise`-d; a file given by path is returned as stored.

    Parameters
    ----------
    name_or_path : str or os.PathLike
        A bare name without directory or ``.nc`` suffix selects the bundled file
        ``ship_gym/data/<name>/<name>_hydro.nc``; anything else is a path.
    validate, **checks
        As :func:`open_database` (validated on opening by default).

    Raises
    ------
    FileNotFoundError
        If the file does not exist (for a bundled name: it has not been built yet).
    DatabaseFileError
        As :func:`open_database`.
    """
    if not isinstance(name_or_path, str | os.PathLike):
        raise TypeError(
            f"database must be a bundled name (e.g. 's175') or a path to a NetCDF file, got "
            f"{type(name_or_path).__name__} {name_or_path!r}"
        )
    text = os.fspath(name_or_path)
    is_name = (
        isinstance(name_or_path, str)
        and os.sep not in text
        and "/" not in text
        and not text.endswith(".nc")
        and not Path(text).exists()
    )
    if not is_name:
        return open_database(text, validate=validate, **checks)
    if not text or not text.replace("_", "").replace("-", "").isalnum():
        raise ValueError(f"invalid bundled database name {text!r}")
    path = bundled_database_path(text)
    if not path.is_file():
        raise FileNotFoundError(
            f"bundled hydrodynamic database {text!r} is not available: expected {str(path)!r}. "
            "It is built by the database script in scripts/ (compute_hull_database + "
            "save_database); run it first, or pass a path to a database file"
        )
    ds = open_database(path, validate=validate, **checks)
    # the library hulls are port/starboard symmetric: remove the BEM's round-off asymmetry
    try:
        return symmetrise(ds)
    except ValueError:  # not a symmetric hull: nothing to impose
        return ds


# ------------------------------------------------------------------------------ accessors
def split_frequencies(
    ds: xr.Dataset, *, require_infinite: bool = False
) -> tuple[xr.Dataset, xr.DataArray | None, xr.DataArray | None]:
    """Separate the finite frequencies from the ω = 0 and ω = ∞ limits.

    Parameters
    ----------
    ds : xarray.Dataset
        Database with an ``omega`` axis.
    require_infinite : bool
        Raise if A(∞) is missing.

    Returns
    -------
    finite : xarray.Dataset
        ``ds`` restricted to 0 < ω < ∞.
    added_mass_zero : xarray.DataArray or None
        A(0) (influenced_dof, radiating_dof) [kg, kg·m, kg·m²], or None if absent.
    added_mass_infinite : xarray.DataArray or None
        A(∞), or None if absent.

    Raises
    ------
    ValueError
        If ``ds`` has no ``omega`` axis, or A(∞) is missing and ``require_infinite``.
    """
    if "omega" not in ds.dims:
        raise ValueError("database has no 'omega' dimension")
    w = ds["omega"].values
    finite = ds.isel(omega=np.flatnonzero(np.isfinite(w) & (w > 0.0)))
    a0 = ainf = None
    if "added_mass" in ds:
        if np.any(w == 0.0):
            a0 = ds["added_mass"].isel(omega=int(np.flatnonzero(w == 0.0)[0]), drop=True)
        if np.any(np.isinf(w)):
            ainf = ds["added_mass"].isel(omega=int(np.flatnonzero(np.isinf(w))[0]), drop=True)
    if require_infinite and ainf is None:
        raise ValueError(
            "database has no infinite-frequency added mass (omega = inf entry); recompute it "
            "with infinite_frequency=True or import a WAMIT .1 file with PER = 0 rows"
        )
    return finite, a0, ainf


class HydroArrays(NamedTuple):
    """Plain NumPy view of a database in DOF order (SI units, our body frame).

    Attributes
    ----------
    omega : (n,) finite frequencies [rad/s]
    added_mass, radiation_damping : (n, 6, 6)
    added_mass_zero, added_mass_infinite : (6, 6) or None
    wave_direction : (m,) headings [rad]
    excitation_force : (n, m, 6) complex, per unit amplitude
    hydrostatic_stiffness, inertia_matrix : (6, 6) or None
    diffraction_force : (n, m, 6) complex per unit amplitude, or None (a database without it)
    """

    omega: np.ndarray
    added_mass: np.ndarray
    radiation_damping: np.ndarray
    added_mass_zero: np.ndarray | None
    added_mass_infinite: np.ndarray | None
    wave_direction: np.ndarray
    excitation_force: np.ndarray
    hydrostatic_stiffness: np.ndarray | None
    inertia_matrix: np.ndarray | None
    diffraction_force: np.ndarray | None = None


def as_arrays(ds: xr.Dataset) -> HydroArrays:
    """NumPy arrays of a database, DOFs in :data:`~ship_gym.conventions.DOF_NAMES` order."""
    dofs = list(DOF_NAMES)
    ds = ds.sel({d: dofs for d in _DOF_DIMS if d in ds.dims})
    finite, a0, ainf = split_frequencies(ds)

    def mat(name: str) -> np.ndarray | None:
        if name not in ds:
            return None
        return ds[name].transpose("influenced_dof", "radiating_dof").values.astype(float)

    return HydroArrays(
        omega=finite["omega"].values.astype(float),
        added_mass=finite["added_mass"].transpose("omega", *_DOF_DIMS).values,
        radiation_damping=finite["radiation_damping"].transpose("omega", *_DOF_DIMS).values,
        added_mass_zero=None if a0 is None else a0.transpose(*_DOF_DIMS).values,
        added_mass_infinite=None if ainf is None else ainf.transpose(*_DOF_DIMS).values,
        wave_direction=ds["wave_direction"].values.astype(float),
        excitation_force=finite["excitation_force"]
        .transpose("omega", "wave_direction", "influenced_dof")
        .values,
        hydrostatic_stiffness=mat("hydrostatic_stiffness"),
        inertia_matrix=mat("inertia_matrix"),
        diffraction_force=None
        if "diffraction_force" not in finite
        else finite["diffraction_force"]
        .transpose("omega", "wave_direction", "influenced_dof")
        .values,
    )


def _asymmetry(ds: xr.Dataset, rtol: float) -> float:
    """Largest symmetric–antisymmetric added-mass coupling over the diagonal scale [-];
    ValueError beyond ``rtol`` (the hull is not port/starboard symmetric)."""
    finite, _, _ = split_frequencies(ds)
    a = finite["added_mass"].sel(influenced_dof=list(DOF_NAMES), radiating_dof=list(DOF_NAMES))
    a = np.abs(a.values)
    diag = np.sqrt(np.einsum("kii->i", a) / max(len(a), 1))
    scale = np.outer(diag, diag)
    m = frames.mirror_signs()
    odd = np.outer(m, m) < 0
    ratio = float(np.max(a[:, odd] / np.maximum(scale[odd], np.finfo(float).tiny)))
    if ratio > rtol:
        raise ValueError(
            f"hull does not look port/starboard symmetric: symmetric-antisymmetric added-mass "
            f"couplings reach {ratio:.3g} of the diagonal scale (> rtol = {rtol})"
        )
    return ratio


def symmetrise(ds: xr.Dataset, *, rtol: float = 1e-2) -> xr.Dataset:
    """Impose the port/starboard symmetry of the hull exactly on a database.

    A BEM run on a symmetric hull leaves round-off in what symmetry makes zero (≈ 2e-5 of the
    diagonal scale for the bundled S175): couplings between the symmetric (surge, heave, pitch)
    and antisymmetric (sway, roll, yaw) modes in every (influenced_dof, radiating_dof) matrix,
    and, in head and following seas, sway/roll/yaw wave forces. Left in, they roll a ship in
    head seas (≈ 1e-5 rad). This zeroes those couplings and replaces each wave force by its
    symmetric part, F_i(β) ← ½[F_i(β) + m_i F_i(2π − β)] with m = (1, −1, 1, −1, 1, −1), for
    every stored heading whose mirror is stored too (β = 0 and π are their own mirrors, so their
    antisymmetric components become exactly 0).

    Parameters
    ----------
    ds : xarray.Dataset
        Database in our frame (:mod:`ship_gym.hydro.database` schema).
    rtol : float
        Largest coupling (relative to the diagonal scale) still taken for round-off.

    Returns
    -------
    xarray.Dataset
        A copy with ``attrs["port_starboard_symmetrised"]`` recording the largest coupling
        removed.

    Raises
    ------
    ValueError
        If the couplings exceed ``rtol``: the hull is not symmetric.
    """
    ratio = _asymmetry(ds, rtol)
    out = ds.copy(deep=True)
    m = frames.mirror_signs()
    odd = xr.DataArray(
        np.outer(m, m) < 0,
        dims=("influenced_dof", "radiating_dof"),
        coords={"influenced_dof": list(DOF_NAMES), "radiating_dof": list(DOF_NAMES)},
    )
    for name, var in ds.data_vars.items():
        if {"influenced_dof", "radiating_dof"} <= set(var.dims):
            mask = odd.sel(influenced_dof=var["influenced_dof"], radiating_dof=var["radiating_dof"])
            out[name] = var.where(~mask, 0.0).assign_attrs(var.attrs)
        elif {"influenced_dof", "wave_direction"} <= set(var.dims):
            beta = np.mod(var["wave_direction"].values.astype(float), 2.0 * np.pi)
            sign = xr.DataArray(
                m, dims=("influenced_dof",), coords={"influenced_dof": list(DOF_NAMES)}
            ).sel(influenced_dof=var["influenced_dof"])
            fixed = var.copy()
            for k, b in enumerate(beta):
                mirror = np.flatnonzero(np.isclose(beta, np.mod(2.0 * np.pi - b, 2.0 * np.pi),
                                                   rtol=0.0, atol=1e-9))  # fmt: skip
                if mirror.size:
                    here = var.isel(wave_direction=k)
                    there = var.isel(wave_direction=int(mirror[0]))
                    fixed[{"wave_direction": k}] = 0.5 * (here + sign * there)
            out[name] = fixed.assign_attrs(var.attrs)
    out.attrs = dict(ds.attrs)
    out.attrs["port_starboard_symmetrised"] = (
        f"symmetric-antisymmetric couplings up to {ratio:.3g} of the diagonal scale zeroed"
    )
    return out


def mirror_headings(ds: xr.Dataset, *, rtol: float = 1e-2) -> xr.Dataset:
    """Complete the headings of a port/starboard symmetric hull to the full circle.

    For a hull symmetric about y = 0, the wave forces at β' = 2π − β follow from those at β by
    the reflection y ↦ −y: F_i(2π − β) = m_i F_i(β) with m = (1, −1, 1, −1, 1, −1). Headings
    already present are kept; new ones are added for β in (0, π) (and π ↦ π, 0 ↦ 0 map onto
    themselves).

    Raises
    ------
    ValueError
        If the added mass shows the hull is not symmetric (couplings between surge/heave/pitch and
        sway/roll/yaw larger than ``rtol`` of the diagonal scale).
    """
    if "wave_direction" not in ds.dims:
        raise ValueError("database has no 'wave_direction' dimension")
    _asymmetry(ds, rtol)
    m = frames.mirror_signs()
    beta = ds["wave_direction"].values
    new = np.mod(2.0 * np.pi - beta, 2.0 * np.pi)
    have = np.any(np.isclose(new[:, None], beta[None, :], rtol=0.0, atol=1e-9), axis=1)
    if np.all(have):
        return ds
    wave_vars = [v for v in ds.data_vars if "wave_direction" in ds[v].dims]
    extra = ds[wave_vars].isel(wave_direction=np.flatnonzero(~have))
    sign = xr.DataArray(m, dims=("influenced_dof",), coords={"influenced_dof": list(DOF_NAMES)})
    sign = sign.sel(influenced_dof=extra["influenced_dof"].values)
    for v in wave_vars:
        if "influenced_dof" in extra[v].dims:
            extra[v] = (extra[v] * sign).transpose(*extra[v].dims).assign_attrs(ds[v].attrs)
    extra = extra.assign_coords(wave_direction=new[~have])
    merged = xr.concat([ds[wave_vars], extra], dim="wave_direction").sortby("wave_direction")
    out = ds.drop_vars(wave_vars).drop_dims("wave_direction", errors="ignore")
    out = out.assign_coords(wave_direction=merged["wave_direction"])
    for v in wave_vars:
        out[v] = merged[v]
    out.attrs = dict(ds.attrs)
    return out
