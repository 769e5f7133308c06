"""The one place where capytaine's (and WAMIT's) z-up frame is converted to ship_gym's body frame.

capytaine (and WAMIT) describe a ship in a right-handed frame with x forward, y to **port** and z
**up**; ship_gym uses x forward, y to **starboard**, z **down** (:mod:`ship_gym.conventions`). The
two frames share their origin O and differ by a rotation of π about x:

    (x, y, z)_ours = (x, −y, −z)_capytaine.

Consequences, all applied here and nowhere else:

* **Points and vectors** (centre of mass, centre of buoyancy, rotation centre…): (x, −y, −z).
  The rotation is proper (det = +1), so panel orientation and outward normals are preserved.
* **Degrees of freedom**: sway, heave, pitch and yaw change sign
  (:data:`~ship_gym.conventions.CAPYTAINE_DOF_SIGNS` = [1, −1, −1, 1, −1, −1]). A generalised
  force F_i becomes s_i F_i and a 6×6 matrix (added mass, damping, hydrostatic stiffness,
  inertia) becomes s_i s_j M_ij.
* **Wave direction**: capytaine's incident wave is ζ = Re(a e^{ik(x cos β_c + y_c sin β_c)}
  e^{−iωt}) (``capytaine/bem/airy_waves.py``: φ = −i g/ω e^{kz} e^{ik(x cos β + y sin β)} and
  η = iω/g φ), i.e. β_c is the direction the waves travel to, measured from +x toward +y_c
  (port). With y_c = −y, x cos β_c + y_c sin β_c = x cos(−β_c) + y sin(−β_c), so the heading in
  ship_gym's convention (measured from +x toward starboard) is β = −β_c (mod 2π). The function is
  an involution: the same formula converts back.
* **Time convention**: none. capytaine and ship_gym both use x(t) = Re(X e^{−iωt}) and both put
  the incident crest at O at t = 0, so complex amplitudes are not conjugated. (WAMIT uses
  Re(X e^{+iωt}): :mod:`ship_gym.hydro.wamit` conjugates before calling this module.)

Nothing here imports capytaine: datasets are plain :mod:`xarray` objects.
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence

import numpy as np
import xarray as xr

from ship_gym.conventions import (
    BODY_FRAME,
    CAPYTAINE_DOF_SIGNS,
    DOF_NAMES,
    TIME_CONVENTION,
    WAVE_HEADING,
)

CAPYTAINE_FRAME: str = (
    "capytaine frame: x forward, y to port, z up; origin on the mean free surface; "
    "wave_direction measured from +x toward +y (port), direction of propagation"
)
"""Frame description of a dataset still in capytaine's (or WAMIT's) axes."""

POINT_SIGNS: np.ndarray = np.array([1.0, -1.0, -1.0])
"""Sign of each coordinate (x, y, z) between the two frames."""

_DOF_DIMS: tuple[str, ...] = ("influenced_dof", "radiating_dof")
_DIRECTION_COORDS: tuple[str, ...] = (
    "wave_direction",
    "encounter_wave_direction",
    "theta",
    "wave_direction_k",
    "wave_direction_l",
)
_POINT_DIM = "space_coordinate"


# ------------------------------------------------------------------------- elementary maps
def dof_signs(names: Iterable[str]) -> np.ndarray:
    """Sign s_i of each named rigid-body DOF between capytaine's frame and ours.

    Parameters
    ----------
    names : iterable of str
        DOF labels (case-insensitive), each one of :data:`~ship_gym.conventions.DOF_NAMES`.

    Returns
    -------
    numpy.ndarray
        (n,) array of ±1.

    Raises
    ------
    ValueError
        If a label is not a rigid-body DOF (flexible modes have no frame rule here).
    """
    lookup = {n.lower(): CAPYTAINE_DOF_SIGNS[i] for i, n in enumerate(DOF_NAMES)}
    out = []
    for name in names:
        key = str(name).lower()
        if key not in lookup:
            raise ValueError(
                f"cannot convert degree of freedom {name!r} between frames; expected one of "
                f"{DOF_NAMES} (generalised/flexible modes are not supported)"
            )
        out.append(lookup[key])
    return np.asarray(out, dtype=float)


def wave_direction_from_capytaine(beta_capytaine: np.ndarray | float) -> np.ndarray | float:
    """ship_gym wave heading β [rad] in [0, 2π) from capytaine's ``wave_direction`` [rad].

    β = −β_c (mod 2π); see the module docstring for the derivation.
    """
    beta = np.mod(-np.asarray(beta_capytaine, dtype=float), 2.0 * np.pi)
    # -0.0 mod 2π is 0.0, and a tiny negative rounding could give exactly 2π: fold it back
    beta = np.where(beta >= 2.0 * np.pi, beta - 2.0 * np.pi, beta) + 0.0
    return float(beta) if np.ndim(beta) == 0 else beta


def wave_direction_to_capytaine(beta: np.ndarray | float) -> np.ndarray | float:
    """capytaine ``wave_direction`` [rad] in [0, 2π) for a ship_gym heading β [rad].

    The map β ↦ −β (mod 2π) is its own inverse.
    """
    return wave_direction_from_capytaine(beta)


def points_from_capytaine(points: np.ndarray) -> np.ndarray:
    """Coordinates (…, 3) [m] in our frame from capytaine's: (x, −y, −z)."""
    p = np.asarray(points, dtype=float)
    if p.shape[-1:] != (3,):
        raise ValueError(f"points must have a last axis of length 3, got shape {p.shape}")
    return p * POINT_SIGNS


points_to_capytaine = points_from_capytaine
"""Coordinates in capytaine's frame from ours (the map is an involution)."""


def vector_from_capytaine(values: np.ndarray) -> np.ndarray:
    """Generalised-force vector(s) (…, 6) in our frame: F_i ↦ s_i F_i."""
    v = np.asarray(values)
    if v.shape[-1:] != (6,):
        raise ValueError(f"DOF vectors must have a last axis of length 6, got shape {v.shape}")
    return v * CAPYTAINE_DOF_SIGNS


vector_to_capytaine = vector_from_capytaine


def matrix_from_capytaine(matrix: np.ndarray) -> np.ndarray:
    """6×6 matrix (or stack (…, 6, 6)) in our frame: M_ij ↦ s_i s_j M_ij."""
    m = np.asarray(matrix)
    if m.shape[-2:] != (6, 6):
        raise ValueError(f"DOF matrices must end with shape (6, 6), got {m.shape}")
    return m * np.outer(CAPYTAINE_DOF_SIGNS, CAPYTAINE_DOF_SIGNS)


matrix_to_capytaine = matrix_from_capytaine


# ------------------------------------------------------------------------- datasets
def _flip_dataset(ds: xr.Dataset) -> xr.Dataset:
    """Apply the (involutive) change of frame to every variable and coordinate of ``ds``."""
    out = ds.copy()
    # 1. DOF signs on every variable (data or coordinate) that has a DOF dimension
    sign_arrays = {}
    for dim in _DOF_DIMS:
        if dim in out.dims:
            labels = [str(v) for v in out[dim].values]
            sign_arrays[dim] = xr.DataArray(dof_signs(labels), dims=(dim,))
    # 2. point coordinates along "space_coordinate"
    point_signs = None
    if _POINT_DIM in out.dims:
        axes = [str(v).lower() for v in out[_POINT_DIM].values]
        if sorted(axes) != ["x", "y", "z"]:
            raise ValueError(
                f"cannot convert {_POINT_DIM!r} coordinate {axes}; expected the labels x, y, z"
            )
        point_signs = xr.DataArray([POINT_SIGNS["xyz".index(a)] for a in axes], dims=(_POINT_DIM,))

    def convert(da: xr.DataArray) -> xr.DataArray:
        # only numeric data variables and non-index coordinates reach this function
        if da.dtype.kind not in "fciu":
            return da
        factor = None
        for dim, s in sign_arrays.items():
            if dim in da.dims:
                factor = s if factor is None else factor * s
        if point_signs is not None and _POINT_DIM in da.dims:
            factor = point_signs if factor is None else factor * point_signs
        if factor is None:
            return da
        converted = (da * factor).transpose(*da.dims)
        converted.attrs = dict(da.attrs)
        return converted.astype(da.dtype, copy=False)

    for name in list(out.data_vars):
        out[name] = convert(out[name])
    non_index = [c for c in out.coords if c not in out.dims]
    for name in non_index:
        out = out.assign_coords({name: convert(out.coords[name])})
    # 3. wave directions (index or not): β ↦ −β mod 2π, then sort the index coordinates
    for name in _DIRECTION_COORDS:
        if name in out.coords:
            c = out.coords[name]
            new = xr.DataArray(
                np.atleast_1d(wave_direction_from_capytaine(c.values)).reshape(c.shape),
                dims=c.dims,
                attrs=dict(c.attrs),
            )
            out = out.assign_coords({name: new})
            if name in out.dims:
                out = out.sortby(name)
    return out


def dataset_from_capytaine(ds: xr.Dataset) -> xr.Dataset:
    """Convert a hydrodynamic dataset from capytaine's z-up frame to ship_gym's body frame.

    Every variable or coordinate with an ``influenced_dof`` / ``radiating_dof`` dimension gets
    the DOF signs (e.g. ``added_mass``, ``radiation_damping``, ``diffraction_force``,
    ``Froude_Krylov_force``, ``excitation_force``, ``hydrostatic_stiffness``,
    ``inertia_matrix``, ``kochin_radiation``), every one with a ``space_coordinate`` dimension
    (``rotation_center``, ``center_of_mass``, ``center_of_buoyancy``…) the point signs, and the
    direction coordinates (``wave_direction``, ``encounter_wave_direction``, ``theta``) are mapped
    β ↦ −β (mod 2π) and the dataset is sorted along them. Complex values are not conjugated.

    Parameters
    ----------
    ds : xarray.Dataset
        Dataset in capytaine's frame with merged (complex) values.

    Returns
    -------
    xarray.Dataset
        The dataset in our frame; ``attrs["frame"]`` is :data:`~ship_gym.conventions.BODY_FRAME`,
        ``attrs["time_convention"]`` and ``attrs["wave_heading"]`` are set.

    Raises
    ------
    ValueError
        If ``ds`` already says it is in our frame, or holds DOFs that are not rigid-body DOFs.
    """
    if not isinstance(ds, xr.Dataset):
        raise ValueError(f"expected an xarray.Dataset, got {type(ds).__name__}")
    if ds.attrs.get("frame") == BODY_FRAME:
        raise ValueError(
            "dataset attrs['frame'] says it is already in the ship_gym body frame; converting "
            "it again would flip its signs back"
        )
    out = _flip_dataset(ds)
    out.attrs = dict(ds.attrs)
    out.attrs["frame"] = BODY_FRAME
    out.attrs["time_convention"] = TIME_CONVENTION
    out.attrs["wave_heading"] = WAVE_HEADING
    out.attrs["converted_from"] = CAPYTAINE_FRAME
    return out


def dataset_to_capytaine(ds: xr.Dataset) -> xr.Dataset:
    """Convert a dataset in ship_gym's body frame back to capytaine's z-up frame.

    The inverse of :func:`dataset_from_capytaine` (the change of frame is an involution), for
    exporting to tools that expect capytaine's (or WAMIT's) axes.

    Raises
    ------
    ValueError
        If ``ds.attrs["frame"]`` is not :data:`~ship_gym.conventions.BODY_FRAME`.
    """
    if not isinstance(ds, xr.Dataset):
        raise ValueError(f"expected an xarray.Dataset, got {type(ds).__name__}")
    if ds.attrs.get("frame") != BODY_FRAME:
        raise ValueError(
            f"dataset attrs['frame'] is {ds.attrs.get('frame')!r}; expected the ship_gym body "
            f"frame {BODY_FRAME!r}"
        )
    out = _flip_dataset(ds)
    out.attrs = {k: v for k, v in ds.attrs.items() if k not in ("converted_from",)}
    out.attrs["frame"] = CAPYTAINE_FRAME
    out.attrs.pop("wave_heading", None)
    return out


def mirror_signs() -> np.ndarray:
    """DOF signs under the reflection y ↦ −y: (1, −1, 1, −1, 1, −1).

    For a port/starboard symmetric hull, F_i(2π − β) = m_i F_i(β) and
    A_ij = m_i m_j A_ij (so sway/roll/yaw decouple from surge/heave/pitch).
    """
    return np.array([1.0, -1.0, 1.0, -1.0, 1.0, -1.0])


def check_dof_order(labels: Sequence[str]) -> None:
    """Raise ValueError unless ``labels`` are exactly :data:`~ship_gym.conventions.DOF_NAMES`."""
    got = tuple(str(v) for v in labels)
    if got != DOF_NAMES:
        raise ValueError(f"DOF labels must be {DOF_NAMES} in that order, got {got}")
