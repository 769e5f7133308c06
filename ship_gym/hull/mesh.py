"""Closed panel meshes of hulls: storage, quality checks, triangulation and waterline clipping.

A :class:`PanelMesh` holds planar-ish quadrilateral and triangular panels in the body frame of
:mod:`ship_gym.conventions` (x forward, y starboard, z down, origin at the design waterline).
Faces are stored as an (n, 4) integer array; a triangle repeats its last vertex
(``faces[:, 3] == faces[:, 2]``), the Nemoh convention. Normals point *out of the hull* (into
the water).

Hydrostatic and Froude–Krylov integrals need the part of the hull below a free surface. They work
on triangles: :func:`clip_triangles` cuts each triangle where the linearly interpolated
submergence changes sign (cut at the waterline, not wet/dry by centroid), so that integrating a
pressure that is linear over each triangle is exact.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np


class MeshError(ValueError):
    """A mesh failed a quality check (not watertight, inward normals, degenerate panels…)."""


def _readonly(a: np.ndarray) -> np.ndarray:
    a = np.array(a, copy=True)
    a.flags.writeable = False
    return a


@dataclass(frozen=True, eq=False)
class PanelMesh:
    """A surface mesh of quadrilateral and triangular panels.

    Parameters
    ----------
    vertices : numpy.ndarray
        (n_vertices, 3) coordinates [m] in the body frame.
    faces : numpy.ndarray
        (n_faces, 4) vertex indices, counter-clockwise seen from the water (outward normal by the
        right-hand rule); a triangle repeats its last index.
    name : str
        Label used in messages and file attributes.
    """

    vertices: np.ndarray
    faces: np.ndarray
    name: str = "mesh"

    def __post_init__(self) -> None:
        v = np.asarray(self.vertices, dtype=float)
        f = np.asarray(self.faces)
        if v.ndim != 2 or v.shape[1] != 3:
            raise MeshError(f"{self.name}: vertices must have shape (n, 3), got {v.shape}")
        if f.ndim != 2 or f.shape[1] not in (3, 4):
            raise MeshError(f"{self.name}: faces must have shape (n, 3) or (n, 4), got {f.shape}")
        if f.shape[1] == 3:
            f = np.column_stack([f, f[:, 2]])
        if not np.issubdtype(f.dtype, np.integer):
            if not np.all(np.equal(np.mod(f, 1), 0)):
                raise MeshError(f"{self.name}: faces must hold integer vertex indices")
        f = f.astype(np.int64)
        if f.size and (f.min() < 0 or f.max() >= len(v)):
            raise MeshError(
                f"{self.name}: face indices must lie in [0, {len(v) - 1}], "
                f"got range [{f.min()}, {f.max()}]"
            )
        if not np.all(np.isfinite(v)):
            raise MeshError(f"{self.name}: vertices contain non-finite coordinates")
        object.__setattr__(self, "vertices", _readonly(v))
        object.__setattr__(self, "faces", _readonly(f))

    # ------------------------------------------------------------------ sizes and geometry
    @property
    def n_faces(self) -> int:
        """Number of panels."""
        return len(self.faces)

    @property
    def n_vertices(self) -> int:
        """Number of vertices."""
        return len(self.vertices)

    @property
    def is_triangle(self) -> np.ndarray:
        """(n_faces,) True for triangular panels."""
        return self.faces[:, 3] == self.faces[:, 2]

    @cached_property
    def vector_areas(self) -> np.ndarray:
        """(n_faces, 3) area-weighted outward normals [m²].

        Half the cross product of the diagonals, exact for any quadrilateral (planar or not) in
        the sense of ∮ r × dr / 2, and for triangles.
        """
        p = self.vertices[self.faces]
        return 0.5 * np.cross(p[:, 2] - p[:, 0], p[:, 3] - p[:, 1])

    @cached_property
    def areas(self) -> np.ndarray:
        """(n_faces,) panel areas [m²] (sum of the two triangles of a quad)."""
        tri, owner = self.triangles_with_owner
        a = 0.5 * np.linalg.norm(np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]), axis=1)
        return np.bincount(owner, weights=a, minlength=self.n_faces)

    @cached_property
    def normals(self) -> np.ndarray:
        """(n_faces, 3) unit outward normals."""
        va = self.vector_areas
        norm = np.linalg.norm(va, axis=1, keepdims=True)
        return va / np.where(norm > 0.0, norm, 1.0)

    @cached_property
    def centroids(self) -> np.ndarray:
        """(n_faces, 3) area centroids [m]."""
        tri, owner = self.triangles_with_owner
        a = 0.5 * np.linalg.norm(np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]), axis=1)
        c = tri.mean(axis=1) * a[:, None]
        out = np.zeros((self.n_faces, 3))
        np.add.at(out, owner, c)
        area = np.maximum(self.areas, np.finfo(float).tiny)
        return out / area[:, None]

    @cached_property
    def triangles_with_owner(self) -> tuple[np.ndarray, np.ndarray]:
        """Triangulation: ((n_tri, 3, 3) coordinates [m], (n_tri,) index of the parent face).

        A quad (a, b, c, d) is split into (a, b, c) and (a, c, d); triangles are kept as they are.
        """
        return self._triangulate(self.vertices)

    @cached_property
    def triangle_indices(self) -> tuple[np.ndarray, np.ndarray]:
        """((n_tri, 3) vertex indices, (n_tri,) parent face) of :attr:`triangles_with_owner`."""
        f = self.faces
        quad = ~self.is_triangle
        t1 = f[:, [0, 1, 2]]
        t2 = f[quad][:, [0, 2, 3]]
        owner = np.concatenate([np.arange(self.n_faces), np.flatnonzero(quad)])
        return np.concatenate([t1, t2]), owner

    def _triangulate(self, vertices: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        idx, owner = self.triangle_indices
        return vertices[idx], owner

    @property
    def bounds(self) -> np.ndarray:
        """(2, 3) minimum and maximum coordinates [m]."""
        return np.array([self.vertices.min(axis=0), self.vertices.max(axis=0)])

    @cached_property
    def volume(self) -> float:
        """Enclosed volume [m³] by the divergence theorem (positive for outward normals)."""
        tri, _ = self.triangles_with_owner
        return float(np.einsum("ij,ij->", tri[:, 0], np.cross(tri[:, 1], tri[:, 2])) / 6.0)

    @cached_property
    def volume_centroid(self) -> np.ndarray:
        """Centroid of the enclosed volume [m] (closed meshes only)."""
        tri, _ = self.triangles_with_owner
        v6 = np.einsum("ij,ij->i", tri[:, 0], np.cross(tri[:, 1], tri[:, 2]))
        c = (tri.sum(axis=1) / 4.0) * v6[:, None]
        return c.sum(axis=0) / v6.sum()

    # ------------------------------------------------------------------ transformations
    def transformed(self, rotation: np.ndarray, translation: np.ndarray) -> PanelMesh:
        """The mesh with vertices ``rotation @ v + translation`` [m]."""
        v = self.vertices @ np.asarray(rotation, dtype=float).T + np.asarray(translation, float)
        return PanelMesh(v, self.faces, self.name)

    def translated(self, shift: np.ndarray) -> PanelMesh:
        """The mesh shifted by ``shift`` [m]."""
        return self.transformed(np.eye(3), shift)

    # ------------------------------------------------------------------ quality
    @cached_property
    def edge_report(self) -> dict[str, int]:
        """Counts of boundary, non-manifold and inconsistently oriented edges."""
        edges = _directed_edges(self.faces)
        key = np.sort(edges, axis=1)
        uniq, inverse, counts = np.unique(key, axis=0, return_inverse=True, return_counts=True)
        inverse = inverse.ravel()
        forward = (edges[:, 0] < edges[:, 1]).astype(int)
        n_forward = np.bincount(inverse, weights=forward, minlength=len(uniq))
        two = counts == 2
        return {
            "edges": len(uniq),
            "boundary": int(np.sum(counts == 1)),
            "non_manifold": int(np.sum(counts > 2)),
            "inconsistent": int(np.sum(two & (n_forward != 1))),
        }

    def check(
        self,
        *,
        closed: bool = True,
        min_area: float | None = None,
    ) -> None:
        """Raise :class:`MeshError` with a clear message if the mesh is not fit for use.

        Parameters
        ----------
        closed : bool
            Require a watertight mesh with consistently oriented, outward normals (a hull to the
            deck). Set False for an open immersed mesh (BEM input).
        min_area : float, optional
            Smallest acceptable panel area [m²]; default 1e-10 × the mean panel area.
        """
        if self.n_faces == 0:
            raise MeshError(f"{self.name}: mesh has no faces")
        areas = self.areas
        tol = 1e-10 * float(np.mean(areas)) if min_area is None else min_area
        bad = np.flatnonzero(areas <= tol)
        if bad.size:
            raise MeshError(
                f"{self.name}: {bad.size} degenerate panel(s) with area <= {tol:.3g} m^2 "
                f"(first: face {bad[0]} with vertices {self.faces[bad[0]].tolist()})"
            )
        rep = self.edge_report
        if rep["non_manifold"]:
            raise MeshError(
                f"{self.name}: {rep['non_manifold']} non-manifold edge(s) shared by more than "
                "two panels"
            )
        if rep["inconsistent"]:
            raise MeshError(
                f"{self.name}: {rep['inconsistent']} edge(s) where neighbouring panels have "
                "opposite orientation; normals must all point out of the hull"
            )
        if closed:
            if rep["boundary"]:
                raise MeshError(
                    f"{self.name}: mesh is not watertight: {rep['boundary']} boundary edge(s) "
                    "belong to a single panel (close the deck and the ends)"
                )
            if self.volume <= 0.0:
                raise MeshError(
                    f"{self.name}: enclosed volume is {self.volume:.6g} m^3 <= 0: normals point "
                    "into the hull; reverse the vertex order of every face"
                )

    def flipped(self) -> PanelMesh:
        """The mesh with the orientation (normal direction) of every panel reversed."""
        f = self.faces
        tri = self.is_triangle
        new = f[:, ::-1].copy()
        # a reversed triangle (c, c, b, a) must again repeat its *last* index
        new[tri] = f[tri][:, [2, 1, 0, 0]]
        return PanelMesh(self.vertices, new, self.name)


def _directed_edges(faces: np.ndarray) -> np.ndarray:
    nxt = np.roll(faces, -1, axis=1)
    e = np.stack([faces, nxt], axis=-1).reshape(-1, 2)
    return e[e[:, 0] != e[:, 1]]


def mesh_from_polygons(
    vertices: np.ndarray,
    polygons: list[list[int]] | np.ndarray,
    *,
    name: str = "mesh",
    merge_tolerance: float = 1e-6,
) -> PanelMesh:
    """Build a clean :class:`PanelMesh` from polygons, merging coincident vertices.

    Consecutive repeated vertices are removed, a quad with a collapsed edge becomes a triangle,
    polygons with fewer than three distinct vertices are dropped and polygons with more than four
    are split into a fan of quads/triangles. Unused vertices are removed.

    Parameters
    ----------
    vertices : numpy.ndarray
        (n, 3) coordinates [m].
    polygons : sequence of sequences of int
        Vertex indices of each panel, counter-clockwise seen from the water.
    merge_tolerance : float
        Vertices closer than this [m] (on a grid of this size) are merged.
    """
    vertices = np.asarray(vertices, dtype=float).reshape(-1, 3)
    inverse, new_vertices = _merge_close_vertices(vertices, merge_tolerance)
    faces: list[list[int]] = []
    for poly in polygons:
        p = [int(inverse[i]) for i in poly]
        cleaned = [q for k, q in enumerate(p) if q != p[k - 1]] if len(p) > 1 else p
        # drop duplicates that are not consecutive (pinched polygon) by keeping first occurrence
        seen: list[int] = []
        for q in cleaned:
            if q not in seen:
                seen.append(q)
        cleaned = seen
        if len(cleaned) < 3:
            continue
        if len(cleaned) == 3:
            faces.append([*cleaned, cleaned[2]])
        elif len(cleaned) == 4:
            faces.append(cleaned)
        else:
            # fan of quads from the first vertex: (0,1,2,3), (0,3,4,5), … last may be a triangle
            k = 1
            while k < len(cleaned) - 1:
                chunk = [cleaned[0], *cleaned[k : k + 3]]
                if len(chunk) == 3:
                    chunk.append(chunk[2])
                faces.append(chunk)
                k += 2
    f = np.array(faces, dtype=np.int64).reshape(-1, 4)
    if len(f):
        # remove zero-area panels (collinear triangles produced by degenerate input)
        probe = PanelMesh(new_vertices, f, name)
        f = f[probe.areas > 1e-12 * max(float(probe.areas.max()), 1e-300)]
    used = np.unique(f)
    remap = -np.ones(len(new_vertices), dtype=np.int64)
    remap[used] = np.arange(len(used))
    return PanelMesh(new_vertices[used], remap[f], name)


def _merge_close_vertices(vertices: np.ndarray, tolerance: float) -> tuple[np.ndarray, np.ndarray]:
    """Cluster vertices closer than ``tolerance`` [m]: (index of each vertex's representative
    in the returned array, representatives). Distance-based (k-d tree), so points on either side
    of a rounding-grid boundary still merge."""
    if len(vertices) == 0:
        return np.zeros(0, dtype=np.int64), vertices
    from scipy.sparse import coo_matrix
    from scipy.sparse.csgraph import connected_components
    from scipy.spatial import cKDTree

    pairs = cKDTree(vertices).query_pairs(tolerance, output_type="ndarray")
    n = len(vertices)
    graph = coo_matrix((np.ones(len(pairs)), (pairs[:, 0], pairs[:, 1])), shape=(n, n))
    _, label = connected_components(graph, directed=False)
    _, first, inverse = np.unique(label, return_index=True, return_inverse=True)
    return inverse.ravel().astype(np.int64), vertices[first]


# ---------------------------------------------------------------------- clipping and integrals
def clip_triangles(
    triangles: np.ndarray, depth: np.ndarray, values: np.ndarray | None = None
) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Keep the submerged part of each triangle, cut where the submergence changes sign.

    The submergence (depth below the free surface, positive in the water) is taken as linear
    along each edge, so the cut points lie where it vanishes. For a plane free surface this is
    exact; under a wave it is the usual panel-level linearisation of the surface.

    Parameters
    ----------
    triangles : numpy.ndarray
        (n, 3, 3) vertex coordinates [m].
    depth : numpy.ndarray
        (n, 3) submergence of each vertex [m]; wet where ≥ 0.
    values : numpy.ndarray, optional
        (n, 3) a field that vanishes on the free surface (e.g. the pressure): carried with the
        original vertices, 0 on the cut. Defaults to ``depth``.

    Returns
    -------
    wet_triangles : numpy.ndarray
        (m, 3, 3) coordinates of the wet triangles [m], orientation preserved.
    wet_depth : numpy.ndarray
        (m, 3) submergence at their vertices [m] (0 on the cut).
    owner : numpy.ndarray
        (m,) index of the parent triangle.
    wet_values : numpy.ndarray
        (m, 3) ``values`` at the wet vertices (0 on the cut).
    """
    vals = depth if values is None else values
    fields = np.stack([depth, vals], axis=-1)  # (n, 3, 2)
    wet = depth >= 0.0
    n_wet = wet.sum(axis=1)
    out_t = [triangles[n_wet == 3]]
    out_f = [fields[n_wet == 3]]
    out_o = [np.flatnonzero(n_wet == 3)]
    for n_case in (1, 2):
        sel = np.flatnonzero(n_wet == n_case)
        if sel.size == 0:
            continue
        w = wet[sel]
        # the "odd" vertex: the single wet one (case 1) or the single dry one (case 2)
        odd = np.argmax(w if n_case == 1 else ~w, axis=1)
        order = (odd[:, None] + np.arange(3)[None, :]) % 3
        t = np.take_along_axis(triangles[sel], order[:, :, None], axis=1)
        f = np.take_along_axis(fields[sel], order[:, :, None], axis=1)
        a, b, c = t[:, 0], t[:, 1], t[:, 2]
        fa, fb, fc = f[:, 0], f[:, 1], f[:, 2]
        da, db, dc = fa[:, :1], fb[:, :1], fc[:, :1]
        p_ab = a + (b - a) * (da / (da - db))
        p_ac = a + (c - a) * (da / (da - dc))
        zero = np.zeros_like(fa)
        if n_case == 1:
            out_t.append(np.stack([a, p_ab, p_ac], axis=1))
            out_f.append(np.stack([fa, zero, zero], axis=1))
            out_o.append(sel)
        else:
            out_t.append(np.stack([p_ab, b, c], axis=1))
            out_f.append(np.stack([zero, fb, fc], axis=1))
            out_t.append(np.stack([p_ab, c, p_ac], axis=1))
            out_f.append(np.stack([zero, fc, zero], axis=1))
            out_o.extend([sel, sel])
    fields_out = np.concatenate(out_f).reshape(-1, 3, 2)
    return (
        np.concatenate(out_t).reshape(-1, 3, 3),
        fields_out[:, :, 0],
        np.concatenate(out_o).astype(np.int64),
        fields_out[:, :, 1],
    )


def pressure_resultant(
    triangles: np.ndarray, pressure: np.ndarray, reference_point: np.ndarray
) -> tuple[np.ndarray, np.ndarray]:
    """Force and moment of a pressure field linear over each triangle, integrated exactly.

    F = −∫ p n dS,  M = −∫ p (r − r₀) × n dS, with n the outward normal, using
    ∫ λᵢ λⱼ dS = S (1 + δᵢⱼ)/12 for the barycentric coordinates λ.

    Parameters
    ----------
    triangles : numpy.ndarray
        (n, 3, 3) vertex coordinates [m].
    pressure : numpy.ndarray
        (n, 3) pressure at the vertices [Pa].
    reference_point : numpy.ndarray
        (3,) point r₀ about which moments are taken [m].

    Returns
    -------
    force, moment : numpy.ndarray
        (3,) [N] and (3,) [N·m] in the axes of the coordinates.
    """
    r = triangles - np.asarray(reference_point, dtype=float)
    vec_area = 0.5 * np.cross(r[:, 1] - r[:, 0], r[:, 2] - r[:, 0])  # S n
    p_mean = pressure.mean(axis=1)
    force = -(p_mean[:, None] * vec_area).sum(axis=0)
    # ∫ p r dS = S/12 (Σ pᵢ rᵢ + Σ pᵢ Σ rᵢ)  →  divided by S since vec_area carries S
    pr = (np.einsum("ni,nij->nj", pressure, r) + pressure.sum(axis=1)[:, None] * r.sum(axis=1)) / 12
    moment = -np.cross(pr, vec_area).sum(axis=0)
    return force, moment


def immersed_part(mesh: PanelMesh, *, tolerance: float = 1e-6) -> PanelMesh:
    """The panels below the plane z = 0 (body frame, z down), cut along the plane.

    This is the open immersed mesh handed to a BEM solver. Panels fully below are kept as they
    are (quads stay quads); panels crossing the plane are clipped polygon-wise
    (Sutherland–Hodgman); panels on or above the plane are dropped.

    Parameters
    ----------
    mesh : PanelMesh
        Closed hull mesh in the body frame.
    tolerance : float
        Vertices within this distance of the plane [m] are snapped onto it.
    """
    z = mesh.vertices[:, 2]
    zf = z[mesh.faces]
    below = np.all(zf >= -tolerance, axis=1) & np.any(zf > tolerance, axis=1)
    crossing = np.any(zf > tolerance, axis=1) & np.any(zf < -tolerance, axis=1)
    verts = [mesh.vertices.copy()]
    verts[0][np.abs(z) <= tolerance, 2] = 0.0
    polys: list[list[int]] = [list(f) for f in mesh.faces[below]]
    n_next = mesh.n_vertices
    extra: list[np.ndarray] = []
    for face in mesh.faces[crossing]:
        idx = list(dict.fromkeys(int(i) for i in face))  # drop the repeated triangle index
        ring = [(i, mesh.vertices[i]) for i in idx]
        out: list[int] = []
        for k, (i0, p0) in enumerate(ring):
            _, p1 = ring[(k + 1) % len(ring)]
            in0, in1 = p0[2] >= -tolerance, p1[2] >= -tolerance
            if in0:
                out.append(i0)
            if in0 != in1:
                s = p0[2] / (p0[2] - p1[2])
                q = p0 + s * (p1 - p0)
                q[2] = 0.0
                extra.append(q)
                out.append(n_next)
                n_next += 1
        if len(out) >= 3:
            polys.append(out)
    allv = np.vstack([verts[0], *extra]) if extra else verts[0]
    scale = float(np.ptp(mesh.vertices, axis=0).max())
    return mesh_from_polygons(
        allv, polys, name=f"{mesh.name} (immersed)", merge_tolerance=1e-8 * scale
    )
