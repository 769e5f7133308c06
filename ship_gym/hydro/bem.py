"""Frequency-domain radiation/diffraction database of a hull with capytaine (the BEM adapter).

This is the only module of ship_gym that imports capytaine (lazily, inside functions, so that
``import ship_gym.hydro.bem`` stays cheap). It turns an immersed :class:`~ship_gym.hull.mesh.
PanelMesh` in our body frame into an :class:`xarray.Dataset` in our body frame with capytaine's
variable names and axes (see :mod:`ship_gym.hydro.database` for the schema).

Method
------
* The mesh is rotated into capytaine's z-up frame ((x, y, z)_c = (x, −y, −z)); the results are
  rotated back by :func:`ship_gym.hydro.frames.dataset_from_capytaine`, the single conversion
  point. Rotations and moments are about O = (0, 0, 0) (our origin on the design waterline,
  amidships), and wave phases refer to O.
* Deep water, zero forward speed, Delhommeau Green function, indirect (source) formulation.
* Radiation problems for the six rigid-body DOFs at every ω of the grid **and** at ω = 0 and
  ω = ∞ (capytaine 3 accepts ``omega=0`` and ``omega=np.inf`` for radiation problems; damping is
  zero there). Diffraction problems (and Froude–Krylov forces) at every finite ω > 0 and heading.
* Port/starboard symmetry (capytaine ``ReflectionSymmetricMesh``, plane ``"xOz"``) is used when
  the mesh is its own mirror image in y (half the influence-matrix work and a cheaper
  block-circulant solve); fore/aft symmetry (plane ``"yOz"``) is nested inside when present too
  (boxes, hemispheres, Wigley hulls), which quarters the work again.
* Irregular frequencies are removed with an interior lid (``generate_lid``), placed slightly
  below the free surface at z_c = −d (see :func:`lid_depth`): a lid at depth d moves the first
  irregular frequency of the lidded body to about ω² ≈ g/d, so d = r_max/π (r_max the largest
  panel radius) puts it at twice the highest frequency the hull mesh resolves (λ ≥ 8 r_max). The
  lid is not put exactly on z = 0 because there both source and collocation points sit on the
  free surface, where the wave part of the free-surface Green function is log-singular and
  poorly tabulated. Measured on a 1280-panel hemisphere (B33 against Hulme 1982): lid at z = 0,
  +15 % at ka = 6 and +79 % at ka = 8; lid at d = r_max/π ≈ 0.02 a, +2 % and +6 %; lid at
  d = 0.2 a, an irregular frequency back at ka ≈ 5 (−18 %), as ω² ≈ g/d predicts; no lid, −44 %
  at ka = 2.5 (the hemisphere's own first irregular frequency). Below ka = 2 all lidded variants
  agree with Hulme to 1.5 %.
"""

from __future__ import annotations

import importlib.util
import logging
import time
import warnings
from collections.abc import Sequence
from datetime import UTC, datetime
from typing import Any

import numpy as np
import xarray as xr

from ship_gym.conventions import (
    BODY_FRAME,
    DOF_NAMES,
    GRAVITY,
    RHO_SEAWATER,
    TIME_CONVENTION,
    WAVE_HEADING,
)
from ship_gym.hydro import frames

LOG = logging.getLogger(__name__)

OMEGA_LIMITS_NOTE = (
    "omega[0] = 0 and omega[-1] = inf are the zero- and infinite-frequency limits: they hold "
    "radiation results only (added mass A(0), A(inf); radiation damping 0); "
    "diffraction_force, Froude_Krylov_force and excitation_force are NaN there"
)
"""Text stored in ``attrs["omega_limits"]`` of every database built here."""

SYMMETRY_NONE = "none"
SYMMETRY_Y = "xOz"
SYMMETRY_XY = "xOz+yOz"


# ----------------------------------------------------------------------------- helpers
def _as_mesh_arrays(mesh: Any) -> tuple[np.ndarray, np.ndarray, str]:
    """Vertices (n, 3), faces (m, 4) and name of a PanelMesh-like object (duck-typed)."""
    try:
        vertices = np.asarray(mesh.vertices, dtype=float)
        faces = np.asarray(mesh.faces)
    except AttributeError as exc:
        raise ValueError(
            f"immersed_mesh must be a PanelMesh (with .vertices and .faces), got "
            f"{type(mesh).__name__}"
        ) from exc
    if vertices.ndim != 2 or vertices.shape[1] != 3:
        raise ValueError(f"mesh vertices must have shape (n, 3), got {vertices.shape}")
    if faces.ndim != 2 or faces.shape[1] != 4:
        raise ValueError(f"mesh faces must have shape (m, 4), got {faces.shape}")
    return vertices, faces.astype(np.int64), str(getattr(mesh, "name", "mesh"))


def _face_radii(vertices: np.ndarray, faces: np.ndarray) -> np.ndarray:
    """Largest centre-to-vertex distance of each panel [m] (capytaine's ``faces_radiuses``)."""
    p = vertices[faces]  # (m, 4, 3); a triangle repeats a vertex, harmless for a max
    centre = p.mean(axis=1, keepdims=True)
    return np.linalg.norm(p - centre, axis=2).max(axis=1)


def resolved_omega_max(immersed_mesh: Any, *, g: float = GRAVITY) -> float:
    """Highest wave frequency [rad/s] the mesh resolves by capytaine's rule λ ≥ 8 r_max.

    Parameters
    ----------
    immersed_mesh : PanelMesh
        Immersed hull mesh [m].
    g : float
        Gravitational acceleration [m/s²].

    Returns
    -------
    float
        ω_max = sqrt(g k) with k = 2π / (8 r_max) (deep water) [rad/s].
    """
    vertices, faces, _ = _as_mesh_arrays(immersed_mesh)
    r_max = float(_face_radii(vertices, faces).max())
    return float(np.sqrt(g * 2.0 * np.pi / (8.0 * r_max)))


def lid_depth(immersed_mesh: Any) -> float:
    """Depth d [m] below the waterline of the irregular-frequency lid.

    d = r_max / π with r_max the largest panel radius, capped at 10 % of the draught: the lid's
    own first irregular frequency, ω² ≈ g/d, then lies at about twice the highest frequency the
    mesh resolves (λ = 8 r_max), while the lid stays off the free surface (see module notes).
    """
    vertices, faces, _ = _as_mesh_arrays(immersed_mesh)
    r_max = float(_face_radii(vertices, faces).max())
    draught = float(vertices[:, 2].max())
    return float(min(r_max / np.pi, 0.1 * draught))


def default_omega_grid(
    immersed_mesh: Any,
    *,
    n_omega: int = 40,
    omega_max: float | None = None,
    g: float = GRAVITY,
) -> np.ndarray:
    """Uniform frequency grid Δω, 2Δω, …, ω_max [rad/s] with Δω = ω_max / n_omega.

    A uniform grid starting one step above ω = 0 suits the cosine/sine transforms of the
    retardation kernels, with the ω = 0 entry added by :func:`compute_database`. ω_max defaults to
    :func:`resolved_omega_max` (the shortest wave the mesh resolves).
    """
    if int(n_omega) != n_omega or n_omega < 2:
        raise ValueError(f"n_omega must be an integer >= 2, got {n_omega!r}")
    w_max = resolved_omega_max(immersed_mesh, g=g) if omega_max is None else float(omega_max)
    if not (np.isfinite(w_max) and w_max > 0.0):
        raise ValueError(f"omega_max must be a positive finite frequency [rad/s], got {w_max!r}")
    return w_max * np.arange(1, int(n_omega) + 1) / int(n_omega)


def _mirror_map(vertices: np.ndarray, axis: int, tol: float) -> np.ndarray | None:
    """Index of the mirror image (coordinate ``axis`` negated) of every vertex, or None."""
    q = np.round(vertices / tol).astype(np.int64)
    lookup = {tuple(row): i for i, row in enumerate(q)}
    qm = q.copy()
    qm[:, axis] *= -1
    out = np.empty(len(q), dtype=np.int64)
    for i, row in enumerate(qm):
        j = lookup.get(tuple(row))
        if j is None:
            return None
        out[i] = j
    return out


def is_mirror_symmetric(vertices: np.ndarray, faces: np.ndarray, axis: int) -> bool:
    """Whether a panel mesh is its own mirror image under ``coordinate[axis] ↦ −coordinate``.

    Every vertex must have a mirror vertex and every panel a mirror panel (same vertex set), to
    1e-7 of the mesh size.
    """
    size = float(np.ptp(vertices, axis=0).max())
    tol = 1e-7 * max(size, 1e-12)
    mirror = _mirror_map(vertices, axis, tol)
    if mirror is None:
        return False
    keys = {frozenset(f.tolist()) for f in faces}
    return all(frozenset(mirror[f].tolist()) in keys for f in faces)


def _validate_mass_matrix(mass_matrix: np.ndarray) -> tuple[np.ndarray, float, np.ndarray]:
    """Checked 6×6 rigid-body mass matrix about O, its mass [kg] and centre of gravity [m]."""
    m6 = np.asarray(mass_matrix, dtype=float)
    if m6.shape != (6, 6) or not np.all(np.isfinite(m6)):
        raise ValueError(f"mass_matrix must be a finite (6, 6) array [SI], got shape {m6.shape}")
    scale = float(np.abs(m6).max())
    if not np.allclose(m6, m6.T, rtol=0.0, atol=1e-9 * scale):
        raise ValueError("mass_matrix must be symmetric (rigid-body mass matrix about O)")
    mass = float(m6[0, 0])
    if mass <= 0.0 or not np.allclose(np.diag(m6)[:3], mass, rtol=1e-9):
        raise ValueError(
            f"mass_matrix diagonal must start with (m, m, m), m > 0 [kg]; got {np.diag(m6)[:3]}"
        )
    # M[3:, :3] = m S(r_G): S[1,0] = z, S[0,2] = y, S[2,1] = x  (Fossen 2011, eq. 3.44)
    cog = np.array([m6[5, 1], m6[3, 2], m6[4, 0]]) / mass
    if np.any(np.linalg.eigvalsh(m6) <= 0.0):
        raise ValueError("mass_matrix must be positive definite")
    return m6, mass, cog


def _validate_omega(omega: Sequence[float] | np.ndarray) -> tuple[np.ndarray, bool, bool]:
    """Sorted finite positive frequencies, and whether 0 / inf were listed explicitly."""
    w = np.atleast_1d(np.asarray(omega, dtype=float))
    if w.ndim != 1 or w.size == 0:
        raise ValueError(
            f"omega must be a non-empty 1-D array of frequencies [rad/s], got {omega!r}"
        )
    if np.any(np.isnan(w)) or np.any(w < 0.0):
        raise ValueError(f"omega must hold frequencies >= 0 [rad/s], got {w}")
    has_zero, has_inf = bool(np.any(w == 0.0)), bool(np.any(np.isinf(w)))
    finite = np.unique(w[np.isfinite(w) & (w > 0.0)])
    if finite.size == 0:
        raise ValueError(f"omega must hold at least one finite frequency > 0 [rad/s], got {w}")
    return finite, has_zero, has_inf


def _validate_directions(wave_directions: Sequence[float] | np.ndarray) -> np.ndarray:
    """Headings [rad] wrapped to [0, 2π), sorted, checked for duplicates."""
    b = np.atleast_1d(np.asarray(wave_directions, dtype=float))
    if b.ndim != 1 or b.size == 0 or not np.all(np.isfinite(b)):
        raise ValueError(
            f"wave_directions must be a non-empty 1-D array of finite headings [rad], got "
            f"{wave_directions!r}"
        )
    wrapped = np.mod(b, 2.0 * np.pi)
    wrapped[np.isclose(wrapped, 2.0 * np.pi, rtol=0.0, atol=1e-12)] = 0.0
    wrapped = np.sort(wrapped)
    if np.any(np.diff(wrapped) < 1e-9):
        raise ValueError(f"wave_directions has duplicate headings (mod 2π): {np.sort(b)} [rad]")
    if np.any(np.abs(b) > 4.0 * np.pi):
        raise ValueError(f"wave_directions must be in radians, got {b} (degrees?)")
    return wrapped


# ----------------------------------------------------------------------------- capytaine side
def _capytaine_body(
    vertices_c: np.ndarray,
    faces: np.ndarray,
    *,
    name: str,
    symmetry: str,
    lid: bool,
    lid_z: float,
    cog_c: np.ndarray,
    mass: float,
) -> tuple[Any, Any, int]:
    """(FloatingBody for BEM, plain full-mesh FloatingBody for hydrostatics, lid panel count)."""
    import capytaine as cpt

    full = cpt.Mesh(vertices_c, faces, name=name)
    dofs = cpt.rigid_body_dofs(rotation_center=np.zeros(3))
    plain_body = cpt.FloatingBody(mesh=full, dofs=dofs, center_of_mass=cog_c, mass=mass, name=name)

    def split(m: Any) -> Any:
        if symmetry == SYMMETRY_NONE:
            return m
        half = m.clipped(origin=(0.0, 0.0, 0.0), normal=(0.0, -1.0, 0.0))  # keeps y >= 0
        if symmetry == SYMMETRY_Y:
            return cpt.ReflectionSymmetricMesh(half, plane="xOz", name=m.name)
        quarter = half.clipped(origin=(0.0, 0.0, 0.0), normal=(-1.0, 0.0, 0.0))  # keeps x >= 0
        inner = cpt.ReflectionSymmetricMesh(quarter, plane="yOz")
        return cpt.ReflectionSymmetricMesh(inner, plane="xOz", name=m.name)

    hull_mesh = split(full)
    lid_mesh = None
    n_lid = 0
    if lid:
        full_lid = full.generate_lid(z=lid_z, name=f"lid of {name}")
        if full_lid.nb_faces > 0:
            lid_mesh = split(full_lid)
            n_lid = int(lid_mesh.nb_faces)
        else:
            warnings.warn(
                f"{name}: no lid could be generated at z = {-lid_z:.3g} m below the waterline "
                "(no waterplane?); irregular frequencies are not removed",
                stacklevel=3,
            )
    body = cpt.FloatingBody(
        mesh=hull_mesh,
        lid_mesh=lid_mesh,
        dofs=cpt.rigid_body_dofs(rotation_center=np.zeros(3)),
        center_of_mass=cog_c,
        mass=mass,
        name=name,
    )
    return body, plain_body, n_lid


def _solve(
    body: Any,
    omega: np.ndarray,
    beta_c: np.ndarray,
    *,
    rho: float,
    g: float,
    n_jobs: int,
    progress: bool,
    name: str,
) -> tuple[list[Any], list[float]]:
    """Solve every radiation/diffraction problem; returns results and seconds per frequency."""
    import capytaine as cpt
    from tqdm.auto import tqdm

    solver = cpt.BEMSolver()

    def problems_at(w: float) -> list[Any]:
        pbs = [
            cpt.RadiationProblem(body=body, omega=w, radiating_dof=dof, rho=rho, g=g)
            for dof in DOF_NAMES
        ]
        if np.isfinite(w) and w > 0.0:
            pbs += [
                cpt.DiffractionProblem(body=body, omega=w, wave_direction=float(b), rho=rho, g=g)
                for b in beta_c
            ]
        return pbs

    results: list[Any] = []
    timings: list[float] = []
    if n_jobs == 1:
        for w in tqdm(omega, desc=f"BEM {name}", unit="freq", disable=not progress):
            t0 = time.perf_counter()
            results += solver.solve_all(
                problems_at(float(w)),
                keep_details=False,
                progress_bar=False,
                _check_wavelength=False,  # checked once in compute_database
            )
            timings.append(time.perf_counter() - t0)
    else:
        t0 = time.perf_counter()
        problems = [pb for w in omega for pb in problems_at(float(w))]
        results = solver.solve_all(
            problems,
            keep_details=False,
            n_jobs=n_jobs,
            progress_bar=progress,
            _check_wavelength=False,
        )
        timings = [(time.perf_counter() - t0) / len(omega)] * len(omega)
    failed = [r for r in results if hasattr(r, "exception")]
    if failed:
        raise RuntimeError(
            f"{name}: {len(failed)} of {len(results)} BEM problems failed; first: "
            f"{failed[0].problem}: {failed[0].exception!r}"
        )
    return results, timings


# ----------------------------------------------------------------------------- public API
def compute_database(
    immersed_mesh: Any,
    *,
    omega: Sequence[float] | np.ndarray,
    wave_directions: Sequence[float] | np.ndarray,
    rho: float = RHO_SEAWATER,
    g: float = GRAVITY,
    mass_matrix: np.ndarray,
    hydrostatic_stiffness: np.ndarray | None = None,
    lid: bool = True,
    symmetry: str | bool = "auto",
    zero_frequency: bool = True,
    infinite_frequency: bool = True,
    n_jobs: int = 1,
    progress: bool = True,
    name: str | None = None,
) -> xr.Dataset:
    """Radiation/diffraction database of an immersed hull, in ship_gym's body frame.

    Parameters
    ----------
    immersed_mesh : PanelMesh
        Hull surface below the design waterline, in our body frame (x forward, y starboard,
        z down, origin O on the waterline amidships), open at z = 0, outward normals.
    omega : array_like
        Wave frequencies [rad/s], finite and > 0 (0 and ``inf`` are accepted and mean the
        limits below).
    wave_directions : array_like
        Wave headings β [rad] in ship_gym's convention (0 following seas, π head seas, π/2 waves
        travelling toward starboard); stored wrapped to [0, 2π) and sorted.
    rho : float
        Water density [kg/m³].
    g : float
        Gravitational acceleration [m/s²].
    mass_matrix : numpy.ndarray
        (6, 6) rigid-body mass matrix about O in our frame [kg, kg·m, kg·m²]; stored as
        ``inertia_matrix``. Mass and centre of gravity are read from it.
    hydrostatic_stiffness : numpy.ndarray, optional
        (6, 6) linear hydrostatic + gravity stiffness about O in our frame [N/m, N, N·m]. By
        default it is computed with capytaine (``compute_hydrostatic_stiffness``, rigid body with
        the mass and centre of gravity of ``mass_matrix``) and converted to our frame.
    lid : bool
        Remove irregular frequencies with an interior lid at depth :func:`lid_depth`.
    symmetry : {"auto", True, False}
        Use port/starboard (and, nested, fore/aft) mesh symmetry: ``"auto"`` when the mesh is
        exactly symmetric, ``True`` to require it (ValueError otherwise), ``False`` never.
    zero_frequency, infinite_frequency : bool
        Add the radiation problems at ω = 0 and ω = ∞ (first and last entries of the ``omega``
        axis).
    n_jobs : int
        Parallel worker processes (needs the optional ``joblib`` package when > 1). With 1, the
        frequencies are solved in turn with a progress bar.
    progress : bool
        Show a progress bar.
    name : str, optional
        Label of the body (default: the mesh name).

    Returns
    -------
    xarray.Dataset
        Dims ``omega``, ``wave_direction``, ``influenced_dof``, ``radiating_dof``; variables
        ``added_mass``, ``radiation_damping`` (ω, i, j), ``diffraction_force``,
        ``Froude_Krylov_force``, ``excitation_force`` (ω, β, i; complex, per unit wave amplitude,
        NaN at ω = 0 and ∞), ``hydrostatic_stiffness`` and ``inertia_matrix`` (i, j). See
        :mod:`ship_gym.hydro.database` for the attributes.

    Raises
    ------
    ValueError
        For bad inputs (mesh above the waterline or with inward normals, bad frequency or
        heading arrays, bad mass matrix…).
    RuntimeError
        If a BEM problem fails.
    """
    import capytaine as cpt

    vertices, faces, mesh_name = _as_mesh_arrays(immersed_mesh)
    name = mesh_name if name is None else str(name)
    if hasattr(immersed_mesh, "check"):
        immersed_mesh.check(closed=False)
    if not (np.isfinite(rho) and rho > 0.0):
        raise ValueError(f"rho must be a positive water density [kg/m^3], got {rho!r}")
    if not (np.isfinite(g) and g > 0.0):
        raise ValueError(f"g must be a positive gravitational acceleration [m/s^2], got {g!r}")
    if int(n_jobs) != n_jobs or n_jobs < 1:
        raise ValueError(f"n_jobs must be a positive integer, got {n_jobs!r}")
    if n_jobs > 1 and importlib.util.find_spec("joblib") is None:
        raise ValueError(
            f"n_jobs={n_jobs} needs the optional package 'joblib' (pip install joblib); "
            "use n_jobs=1"
        )
    size = float(np.ptp(vertices, axis=0).max())
    z_tol = 1e-6 * size
    if vertices[:, 2].min() < -z_tol:
        n_above = int(np.sum(vertices[faces].mean(axis=1)[:, 2] < -z_tol))
        raise ValueError(
            f"{name}: immersed_mesh reaches z = {vertices[:, 2].min():.4g} m above the waterline "
            f"({n_above} panel centroids at z < 0); pass the mesh clipped at z = 0 (z is down)"
        )
    volume = float(getattr(immersed_mesh, "volume", np.nan))
    if np.isfinite(volume) and volume <= 0.0:
        raise ValueError(
            f"{name}: displaced volume from the panels is {volume:.6g} m^3 <= 0: normals point "
            "into the hull (or the mesh is not a hull below the waterline)"
        )
    finite_omega, listed_zero, listed_inf = _validate_omega(omega)
    zero_frequency = bool(zero_frequency or listed_zero)
    infinite_frequency = bool(infinite_frequency or listed_inf)
    betas = _validate_directions(wave_directions)
    m6, mass, cog = _validate_mass_matrix(mass_matrix)
    if hydrostatic_stiffness is not None:
        c6 = np.asarray(hydrostatic_stiffness, dtype=float)
        if c6.shape != (6, 6) or not np.all(np.isfinite(c6)):
            raise ValueError(
                f"hydrostatic_stiffness must be a finite (6, 6) array [SI], got shape {c6.shape}"
            )

    # symmetry of the mesh (y: port/starboard; x: fore/aft, only nested inside y)
    if symmetry not in ("auto", True, False):
        raise ValueError(f"symmetry must be 'auto', True or False, got {symmetry!r}")
    sym_y = is_mirror_symmetric(vertices, faces, axis=1)
    if symmetry is True and not sym_y:
        raise ValueError(f"{name}: symmetry=True but the mesh is not port/starboard symmetric")
    if symmetry is False or not sym_y:
        sym = SYMMETRY_NONE
    else:
        sym = SYMMETRY_XY if is_mirror_symmetric(vertices, faces, axis=0) else SYMMETRY_Y
    if np.isfinite(volume) and abs(mass - rho * volume) > 0.01 * rho * volume:
        warnings.warn(
            f"{name}: mass {mass:.6g} kg differs from the displaced mass rho*V = "
            f"{rho * volume:.6g} kg by more than 1 %: the hull is not in equilibrium at this "
            "draught",
            stacklevel=2,
        )

    # resolution and irregular-frequency checks (done once here, not by capytaine per problem)
    w_res = resolved_omega_max(immersed_mesh, g=g)
    if finite_omega.max() > w_res * (1.0 + 1e-9):
        warnings.warn(
            f"{name}: omega up to {finite_omega.max():.4g} rad/s exceeds {w_res:.4g} rad/s, the "
            "highest frequency the mesh resolves (wavelength >= 8 x largest panel radius); "
            "results above it are unreliable",
            stacklevel=2,
        )
    d_lid = lid_depth(immersed_mesh) if lid else 0.0

    vertices_c = frames.points_to_capytaine(vertices)
    cog_c = frames.points_to_capytaine(cog)
    body, plain_body, n_lid = _capytaine_body(
        vertices_c, faces, name=name, symmetry=sym, lid=lid, lid_z=-d_lid, cog_c=cog_c, mass=mass
    )
    w_irr = float(body.first_irregular_frequency_estimate(g=g))
    if w_irr < finite_omega.max():
        warnings.warn(
            f"{name}: irregular frequencies may appear above {w_irr:.4g} rad/s (< omega max "
            f"{finite_omega.max():.4g} rad/s); "
            + ("use lid=True" if not lid else "the lid is too deep for this frequency range"),
            stacklevel=2,
        )

    all_omega = np.concatenate(
        [[0.0] if zero_frequency else [], finite_omega, [np.inf] if infinite_frequency else []]
    )
    beta_c = np.asarray(frames.wave_direction_to_capytaine(betas), dtype=float)
    t_start = time.perf_counter()
    results, timings = _solve(
        body, all_omega, beta_c, rho=rho, g=g, n_jobs=int(n_jobs), progress=progress, name=name
    )
    elapsed = time.perf_counter() - t_start

    ds_c = cpt.assemble_dataset(
        results, freq=False, wavelength=False, mesh=False, hydrostatics=False
    )
    keep = ["added_mass", "radiation_damping", "diffraction_force", "Froude_Krylov_force",
            "excitation_force"]  # fmt: skip
    ds_c = ds_c[keep]
    ds_c = ds_c.drop_vars([c for c in ds_c.coords if c not in ds_c.dims and c not in
                           ("period", "wavenumber")])  # fmt: skip
    ds_c = ds_c.assign_coords(
        influenced_dof=np.asarray(ds_c["influenced_dof"].values, dtype=str),
        radiating_dof=np.asarray(ds_c["radiating_dof"].values, dtype=str),
    )
    ds_c = ds_c.reindex(influenced_dof=list(DOF_NAMES), radiating_dof=list(DOF_NAMES))

    if hydrostatic_stiffness is None:
        c_c = plain_body.compute_hydrostatic_stiffness(rho=rho, g=g)
        c_c = c_c.sel(influenced_dof=list(DOF_NAMES), radiating_dof=list(DOF_NAMES)).values
        c6 = frames.matrix_from_capytaine(np.asarray(c_c, dtype=float))
        c_source = (
            f"capytaine {cpt.__version__} compute_hydrostatic_stiffness (rigid body, about O)"
        )
    else:
        c_source = "given by the caller"

    ds = frames.dataset_from_capytaine(ds_c)
    # exact headings as requested (the double change of sign may differ by an ulp)
    if not np.allclose(ds["wave_direction"].values, betas, rtol=0.0, atol=1e-9):
        raise RuntimeError(
            f"internal error: headings {ds['wave_direction'].values} do not match {betas}"
        )
    ds = ds.assign_coords(wave_direction=betas)
    dof_dims = ("influenced_dof", "radiating_dof")
    ds["hydrostatic_stiffness"] = xr.DataArray(c6, dims=dof_dims)
    ds["inertia_matrix"] = xr.DataArray(m6, dims=dof_dims)
    _annotate(ds)
    ds.attrs = {
        "title": f"ship_gym hydrodynamic database of {name}",
        "frame": BODY_FRAME,
        "reference_point": "O = (0, 0, 0): rotations, moments and wave phases refer to O",
        "time_convention": TIME_CONVENTION,
        "wave_heading": WAVE_HEADING,
        "omega_limits": OMEGA_LIMITS_NOTE if (zero_frequency or infinite_frequency) else "none",
        "rho": float(rho),
        "g": float(g),
        "water_depth": "infinite",
        "forward_speed": 0.0,
        "mesh_name": name,
        "n_panels": len(faces),
        "n_lid_panels": int(n_lid),
        "lid_z": float(d_lid) if lid else "none",
        "symmetry": sym,
        "mass": float(mass),
        "cog": np.asarray(cog, dtype=float),
        "displaced_volume": float(volume) if np.isfinite(volume) else "unknown",
        "hydrostatic_stiffness_source": c_source,
        "irregular_frequency_estimate": w_irr,
        "resolved_omega_max": float(w_res),
        "source": (
            f"capytaine {cpt.__version__}: BEMSolver(DefaultMatrixEngine(Delhommeau), "
            "method='indirect'), deep water, zero forward speed"
        ),
        "created": datetime.now(UTC).isoformat(timespec="seconds"),
        "created_by": "ship_gym.hydro.bem.compute_database",
        "bem_seconds_total": float(elapsed),
        "bem_seconds_per_frequency": np.asarray(timings, dtype=float),
    }
    return ds


def _annotate(ds: xr.Dataset) -> None:
    """Long names and units of the variables and coordinates (in place)."""
    info = {
        "omega": ("Wave angular frequency (0 and inf are the radiation limits)", "rad/s"),
        "wave_direction": ("Wave heading beta (ship_gym convention, see attrs)", "rad"),
        "period": ("Wave period", "s"),
        "wavenumber": ("Deep-water wavenumber", "rad/m"),
        "added_mass": ("Added mass A_ij (force i per acceleration j)", "kg, kg m, kg m^2"),
        "radiation_damping": ("Radiation damping B_ij", "kg/s, kg m/s, kg m^2/s"),
        "diffraction_force": ("Diffraction force per unit wave amplitude", "N/m, N m/m"),
        "Froude_Krylov_force": ("Froude-Krylov force per unit wave amplitude", "N/m, N m/m"),
        "excitation_force": ("Wave excitation force per unit wave amplitude", "N/m, N m/m"),
        "hydrostatic_stiffness": ("Hydrostatic and gravity stiffness about O", "N/m, N, N m"),
        "inertia_matrix": ("Rigid-body mass matrix about O", "kg, kg m, kg m^2"),
    }
    for key, (long_name, units) in info.items():
        if key in ds.variables:
            ds[key].attrs.update(long_name=long_name, units=units)


def compute_hull_database(
    hull: Any,
    *,
    omega: Sequence[float] | np.ndarray | None = None,
    n_omega: int = 40,
    omega_max: float | None = None,
    wave_directions: Sequence[float] | np.ndarray | None = None,
    hydrostatic_stiffness: np.ndarray | None = None,
    **kwargs: Any,
) -> xr.Dataset:
    """:func:`compute_database` for a :class:`ship_gym.hull.Hull` (duck-typed).

    Parameters
    ----------
    hull : Hull
        Needs ``.immersed_mesh`` (PanelMesh in our frame, clipped at z = 0),
        ``.mass.rigid_body_matrix()`` (6×6 about O), ``.rho`` [kg/m³], ``.g`` [m/s²] and
        ``.name``.
    omega : array_like, optional
        Frequencies [rad/s]; default :func:`default_omega_grid` (``n_omega`` uniform steps up to
        ``omega_max``, which defaults to the highest frequency the mesh resolves).
    n_omega : int
        Number of finite frequencies of the default grid.
    omega_max : float, optional
        Highest frequency of the default grid [rad/s].
    wave_directions : array_like, optional
        Headings [rad]; default 0°, 30°, …, 180° (following to head seas; the other half follows
        by port/starboard symmetry, see :func:`ship_gym.hydro.database.mirror_headings`).
    hydrostatic_stiffness : numpy.ndarray, optional
        6×6 stiffness about O [SI]; default computed by capytaine from the mesh and mass.
    **kwargs
        Passed to :func:`compute_database` (``lid``, ``symmetry``, ``n_jobs``, ``progress``…).
    """
    try:
        mesh = hull.immersed_mesh
        m6 = np.asarray(hull.mass.rigid_body_matrix(), dtype=float)
        rho = float(getattr(hull, "rho", RHO_SEAWATER))
        g = float(getattr(hull, "g", GRAVITY))
        name = str(getattr(hull, "name", getattr(mesh, "name", "hull")))
    except AttributeError as exc:
        raise ValueError(
            "hull must provide .immersed_mesh and .mass.rigid_body_matrix() (a ship_gym Hull); "
            f"got {type(hull).__name__}: {exc}"
        ) from exc
    if omega is None:
        omega = default_omega_grid(mesh, n_omega=n_omega, omega_max=omega_max, g=g)
    if wave_directions is None:
        wave_directions = np.deg2rad(np.arange(0.0, 181.0, 30.0))
    kwargs.setdefault("name", name)
    return compute_database(
        mesh,
        omega=omega,
        wave_directions=wave_directions,
        rho=rho,
        g=g,
        mass_matrix=m6,
        hydrostatic_stiffness=hydrostatic_stiffness,
        **kwargs,
    )
