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
  (boxes, hemispheres, Wigley hulls), which quarters the work again. The half (quarter) mesh
  keeps our panels as they are and cuts only those straddling the plane (see
  :func:`_positive_side`: capytaine's own clipper re-splits the panels that touch the plane,
  which made the Wigley hull fail with an IndexError).
* Irregular frequencies are removed with an interior lid that fills the hull's section at
  z_c = −d (:func:`_conforming_lid`; capytaine's ``generate_lid`` is the fallback for sections
  it cannot grid, such as two hulls: it covered only 27–86 % of the section of the library
  hulls, Wigley 27 %, box barge 84 %, S175 86 %, and nothing once split by symmetry on the box
  barge, leaving irregular frequencies: B44 < 0, 0.84 sway–roll damping asymmetry), placed
  slightly below the free surface (see :func:`lid_depth`): a lid at depth d moves the first
  irregular frequency of the lidded body to about ω² ≈ g/d, so d = r_max/π (r_max the largest
  panel radius) puts it at twice the highest frequency the hull mesh resolves (λ ≥ 8 r_max). The
  lid is not put exactly on z = 0 because there both source and collocation points sit on the
  free surface, where the wave part of the free-surface Green function is log-singular and
  poorly tabulated. Measured on a 1280-panel hemisphere (B33 against Hulme 1982): lid at z = 0,
  +15 % at ka = 6 and +79 % at ka = 8; lid at d = r_max/π ≈ 0.02 a, +2 % and +6 %; lid at
  d = 0.2 a, an irregular frequency back at ka ≈ 5 (−18 %), as ω² ≈ g/d predicts; no lid, −44 %
  at ka = 2.5 (the hemisphere's own first irregular frequency). Below ka = 2 all lidded variants
  agree with Hulme to 1.5 % (measured with ``generate_lid``; the conforming lid passes the same
  Hulme test, ``tests/validation/test_bem_hemisphere.py``).
* Each frequency is solved in turn (``n_jobs`` frequencies at a time in parallel) and can be
  kept in a ``checkpoint`` folder, so that an interrupted or failed run resumes where it
  stopped; capytaine's exceptions are raised as :class:`BEMError` naming the hull, the
  frequency and what to change.
"""

from __future__ import annotations

import contextlib
import hashlib
import importlib.util
import itertools
import logging
import os
import tempfile
import time
import warnings
from collections.abc import Sequence
from datetime import UTC, datetime
from pathlib import Path
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


def _panels_in_plane(vertices: np.ndarray, faces: np.ndarray, axis: int) -> bool:
    """Whether a panel lies in the plane ``coordinate[axis] = 0`` (it cannot be mirrored)."""
    size = float(np.ptp(vertices, axis=0).max())
    return bool(np.any(np.all(np.abs(vertices[faces, axis]) <= 1e-7 * max(size, 1e-12), axis=1)))


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
class BEMError(RuntimeError):
    """capytaine failed on a hull: names the hull, the frequency being solved and what to change.

    Attributes
    ----------
    hull : str
        Name of the body.
    omega : float or None
        Frequency [rad/s] being solved (0 and inf: the radiation limits), None while building
        the capytaine body.
    hint : str
        What to change (mesh, lid, symmetry, frequency range).
    """

    def __init__(self, hull: str, omega: float | None, hint: str, cause: BaseException) -> None:
        self.hull, self.omega, self.hint = hull, omega, hint
        where = (
            "while building the capytaine body (mesh, lid, symmetry)"
            if omega is None
            else f"while solving omega = {omega:.6g} rad/s"
        )
        super().__init__(
            f"{hull}: capytaine failed {where}: {type(cause).__name__}: {cause}; {hint}"
        )


def _bem_hint(exc: BaseException, omega: float | None) -> str:
    """What to change after a capytaine exception ``exc`` at ``omega`` [rad/s] (None: set-up)."""
    text = f"{type(exc).__name__} {exc}".lower()
    if isinstance(exc, np.linalg.LinAlgError) or "singular" in text:
        return (
            "the BEM matrix is singular: look for overlapping or duplicated panels and lid "
            "panels, or an irregular frequency (keep lid=True, or lower omega_max)"
        )
    if omega is not None and (omega == 0.0 or np.isinf(omega)):
        return (
            "this is a radiation limit: pass zero_frequency=False / infinite_frequency=False to "
            "skip it, and check the mesh (degenerate or folded panels)"
        )
    if omega is None or isinstance(exc, IndexError | KeyError):
        return (
            "check the mesh: degenerate or folded panels, panels on a symmetry plane, vertices "
            "that are only nearly symmetric (try symmetry=False), or the lid (try lid=False)"
        )
    return (
        "check the mesh (degenerate or folded panels; try symmetry=False), the lid (try "
        "lid=False) and the frequency range (omega up to resolved_omega_max of the mesh)"
    )


def _positive_side(
    vertices: np.ndarray, faces: np.ndarray, axis: int, *, name: str
) -> tuple[np.ndarray, np.ndarray]:
    """Panels of a mirror-symmetric mesh on the side ``coordinate[axis] >= 0`` (capytaine frame).

    Panels wholly on that side (vertices on the plane allowed) are kept as they are; only panels
    that straddle the plane are cut, by capytaine's clipper. capytaine's ``clipped`` is not used
    on the whole mesh because it re-splits every panel that merely *touches* the plane: a folded
    quad with three vertices on the plane (the Wigley hull's stem and stern foot, where keel and
    stem meet on the centre plane) leaves a triangle lying *in* the plane, which the reflection
    then duplicates. The symmetric mesh then holds a pair of coincident panels that
    ``merged()`` drops, its face count no longer matches the merged mesh, and capytaine fails
    with an IndexError in ``connected_components`` (``first_irregular_frequency_estimate``).

    Raises
    ------
    ValueError
        If a panel lies in the symmetry plane (a zero-thickness fin cannot be mirrored).
    """
    v = np.array(vertices, dtype=float)
    tol = 1e-7 * max(float(np.ptp(v, axis=0).max()), 1e-12)
    v[np.abs(v[:, axis]) <= tol, axis] = 0.0  # exactly on the plane: mirrors onto itself
    s = v[faces, axis]
    in_plane = np.all(s == 0.0, axis=1)
    if np.any(in_plane):
        k = int(np.flatnonzero(in_plane)[0])
        raise ValueError(
            f"{name}: {int(in_plane.sum())} panel(s) lie in the symmetry plane "
            f"{'xOz' if axis == 1 else 'yOz'} (first: face {k}); remove them from the mesh or "
            "pass symmetry=False"
        )
    keep = np.all(s >= 0.0, axis=1)
    straddle = np.any(s < 0.0, axis=1) & np.any(s > 0.0, axis=1)
    out_v, out_f = v, faces[keep]
    if np.any(straddle):
        import capytaine as cpt

        normal = np.zeros(3)
        normal[axis] = -1.0  # capytaine keeps the side opposite to the normal
        cut = cpt.Mesh(v, faces[straddle], auto_check=False).clipped(
            origin=(0.0, 0.0, 0.0), normal=tuple(normal)
        )
        cut_v = np.asarray(cut.vertices, dtype=float)
        cut_v[np.abs(cut_v[:, axis]) <= tol, axis] = 0.0
        out_f = np.vstack([out_f, np.asarray(cut.faces, dtype=np.int64) + len(v)])
        out_v = np.vstack([v, cut_v])
    return out_v, out_f


def _section_segments(vertices: np.ndarray, faces: np.ndarray, z: float) -> np.ndarray:
    """(n, 2, 2) horizontal (x, y) segments where the panels cross the plane z (capytaine frame).

    Each panel edge whose ends lie strictly below and at-or-above the plane is cut; the cuts of
    one panel are paired (upward cut, next downward cut) in the panel's vertex order, so that
    neighbouring panels' segments chain into consistently oriented loops.
    """
    p = vertices[faces]  # (m, 4, 3); a triangle repeats its last vertex: a zero edge, no cut
    q = np.roll(p, -1, axis=1)
    sa, sb = p[..., 2] - z, q[..., 2] - z
    cut = (sa < 0.0) != (sb < 0.0)
    t = np.where(cut, sa / np.where(cut, sa - sb, 1.0), 0.0)
    pts = p[..., :2] + t[..., None] * (q[..., :2] - p[..., :2])
    up = cut & (sa < 0.0)  # the edge leaves the part below the plane
    segs = []
    for i in np.flatnonzero(cut.any(axis=1)):
        k = np.flatnonzero(cut[i])
        k = np.roll(k, -int(np.argmax(up[i, k])))  # start at an upward cut: (up, down) pairs
        for a, b in zip(k[0::2], k[1::2], strict=False):
            segs.append(pts[i, [a, b]])
    return np.array(segs, dtype=float).reshape(-1, 2, 2)


def _conforming_lid(
    vertices: np.ndarray, faces: np.ndarray, z: float
) -> tuple[np.ndarray, np.ndarray] | None:
    """Lid panels filling the hull's horizontal section at z (capytaine frame), or None.

    The section at the lid depth is cut from the hull panels; the lid is a structured grid
    between its edges: stations at the x of the section's own vertices (merged when closer than
    half the target panel size h, the root-mean-square hull panel size; subdivided when further
    apart than 2.5 h), and at each station an even number of steps of at most h from the lowest
    to the highest y of the section (an even number: y = 0 is a grid line). The
    lid edge therefore follows the hull section panel by panel. This replaces capytaine's
    ``generate_lid`` (a rectangle of candidate points kept by a point-in-panel parity count),
    which drops the candidates that fall on edges of the hull panels below: on a box barge,
    whose flat bottom is a grid like the candidates', it covered 40 % of the waterplane and,
    split by the symmetry planes, nothing at all.

    Returns None when the section is not a single region spanned by one y-interval per x
    (checked by comparing the lid's area with the section's): the caller falls back to
    ``generate_lid``.
    """
    segs = _section_segments(vertices, faces, z)
    if len(segs) < 3:
        return None
    # signed area of the section (Green's theorem over the oriented segments)
    area = 0.5 * float(np.sum(segs[:, 0, 0] * segs[:, 1, 1] - segs[:, 1, 0] * segs[:, 0, 1]))
    area = abs(area)
    pts = segs.reshape(-1, 2)
    span = float(np.ptp(pts, axis=0).max())
    if area <= 1e-9 * span**2:
        return None
    p = vertices[faces]
    panel_area = 0.5 * np.linalg.norm(np.cross(p[:, 2] - p[:, 0], p[:, 3] - p[:, 1]), axis=1)
    h = float(np.sqrt(np.mean(panel_area)))
    xs = np.unique(pts[:, 0])
    stations = [float(xs[0])]
    for x in xs[1:]:
        if x - stations[-1] >= 0.5 * h:
            stations.append(float(x))
    if xs[-1] - stations[-1] > 1e-9 * span:  # keep the far end exactly
        if xs[-1] - stations[-1] < 0.5 * h and len(stations) > 1:
            stations[-1] = float(xs[-1])
        else:
            stations.append(float(xs[-1]))
    fine: list[float] = [stations[0]]
    for a, b in itertools.pairwise(stations):
        n = max(1, int(np.ceil((b - a) / (2.5 * h))))
        fine.extend(np.linspace(a, b, n + 1)[1:].tolist())
    x_st = np.array(fine)
    x0, x1 = segs[:, 0, 0], segs[:, 1, 0]
    y0, y1 = segs[:, 0, 1], segs[:, 1, 1]
    lo, hi = np.minimum(x0, x1), np.maximum(x0, x1)
    eps = 1e-9 * span
    y_lo, y_hi = np.empty(len(x_st)), np.empty(len(x_st))
    for k, x in enumerate(x_st):
        on = (lo <= x + eps) & (hi >= x - eps)
        if not np.any(on):
            return None
        dx = x1[on] - x0[on]
        par = np.abs(dx) <= eps
        t = np.clip((x - x0[on]) / np.where(par, 1.0, dx), 0.0, 1.0)
        ys = np.where(par, y0[on], y0[on] + t * (y1[on] - y0[on]))
        ys = np.concatenate([ys, y1[on][par]])
        y_lo[k], y_hi[k] = ys.min(), ys.max()
    width = float(np.max(y_hi - y_lo))
    n_y = max(2, 2 * int(np.ceil(width / (2.0 * h))))
    u = np.linspace(0.0, 1.0, n_y + 1)
    grid = np.stack(
        [
            np.broadcast_to(x_st[:, None], (len(x_st), n_y + 1)),
            y_lo[:, None] + (y_hi - y_lo)[:, None] * u[None, :],
            np.full((len(x_st), n_y + 1), z),
        ],
        axis=-1,
    ).reshape(-1, 3)
    key = np.round(grid / (1e-9 * span)).astype(np.int64)
    _, first, inverse = np.unique(key, axis=0, return_index=True, return_inverse=True)
    inverse = inverse.ravel()
    lid_v = grid[first]
    lid_f = []
    m = n_y + 1
    for i in range(len(x_st) - 1):
        for j in range(n_y):
            quad = [inverse[i * m + j], inverse[(i + 1) * m + j], inverse[(i + 1) * m + j + 1],
                    inverse[i * m + j + 1]]  # fmt: skip
            ring = [int(q) for k, q in enumerate(quad) if q != quad[k - 1]]
            ring = list(dict.fromkeys(ring))
            if len(ring) == 3:
                lid_f.append([*ring, ring[2]])
            elif len(ring) == 4:
                lid_f.append(ring)
    if not lid_f:
        return None
    lid_faces = np.array(lid_f, dtype=np.int64)
    q = lid_v[lid_faces]
    lid_area = 0.5 * float(np.abs(np.cross(q[:, 2] - q[:, 0], q[:, 3] - q[:, 1])[:, 2]).sum())
    if abs(lid_area / area - 1.0) > 0.02:
        return None
    return lid_v, lid_faces


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
) -> tuple[Any, Any, int, str]:
    """(FloatingBody for BEM, plain full-mesh FloatingBody for hydrostatics, lid panel count,
    how the lid was made)."""
    import capytaine as cpt

    full = cpt.Mesh(vertices_c, faces, name=name)
    dofs = cpt.rigid_body_dofs(rotation_center=np.zeros(3))
    plain_body = cpt.FloatingBody(mesh=full, dofs=dofs, center_of_mass=cog_c, mass=mass, name=name)

    def split(v: np.ndarray, f: np.ndarray, label: str) -> Any:
        if symmetry == SYMMETRY_NONE:
            return cpt.Mesh(v, f, name=label)
        hv, hf = _positive_side(v, f, 1, name=label)  # y_c >= 0
        if symmetry == SYMMETRY_Y:
            return cpt.ReflectionSymmetricMesh(cpt.Mesh(hv, hf), plane="xOz", name=label)
        qv, qf = _positive_side(hv, hf, 0, name=label)  # and x >= 0
        inner = cpt.ReflectionSymmetricMesh(cpt.Mesh(qv, qf), plane="yOz")
        return cpt.ReflectionSymmetricMesh(inner, plane="xOz", name=label)

    hull_mesh = split(vertices_c, faces, name)
    lid_mesh = None
    n_lid = 0
    lid_source = "none"
    if lid:
        made = _conforming_lid(vertices_c, faces, lid_z)
        lid_source = "conforming grid of the hull section at the lid depth"
        if made is None:
            generated = full.generate_lid(z=lid_z)
            made = (np.asarray(generated.vertices), np.asarray(generated.faces, dtype=np.int64))
            lid_source = "capytaine generate_lid"
        if len(made[1]) > 0:
            lid_mesh = split(made[0], made[1], f"lid of {name}")
            n_lid = int(lid_mesh.nb_faces)
        else:
            lid_source = "none"
            warnings.warn(
                f"{name}: no lid could be generated at z = {-lid_z:.3g} m below the waterline "
                "(no waterplane?); irregular frequencies are not removed",
                stacklevel=3,
            )
    for label, m in (("hull", hull_mesh), ("lid", lid_mesh)):
        if m is not None and symmetry != SYMMETRY_NONE and m.merged().nb_faces != m.nb_faces:
            raise RuntimeError(
                f"{name}: the symmetric {label} mesh holds coincident panels "
                f"({m.nb_faces} panels, {m.merged().nb_faces} once merged): a panel lies on a "
                "symmetry plane; pass symmetry=False"
            )
    body = cpt.FloatingBody(
        mesh=hull_mesh,
        lid_mesh=lid_mesh,
        dofs=cpt.rigid_body_dofs(rotation_center=np.zeros(3)),
        center_of_mass=cog_c,
        mass=mass,
        name=name,
    )
    return body, plain_body, n_lid, lid_source


_FORCES = ("diffraction_force", "Froude_Krylov_force", "excitation_force")
_CHECKPOINT_FORMAT = "ship_gym.hydro.bem checkpoint v1"


def _solve_frequency(
    solver: Any,
    body: Any,
    omega: float,
    beta_c: np.ndarray,
    *,
    rho: float,
    g: float,
) -> dict[str, np.ndarray]:
    """Solve the radiation (and, for 0 < ω < ∞, diffraction) problems at one frequency.

    Returns arrays in capytaine's frame: ``added_mass`` and ``radiation_damping`` (6, 6)
    [influenced, radiating] and, at finite ω, the complex wave forces (n_β, 6) for the headings
    ``np.sort(beta_c)``. capytaine's exceptions (raised, or returned as failed results) are
    raised as they are; :func:`compute_database` adds the hull, ω and a hint.
    """
    import capytaine as cpt

    problems = [
        cpt.RadiationProblem(body=body, omega=omega, radiating_dof=dof, rho=rho, g=g)
        for dof in DOF_NAMES
    ]
    finite = bool(np.isfinite(omega) and omega > 0.0)
    if finite:
        problems += [
            cpt.DiffractionProblem(body=body, omega=omega, wave_direction=float(b), rho=rho, g=g)
            for b in beta_c
        ]
    results = solver.solve_all(
        problems,
        keep_details=False,
        progress_bar=False,
        _check_wavelength=False,  # checked once in compute_database
    )
    failed = [r for r in results if hasattr(r, "exception")]
    if failed:
        raise failed[0].exception
    ds = cpt.assemble_dataset(results, freq=False, wavelength=False, mesh=False, hydrostatics=False)
    dofs = list(DOF_NAMES)
    ds = ds.assign_coords(
        influenced_dof=np.asarray(ds["influenced_dof"].values, dtype=str),
        radiating_dof=np.asarray(ds["radiating_dof"].values, dtype=str),
    )
    out: dict[str, np.ndarray] = {"omega": np.array(omega, dtype=np.float64)}
    for key in ("added_mass", "radiation_damping"):
        x = ds[key].sel(influenced_dof=dofs, radiating_dof=dofs)
        out[key] = np.asarray(x.transpose(..., "influenced_dof", "radiating_dof").values, float)
        out[key] = out[key].reshape(6, 6)
    if finite:
        if not np.allclose(ds["wave_direction"].values, np.sort(beta_c), rtol=0.0, atol=1e-12):
            raise RuntimeError(
                f"internal error: capytaine headings {ds['wave_direction'].values} do not match "
                f"{np.sort(beta_c)}"
            )
        for key in _FORCES:
            x = ds[key].sel(influenced_dof=dofs).transpose(..., "wave_direction", "influenced_dof")
            out[key] = np.asarray(x.values, dtype=complex).reshape(len(beta_c), 6)
    return out


def _checkpoint_key(
    vertices: np.ndarray,
    faces: np.ndarray,
    *,
    rho: float,
    g: float,
    mass_matrix: np.ndarray,
    omega: float,
    wave_directions: np.ndarray,
    lid: bool,
    lid_z: float,
    symmetry: str,
    capytaine_version: str,
    lid_source: str = "",
) -> str:
    """SHA-256 of everything that defines the BEM problems at one frequency (hex digest).

    ``_CHECKPOINT_FORMAT`` is hashed too: change it when the way the problems are built from
    these inputs changes (mesh split, lid construction), so that old checkpoints are not reused.
    """
    h = hashlib.sha256(_CHECKPOINT_FORMAT.encode())
    for arr in (
        np.asarray(vertices, dtype=np.float64),
        np.asarray(faces, dtype=np.int64),
        np.asarray(mass_matrix, dtype=np.float64),
        np.asarray(wave_directions, dtype=np.float64),
        np.array([rho, g, omega, lid_z], dtype=np.float64),
    ):
        h.update(repr(arr.shape).encode())
        h.update(np.ascontiguousarray(arr).tobytes())
    h.update(
        f"lid={bool(lid)}:{lid_source};symmetry={symmetry};capytaine={capytaine_version}".encode()
    )
    return h.hexdigest()


def _checkpoint_dir(checkpoint: str | os.PathLike[str]) -> Path:
    """The checkpoint folder, created if needed; ValueError naming it when unusable."""
    path = Path(checkpoint)
    if path.exists() and not path.is_dir():
        raise ValueError(f"checkpoint must be a directory, got the file {str(path)!r}")
    try:
        path.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise ValueError(f"checkpoint: cannot create the directory {str(path)!r}: {exc}") from None
    if not os.access(path, os.W_OK):
        raise ValueError(f"checkpoint: the directory {str(path)!r} is not writable")
    return path


def _write_checkpoint(path: Path, arrays: dict[str, np.ndarray]) -> None:
    """Write ``arrays`` to ``path`` (.npz) atomically: a temporary file, then os.replace."""
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.stem}-", suffix=".tmp")
    try:
        with os.fdopen(fd, "wb") as fh:
            np.savez(fh, allow_pickle=False, **arrays)
        os.replace(tmp, path)
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        raise


def _read_checkpoint(path: Path, omega: float, n_beta: int) -> dict[str, np.ndarray] | None:
    """The arrays of one solved frequency, or None if the file is missing or unreadable."""
    if not path.is_file():
        return None
    try:
        with np.load(path, allow_pickle=False) as data:
            out = {key: data[key] for key in data.files}
    except (OSError, ValueError, EOFError) as exc:
        LOG.warning("ignoring unreadable BEM checkpoint %s (%s); solving again", path, exc)
        return None
    finite = bool(np.isfinite(omega) and omega > 0.0)
    shapes = {"added_mass": (6, 6), "radiation_damping": (6, 6)}
    if finite:
        shapes.update({key: (n_beta, 6) for key in _FORCES})
    if float(out.get("omega", np.nan)) != omega and not (
        np.isinf(omega) and np.isinf(out.get("omega", 0.0))
    ):
        LOG.warning("ignoring BEM checkpoint %s: it holds another frequency", path)
        return None
    if any(key not in out or out[key].shape != shape for key, shape in shapes.items()):
        LOG.warning("ignoring BEM checkpoint %s: unexpected content", path)
        return None
    return out


def _solve_all_frequencies(
    body: Any,
    omega: np.ndarray,
    beta_c: np.ndarray,
    *,
    rho: float,
    g: float,
    n_jobs: int,
    progress: bool,
    name: str,
    keys: list[str],
    checkpoint_dir: Path | None,
) -> tuple[list[dict[str, np.ndarray]], list[float], int]:
    """Solve every frequency in chunks, reusing and writing checkpoints.

    Returns the per-frequency arrays (see :func:`_solve_frequency`), the seconds spent per
    frequency (as recorded when it was solved) and the number of frequencies read back from
    ``checkpoint_dir``.
    """
    import capytaine as cpt
    from tqdm.auto import tqdm

    solver = cpt.BEMSolver()
    solved: list[dict[str, np.ndarray] | None] = [None] * len(omega)
    n_reused = 0
    if checkpoint_dir is not None:
        for k, (w, key) in enumerate(zip(omega, keys, strict=True)):
            solved[k] = _read_checkpoint(checkpoint_dir / f"{key}.npz", float(w), len(beta_c))
            n_reused += solved[k] is not None
    todo = [k for k in range(len(omega)) if solved[k] is None]
    chunk = 1 if n_jobs == 1 else n_jobs
    with tqdm(
        total=len(omega), initial=n_reused, desc=f"BEM {name}", unit="freq", disable=not progress
    ) as bar:
        for start in range(0, len(todo), chunk):
            ks = todo[start : start + chunk]
            t0 = time.perf_counter()
            if len(ks) == 1:
                w = float(omega[ks[0]])
                try:
                    out = [_solve_frequency(solver, body, w, beta_c, rho=rho, g=g)]
                except Exception as exc:
                    raise BEMError(name, w, _bem_hint(exc, w), exc) from exc
            else:
                import joblib

                try:
                    out = joblib.Parallel(n_jobs=len(ks))(
                        joblib.delayed(_solve_frequency)(
                            cpt.BEMSolver(), body, float(omega[k]), beta_c, rho=rho, g=g
                        )
                        for k in ks
                    )
                except Exception as exc:
                    w = float(omega[ks[0]])
                    raise BEMError(
                        name,
                        w,
                        f"(chunk of omega = {w:.6g} to {float(omega[ks[-1]]):.6g} "
                        f"rad/s) {_bem_hint(exc, w)}",
                        exc,
                    ) from exc
            seconds = (time.perf_counter() - t0) / len(ks)
            for k, arrays in zip(ks, out, strict=True):
                arrays["seconds"] = np.array(seconds, dtype=np.float64)
                solved[k] = arrays
                if checkpoint_dir is not None:
                    _write_checkpoint(checkpoint_dir / f"{keys[k]}.npz", arrays)
            bar.update(len(ks))
    done = [s for s in solved if s is not None]
    assert len(done) == len(omega)
    return done, [float(s.get("seconds", np.nan)) for s in done], int(n_reused)


def _assemble(
    solved: list[dict[str, np.ndarray]], omega: np.ndarray, beta_c: np.ndarray, *, g: float
) -> xr.Dataset:
    """capytaine-frame dataset (merged complex values) from the per-frequency arrays."""
    n_b = len(beta_c)
    nan_forces = np.full((n_b, 6), np.nan + 1j * np.nan)
    dof = list(DOF_NAMES)
    data: dict[str, Any] = {
        key: (("omega", "influenced_dof", "radiating_dof"), np.stack([s[key] for s in solved]))
        for key in ("added_mass", "radiation_damping")
    }
    for key in _FORCES:
        stack = np.stack([s.get(key, nan_forces) for s in solved]).astype(complex)
        data[key] = (("omega", "wave_direction", "influenced_dof"), stack)
    with np.errstate(divide="ignore"):
        period = 2.0 * np.pi / omega
    return xr.Dataset(
        data,
        coords={
            "omega": omega,
            "period": ("omega", period),
            "wavenumber": ("omega", omega**2 / g),
            "influenced_dof": dof,
            "radiating_dof": dof,
            "wave_direction": np.asarray(beta_c, dtype=float),
        },
    )


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
    checkpoint: str | os.PathLike[str] | None = None,
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
        Parallel worker processes (needs the optional ``joblib`` package when > 1). The
        frequencies are solved in chunks (one frequency with 1 job, ``n_jobs`` frequencies in
        parallel otherwise) with a progress bar.
    progress : bool
        Show a progress bar.
    name : str, optional
        Label of the body (default: the mesh name).
    checkpoint : str or os.PathLike, optional
        Directory (created if needed) where each solved frequency is written as soon as its
        chunk is done (``<key>.npz``, atomically: a temporary file, then ``os.replace``). The key
        is a SHA-256 of everything that defines the problems at that frequency: mesh vertices
        and faces, rho, g, mass matrix, ω, wave directions, lid (and its depth), symmetry and
        the capytaine version. A rerun with the same directory reads the frequencies already
        there instead of solving them again, so an interrupted run loses at most one chunk;
        files of other problems in the directory are ignored.

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
    BEMError
        (a RuntimeError) if capytaine fails while building the body or solving a frequency:
        names the hull, the frequency and what to change. Frequencies solved before the
        failure are kept in ``checkpoint`` when given.
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
    checkpoint_dir = None if checkpoint is None else _checkpoint_dir(checkpoint)
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
    if symmetry is True and _panels_in_plane(vertices, faces, axis=1):
        raise ValueError(
            f"{name}: symmetry=True but panels lie in the port/starboard symmetry plane y = 0"
        )
    if symmetry is False or not sym_y or _panels_in_plane(vertices, faces, axis=1):
        sym = SYMMETRY_NONE
    elif is_mirror_symmetric(vertices, faces, axis=0) and not _panels_in_plane(
        vertices, faces, axis=0
    ):
        sym = SYMMETRY_XY
    else:
        sym = SYMMETRY_Y
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
    try:
        body, plain_body, n_lid, lid_source = _capytaine_body(
            vertices_c,
            faces,
            name=name,
            symmetry=sym,
            lid=lid,
            lid_z=-d_lid,
            cog_c=cog_c,
            mass=mass,
        )
        w_irr = float(body.first_irregular_frequency_estimate(g=g))
    except Exception as exc:
        raise BEMError(name, None, _bem_hint(exc, None), exc) from exc
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
    keys = [
        _checkpoint_key(
            vertices,
            faces,
            rho=rho,
            g=g,
            mass_matrix=m6,
            omega=float(w),
            wave_directions=betas,
            lid=lid,
            lid_z=d_lid,
            symmetry=sym,
            capytaine_version=str(cpt.__version__),
            lid_source=lid_source,
        )
        for w in all_omega
    ]
    solved, timings, n_reused = _solve_all_frequencies(
        body,
        all_omega,
        beta_c,
        rho=rho,
        g=g,
        n_jobs=int(n_jobs),
        progress=progress,
        name=name,
        keys=keys,
        checkpoint_dir=checkpoint_dir,
    )
    elapsed = time.perf_counter() - t_start
    ds_c = _assemble(solved, all_omega, np.sort(beta_c), g=g)

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
        "lid_source": lid_source,
        "checkpoint_frequencies_reused": int(n_reused),
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
    checkpoint: str | os.PathLike[str] | None = None,
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
    checkpoint : str or os.PathLike, optional
        Directory keeping every solved frequency, reused by a rerun (see
        :func:`compute_database`).
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
        checkpoint=checkpoint,
        **kwargs,
    )
