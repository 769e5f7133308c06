"""Nonlinear Froude–Krylov + hydrostatic force over the instantaneous wetted hull (stage 2).

The incident-wave and hydrostatic pressure (Wheeler-stretched in deep water, see
:mod:`ship_gym.waves`)

    p = ρ g (Z + Σⱼ Re[cⱼ(t) e^{−kⱼ d} e^{−i kⱼ (X cos χⱼ + Y sin χⱼ)}]),   d = Z + ζ(X, Y, t) ≥ 0,

is evaluated at the hull vertices in their instantaneous earth position (Z down, ζ up), and
integrated over the hull triangles below the incident-wave surface. Triangles crossing the surface
are cut where the submergence d changes sign (linear along each edge), not classified wet/dry by
centroid; the pressure vanishes on the cut. Pressure is taken linear over each (cut) triangle,
which integrates the hydrostatic part exactly; in calm water this is the same integral as
:func:`ship_gym.hull.hydrostatics.pressure_integral`, so the GZ curve is reproduced (the mirror
pairing below changes the triangles only where a quad is split along the other diagonal, which
for a planar quad and a linear pressure gives the same integral).

The rule is port–starboard symmetric: a triangle cut into a wet quadrilateral is integrated as
the mean of the quadrilateral's two splits, and on a mirror-symmetric mesh every triangle is
paired with its mirror image (:class:`HullPanels`), so that an upright ship in head or following
seas gets no sway force, roll or yaw moment beyond round-off (tested at 1e-12 of ρg∇ and ρg∇B).

Three implementations, which the tests hold to 1e-6 (2e-6 for ``fast32``) relative agreement:

* ``method="fast"``: a numba kernel that evaluates the wave once per *vertex* (elevation and
  pressure share the per-component spatial terms), with branch-free polynomial sin/cos/exp that
  LLVM vectorises across vertices (:mod:`ship_gym.numerics.fastmath`), and the time factor and the
  ship's horizontal position folded into one modulus and phase per component. The integration
  counts every triangle as wet through precomputed per-vertex weights and corrects only the
  triangles that cross the surface. The polynomials run at the floating-point throughput limit
  (details in the comments of the kernel section; ``benchmarks/bench_froude_krylov.py``). A
  batched variant evaluates many ships in one call, optionally with numba threads
  (``parallel=True``).
* ``method="fast32"``: the same kernel with the wave sums (elevation and dynamic pressure) in
  float32, 8 SIMD lanes instead of 4; force and moment within ~1e-7 of the hydrostatic ones
  of ``"fast"`` (tested at 2e-6).
* ``method="reference"``: plain numpy (``np.cos``/``np.exp`` on the vertex × component matrix)
  with :func:`ship_gym.hull.mesh.clip_triangles` and
  :func:`ship_gym.hull.mesh.pressure_resultant`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Literal, NamedTuple

import numba as nb
import numpy as np

from ship_gym.forces.base import ForceContext, ForceModel
from ship_gym.hull.hull import Hull
from ship_gym.hull.mesh import PanelMesh, clip_triangles, pressure_resultant
from ship_gym.numerics.fastmath import (
    cos_turns,
    cos_turns_nonneg_f32,
    exp2_neg,
    exp2_neg_f32,
    exp2_neg_unclamped_f32,
)
from ship_gym.waves.wave_field import WaveField

Method = Literal["fast", "fast32", "reference"]
_METHODS = ("fast", "fast32", "reference")


@dataclass(frozen=True, eq=False)
class HullPanels:
    """Triangulated hull geometry in the body frame, laid out for the kernels.

    Attributes
    ----------
    vertices : numpy.ndarray
        (n_vertices, 3) body-frame coordinates [m], C-contiguous float64.
    triangles : numpy.ndarray
        (n_triangles, 3) vertex indices (outward normals), int64.
    mirror : bool
        Make the integration port–starboard symmetric when the vertices are (see the notes).
    integration_triangles : numpy.ndarray
        (m, 3) the triangles that the kernels integrate over: ``triangles``, plus the mirror
        image of each triangle whose image is not among them (derived, not an argument).
    integration_weights : numpy.ndarray
        (m,) weight of each integration triangle [-]: 1, or ½ for a triangle and the added
        mirror image of it (derived).

    Notes
    -----
    **Mirror symmetry.** An upright ship in head or following seas on a hull that is its own
    mirror image in the body xz-plane must get no sway force, roll or yaw moment. Two parts of
    the integration could break that, both at the order of the panel size squared:

    * a quadrilateral panel is integrated as two triangles with the pressure linear on each, so
      the diagonal matters; a panel and its mirror image split along diagonals that are not
      images of each other, a panel straddling the centreline (whose two splits are each other's
      images), or faces that are not images of faces at all (a transom capped by a fan from an
      off-centre vertex) give an asymmetric rule;
    * the wet part of a triangle with two wet vertices is a quadrilateral; the kernels integrate
      it as the mean of its two splits (:func:`_integrate`), since one split would depend on the
      sense in which the triangle is listed, and a mirror image is listed in the opposite sense.
      (This one was the 3e-6 ρg∇B roll and yaw moment of the library S175 in head and following
      seas: its mismatched quads are deck panels and flat end panels, on which a head-sea
      pressure varies along one edge direction only and the split does not matter.)

    For the first, when every vertex has a mirror image among the vertices (``y → −y`` within
    1e-9 of the mesh's extent) and ``mirror`` is true, each triangle whose mirror image (same
    vertices, same sense after reflection) is not in ``triangles`` is integrated at weight ½
    together with that image at weight ½. The integration triangles are then exactly their own
    mirror image: the sway force, roll and yaw moment of a symmetric pressure field cancel to
    round-off, and the symmetric components are those of ``triangles`` (a mesh and its image
    give the same ones). Triangles whose image is present keep weight 1, so a mirror-consistent
    triangulation (:meth:`from_mesh`) costs little (the S175: 74 triangles added to 4796; 148
    at weight ½). The weights enter the kernels only through the per-vertex weights and the
    precomputed area vectors (the load of a triangle, cut or not, is linear in its area vector).
    A mesh without a mirror-image vertex set is integrated as given.

    On construction the arrays are converted to that layout and the fast kernel's own layout is
    derived once (vertex order by depth, per-vertex integration weights, neighbour extents):
    build one ``HullPanels`` per hull and reuse it.
    """

    vertices: np.ndarray
    triangles: np.ndarray
    mirror: bool = True
    integration_triangles: np.ndarray = field(init=False, repr=False, compare=False)
    integration_weights: np.ndarray = field(init=False, repr=False, compare=False)
    _layout: _KernelLayout = field(init=False, repr=False, compare=False)

    def __post_init__(self) -> None:
        v = np.ascontiguousarray(self.vertices, dtype=np.float64)
        tri = np.ascontiguousarray(self.triangles, dtype=np.int64)
        if v.ndim != 2 or v.shape[1] != 3 or tri.ndim != 2 or tri.shape[1] != 3:
            raise ValueError(f"expected (n, 3) vertices and triangles, got {v.shape}, {tri.shape}")
        object.__setattr__(self, "vertices", v)
        object.__setattr__(self, "triangles", tri)
        image = _mirror_map(v) if self.mirror else None
        if image is None:
            tri_all, weight = tri, np.ones(tri.shape[0])
        else:
            tri_all, weight = _mirror_union(tri, image)
        object.__setattr__(self, "integration_triangles", tri_all)
        object.__setattr__(self, "integration_weights", weight)
        object.__setattr__(self, "_layout", _KernelLayout.build(v, tri_all, weight))

    @classmethod
    def from_mesh(cls, mesh: PanelMesh, *, mirror: bool = True) -> HullPanels:
        """Triangulate a closed hull mesh.

        Quads are split along the diagonal (0, 2), except that of a pair of mirror-image quads
        (body xz-plane) the one listed second is split along the mirror image of the first one's
        diagonal, so that the pair gives mirror-image triangles (see the notes of the class;
        with ``mirror=False`` or an asymmetric mesh, all along (0, 2) as
        :attr:`PanelMesh.triangle_indices`).
        """
        mesh.check(closed=True)
        tri, _ = mesh.triangle_indices
        v = np.ascontiguousarray(mesh.vertices, dtype=np.float64)
        image = _mirror_map(v) if mirror else None
        if image is not None:
            tri = _mirror_consistent_split(np.asarray(mesh.faces, dtype=np.int64), image)
        return cls(v, np.ascontiguousarray(tri, dtype=np.int64), mirror)


_MIRROR_TOLERANCE = 1e-9  # a vertex's mirror image: within this fraction of the mesh's extent


def _mirror_map(vertices: np.ndarray) -> np.ndarray | None:
    """Index of the mirror image (x, −y, z) of each vertex among the vertices, or None.

    None when some vertex has no image within ``_MIRROR_TOLERANCE`` × the largest coordinate
    [m], or the pairing is not one-to-one (coincident vertices).
    """
    if vertices.shape[0] == 0:
        return None
    from scipy.spatial import cKDTree

    tol = _MIRROR_TOLERANCE * max(float(np.abs(vertices).max()), 1.0)
    distance, image = cKDTree(vertices).query(vertices * np.array([1.0, -1.0, 1.0]))
    if not np.all(distance <= tol) or not np.array_equal(
        image[image], np.arange(vertices.shape[0])
    ):
        return None
    return np.asarray(image, dtype=np.int64)


def _row_ids(a: np.ndarray, b: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Integer ids of the rows of a and of b (non-negative ints), equal for equal rows."""
    rows = np.concatenate([a, b]).astype(np.int64)
    base = int(rows.max(initial=0)) + 1
    if base ** rows.shape[1] < 2**62:  # one integer per row (mixed radix)
        ids = np.zeros(rows.shape[0], dtype=np.int64)
        for q in range(rows.shape[1]):
            ids = ids * base + rows[:, q]
    else:
        ids = np.unique(rows, axis=0, return_inverse=True)[1].ravel()
    return ids[: a.shape[0]], ids[a.shape[0] :]


def _cyclic_canonical(tri: np.ndarray) -> np.ndarray:
    """Each triangle rotated to start at its smallest vertex index (the sense is kept).

    The sense matters: a face lying in the centreline plane is mirrored onto its own vertices
    listed in the opposite sense (the other side of a zero-thickness stem or skeg).
    """
    start = np.argmin(tri, axis=1)
    return np.take_along_axis(tri, (start[:, None] + np.arange(3)[None, :]) % 3, axis=1)


def _mirror_union(tri: np.ndarray, image: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The triangles and the mirror images missing among them, with weights 1 or ½ each.

    The image of (a, b, c) is (m c, m b, m a): reversed, so that the outward normal stays
    outward. A triangle whose image is in ``tri`` (itself included, listed in the same sense)
    keeps weight 1.
    """
    mirrored = image[tri][:, ::-1]
    own, of_image = _row_ids(_cyclic_canonical(tri), _cyclic_canonical(mirrored))
    present = np.isin(of_image, own)
    tri_all = np.ascontiguousarray(np.concatenate([tri, mirrored[~present]]), dtype=np.int64)
    weight = np.concatenate([np.where(present, 1.0, 0.5), np.full(int((~present).sum()), 0.5)])
    return tri_all, weight


def _mirror_consistent_split(faces: np.ndarray, image: np.ndarray) -> np.ndarray:
    """(n_tri, 3) triangles of quad/triangle faces (a, b, c, d; triangles with d = c).

    Quads split along (a, c), except the second of a mirror-image pair of quads (the same
    vertex set after reflection), which takes the image of the first one's diagonal. The first
    triangle of every face, in face order, then the second triangles of the quads (the layout
    of :attr:`PanelMesh.triangle_indices`).
    """
    quad = faces[:, 3] != faces[:, 2]
    code, code_image = _row_ids(np.sort(faces, axis=1), np.sort(image[faces], axis=1))
    first: dict[int, int] = {}
    for i in np.flatnonzero(quad):
        first.setdefault(int(code[i]), int(i))
    start = np.zeros(faces.shape[0], dtype=np.int64)  # split along (start, start + 2) of the face
    for i in np.flatnonzero(quad):
        j = first.get(int(code_image[i]), -1)
        if j < 0 or j >= i:
            continue
        # the image of the first quad's diagonal (its vertices 0 and 2)
        ends = {int(image[faces[j, 0]]), int(image[faces[j, 2]])}
        if int(faces[i, 0]) in ends and int(faces[i, 2]) in ends:
            continue
        start[i] = 1
    cyc = (start[:, None] + np.arange(4)[None, :]) % 4
    f = np.where(quad[:, None], np.take_along_axis(faces, cyc, axis=1), faces)
    return np.concatenate([f[:, [0, 1, 2]], f[quad][:, [0, 2, 3]]])


@dataclass(frozen=True, eq=False)
class WaveComponents:
    """Plain arrays of an incident wave for the kernels (one ship).

    Attributes
    ----------
    wavenumber : numpy.ndarray
        (n,) kⱼ [rad/m].
    cos_direction, sin_direction : numpy.ndarray
        (n,) cos χⱼ, sin χⱼ of the propagation directions (earth frame).
    """

    wavenumber: np.ndarray
    cos_direction: np.ndarray
    sin_direction: np.ndarray

    @classmethod
    def from_arrays(cls, wavenumber: np.ndarray, direction: np.ndarray) -> WaveComponents:
        """From kⱼ [rad/m] and χⱼ [rad]."""
        k = np.ascontiguousarray(wavenumber, dtype=np.float64)
        chi = np.asarray(direction, dtype=np.float64)
        if k.shape != chi.shape or k.ndim != 1:
            raise ValueError(
                f"wavenumber and direction must be 1-D of equal length, got {k.shape}, {chi.shape}"
            )
        return cls(k, np.ascontiguousarray(np.cos(chi)), np.ascontiguousarray(np.sin(chi)))

    def local_amplitudes(self, phasor: np.ndarray, x: float, y: float) -> np.ndarray:
        """Fold the ship's horizontal position into the complex amplitudes.

        cⱼ' = cⱼ(t) e^{−i kⱼ (x cos χⱼ + y sin χⱼ)}, so that the kernels see phases of the vertex
        positions *relative to O* only (small arguments, one complex exponential per component
        per step here instead of one per vertex and component there).

        Parameters
        ----------
        phasor : numpy.ndarray
            (n,) complex cⱼ(t) [m] with ζ = Re Σ cⱼ e^{−i kⱼ (X cos χⱼ + Y sin χⱼ)}.
        x, y : float
            Earth position of O [m].
        """
        s = self.wavenumber * (x * self.cos_direction + y * self.sin_direction)
        return np.asarray(phasor, dtype=np.complex128) * np.exp(-1j * s)


# ----------------------------------------------------------------------------- fast kernel
# Layout and flags (DESIGN.md §5; chosen by measurement with benchmarks/bench_froude_krylov.py on
# a 2-core AVX2/FMA machine, the figures in docs/benchmarks.md):
#
# * Vertices are processed in blocks of _BLOCK, *components in the outer loop and vertices in the
#   inner loop*: every hot loop vectorises across vertices, with no reduction over components, so
#   no "reassoc" flag is needed anywhere (results do not depend on the vector width) and there is
#   no per-vertex loop overhead (horizontal sums, remainders). The spatial term of each
#   (component, vertex) pair, Re cⱼ e^{−iθ}, is computed once, kept in a block buffer, and shared
#   by the elevation sum and the pressure sum. The inner loops are small @njit functions called
#   with offsets (no slices, whose array objects cost reference counting per call) and unsigned
#   indices (numba's negative-index wraparound code slows these loops markedly; measured:
#   docs/benchmarks.md).
# * Phases are formed in turns (kⱼ cos χⱼ / 2π per call), and each component enters as modulus
#   and phase offset, Re cⱼ e^{−iθ} = |cⱼ| cos(θ − arg cⱼ): the spatial term is one cosine
#   (:func:`~ship_gym.numerics.fastmath.cos_turns`: range reduction by one exact subtraction, one
#   even polynomial, two cosine-only angle doublings; 13 multiply/FMA operations per pair with
#   the phase, against 22 with sin and cos). The decay e^{−k d} = 2^{−(k/ln2) d} needs no
#   Cody–Waite step either (:func:`~ship_gym.numerics.fastmath.exp2_neg`; 13 operations per pair
#   with the product and the sum). Both are the "kernel tier" polynomials of fastmath (errors
#   ≲ 1e-12; forces within ~1e-13 of the libm reference; faster than the few-ulp ones).
#   The kernel runs at the FMA units' throughput limit for these (measured: docs/benchmarks.md)
#   (not memory- or overhead-bound: two components per loop, other block sizes or fewer stores
#   change nothing measurable).
# * The kernel's vertex order is sorted by body z (:class:`_KernelLayout`), so the vertices of a
#   pressure sub-block (_SUB) tend to be all wet or all dry: the decayed sum runs over the wet
#   range of each sub-block only (dry vertices inside it are evaluated with d = 0 and discarded;
#   ~18 % extra pairs for the S175 in a 4 m sea). Its rows are padded to whole vectors.
# * Exact skips: the top of the hull (a tail of the kernel order) where the vertices and all
#   their mesh neighbours lie above the highest possible crest Σ|cⱼ| needs no wave sums (for the
#   upright S175: a third of the vertices in calm water, a sixth for Σ|cⱼ| = 3.5 m; none in a 4 m
#   sea of 50 components, Σ|cⱼ| ≈ 14 m);
#   components with e^{−kⱼ d} < 2^−54 over a whole sub-block are left out of its pressure sum
#   (relative contribution < 6e-17); only the triangles whose vertex range spans both the first
#   dry and the last wet vertex are examined for a crossing.
# * Integration: −∫p n dS and −∫p r × n dS are linear in the vertex pressures, so the fully wet
#   triangles are summed as −Σᵥ pᵥ wᵥ with per-vertex weights precomputed in the body frame; the
#   crossing triangles replace their whole-triangle term by their cut part. A cut piece lies in
#   its triangle's plane, so its area vector is a known multiple of the triangle's (precomputed,
#   ``_KernelLayout.areas``): one scalar and one cross product per crossing triangle. With
#   unsigned vertex indices (no wraparound code) the time of the whole integration (of the
#   1500-face S175: docs/benchmarks.md) is mostly the scan of the candidate triangles (their depth
#   gathers); a branch-free two-pass scan was not faster.
# * Work arrays are allocated per call inside the kernel (a small cost: docs/benchmarks.md);
#   there is no shared mutable state, the kernels release the GIL (nogil), and concurrent calls
#   from Python threads are safe.
# * Threads: the default is serial. ``parallel=True`` in the batch runs a numba prange over ships
#   (numba's OpenMP layer, ``NUMBA_NUM_THREADS`` = cores). torch's intra-op pool in the same
#   process competes for the same cores (two OpenMP runtimes, whose workers spin for a while
#   after each parallel region), and so does anything else running on the machine: a parallel
#   region waits for its slowest thread, so on a busy 2-core machine one call can take a whole
#   scheduler slice (milliseconds). For RL training on few cores keep the default and run
#   environments in separate processes, or give the pools disjoint shares (numba.set_num_threads
#   / torch.set_num_threads) and benchmark that setting
#   (``benchmarks/bench_froude_krylov.py --parallel --torch``).
_FM = {"contract", "nsz"}
_BLOCK = 256  # vertices per elevation block (a multiple of _SUB)
_SUB = 64  # vertices per pressure sub-block (a multiple of 4)
_INV_TWO_PI = 1.0 / (2.0 * np.pi)
_INV_LN2 = 1.0 / np.log(2.0)
_DECAY_CUTOFF = 54.0


@dataclass(frozen=True, eq=False)
class _KernelLayout:
    """Vertex order and derived arrays of a hull for the fast kernel (built once per hull)."""

    order: np.ndarray  # (n_v,) kernel index → original vertex index (sorted by body z)
    body: np.ndarray  # (3, n_v) body coordinates in kernel order (structure of arrays)
    triangles: np.ndarray  # (n_t, 3) triangles in kernel vertex indices, by largest index
    tri_last: np.ndarray  # (n_t,) largest kernel vertex index of each triangle (ascending)
    tri_first: np.ndarray  # (n_t,) smallest kernel vertex index of each triangle
    spread: np.ndarray  # (6, n_v) min (rows 0-2) and max (3-5) of b_u − b_v over neighbours u
    weights: np.ndarray  # (6, n_v) force/moment per unit vertex pressure, all triangles wet
    areas: np.ndarray  # (3, n_t) area vector ½ (b − a) × (c − a) of each triangle (a, b, c)

    @classmethod
    def build(
        cls, vertices: np.ndarray, triangles: np.ndarray, weight: np.ndarray
    ) -> _KernelLayout:
        """From the vertices [m], the integration triangles and their weights [-] (the area
        vectors are scaled by them: the kernels see a triangle of weight w as w × its load)."""
        order = np.argsort(-vertices[:, 2], kind="stable")
        rank = np.empty_like(order)
        rank[order] = np.arange(order.size)
        tri = rank[triangles]
        by_last = np.argsort(tri.max(axis=1), kind="stable")
        tri = np.ascontiguousarray(tri[by_last], dtype=np.int64)
        weight = np.asarray(weight, dtype=np.float64)[by_last]
        tri_last = np.ascontiguousarray(tri.max(axis=1))
        tri_first = np.ascontiguousarray(tri.min(axis=1))
        body = np.ascontiguousarray(vertices[order].T, dtype=np.float64)
        spread = np.zeros((6, order.size))
        for a, b in ((0, 1), (1, 2), (2, 0), (1, 0), (2, 1), (0, 2)):
            edge = body[:, tri[:, b]] - body[:, tri[:, a]]
            for q in range(3):
                np.minimum.at(spread[q], tri[:, a], edge[q])
                np.maximum.at(spread[3 + q], tri[:, a], edge[q])
        # With p linear on a triangle (area vector N), −∫p n dS = −Σᵢ pᵢ N/3 and
        # −∫p r × n dS = −Σᵢ pᵢ (rᵢ + Σⱼrⱼ) × N/12: summed over the triangles at each vertex, the
        # force and moment of the fully wet triangles are −Σᵥ pᵥ wᵥ in the body frame.
        r = body[:, tri]  # (3, n_t, 3)
        area = 0.5 * np.cross(r[:, :, 1] - r[:, :, 0], r[:, :, 2] - r[:, :, 0], axis=0) * weight
        rsum = r.sum(axis=2)
        weights = np.zeros((6, order.size))
        for i in range(3):
            arm = np.cross(r[:, :, i] + rsum, area, axis=0) / 12.0
            for q in range(3):
                np.add.at(weights[q], tri[:, i], area[q] / 3.0)
                np.add.at(weights[3 + q], tri[:, i], arm[q])
        return cls(
            order, body, tri, tri_last, tri_first, spread, weights, np.ascontiguousarray(area)
        )


@nb.njit(fastmath=_FM, cache=True)
def _spatial_row(
    a: float,
    b: float,
    p: float,
    m: float,
    rx: np.ndarray,
    ry: np.ndarray,
    v0: int,
    spatial: np.ndarray,
    s0: int,
    zeta: np.ndarray,
    n: int,
) -> None:  # pragma: no cover - compiled
    """One component over a block: S = m cos 2πt, t = a x + b y + p at vertex v0 + u, stored at
    spatial[s0 + u]; ζᵤ += S (u < n).

    Offsets into flat buffers instead of slices (no array objects, with their reference counts,
    per call), unsigned so that numba emits no negative-index wraparound (slower; measured:
    docs/benchmarks.md).
    """
    vo = nb.uint64(v0)
    so = nb.uint64(s0)
    for u in range(nb.uint64(n)):
        s = cos_turns(a * rx[vo + u] + (b * ry[vo + u] + p), m)
        spatial[so + u] = s
        zeta[u] += s


@nb.njit(fastmath=_FM, cache=True)
def _decayed_row(
    k2: float, dpos: np.ndarray, spatial: np.ndarray, s0: int, acc: np.ndarray, n: int
) -> None:  # pragma: no cover - compiled
    """One component over a sub-block: accᵤ += 2^{−k2 dᵤ} spatial[s0 + u] (u < n)."""
    so = nb.uint64(s0)
    for u in range(nb.uint64(n)):
        acc[u] += exp2_neg(k2 * dpos[u]) * spatial[so + u]


@nb.njit(fastmath={"contract", "nsz", "reassoc"}, cache=True)
def _wet_sums(
    weights: np.ndarray, pres: np.ndarray
) -> tuple[float, float, float, float, float, float]:  # pragma: no cover - compiled
    """−Σᵥ pᵥ w_qᵥ, q = 0…5 (plain sums: "reassoc" lets them vectorise)."""
    a0 = a1 = a2 = a3 = a4 = a5 = 0.0
    for v in range(pres.shape[0]):
        p = pres[v]
        a0 -= p * weights[0, v]
        a1 -= p * weights[1, v]
        a2 -= p * weights[2, v]
        a3 -= p * weights[3, v]
        a4 -= p * weights[4, v]
        a5 -= p * weights[5, v]
    return a0, a1, a2, a3, a4, a5


@nb.njit(fastmath=_FM, cache=True, inline="always")
def _split_mean_moment(c14, h, p1, c1, ab, c4, ac, g2, e, g3, b):  # pragma: no cover - compiled
    """One component of 24 × the first moment of the pressure over a wet quadrilateral, mean of
    its two triangle splits (the body of :func:`_integrate`)."""
    return c14 * h + p1 * (c1 * ab + c4 * ac) + g2 * (ab + e + e + ac) + g3 * (ab + b + b + ac)


@nb.njit(fastmath=_FM, cache=True)
def _integrate(
    tri: np.ndarray,
    tri_last: np.ndarray,
    tri_first: np.ndarray,
    body: np.ndarray,
    weights: np.ndarray,
    areas: np.ndarray,
    rot: np.ndarray,
    depth: np.ndarray,
    pres: np.ndarray,
    out: np.ndarray,
) -> None:  # pragma: no cover - compiled
    """Add the force and moment (earth axes) of the pressure below the surface to out[0:6].

    Every triangle is first counted as wet (vertex weights, p = 0 at dry vertices); the triangles
    crossing the surface are then corrected: their cut part replaces their whole-triangle term.
    Works in the body frame (cuts are linear, so they commute with the rotation) and rotates once.

    A cut piece of a triangle (a, b, c) lies in its plane, and its area vector is a multiple of
    the triangle's N = ½ (b − a) × (c − a): with the lone vertex a and the cut points
    a + s_ab (b − a), a + s_ac (c − a), the corner triangle has s_ab s_ac N, and the other two
    pieces (1 − s_ab) N and s_ab (1 − s_ac) N, or, split along the other diagonal,
    (1 − s_ab) s_ac N and (1 − s_ac) N; the wet quadrilateral is taken as the mean of the two
    splits, so that its load does not depend on the sense in which the triangle is listed
    (mirror-image triangles give mirror-image loads). With p linear on a piece, its load is
    −(S/3 Σpᵢ) n and −q × N_piece, q = (Σ pᵢ rᵢ + Σpᵢ Σrᵢ)/12 (per unit area vector), so
    the correction of a crossing triangle is −P N and −Q × N for one scalar P and one vector Q:
    a single cross product per triangle, with N precomputed (``areas``).
    """
    f0, f1, f2, m0, m1, m2 = _wet_sums(weights, pres)
    x, y, z = body[0], body[1], body[2]
    # a crossing triangle has a dry vertex (index ≥ first_dry) and a wet one (≤ last_wet): with the
    # triangles sorted by their largest index, only a range of them needs looking at
    first_dry = 0
    while first_dry < depth.shape[0] and depth[first_dry] >= 0.0:
        first_dry += 1
    last_wet = depth.shape[0] - 1
    while last_wet >= 0 and not depth[last_wet] >= 0.0:
        last_wet -= 1
    third = 1.0 / 3.0
    sixth = 1.0 / 6.0
    twelfth = 1.0 / 12.0
    twentyfourth = 1.0 / 24.0
    n_tri: int = tri.shape[0]
    for t in range(nb.uint64(np.searchsorted(tri_last, first_dry)), nb.uint64(n_tri)):
        if tri_first[t] > last_wet:
            continue
        # (unsigned indices: no negative-index wraparound code)
        i0, i1, i2 = nb.uint64(tri[t, 0]), nb.uint64(tri[t, 1]), nb.uint64(tri[t, 2])
        w0, w1, w2 = depth[i0] >= 0.0, depth[i1] >= 0.0, depth[i2] >= 0.0
        n_wet = int(w0) + int(w1) + int(w2)
        if n_wet == 0 or n_wet == 3:
            continue
        # rotate (cyclically: N keeps its sign) so that the lone wet or lone dry vertex is a
        if (n_wet == 1 and w0) or (n_wet == 2 and not w0):
            a, b, e = i0, i1, i2
        elif (n_wet == 1 and w1) or (n_wet == 2 and not w1):
            a, b, e = i1, i2, i0
        else:
            a, b, e = i2, i0, i1
        pa, pb, pe = pres[a], pres[b], pres[e]
        ax, ay, az = x[a], y[a], z[a]
        bx, by, bz = x[b], y[b], z[b]
        ex, ey, ez = x[e], y[e], z[e]
        # whole-triangle term (already counted in the vertex weights), to be taken off
        psum = pa + pb + pe
        p_scale = -psum * third
        sx, sy, sz = ax + bx + ex, ay + by + ey, az + bz + ez
        qx = -(pa * ax + pb * bx + pe * ex + psum * sx) * twelfth
        qy = -(pa * ay + pb * by + pe * ey + psum * sy) * twelfth
        qz = -(pa * az + pb * bz + pe * ez + psum * sz) * twelfth
        da = depth[a]
        sab = da / (da - depth[b])
        sac = da / (da - depth[e])
        abx, aby, abz = ax + sab * (bx - ax), ay + sab * (by - ay), az + sab * (bz - az)
        acx, acy, acz = ax + sac * (ex - ax), ay + sac * (ey - ay), az + sac * (ez - az)
        if n_wet == 1:
            # corner (a, ab, ac), p = (pa, 0, 0), area vector s_ab s_ac N
            c1 = sab * sac
            p_scale += c1 * pa * third
            g = c1 * pa * twelfth
            qx += g * (ax + ax + abx + acx)
            qy += g * (ay + ay + aby + acy)
            qz += g * (az + az + abz + acz)
        else:
            # the wet quadrilateral (ab, b, e, ac), p = (0, pb, pe, 0), as the mean of its two
            # splits (one split would depend on the triangle's vertex order: a triangle and its
            # mirror image, listed in the opposite sense, would be cut into non-mirror pieces):
            # (ab, b, e) + (ab, e, ac), area vectors (1 − s_ab) N and s_ab (1 − s_ac) N, and
            # (ab, b, ac) + (b, e, ac), area vectors (1 − s_ab) s_ac N and (1 − s_ac) N
            c1 = 1.0 - sab
            c2 = sab * (1.0 - sac)
            c3 = c1 * sac
            c4 = 1.0 - sac
            c14 = c1 + c4
            p1 = pb + pe
            p_scale += ((c14 + c3) * pb + (c14 + c2) * pe) * sixth
            g2 = c2 * pe
            g3 = c3 * pb
            hx = pb * bx + pe * ex + p1 * (bx + ex)
            hy = pb * by + pe * ey + p1 * (by + ey)
            hz = pb * bz + pe * ez + p1 * (bz + ez)
            qx += _split_mean_moment(c14, hx, p1, c1, abx, c4, acx, g2, ex, g3, bx) * twentyfourth
            qy += _split_mean_moment(c14, hy, p1, c1, aby, c4, acy, g2, ey, g3, by) * twentyfourth
            qz += _split_mean_moment(c14, hz, p1, c1, abz, c4, acz, g2, ez, g3, bz) * twentyfourth
        nx, ny, nz = areas[0, t], areas[1, t], areas[2, t]
        f0 -= p_scale * nx
        f1 -= p_scale * ny
        f2 -= p_scale * nz
        m0 -= qy * nz - qz * ny
        m1 -= qz * nx - qx * nz
        m2 -= qx * ny - qy * nx
    f = (f0, f1, f2, m0, m1, m2)
    for q in range(3):
        out[q] += rot[q, 0] * f[0] + rot[q, 1] * f[1] + rot[q, 2] * f[2]
        out[3 + q] += rot[q, 0] * f[3] + rot[q, 1] * f[4] + rot[q, 2] * f[5]


@nb.njit(fastmath=_FM, cache=True)
def _fold_components(
    k, cos_dir, sin_dir, amp, x0, y0, kxt, kyt, k2, mod, offset
):  # pragma: no cover
    """Per-component set-up of the kernels, into float64 or float32 arrays (computed in float64).

    Wave vector [turns/m], k / ln 2 [1/m], and Re cⱼ e^{−iθ} = |cⱼ| cos(θ − arg cⱼ) as modulus
    [m] and phase offset [turns], with the ship's horizontal position (x0, y0) folded in.
    Returns crest = Σ|cⱼ| [m], a bound of ζ everywhere.
    """
    crest = 0.0
    for j in range(k.shape[0]):
        ax = k[j] * cos_dir[j] * _INV_TWO_PI
        ay = k[j] * sin_dir[j] * _INV_TWO_PI
        kxt[j] = ax
        kyt[j] = ay
        k2[j] = k[j] * _INV_LN2
        mod[j] = abs(amp[j])
        t = ax * x0 + ay * y0 - np.arctan2(amp[j].imag, amp[j].real) * _INV_TWO_PI
        offset[j] = t - np.rint(t)
        crest += abs(amp[j])
    return crest


@nb.njit(fastmath=_FM, cache=True, nogil=True)
def _fk_one_ship(
    body: np.ndarray,
    tri: np.ndarray,
    tri_last: np.ndarray,
    tri_first: np.ndarray,
    spread: np.ndarray,
    weights: np.ndarray,
    areas: np.ndarray,
    rot: np.ndarray,
    x0: float,
    y0: float,
    z0: float,
    k: np.ndarray,
    cos_dir: np.ndarray,
    sin_dir: np.ndarray,
    amp: np.ndarray,
    rho_g: float,
    out: np.ndarray,
) -> None:  # pragma: no cover - compiled
    """Force and moment about O (earth axes) of one ship at (x0, y0, z0); adds to out[0:6].

    body (3, n_v), tri, tri_last, tri_first, spread and weights are the :class:`_KernelLayout`
    arrays; amp the complex amplitudes cⱼ(t) of ζ = Re Σ cⱼ e^{−ikⱼ(X cos χⱼ + Y sin χⱼ)} (with
    x0 = y0 = 0: already local, :meth:`WaveComponents.local_amplitudes`).
    """
    kxt, kyt, k2, mod, offset = np.empty((5, k.shape[0]))
    crest = _fold_components(k, cos_dir, sin_dir, amp, x0, y0, kxt, kyt, k2, mod, offset)
    _fk_core(
        body, tri, tri_last, tri_first, spread, weights, areas, rot, z0, kxt, kyt, k2,
        mod, offset, crest, rho_g, out,
    )  # fmt: skip


@nb.njit(fastmath=_FM, cache=True, nogil=True)
def _fk_core(
    body: np.ndarray,
    tri: np.ndarray,
    tri_last: np.ndarray,
    tri_first: np.ndarray,
    spread: np.ndarray,
    weights: np.ndarray,
    areas: np.ndarray,
    rot: np.ndarray,
    z0: float,
    kxt: np.ndarray,
    kyt: np.ndarray,
    k2: np.ndarray,
    mod: np.ndarray,
    offset: np.ndarray,
    crest: float,
    rho_g: float,
    out: np.ndarray,
) -> None:  # pragma: no cover - compiled
    """The kernel after the per-component set-up (:func:`_fk_one_ship`): wave vectors kxt, kyt
    [turns/m], k2 = k/ln 2 [1/m], moduli [m] and phase offsets [turns] of the components at
    the ship's O, crest = Σ mod ≥ ζ; adds the earth-axis force and moment about O to out."""
    n_v: int = body.shape[1]
    n_c = kxt.shape[0]
    rx = np.empty(n_v)
    ry = np.empty(n_v)
    rz = np.empty(n_v)
    r00, r01, r02 = rot[0, 0], rot[0, 1], rot[0, 2]  # (locals: no reloads, the loop vectorises)
    r10, r11, r12 = rot[1, 0], rot[1, 1], rot[1, 2]
    r20, r21, r22 = rot[2, 0], rot[2, 1], rot[2, 2]
    bxs, bys, bzs = body[0], body[1], body[2]
    for v in range(nb.uint64(n_v)):
        bx, by, bz = bxs[v], bys[v], bzs[v]
        rx[v] = r00 * bx + r01 * by + r02 * bz
        ry[v] = r10 * bx + r11 * by + r12 * bz
        rz[v] = r20 * bx + r21 * by + r22 * bz
    depth = np.empty(n_v)
    pres = np.empty(n_v)
    # block buffers (the pressure rows are padded to a multiple of 4 lanes, i.e. no scalar
    # remainder loop; the padding lanes must hold finite values, their results are discarded)
    spatial = np.empty(n_c * _BLOCK)
    zeta = np.zeros(_BLOCK)
    dpos = np.empty(_SUB)
    acc = np.empty(_SUB)
    # Certainly dry vertices whose mesh neighbours are all certainly dry too (earth z < −Σ|cⱼ|)
    # need no wave sums: their depth only has to be negative. Only a tail of the kernel order
    # (the top of the hull) is skipped, so that the loops stay contiguous.
    n_wave = n_v
    while n_wave > 0:
        v = n_wave - 1
        rise = 0.0  # ≥ max over the neighbours u of (earth z_u − earth z_v)
        for q in range(3):
            rise += max(rot[2, q] * spread[q, v], rot[2, q] * spread[3 + q, v])
        if not z0 + rz[v] + rise + crest < 0.0:  # (NaN: not skipped)
            break
        depth[v] = z0 + rz[v] + crest
        pres[v] = 0.0
        n_wave -= 1
    for v0 in range(0, n_wave, _BLOCK):
        v1 = min(v0 + _BLOCK, n_wave)
        nb_ = v1 - v0
        for u in range(nb_):
            zeta[u] = z0 + rz[v0 + u]
        for j in range(n_c):
            s0 = j * _BLOCK
            _spatial_row(kxt[j], kyt[j], offset[j], mod[j], rx, ry, v0, spatial, s0, zeta, nb_)
        for u in range(nb_, min(nb_ + 3, _BLOCK)):  # padding lanes of a short last block
            zeta[u] = 0.0
            for j in range(n_c):
                spatial[j * _BLOCK + u] = 0.0
        vo = nb.uint64(v0)
        for u in range(nb.uint64(nb_)):
            depth[vo + u] = zeta[u]
            pres[vo + u] = 0.0
        for u0 in range(0, nb_, _SUB):
            # the wet range [lo, hi) of the sub-block, widened to whole vectors
            u1 = min(u0 + _SUB, nb_)
            lo = u0
            while lo < u1 and not zeta[lo] >= 0.0:
                lo += 1
            if lo == u1:
                continue
            hi = u1
            while not zeta[hi - 1] >= 0.0:
                hi -= 1
            lo -= lo % 4
            hi = min(hi + (-hi) % 4, _BLOCK)
            n = hi - lo
            dmin = np.inf  # (0 where a dry vertex lies in the range: no component is skipped)
            for u in range(n):
                dp = max(zeta[lo + u], 0.0)
                dpos[u] = dp
                acc[u] = 0.0
                dmin = min(dmin, dp)
            for j in range(n_c):
                if k2[j] * dmin < _DECAY_CUTOFF:
                    _decayed_row(k2[j], dpos, spatial, j * _BLOCK + lo, acc, n)
            for u in range(lo, min(hi, nb_)):
                if zeta[u] >= 0.0:
                    pres[v0 + u] = rho_g * (z0 + rz[v0 + u] + acc[u - lo])
    _integrate(tri, tri_last, tri_first, body, weights, areas, rot, depth, pres, out)


# ----------------------------------------------------------------------------- float32 kernel
# The same algorithm with the wave sums in single precision (``method="fast32"``): 8 lanes per
# AVX2 vector instead of 4 and shorter polynomials (:func:`~ship_gym.numerics.fastmath.
# cos_turns_f32`, :func:`~ship_gym.numerics.fastmath.exp2_neg_f32`). What stays float64: the
# rotation of the vertices, the hydrostatic part z of the depth and of the pressure, the
# integration; only the wave terms (elevation ζ and the decayed dynamic pressure Σ e^{−k d} S)
# are summed in float32. Errors: the phase in turns is formed in float32 (|t| ≲ 8 turns for
# the S175 in a Tp = 11 s sea: ≲ 5e-7 turn), each term carries ≲ 3e-7 of its amplitude, so ζ
# and the dynamic pressure are off by ~1e-6 of their size; the force and moment by ~1e-7 of the
# hydrostatic ones (tests/forces/test_froude_krylov.py holds them to the reference at 2e-6).
# The pair loops use the lean float32 polynomials (:func:`~ship_gym.numerics.fastmath.
# cos_turns_nonneg_f32`: degree 8, the modulus folded into the coefficients, 7 multiply/FMA
# operations per pair besides the phase; :func:`~ship_gym.numerics.fastmath.
# exp2_neg_unclamped_f32`: degree 5, the 2^−n scaling an integer subtraction on the exponent
# field, no clamp, 7 with the product and the sum). The clamp is hoisted to the sub-block:
# a component whose (k/ln 2)·max d reaches 125 there takes the clamped
# :func:`~ship_gym.numerics.fastmath.exp2_neg_f32` (never in ordinary seas). Against the
# degree-10/6 polynomials with a clamp per pair, less kernel time (S175-full, 1500 faces, Hs 5 m;
# measured: docs/benchmarks.md), and the forces stay as close to the float64 reference (≲ 3e-7
# of the force scale over S175-full states, ≲ 1.4e-7 on the tests' seas). Tried without gain:
# two components per pair loop (elevation or pressure), Estrin evaluation of 2^x, numba-inlined
# pair loops (slower);
# pressure sub-blocks of 128 vertices are faster than 64, elevation blocks of 128 not faster
# than 256 (nor are 512–1536 with sub-blocks of 128–512; outputs bit-identical; the timings in
# docs/benchmarks.md). Also tried, on S175-full states (1500 vertices, ≈ 1/3 of them dry, ≈ 220
# crossing triangles):
#   - skipping the vertices that are certainly dry with all their neighbours (a long-crested
#     sea is a 1-D function ζ(s) of the projection s on the wave direction: ζ on a coarse grid
#     of s plus the bound max|ζ''| h²/8 = Σ|cⱼ|kⱼ² h²/8 gives a local crest; outputs
#     bit-identical): it skips 110–420 of the 1500 vertices, but the per-vertex classification,
#     the compaction of the kept vertices and the scatter back are scalar loops that cost
#     more per vertex than the wave sums saved per skipped vertex (the kernel got slower;
#     docs/benchmarks.md);
#   - sorting the vertices by body-z bands, then x (the pressure rows' padding is ≈ 10 % of the
#     wet vertices with the plain body-z order; ≤ 3 % less with the others);
#   - finding the crossing triangles in two passes (a branch-free mixed-wetness flag and a
#     compaction, then the cut of those only): slower than the branchy scan
#     (docs/benchmarks.md).
_F32 = np.float32
_SUB_F32 = 128  # vertices per pressure sub-block of the float32 kernel (a multiple of 8)
_DECAY_CUTOFF_F32 = 30.0  # 2^−30 ≈ 1e-9: below float32 resolution of the sum
_EXP2_UNCLAMPED_F32 = 125.0  # range of exp2_neg_unclamped_f32 (2^−y, y ≤ 125)


@nb.njit(fastmath=_FM, cache=True)
def _spatial_row_f32(
    a: np.float32,
    b: np.float32,
    p: np.float32,
    m: np.float32,
    rx: np.ndarray,
    ry: np.ndarray,
    v0: int,
    spatial: np.ndarray,
    s0: int,
    zeta: np.ndarray,
    n: int,
) -> None:  # pragma: no cover - compiled
    """float32 :func:`_spatial_row`."""
    vo = nb.uint64(v0)
    so = nb.uint64(s0)
    for u in range(nb.uint64(n)):
        s = cos_turns_nonneg_f32(a * rx[vo + u] + (b * ry[vo + u] + p), m)
        spatial[so + u] = s
        zeta[u] += s


@nb.njit(fastmath=_FM, cache=True)
def _spatial_row_1d_f32(
    kt: np.float32,
    p: np.float32,
    m: np.float32,
    proj: np.ndarray,
    spatial: np.ndarray,
    s0: int,
    zeta: np.ndarray,
    n: int,
) -> None:  # pragma: no cover - compiled
    """:func:`_spatial_row_f32` of a long-crested sea: phase kt·proj[u] + p [turns]."""
    so = nb.uint64(s0)
    for u in range(nb.uint64(n)):
        s = cos_turns_nonneg_f32(kt * proj[u] + p, m)
        spatial[so + u] = s
        zeta[u] += s


@nb.njit(fastmath=_FM, cache=True)
def _decayed_row_f32(
    k2: np.float32, dpos: np.ndarray, spatial: np.ndarray, s0: int, acc: np.ndarray, n: int
) -> None:  # pragma: no cover - compiled
    """float32 :func:`_decayed_row` for k2 · max dpos < _EXP2_UNCLAMPED_F32 (no clamp)."""
    so = nb.uint64(s0)
    for u in range(nb.uint64(n)):
        acc[u] += exp2_neg_unclamped_f32(k2 * dpos[u]) * spatial[so + u]


@nb.njit(fastmath=_FM, cache=True)
def _decayed_row_clamped_f32(
    k2: np.float32, dpos: np.ndarray, spatial: np.ndarray, s0: int, acc: np.ndarray, n: int
) -> None:  # pragma: no cover - compiled
    """:func:`_decayed_row_f32` for any k2 · dpos ≥ 0 (2^−y clamped at y = 126)."""
    so = nb.uint64(s0)
    for u in range(nb.uint64(n)):
        acc[u] += exp2_neg_f32(k2 * dpos[u]) * spatial[so + u]


@nb.njit(fastmath=_FM, cache=True, nogil=True)
def _fk_one_ship_f32(
    body: np.ndarray,
    tri: np.ndarray,
    tri_last: np.ndarray,
    tri_first: np.ndarray,
    spread: np.ndarray,
    weights: np.ndarray,
    areas: np.ndarray,
    rot: np.ndarray,
    x0: float,
    y0: float,
    z0: float,
    k: np.ndarray,
    cos_dir: np.ndarray,
    sin_dir: np.ndarray,
    amp: np.ndarray,
    rho_g: float,
    out: np.ndarray,
) -> None:  # pragma: no cover - compiled
    """:func:`_fk_one_ship` with the wave sums in float32 (same arguments, float64 arrays)."""
    kxt, kyt, k2, mod, offset = np.empty((5, k.shape[0]), dtype=np.float32)
    crest = _fold_components(k, cos_dir, sin_dir, amp, x0, y0, kxt, kyt, k2, mod, offset)
    _fk_core_f32(
        body, tri, tri_last, tri_first, spread, weights, areas, rot, z0, kxt, kyt, k2,
        mod, offset, crest, rho_g, out,
    )  # fmt: skip


@nb.njit(cache=True)
def _wet_range(depth: np.ndarray, v0: int, n: int) -> tuple[int, int]:  # pragma: no cover
    """(first, last + 1) offsets from v0 of the vertices with depth ≥ 0 among depth[v0:v0 + n],
    (n, 0) if none: integer min/max reductions without branches (they vectorise)."""
    lo = n
    hi = 0
    vo = nb.uint64(v0)
    for u in range(n):
        wet = depth[vo + nb.uint64(u)] >= 0.0
        lo = min(lo, u if wet else n)
        hi = max(hi, u + 1 if wet else 0)
    return lo, hi


@nb.njit(fastmath=_FM, cache=True)
def _store_pressure(
    depth: np.ndarray,
    rz: np.ndarray,
    acc: np.ndarray,
    pres: np.ndarray,
    z0: float,
    rho_g: float,
    v0: int,
    n: int,
) -> None:  # pragma: no cover - compiled
    """pres[v0 + u] = ρg (z + acc[u]) where wet (depth ≥ 0), else 0 (a select: vectorises)."""
    vo = nb.uint64(v0)
    for u in range(nb.uint64(n)):
        p = rho_g * (z0 + rz[vo + u] + acc[u])
        pres[vo + u] = p if depth[vo + u] >= 0.0 else 0.0


@nb.njit(fastmath=_FM, cache=True, nogil=True)
def _fk_core_f32(
    body: np.ndarray,
    tri: np.ndarray,
    tri_last: np.ndarray,
    tri_first: np.ndarray,
    spread: np.ndarray,
    weights: np.ndarray,
    areas: np.ndarray,
    rot: np.ndarray,
    z0: float,
    kxt: np.ndarray,
    kyt: np.ndarray,
    k2: np.ndarray,
    mod: np.ndarray,
    offset: np.ndarray,
    crest: float,
    rho_g: float,
    out: np.ndarray,
) -> None:  # pragma: no cover - compiled
    """:func:`_fk_core` with the wave sums in float32: kxt, kyt, k2, mod and offset are float32
    arrays."""
    n_v: int = body.shape[1]
    n_c = kxt.shape[0]
    # A long-crested sea (all components along one direction ±(ux, uy), the usual case): the
    # phase is kⱼ/2π times the one projection s = ux x + uy y, formed once per vertex, so the
    # pair loop has one multiply-add for the phase instead of two (and one stream fewer)
    jmax = 0
    for j in range(n_c):
        if abs(kxt[j]) + abs(kyt[j]) > abs(kxt[jmax]) + abs(kyt[jmax]):
            jmax = j
    norm = math.hypot(float(kxt[jmax]), float(kyt[jmax]))
    ux, uy = (kxt[jmax] / norm, kyt[jmax] / norm) if norm > 0.0 else (1.0, 0.0)
    collinear = True
    kt = np.empty(n_c, dtype=np.float32)
    for j in range(n_c):
        kt[j] = kxt[j] * ux + kyt[j] * uy
        collinear &= abs(kxt[j] * uy - kyt[j] * ux) <= 1e-7 * norm
    rx = np.empty(n_v, dtype=np.float32)
    ry = np.empty(n_v, dtype=np.float32)
    rz = np.empty(n_v)
    r00, r01, r02 = rot[0, 0], rot[0, 1], rot[0, 2]
    r10, r11, r12 = rot[1, 0], rot[1, 1], rot[1, 2]
    r20, r21, r22 = rot[2, 0], rot[2, 1], rot[2, 2]
    bxs, bys, bzs = body[0], body[1], body[2]
    for v in range(nb.uint64(n_v)):
        bx, by, bz = bxs[v], bys[v], bzs[v]
        rx[v] = r00 * bx + r01 * by + r02 * bz
        ry[v] = r10 * bx + r11 * by + r12 * bz
        rz[v] = r20 * bx + r21 * by + r22 * bz
    depth = np.empty(n_v)
    pres = np.empty(n_v)
    spatial = np.empty(n_c * _BLOCK, dtype=np.float32)
    zeta = np.zeros(_BLOCK, dtype=np.float32)
    proj = np.zeros(_BLOCK, dtype=np.float32)
    dpos = np.empty(_SUB_F32, dtype=np.float32)
    acc = np.empty(_SUB_F32, dtype=np.float32)
    n_wave = n_v
    while n_wave > 0:
        v = n_wave - 1
        rise = 0.0
        for q in range(3):
            rise += max(rot[2, q] * spread[q, v], rot[2, q] * spread[3 + q, v])
        if not z0 + rz[v] + rise + crest < 0.0:
            break
        depth[v] = z0 + rz[v] + crest
        pres[v] = 0.0
        n_wave -= 1
    zero = np.float32(0.0)
    for v0 in range(0, n_wave, _BLOCK):
        v1 = min(v0 + _BLOCK, n_wave)
        nb_ = v1 - v0
        for u in range(_BLOCK):
            zeta[u] = zero
        if collinear:
            for u in range(nb_):
                proj[u] = ux * rx[v0 + u] + uy * ry[v0 + u]
            for j in range(n_c):
                _spatial_row_1d_f32(kt[j], offset[j], mod[j], proj, spatial, j * _BLOCK, zeta, nb_)
        else:
            for j in range(n_c):
                _spatial_row_f32(
                    kxt[j], kyt[j], offset[j], mod[j], rx, ry, v0, spatial, j * _BLOCK, zeta, nb_
                )
        for u in range(nb_, min(nb_ + 7, _BLOCK)):  # padding lanes of a short last block
            for j in range(n_c):
                spatial[j * _BLOCK + u] = zero
        vo = nb.uint64(v0)
        for u in range(nb.uint64(nb_)):
            depth[vo + u] = (z0 + rz[vo + u]) + zeta[u]
            pres[vo + u] = 0.0
        for u0 in range(0, nb_, _SUB_F32):
            u1 = min(u0 + _SUB_F32, nb_)
            # the wet range [lo, hi) of the sub-block: branch-free min/max reductions
            lo, hi = _wet_range(depth, v0 + u0, u1 - u0)
            if hi == 0:
                continue
            lo += u0
            hi += u0
            lo -= lo % 8
            hi = min(hi + (-hi) % 8, _BLOCK)
            n = hi - lo
            dmin = np.inf
            dmax = 0.0
            for u in range(n):
                dp = max(depth[v0 + lo + u], 0.0) if lo + u < nb_ else 0.0
                dpos[u] = dp
                acc[u] = zero
                dmin = min(dmin, dp)
                dmax = max(dmax, dp)
            for j in range(n_c):
                if k2[j] * dmin < _DECAY_CUTOFF_F32:
                    if k2[j] * dmax < _EXP2_UNCLAMPED_F32:
                        _decayed_row_f32(k2[j], dpos, spatial, j * _BLOCK + lo, acc, n)
                    else:
                        _decayed_row_clamped_f32(k2[j], dpos, spatial, j * _BLOCK + lo, acc, n)
            _store_pressure(depth, rz, acc, pres, z0, rho_g, v0 + lo, min(hi, nb_) - lo)
    _integrate(tri, tri_last, tri_first, body, weights, areas, rot, depth, pres, out)


# a mesh's kernel arrays: body, tri, tri_last, tri_first, spread, weights, areas
MeshArrays = tuple[
    np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray, np.ndarray
]


@nb.njit(cache=True, nogil=True)
def _fk_batch_ship(
    s, mesh: MeshArrays, rot, z0, k, cx, sx, amp, rho_g, out, single
):  # pragma: no cover
    """Ship s of a batch: the float32 or float64 one-ship kernel (``mesh`` = its 7 arrays)."""
    if single:
        _fk_one_ship_f32(*mesh, rot[s], 0.0, 0.0, z0[s], k[s], cx[s], sx[s], amp[s], rho_g, out[s])
    else:
        _fk_one_ship(*mesh, rot[s], 0.0, 0.0, z0[s], k[s], cx[s], sx[s], amp[s], rho_g, out[s])


@nb.njit(cache=True, nogil=True)
def _fk_batch(
    body: np.ndarray,
    tri: np.ndarray,
    tri_last: np.ndarray,
    tri_first: np.ndarray,
    spread: np.ndarray,
    weights: np.ndarray,
    areas: np.ndarray,
    rot: np.ndarray,
    z0: np.ndarray,
    k: np.ndarray,
    cx: np.ndarray,
    sx: np.ndarray,
    amp: np.ndarray,
    rho_g: float,
    out: np.ndarray,
    single: bool,
) -> None:  # pragma: no cover - compiled
    mesh = (body, tri, tri_last, tri_first, spread, weights, areas)
    for s in range(rot.shape[0]):
        _fk_batch_ship(s, mesh, rot, z0, k, cx, sx, amp, rho_g, out, single)


@nb.njit(cache=True, nogil=True, parallel=True)
def _fk_batch_parallel(
    body: np.ndarray,
    tri: np.ndarray,
    tri_last: np.ndarray,
    tri_first: np.ndarray,
    spread: np.ndarray,
    weights: np.ndarray,
    areas: np.ndarray,
    rot: np.ndarray,
    z0: np.ndarray,
    k: np.ndarray,
    cx: np.ndarray,
    sx: np.ndarray,
    amp: np.ndarray,
    rho_g: float,
    out: np.ndarray,
    single: bool,
) -> None:  # pragma: no cover - compiled
    mesh = (body, tri, tri_last, tri_first, spread, weights, areas)
    for s in nb.prange(rot.shape[0]):
        _fk_batch_ship(s, mesh, rot, z0, k, cx, sx, amp, rho_g, out, single)


# ----------------------------------------------------------------------------- public API
def froude_krylov_hydrostatic(
    panels: HullPanels,
    waves: WaveComponents,
    phasor: np.ndarray,
    position: np.ndarray,
    rotation: np.ndarray,
    *,
    rho: float,
    g: float,
    method: Method = "fast",
) -> np.ndarray:
    """Incident-wave + hydrostatic pressure force on the instantaneous wetted hull.

    Parameters
    ----------
    panels : HullPanels
        Triangulated closed hull (body frame).
    waves : WaveComponents
        Wavenumbers and directions of the incident components.
    phasor : numpy.ndarray
        (n,) complex amplitudes cⱼ(t) [m] (ramp included): ζ = Re Σ cⱼ e^{−i kⱼ(X cos χⱼ +
        Y sin χⱼ)}. Zeros give calm water.
    position : numpy.ndarray
        (3,) earth position of O [m] (NED, z down).
    rotation : numpy.ndarray
        (3, 3) body-to-earth rotation matrix.
    rho, g : float
        Water density [kg/m³] and gravity [m/s²].
    method : {"fast", "fast32", "reference"}
        Numba kernel (float64, or with the wave sums in float32: see the notes of the float32
        kernel section; about twice as fast, errors ~1e-7 of the hydrostatic force) or numpy
        reference implementation.

    Returns
    -------
    numpy.ndarray
        (6,) force [N] and moment about O [N·m], in **earth** axes.
    """
    position = np.asarray(position, dtype=np.float64)
    rotation = np.ascontiguousarray(rotation, dtype=np.float64)
    if method in ("fast", "fast32"):
        kernel = _fk_one_ship_f32 if method == "fast32" else _fk_one_ship
        # the kernel folds the horizontal position into the amplitudes itself (saves the numpy
        # calls of doing it here, per evaluation; measured: docs/benchmarks.md)
        out = np.zeros(6)
        lay = panels._layout
        kernel(
            lay.body,
            lay.triangles,
            lay.tri_last,
            lay.tri_first,
            lay.spread,
            lay.weights,
            lay.areas,
            rotation,
            float(position[0]),
            float(position[1]),
            float(position[2]),
            waves.wavenumber,
            waves.cos_direction,
            waves.sin_direction,
            np.ascontiguousarray(phasor, dtype=np.complex128),
            rho * g,
            out,
        )
        return out
    if method == "reference":
        amp = waves.local_amplitudes(phasor, position[0], position[1])
        return _reference(panels, waves, amp, position, rotation, rho, g)
    raise ValueError(f"method must be one of {_METHODS}, got {method!r}")


def froude_krylov_hydrostatic_batch(
    panels: HullPanels,
    wavenumber: np.ndarray,
    cos_direction: np.ndarray,
    sin_direction: np.ndarray,
    local_amplitude: np.ndarray,
    depth_of_origin: np.ndarray,
    rotation: np.ndarray,
    *,
    rho: float,
    g: float,
    parallel: bool = False,
    single_precision: bool = False,
) -> np.ndarray:
    """Batched fast kernel: many ships (same hull) in one call.

    Parameters
    ----------
    panels : HullPanels
        Shared hull geometry.
    wavenumber, cos_direction, sin_direction : numpy.ndarray
        (n_ships, n) wave arrays of each ship's sea.
    local_amplitude : numpy.ndarray
        (n_ships, n) complex amplitudes with each ship's horizontal position folded in
        (:meth:`WaveComponents.local_amplitudes`).
    depth_of_origin : numpy.ndarray
        (n_ships,) earth z of each ship's O [m].
    rotation : numpy.ndarray
        (n_ships, 3, 3) body-to-earth rotations.
    parallel : bool
        Spread the ships over numba's threads (prange; ``NUMBA_NUM_THREADS``, by default one per
        core). Off by default: in a process that also runs torch, the two thread pools compete
        for the cores (see the notes of the fast-kernel section). Results are identical.
    single_precision : bool
        Wave sums in float32 (``method="fast32"`` of :func:`froude_krylov_hydrostatic`).

    Returns
    -------
    numpy.ndarray
        (n_ships, 6) force and moment about O in earth axes.
    """
    n = rotation.shape[0]
    out = np.zeros((n, 6))
    lay = panels._layout
    kernel = _fk_batch_parallel if parallel else _fk_batch
    kernel(
        lay.body,
        lay.triangles,
        lay.tri_last,
        lay.tri_first,
        lay.spread,
        lay.weights,
        lay.areas,
        np.ascontiguousarray(rotation, dtype=np.float64),
        np.ascontiguousarray(depth_of_origin, dtype=np.float64),
        np.ascontiguousarray(wavenumber, dtype=np.float64),
        np.ascontiguousarray(cos_direction, dtype=np.float64),
        np.ascontiguousarray(sin_direction, dtype=np.float64),
        np.ascontiguousarray(local_amplitude, dtype=np.complex128),
        rho * g,
        out,
        bool(single_precision),
    )
    return out


def _reference(
    panels: HullPanels,
    waves: WaveComponents,
    amp: np.ndarray,
    position: np.ndarray,
    rotation: np.ndarray,
    rho: float,
    g: float,
) -> np.ndarray:
    rel = panels.vertices @ rotation.T
    z = position[2] + rel[:, 2]
    phase = waves.wavenumber[None, :] * (
        rel[:, 0:1] * waves.cos_direction[None, :] + rel[:, 1:2] * waves.sin_direction[None, :]
    )
    spatial = np.cos(phase) * amp.real[None, :] + np.sin(phase) * amp.imag[None, :]
    depth = z + spatial.sum(axis=1)
    decay = np.exp(-np.outer(np.clip(depth, 0.0, None), waves.wavenumber))
    pressure = np.where(depth >= 0.0, rho * g * (z + (decay * spatial).sum(axis=1)), 0.0)
    idx = panels.integration_triangles
    weight = panels.integration_weights
    n_wet = (depth[idx] >= 0.0).sum(axis=1)
    # clip_triangles splits the wet quadrilateral of a triangle with two wet vertices along a
    # diagonal that depends on the vertex order: those triangles are clipped in both senses,
    # (a, b, c) and (a, c, b) (area vector −N), and the two results averaged, as the kernel does
    two = n_wet == 2
    tri = np.concatenate([idx[~two], idx[two], idx[two][:, ::-1]])
    w = np.concatenate([weight[~two], 0.5 * weight[two], -0.5 * weight[two]])
    wet, _, owner, p_wet = clip_triangles(rel[tri], depth[tri], pressure[tri])
    # the load is linear in the pressure: a triangle of weight w carries w × its pressure
    force, moment = pressure_resultant(wet, p_wet * w[owner][:, None], np.zeros(3))
    return np.concatenate([force, moment])


class FroudeKrylovHydrostatics(ForceModel):
    """Force model: nonlinear incident-wave + hydrostatic pressure on the instantaneous hull.

    Parameters
    ----------
    hull : Hull
        Hull with its closed mesh (to the deck).
    wave_field : WaveField or None
        Incident waves (None: calm water, pure hydrostatics).
    method : {"fast", "fast32", "reference"}
        Kernel implementation (:func:`froude_krylov_hydrostatic`).

    Notes
    -----
    The force is returned in body axes about O: F_b = Rᵀ F_e, M_b = Rᵀ M_e.
    """

    name = "froude_krylov_hydrostatic"

    def __init__(self, hull: Hull, wave_field: WaveField | None = None, *, method: Method = "fast"):
        if method not in _METHODS:
            raise ValueError(f"method must be one of {_METHODS}, got {method!r}")
        self.hull = hull
        self.method: Method = method
        self.panels = HullPanels.from_mesh(hull.mesh)
        self.wave_field = wave_field
        if wave_field is None or wave_field.n_components == 0:
            self.waves = WaveComponents.from_arrays(np.zeros(1), np.zeros(1))
        else:
            self.waves = WaveComponents.from_arrays(wave_field.wavenumber, wave_field.direction)
        self._calm = np.zeros(self.waves.wavenumber.shape, dtype=np.complex128)

    def evaluate(self, ctx: ForceContext, states: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """Body-axis force and moment about O (see :func:`froude_krylov_hydrostatic`)."""
        phasor = self._calm if ctx.wave_phasor is None else ctx.wave_phasor
        f = froude_krylov_hydrostatic(
            self.panels,
            self.waves,
            phasor,
            ctx.eta[:3],
            ctx.rotation,
            rho=self.hull.rho,
            g=self.hull.g,
            method=self.method,
        )
        rt = ctx.rotation.T
        return np.concatenate([rt @ f[:3], rt @ f[3:]]), _NO_STATES


_NO_STATES = np.zeros(0)


# =============================================================================================
# row kernel of the compiled path (protocol: ship_gym.forces.base.RowPart)
# =============================================================================================
class FroudeKrylovRecord(NamedTuple):
    """The kernel's hull layout (:class:`_KernelLayout`), ρg [N/m³] and the wave-sum precision."""

    body: np.ndarray
    tri: np.ndarray
    tri_last: np.ndarray
    tri_first: np.ndarray
    spread: np.ndarray
    weights: np.ndarray
    areas: np.ndarray
    rho_g: float
    single: bool


def froude_krylov_record(layout: _KernelLayout, rho_g: float, single: bool) -> FroudeKrylovRecord:
    """The record of :func:`froude_krylov_row` for a hull layout (contiguous arrays)."""

    def c(a, dtype=np.float64):
        return np.ascontiguousarray(a, dtype=dtype)

    return FroudeKrylovRecord(
        c(layout.body), c(layout.triangles, np.int64), c(layout.tri_last, np.int64),
        c(layout.tri_first, np.int64), c(layout.spread), c(layout.weights), c(layout.areas),
        float(rho_g), bool(single),
    )  # fmt: skip


@nb.njit(cache=True, nogil=True)
def froude_krylov_row(s, t, q, v, z, zdot, ctx, rec, out):  # pragma: no cover - compiled
    """Row kernel: Froude–Krylov + hydrostatic force on the instantaneous wetted hull of ship s
    (:func:`_fk_core`, or :func:`_fk_core_f32` with float32 wave sums), earth axes, turned into
    body axes, Fᵇ = Rᵀ Fᵉ, and added to ``out`` [N, N·m]."""
    fe = np.zeros(6)
    w = ctx.waves
    rot = ctx.rot
    if rec.single:
        _fk_core_f32(
            rec.body, rec.tri, rec.tri_last, rec.tri_first, rec.spread, rec.weights, rec.areas,
            rot, q[2], w.kxt32[s], w.kyt32[s], w.k232[s], ctx.mod.astype(np.float32),
            ctx.offset.astype(np.float32), ctx.shared[0], rec.rho_g, fe,
        )  # fmt: skip
    else:
        _fk_core(
            rec.body, rec.tri, rec.tri_last, rec.tri_first, rec.spread, rec.weights, rec.areas,
            rot, q[2], w.kxt[s], w.kyt[s], w.k2[s], ctx.mod, ctx.offset, ctx.shared[0],
            rec.rho_g, fe,
        )  # fmt: skip
    for i in range(3):
        out[i] += rot[0, i] * fe[0] + rot[1, i] * fe[1] + rot[2, i] * fe[2]
    for i in range(3):
        out[3 + i] += rot[0, i] * fe[3] + rot[1, i] * fe[4] + rot[2, i] * fe[5]
