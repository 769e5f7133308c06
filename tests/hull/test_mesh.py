"""PanelMesh geometry, quality checks, polygon cleaning, waterline clipping and pressure integrals.

Every expected value is computed from analytic geometry, independently of the mesh code.
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest

from ship_gym.hull.mesh import (
    MeshError,
    PanelMesh,
    clip_triangles,
    mesh_from_polygons,
    pressure_resultant,
)

RHO, G = 1025.0, 9.81
L, B, H, T = 10.0, 4.0, 3.0, 1.2  # box length, beam, depth, draught [m] (T ≠ H/2 on purpose)


def box(x=(-L / 2, L / 2), y=(-B / 2, B / 2), z=(-(H - T), T), name="box") -> PanelMesh:
    """Closed box of six quads with outward normals (checked against the face offsets)."""
    v = np.array([[x[i], y[j], z[k]] for k in (0, 1) for j in (0, 1) for i in (0, 1)], float)

    def n(i: int, j: int, k: int) -> int:
        return i + 2 * j + 4 * k

    # each face listed counter-clockwise seen from outside, by hand
    faces = [
        [n(0, 0, 0), n(0, 0, 1), n(0, 1, 1), n(0, 1, 0)],  # x = x0, normal -x
        [n(1, 0, 0), n(1, 1, 0), n(1, 1, 1), n(1, 0, 1)],  # x = x1, normal +x
        [n(0, 0, 0), n(1, 0, 0), n(1, 0, 1), n(0, 0, 1)],  # y = y0, normal -y
        [n(0, 1, 0), n(0, 1, 1), n(1, 1, 1), n(1, 1, 0)],  # y = y1, normal +y
        [n(0, 0, 0), n(0, 1, 0), n(1, 1, 0), n(1, 0, 0)],  # z = z0, normal -z
        [n(0, 0, 1), n(1, 0, 1), n(1, 1, 1), n(0, 1, 1)],  # z = z1, normal +z
    ]
    return PanelMesh(v, np.array(faces), name)


def roll_matrix(phi: float) -> np.ndarray:
    """Body → earth rotation for a roll φ [rad] (starboard down for φ > 0, z down)."""
    c, s = np.cos(phi), np.sin(phi)
    return np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])


# ---------------------------------------------------------------------- panel geometry
def test_unit_square() -> None:
    sq = PanelMesh([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], [[0, 1, 2, 3]])
    np.testing.assert_allclose(sq.areas, [1.0])
    np.testing.assert_allclose(sq.normals, [[0.0, 0.0, 1.0]])
    np.testing.assert_allclose(sq.vector_areas, [[0.0, 0.0, 1.0]])
    np.testing.assert_allclose(sq.centroids, [[0.5, 0.5, 0.0]])
    assert not sq.is_triangle[0]


def test_triangle_in_3d() -> None:
    a, b, c = np.array([1.0, 2.0, 3.0]), np.array([4.0, 0.0, 1.0]), np.array([-1.0, 1.0, 5.0])
    tri = PanelMesh([a, b, c], [[0, 1, 2]])  # (n, 3) faces are accepted
    assert tri.faces.tolist() == [[0, 1, 2, 2]]
    assert tri.is_triangle[0]
    cross = np.array(
        [
            (b - a)[1] * (c - a)[2] - (b - a)[2] * (c - a)[1],
            (b - a)[2] * (c - a)[0] - (b - a)[0] * (c - a)[2],
            (b - a)[0] * (c - a)[1] - (b - a)[1] * (c - a)[0],
        ]
    )
    area = 0.5 * np.sqrt(np.sum(cross**2))
    np.testing.assert_allclose(tri.areas, [area], rtol=1e-14)
    np.testing.assert_allclose(tri.normals[0], cross / (2 * area), rtol=1e-14)
    np.testing.assert_allclose(tri.centroids[0], (a + b + c) / 3, rtol=1e-14)


def test_trapezoid_centroid() -> None:
    """Trapezoid with parallel sides 4 (y = 0) and 2 (y = 2): area 6, centroid y = 8/9."""
    trap = PanelMesh([[0, 0, 0], [4, 0, 0], [3, 2, 0], [1, 2, 0]], [[0, 1, 2, 3]])
    np.testing.assert_allclose(trap.areas, [6.0])
    np.testing.assert_allclose(trap.vector_areas, [[0.0, 0.0, 6.0]])
    np.testing.assert_allclose(trap.centroids, [[2.0, 8.0 / 9.0, 0.0]], rtol=1e-14)


def test_box_volume_and_centroid_exact() -> None:
    mesh = box(x=(1.0, 11.0), y=(-2.0, 2.0), z=(0.5, 3.5))
    mesh.check()
    assert mesh.volume == 120.0
    np.testing.assert_allclose(mesh.volume_centroid, [6.0, 0.0, 2.0], rtol=0, atol=1e-14)
    np.testing.assert_allclose(mesh.areas.sum(), 2 * (10 * 4 + 10 * 3 + 4 * 3))
    np.testing.assert_allclose(mesh.vector_areas.sum(axis=0), 0.0, atol=1e-12)
    np.testing.assert_array_equal(mesh.bounds, [[1.0, -2.0, 0.5], [11.0, 2.0, 3.5]])
    assert mesh.edge_report == {"edges": 12, "boundary": 0, "non_manifold": 0, "inconsistent": 0}


def test_transformed_rotation_keeps_volume_and_moves_centroid() -> None:
    mesh = box()
    r = roll_matrix(0.3)
    moved = mesh.transformed(r, [1.0, 2.0, 3.0])
    assert moved.volume == pytest.approx(mesh.volume, rel=1e-13)
    np.testing.assert_allclose(moved.volume_centroid, r @ mesh.volume_centroid + [1, 2, 3])
    np.testing.assert_allclose(mesh.translated([0, 0, 1]).bounds[:, 2], [-(H - T) + 1, T + 1])


def test_mesh_is_immutable() -> None:
    mesh = box()
    with pytest.raises(ValueError, match="read-only"):
        mesh.vertices[0, 0] = 1.0
    with pytest.raises(AttributeError):
        mesh.name = "other"  # type: ignore[misc]


# ---------------------------------------------------------------------- construction errors
def test_constructor_rejects_bad_input() -> None:
    with pytest.raises(MeshError, match="shape"):
        PanelMesh(np.zeros((3, 2)), [[0, 1, 2]])
    with pytest.raises(MeshError, match="indices"):
        PanelMesh(np.zeros((3, 3)), [[0, 1, 3]])
    with pytest.raises(MeshError, match="non-finite"):
        PanelMesh([[0, 0, 0], [1, 0, 0], [0, np.nan, 0]], [[0, 1, 2]])
    with pytest.raises(MeshError, match="integer"):
        PanelMesh(np.zeros((3, 3)), [[0.0, 1.5, 2.0]])


# ---------------------------------------------------------------------- check()
def _degenerate() -> PanelMesh:
    m = box()
    mid = 0.5 * (m.vertices[0] + m.vertices[1])  # on the edge 0-1: a zero-area triangle
    v = np.vstack([m.vertices, mid])
    return PanelMesh(v, np.vstack([m.faces, [0, 8, 1, 1]]), "degenerate")


def _open() -> PanelMesh:
    m = box()
    return PanelMesh(m.vertices, m.faces[1:], "open")


def _inconsistent() -> PanelMesh:
    m = box()
    f = m.faces.copy()
    f[2] = f[2, ::-1]
    return PanelMesh(m.vertices, f, "inconsistent")


def _non_manifold() -> PanelMesh:
    m = box()
    return PanelMesh(m.vertices, np.vstack([m.faces, m.faces[:1]]), "non_manifold")


@pytest.mark.parametrize(
    ("make", "message"),
    [
        (_degenerate, "degenerate panel"),
        (_open, "not watertight"),
        (_inconsistent, "opposite orientation"),
        (_non_manifold, "non-manifold"),
        (lambda: box().flipped(), "normals point into the hull"),
        (lambda: PanelMesh(np.zeros((0, 3)), np.zeros((0, 4), int), "empty"), "no faces"),
    ],
)
def test_check_errors(make, message: str) -> None:
    mesh = make()
    with pytest.raises(MeshError, match=message):
        mesh.check()


def test_check_open_mesh_allowed_when_not_closed() -> None:
    _open().check(closed=False)
    box().flipped().check(closed=False)  # orientation of an open mesh is not judged
    with pytest.raises(MeshError, match="opposite orientation"):
        _inconsistent().check(closed=False)


# ---------------------------------------------------------------------- flipped()
def test_flipped_reverses_normals_and_keeps_triangles_valid() -> None:
    # square pyramid: a quad base and four triangles
    v = np.array([[0, 0, 0], [2, 0, 0], [2, 2, 0], [0, 2, 0], [1, 1, -3]], float)
    faces = [[0, 1, 2, 3], [0, 4, 1, 1], [1, 4, 2, 2], [2, 4, 3, 3], [3, 4, 0, 0]]
    pyramid = PanelMesh(v, faces, "pyramid")
    pyramid.check()
    assert pyramid.volume == pytest.approx(4.0 * 3.0 / 3.0, rel=1e-14)
    flipped = pyramid.flipped()
    assert flipped.name == "pyramid"
    np.testing.assert_allclose(flipped.normals, -pyramid.normals, atol=1e-15)
    np.testing.assert_allclose(flipped.areas, pyramid.areas)
    np.testing.assert_allclose(flipped.centroids, pyramid.centroids, atol=1e-15)
    np.testing.assert_array_equal(flipped.is_triangle, pyramid.is_triangle)
    tri = flipped.faces[flipped.is_triangle]
    assert np.all(tri[:, 3] == tri[:, 2])
    assert np.all(tri[:, 0] != tri[:, 1]) and np.all(tri[:, 1] != tri[:, 2])
    for f_new, f_old in zip(flipped.faces, pyramid.faces, strict=True):
        assert set(f_new.tolist()) == set(f_old.tolist())
    assert flipped.volume == pytest.approx(-pyramid.volume, rel=1e-14)
    with pytest.raises(MeshError, match="into the hull"):
        flipped.check()
    np.testing.assert_array_equal(flipped.flipped().normals, pyramid.normals)
    flipped.flipped().check()


# ---------------------------------------------------------------------- mesh_from_polygons
def test_mesh_from_polygons_merges_duplicate_vertices() -> None:
    ref = box()
    rng = np.random.default_rng(1)
    polys, coords = [], []
    for f in ref.faces:  # every face with its own copies of the corners, slightly perturbed
        polys.append(list(range(len(coords), len(coords) + 4)))
        coords.extend(ref.vertices[f] + rng.uniform(-1e-9, 1e-9, (4, 3)))
    mesh = mesh_from_polygons(np.array(coords), polys, name="merged")
    assert mesh.n_vertices == 8
    assert mesh.n_faces == 6
    assert mesh.name == "merged"
    mesh.check()
    assert mesh.volume == pytest.approx(L * B * H, rel=1e-8)


def test_mesh_from_polygons_collapsed_quad_edge_becomes_triangle() -> None:
    v = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [1, 1, 1e-9], [0, 1, 0]], float)
    mesh = mesh_from_polygons(v, [[0, 1, 2, 3], [0, 2, 4, 4]])
    assert mesh.n_vertices == 4
    assert mesh.is_triangle.tolist() == [True, True]
    assert np.all(mesh.faces[:, 3] == mesh.faces[:, 2])
    np.testing.assert_allclose(mesh.areas, [0.5, 0.5])
    np.testing.assert_allclose(mesh.normals[:, 2], [1.0, 1.0])


def test_mesh_from_polygons_drops_degenerate_and_splits_polygons() -> None:
    ang = np.arange(6) * np.pi / 3
    hexagon = np.column_stack([np.cos(ang), np.sin(ang), np.zeros(6)])
    v = np.vstack([hexagon, [[5, 5, 5]]])
    mesh = mesh_from_polygons(v, [list(range(6)), [6, 6, 6]])  # the point polygon is dropped
    assert mesh.n_vertices == 6
    assert mesh.n_faces == 2
    np.testing.assert_allclose(mesh.areas.sum(), 1.5 * np.sqrt(3.0))
    assert np.all(mesh.normals[:, 2] > 0.0)


def test_mesh_from_polygons_merges_close_vertices_across_grid_boundary() -> None:
    v = np.array([[0.5e-6 - 1e-12, 0, 0], [0.5e-6 + 1e-12, 0, 0], [1, 0, 0], [0, 1, 0]])
    mesh = mesh_from_polygons(v, [[0, 2, 3], [1, 3, 2]], merge_tolerance=1e-6)
    assert mesh.n_vertices == 3


def test_mesh_from_polygons_removes_vertices_of_dropped_degenerate_panels() -> None:
    v = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [5, 5, 5], [6, 6, 6], [7, 7, 7]], float)
    mesh = mesh_from_polygons(v, [[0, 1, 2], [3, 4, 5]])  # the second triangle is collinear
    assert mesh.n_faces == 1
    assert mesh.n_vertices == 3
    np.testing.assert_array_equal(mesh.bounds, [[0, 0, 0], [1, 1, 0]])


def test_mesh_from_polygons_without_polygons_is_silent() -> None:
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        mesh = mesh_from_polygons(np.zeros((3, 3)), [])
    assert mesh.n_faces == 0


# ---------------------------------------------------------------------- clip_triangles
# a triangle in the plane y = 0; submergence measured as +z (case one wet vertex) or −z (two)
TRI = np.array([[[0.0, 0.0, 1.0], [3.0, 0.0, -2.0], [-1.0, 0.0, -1.0]]])
TRI_AREA = 4.5  # shoelace in (x, z): ½|0·(−2+1) + 3·(−1−1) + (−1)·(1+2)| = 9/2
# one wet vertex (0, 1): cut points (1, 0) on a-b (1/3 of the way), (−0.5, 0) on a-c (1/2)
WET_ONE = 0.5 * 1.5 * 1.0


def _wet_vector_area(t: np.ndarray) -> np.ndarray:
    return 0.5 * np.cross(t[:, 1] - t[:, 0], t[:, 2] - t[:, 0]).sum(axis=0)


def test_clip_one_wet_vertex() -> None:
    wet, depth, owner, _ = clip_triangles(TRI, TRI[:, :, 2])
    assert wet.shape == (1, 3, 3)
    np.testing.assert_allclose(wet[0], [[0, 0, 1], [1, 0, 0], [-0.5, 0, 0]], atol=1e-15)
    np.testing.assert_allclose(depth, [[1.0, 0.0, 0.0]])
    assert owner.tolist() == [0]
    parent = 0.5 * np.cross(TRI[0, 1] - TRI[0, 0], TRI[0, 2] - TRI[0, 0])
    np.testing.assert_allclose(_wet_vector_area(wet), parent / TRI_AREA * WET_ONE, atol=1e-15)


def test_clip_two_wet_vertices() -> None:
    wet, depth, owner, _ = clip_triangles(TRI, -TRI[:, :, 2])
    assert len(wet) == 2
    assert owner.tolist() == [0, 0]
    parent = 0.5 * np.cross(TRI[0, 1] - TRI[0, 0], TRI[0, 2] - TRI[0, 0])
    # same orientation as the parent, area = total − the dry corner triangle
    np.testing.assert_allclose(
        _wet_vector_area(wet), parent / TRI_AREA * (TRI_AREA - WET_ONE), atol=1e-14
    )
    each = 0.5 * np.cross(wet[:, 1] - wet[:, 0], wet[:, 2] - wet[:, 0])
    assert np.all(each @ parent > 0.0)
    np.testing.assert_allclose(depth, -wet[:, :, 2], atol=1e-15)  # 0 on the cut, kept elsewhere


def test_clip_all_or_nothing_and_vertex_on_the_surface() -> None:
    wet, _, owner, _ = clip_triangles(TRI, np.full((1, 3), 0.5))
    np.testing.assert_array_equal(wet, TRI)
    assert owner.tolist() == [0]
    assert len(clip_triangles(TRI, np.full((1, 3), -0.5))[0]) == 0
    wet, _, _, _ = clip_triangles(TRI, np.array([[0.0, -1.0, -1.0]]))  # touches the surface
    np.testing.assert_allclose(_wet_vector_area(wet), 0.0, atol=1e-15)


def test_clip_wet_and_dry_parts_tile_each_triangle() -> None:
    rng = np.random.default_rng(7)
    tri = rng.normal(size=(200, 3, 3))
    depth = rng.normal(size=(200, 3))
    wet, _, ow, _ = clip_triangles(tri, depth)
    dry, _, od, _ = clip_triangles(tri, -depth)  # the dry part is the wet part of −depth (± ties)
    va = 0.5 * np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    total = np.zeros_like(va)
    for t, o in ((wet, ow), (dry, od)):
        np.add.at(total, o, 0.5 * np.cross(t[:, 1] - t[:, 0], t[:, 2] - t[:, 0]))
    np.testing.assert_allclose(total, va, atol=1e-12)


# ---------------------------------------------------------------------- Archimedes
def _half_plane_clip(poly: np.ndarray, keep) -> np.ndarray:
    """Sutherland–Hodgman: the part of a 2-D polygon where keep(point) >= 0 (linear keep)."""
    out = []
    for k in range(len(poly)):
        p, q = poly[k], poly[(k + 1) % len(poly)]
        fp, fq = keep(p), keep(q)
        if fp >= 0:
            out.append(p)
        if (fp >= 0) != (fq >= 0):
            out.append(p + (q - p) * fp / (fp - fq))
    return np.array(out)


def _polygon_area_centroid(poly: np.ndarray) -> tuple[float, np.ndarray]:
    x, y = poly[:, 0], poly[:, 1]
    xn, yn = np.roll(x, -1), np.roll(y, -1)
    cross = x * yn - xn * y
    area = cross.sum() / 2
    return area, np.array([((x + xn) * cross).sum(), ((y + yn) * cross).sum()]) / (6 * area)


def _hydrostatics(phi: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Force, moment about the earth origin, and the wet triangles of the box heeled by φ."""
    rot = roll_matrix(phi)
    tri, _ = box().triangles_with_owner
    tri_earth = tri @ rot.T
    wet, depth, _, _ = clip_triangles(tri_earth, tri_earth[:, :, 2])
    force, moment = pressure_resultant(wet, RHO * G * depth, np.zeros(3))
    return force, moment, rot


def _check_archimedes(phi: float, volume: float, centre_body: np.ndarray) -> None:
    force, moment_o, rot = _hydrostatics(phi)
    weight = RHO * G * volume
    np.testing.assert_allclose(force, [0.0, 0.0, -weight], rtol=1e-12, atol=1e-9 * weight)
    centre = rot @ centre_body
    # about the buoyancy centre the moment vanishes; about O it is r_B × F
    tri, _ = box().triangles_with_owner
    tri_earth = tri @ rot.T
    wet, depth, _, _ = clip_triangles(tri_earth, tri_earth[:, :, 2])
    _, moment_b = pressure_resultant(wet, RHO * G * depth, centre)
    np.testing.assert_allclose(moment_b, 0.0, atol=1e-10 * weight * L)
    np.testing.assert_allclose(moment_o, np.cross(centre, force), atol=1e-10 * weight * L)


def test_archimedes_upright_box() -> None:
    _check_archimedes(0.0, L * B * T, np.array([0.0, 0.0, T / 2]))


def test_archimedes_box_heeled_10_degrees() -> None:
    """Wall-sided at 10°: V = L B T, B at (0, B² tanφ / 12T, T/2 − B² tan²φ / 24T)."""
    phi = np.radians(10.0)
    t = np.tan(phi)
    assert B / 2 * t < min(T, H - T)  # the waterline stays on the sides
    centre = np.array([0.0, B**2 * t / (12 * T), T / 2 - B**2 * t**2 / (24 * T)])
    _check_archimedes(phi, L * B * T, centre)


@pytest.mark.parametrize("heel_deg", [25.0, 40.0, 70.0, 135.0])
def test_archimedes_box_heeled_beyond_wall_sided(heel_deg: float) -> None:
    """Large heels: bilge out of the water (40°), deck edge under (70°), past capsize (135°).

    The wet part of the midship section is clipped independently in 2-D (Sutherland–Hodgman) and
    its area and centroid come from the shoelace formula.
    """
    phi = np.radians(heel_deg)
    s, c = np.sin(phi), np.cos(phi)
    section = np.array([[-B / 2, -(H - T)], [B / 2, -(H - T)], [B / 2, T], [-B / 2, T]])
    wet = _half_plane_clip(section, lambda p: s * p[0] + c * p[1])  # earth depth ≥ 0
    area, (yc, zc) = _polygon_area_centroid(wet)
    if heel_deg >= 40.0:
        assert abs(area - B * T) > 0.01 * B * T  # really not wall-sided any more
    _check_archimedes(phi, L * area, np.array([0.0, yc, zc]))
