"""Mesh files: round trips in every format, symmetry flags, frames and clear failures."""

from __future__ import annotations

import os
import stat
import struct
from pathlib import Path

import numpy as np
import pytest

from ship_gym.hull import mesh_io
from ship_gym.hull.mesh import MeshError, PanelMesh
from ship_gym.hull.mesh_io import MeshFileError, detect_format, read_mesh, write_mesh

L, B, H = 10.0, 4.0, 3.0

# (format given to write_mesh, binary flag, file suffix)
WRITE_CASES = {
    "stl": ("stl", True, ".stl"),
    "stl_ascii": ("stl", False, ".stl"),
    "gdf": ("gdf", True, ".gdf"),
    "dat": ("dat", True, ".dat"),
    "obj": ("obj", True, ".obj"),
}


# ---------------------------------------------------------------------- geometry builders
def _orient_outward(vertices: np.ndarray, polys: list[list[int]], centre) -> list[list[int]]:
    """Order each convex panel of a star-shaped closed surface so its normal points outward."""
    out = []
    for p in polys:
        q = vertices[p]
        n = np.cross(q[1] - q[0], q[2] - q[0])
        if len(p) == 4 and np.linalg.norm(n) == 0.0:
            n = np.cross(q[2] - q[0], q[3] - q[0])
        out.append(p if np.dot(n, q.mean(axis=0) - centre) > 0.0 else p[::-1])
    return out


def box(
    x: tuple[float, float] = (-L / 2, L / 2),
    y: tuple[float, float] = (-B / 2, B / 2),
    z: tuple[float, float] = (-H / 2, H / 2),
    drop: tuple[str, ...] = (),
    name: str = "box",
) -> PanelMesh:
    """Closed box of six quads; ``drop`` removes faces named like "y0" (the face at y = y[0])."""
    v = np.array([[x[i], y[j], z[k]] for k in (0, 1) for j in (0, 1) for i in (0, 1)], float)

    def idx(i: int, j: int, k: int) -> int:
        return i + 2 * j + 4 * k

    faces = {
        "x0": [idx(0, 0, 0), idx(0, 1, 0), idx(0, 1, 1), idx(0, 0, 1)],
        "x1": [idx(1, 0, 0), idx(1, 1, 0), idx(1, 1, 1), idx(1, 0, 1)],
        "y0": [idx(0, 0, 0), idx(1, 0, 0), idx(1, 0, 1), idx(0, 0, 1)],
        "y1": [idx(0, 1, 0), idx(1, 1, 0), idx(1, 1, 1), idx(0, 1, 1)],
        "z0": [idx(0, 0, 0), idx(1, 0, 0), idx(1, 1, 0), idx(0, 1, 0)],
        "z1": [idx(0, 0, 1), idx(1, 0, 1), idx(1, 1, 1), idx(0, 1, 1)],
    }
    centre = np.array([np.mean(x), np.mean(y), np.mean(z)])
    polys = _orient_outward(v, [f for k, f in faces.items() if k not in drop], centre)
    return PanelMesh(v, np.array(polys), name)


def sphere(radius: float = 3.0, n_lat: int = 7, n_lon: int = 12) -> PanelMesh:
    """Closed UV sphere: triangles at the poles, quads elsewhere.

    Coordinates are rounded to float32 so that binary STL (float32) round-trips exactly.
    """
    theta = np.linspace(0.0, np.pi, n_lat + 1)[1:-1]
    phi = np.linspace(0.0, 2.0 * np.pi, n_lon, endpoint=False)
    ring = np.stack(
        [
            np.outer(np.sin(theta), np.cos(phi)),
            np.outer(np.sin(theta), np.sin(phi)),
            np.outer(np.cos(theta), np.ones_like(phi)),
        ],
        axis=-1,
    ).reshape(-1, 3)
    v = radius * np.vstack([[0.0, 0.0, 1.0], ring, [0.0, 0.0, -1.0]]) + [0.5, -0.25, 0.75]
    v = v.astype(np.float32).astype(np.float64)
    south = len(v) - 1

    def r(i: int, j: int) -> int:
        return 1 + i * n_lon + j % n_lon

    polys = [[0, r(0, j), r(0, j + 1), r(0, j + 1)] for j in range(n_lon)]
    polys += [
        [r(i, j), r(i + 1, j), r(i + 1, j + 1), r(i, j + 1)]
        for i in range(n_lat - 2)
        for j in range(n_lon)
    ]
    polys += [
        [south, r(n_lat - 2, j), r(n_lat - 2, j + 1), r(n_lat - 2, j + 1)] for j in range(n_lon)
    ]
    centre = v.mean(axis=0)
    oriented = [
        [*o, o[-1]] if len(o) == 3 else o
        for o in _orient_outward(v, [list(dict.fromkeys(p)) for p in polys], centre)
    ]
    return PanelMesh(v, np.array(oriented), "sphere")


# ---------------------------------------------------------------------- comparison helpers
def _match(a: np.ndarray, b: np.ndarray, tol: float = 1e-6) -> np.ndarray:
    """Index in ``b`` of each vertex of ``a``; asserts a one-to-one match within ``tol`` [m]."""
    assert a.shape == b.shape
    d = np.linalg.norm(a[:, None, :] - b[None, :, :], axis=2)
    j = d.argmin(axis=1)
    assert d[np.arange(len(a)), j].max() < tol
    assert len(set(j.tolist())) == len(a)
    return j


def _canonical(polys) -> set[tuple[int, ...]]:
    """Faces as sets of cyclic vertex sequences (orientation kept, rotation ignored)."""
    out = set()
    for p in polys:
        p = list(dict.fromkeys(int(i) for i in p))
        k = p.index(min(p))
        out.add(tuple(p[k:] + p[:k]))
    return out


def _assert_same_mesh(read: PanelMesh, ref: PanelMesh, triangulated: bool) -> None:
    j = _match(read.vertices, ref.vertices)
    ref_polys = ref.triangle_indices[0] if triangulated else ref.faces
    assert _canonical(j[read.faces]) == _canonical(ref_polys)
    assert read.volume == pytest.approx(ref.volume, rel=1e-9)


def _write(mesh: PanelMesh, folder: Path, case: str, stem: str = "hull", **kw) -> Path:
    fmt, binary, suffix = WRITE_CASES[case]
    return write_mesh(mesh, folder / f"{stem}{suffix}", fmt, binary=binary, **kw)


def _gdf_text(panels: np.ndarray, isx: int, isy: int) -> str:
    lines = ["half hull", "1.0 9.81", f"{isx} {isy}", str(len(panels))]
    lines += [" ".join(repr(float(c)) for c in p.ravel()) for p in panels]
    return "\n".join(lines) + "\n"


# ---------------------------------------------------------------------- round trips
@pytest.mark.parametrize("frame", ["z_up", "z_down"])
@pytest.mark.parametrize("case", list(WRITE_CASES))
@pytest.mark.parametrize("shape", ["box", "sphere"])
def test_round_trip(tmp_path: Path, case: str, frame: str, shape: str) -> None:
    mesh = box() if shape == "box" else sphere()
    path = _write(mesh, tmp_path, case, frame=frame)
    read = read_mesh(path, frame=frame)
    assert read.name == "hull"
    _assert_same_mesh(read, mesh, triangulated=case.startswith("stl"))
    if shape == "box":
        assert read.volume == L * B * H


def test_round_trip_sphere_has_both_panel_kinds() -> None:
    mesh = sphere()
    mesh.check()
    assert mesh.is_triangle.any()
    assert (~mesh.is_triangle).any()


def test_binary_and_ascii_stl_both_read(tmp_path: Path) -> None:
    mesh = sphere()
    p_bin = write_mesh(mesh, tmp_path / "b.stl")
    p_asc = write_mesh(mesh, tmp_path / "a.stl", binary=False)
    assert p_asc.read_bytes().startswith(b"solid")
    assert not p_bin.read_bytes().startswith(b"solid")
    assert len(p_bin.read_bytes()) == 84 + 50 * len(mesh.triangle_indices[0])
    a, b = read_mesh(p_asc), read_mesh(p_bin)
    _assert_same_mesh(a, mesh, triangulated=True)
    _assert_same_mesh(b, mesh, triangulated=True)


def test_binary_stl_whose_header_starts_with_solid(tmp_path: Path) -> None:
    """Some CAD exporters start the binary header with 'solid'; the size decides."""
    path = write_mesh(box(), tmp_path / "cad.stl")
    data = bytearray(path.read_bytes())
    data[:80] = b"solid exported by some CAD tool".ljust(80)
    path.write_bytes(bytes(data))
    assert read_mesh(path).volume == L * B * H


def test_hand_written_ascii_stl(tmp_path: Path) -> None:
    """Tetrahedron with zero stored normals (ignored) and upper-case keywords, z-down file."""
    v = np.array([[0.0, 0, 0], [1.0, 0, 0], [0.0, 1, 0], [0.0, 0, 1]])
    tris = [(0, 2, 1), (0, 1, 3), (0, 3, 2), (1, 2, 3)]
    body = "".join(
        "FACET NORMAL 0 0 0\nOUTER LOOP\n"
        + "".join(f"VERTEX {v[i][0]:e} {v[i][1]:e} {v[i][2]:e}\n" for i in t)
        + "ENDLOOP\nENDFACET\n"
        for t in tris
    )
    path = tmp_path / "tet.stl"
    path.write_text(f"solid tet\n{body}endsolid tet\n")
    mesh = read_mesh(path, frame="z_down")
    assert mesh.n_faces == 4
    assert mesh.n_vertices == 4
    assert mesh.volume == pytest.approx(1.0 / 6.0, rel=1e-12)


def test_obj_with_texture_syntax_negative_indices_and_hexagons(tmp_path: Path) -> None:
    """Hexagonal prism: 6-gon caps (split into quads), v/vt/vn tokens, relative indices."""
    a, h = 2.0, 3.0
    ang = np.arange(6) * np.pi / 3.0
    ring = np.column_stack([a * np.cos(ang), a * np.sin(ang)]).tolist()
    lines = ["# prism", "o prism", "vt 0 0", "vn 0 0 1"]
    lines += [f"v {x!r} {y!r} 0.0" for x, y in ring] + [f"v {x!r} {y!r} {h!r}" for x, y in ring]
    # z-down file: the face z = h has outward normal +z, i.e. counter-clockwise about +z
    lines.append("f " + " ".join(f"{i}/1/1" for i in range(7, 13)))
    lines.append("f " + " ".join(f"{i}//1" for i in range(6, 0, -1)))  # z = 0, normal -z
    for k in range(6):
        i, j = k + 1, (k + 1) % 6 + 1
        lines.append(f"f {i} {j} {j + 6} {i + 6}")
    lines[-1] = "f -7 -12 -6 -1"  # the last side face "f 6 1 7 12" with relative indices
    path = tmp_path / "prism.obj"
    path.write_text("\n".join(lines) + "\n")
    mesh = read_mesh(path, frame="z_down")
    assert mesh.volume == pytest.approx(1.5 * np.sqrt(3.0) * a**2 * h, rel=1e-12)


def test_format_override_and_detection(tmp_path: Path) -> None:
    path = write_mesh(box(), tmp_path / "hull.txt", format="nemoh")
    assert path.read_text().startswith("2 0")
    assert read_mesh(path, format="dat").volume == L * B * H
    assert detect_format("a/b/HULL.GDF") == "gdf"
    assert detect_format("x.mesh", "wamit") == "gdf"
    with pytest.raises(ValueError, match="extension"):
        read_mesh(path)
    with pytest.raises(ValueError, match="unknown mesh format"):
        detect_format("x.stl", "iges")


# ---------------------------------------------------------------------- frames
def test_z_up_file_becomes_z_down(tmp_path: Path) -> None:
    file_box = box(x=(0.0, L), y=(0.5, 4.5), z=(-2.0, 1.0))
    path = write_mesh(file_box, tmp_path / "zup.obj", frame="z_down")  # coordinates as given
    mesh = read_mesh(path)  # default frame="z_up"
    np.testing.assert_array_equal(mesh.bounds, [[0.0, -4.5, -1.0], [L, -0.5, 2.0]])
    assert mesh.volume == pytest.approx(L * 4.0 * 3.0, rel=1e-12)
    as_is = read_mesh(path, frame="z_down")
    np.testing.assert_array_equal(as_is.bounds, [[0.0, 0.5, -2.0], [L, 4.5, 1.0]])


def test_write_z_up_then_read_z_down_mirrors(tmp_path: Path) -> None:
    mesh = sphere()
    read = read_mesh(write_mesh(mesh, tmp_path / "s.gdf"), frame="z_down")
    _match(read.vertices * [1.0, -1.0, -1.0], mesh.vertices)
    assert read.volume == pytest.approx(mesh.volume, rel=1e-12)


def test_scale_then_translate(tmp_path: Path) -> None:
    mm = box(x=(0.0, 10_000.0), y=(-2_000.0, 2_000.0), z=(0.0, 3_000.0))
    path = write_mesh(mm, tmp_path / "mm.dat", frame="z_down")
    mesh = read_mesh(path, frame="z_down", scale=1e-3, translate=(-5.0, 0.0, -2.0))
    np.testing.assert_allclose(mesh.bounds, [[-5.0, -2.0, -2.0], [5.0, 2.0, 1.0]], atol=1e-12)


def test_bad_arguments(tmp_path: Path) -> None:
    path = write_mesh(box(), tmp_path / "b.obj")
    with pytest.raises(ValueError, match="frame"):
        read_mesh(path, frame="y_up")  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="scale"):
        read_mesh(path, scale=-1.0)
    with pytest.raises(ValueError, match="translate"):
        read_mesh(path, translate=(0.0, 1.0))


# ---------------------------------------------------------------------- symmetric halves
def _half_box_panels(drop: tuple[str, ...]) -> np.ndarray:
    """Panels (n, 4, 3) of the part y >= 0 (and x >= 0 if "x0" dropped) of the L×B×H box."""
    x = (0.0, L / 2) if "x0" in drop else (-L / 2, L / 2)
    half = box(x=x, y=(0.0, B / 2), drop=drop)
    return half.vertices[half.faces]


def test_gdf_isy_half_is_mirrored_to_the_full_closed_hull(tmp_path: Path) -> None:
    path = tmp_path / "half.gdf"
    path.write_text(_gdf_text(_half_box_panels(("y0",)), isx=0, isy=1))
    mesh = read_mesh(path)
    assert mesh.volume == pytest.approx(L * B * H, rel=1e-12)
    np.testing.assert_allclose(mesh.bounds, [[-L / 2, -B / 2, -H / 2], [L / 2, B / 2, H / 2]])


def test_gdf_isx_isy_quarter_is_mirrored_twice(tmp_path: Path) -> None:
    path = tmp_path / "quarter.gdf"
    path.write_text(_gdf_text(_half_box_panels(("y0", "x0")), isx=1, isy=1))
    mesh = read_mesh(path)
    assert mesh.volume == pytest.approx(L * B * H, rel=1e-12)
    assert mesh.n_faces == 2 * 2 + 2 * 2 + 2 * 4  # sides and ends in halves, deck/bottom quarters


def test_gdf_half_without_flag_fails_with_symmetry_hint(tmp_path: Path) -> None:
    path = tmp_path / "half.gdf"
    path.write_text(_gdf_text(_half_box_panels(("y0",)), isx=0, isy=0))
    with pytest.raises(MeshError, match=r"watertight.*y = 0.*ISY = 1") as err:
        read_mesh(path)
    assert str(path) in str(err.value)


def test_nemoh_symmetric_half(tmp_path: Path) -> None:
    half = box(y=(0.0, B / 2), drop=("y0",))
    path = write_mesh(half, tmp_path / "half.dat")
    text = path.read_text()
    with pytest.raises(MeshError, match="'2 1'"):
        read_mesh(path)
    path.write_text(text.replace("2 0", "2 1", 1))
    assert read_mesh(path).volume == pytest.approx(L * B * H, rel=1e-12)


# ---------------------------------------------------------------------- orientation
@pytest.mark.parametrize("case", list(WRITE_CASES))
def test_inward_normals_fail_then_fixed(tmp_path: Path, case: str) -> None:
    path = _write(box().flipped(), tmp_path, case)
    with pytest.raises(MeshError, match="orientation") as err:
        read_mesh(path)
    assert "fix_orientation=True" in str(err.value)
    assert str(path) in str(err.value)
    mesh = read_mesh(path, fix_orientation=True)
    mesh.check()
    assert mesh.volume == L * B * H


def test_inward_wetted_surface_open_at_waterline(tmp_path: Path) -> None:
    """An open BEM mesh (no lid at z = 0) with inward normals is detected and fixed."""
    wetted = box(z=(0.0, 2.0), drop=("z0",))
    path = write_mesh(wetted.flipped(), tmp_path / "wet.gdf")
    with pytest.raises(MeshError, match="orientation"):
        read_mesh(path, closed=False)
    mesh = read_mesh(path, closed=False, fix_orientation=True)
    assert np.sum(mesh.vector_areas[:, 2] * mesh.centroids[:, 2]) == pytest.approx(L * B * 2.0)
    assert read_mesh(write_mesh(wetted, tmp_path / "ok.gdf"), closed=False).n_faces == 5


def test_wetted_surface_read_as_closed_hints_closed_false(tmp_path: Path) -> None:
    path = write_mesh(box(z=(0.0, 2.0), drop=("z0",)), tmp_path / "wet.obj")
    with pytest.raises(MeshError, match=r"watertight.*closed=False"):
        read_mesh(path)


# ---------------------------------------------------------------------- broken files
@pytest.mark.parametrize("case", list(WRITE_CASES))
def test_open_mesh_fails_naming_the_file(tmp_path: Path, case: str) -> None:
    path = _write(box(drop=("x1",)), tmp_path, case, stem="open_hull")
    with pytest.raises(MeshError, match="watertight") as err:
        read_mesh(path)
    assert str(path) in str(err.value)
    assert read_mesh(path, closed=False).n_faces in (5, 10)


@pytest.mark.parametrize("case", list(WRITE_CASES))
def test_truncated_file_fails_clearly(tmp_path: Path, case: str) -> None:
    path = _write(sphere(), tmp_path, case)
    data = path.read_bytes()
    path.write_bytes(data[: int(0.6 * len(data))])
    with pytest.raises(MeshError) as err:
        read_mesh(path)
    message = str(err.value)
    assert str(path) in message
    assert "truncated" in message.replace(str(path), "")
    if case == "gdf":
        assert "NPAN = 84" in message


def test_gdf_with_more_panels_than_npan(tmp_path: Path) -> None:
    path = write_mesh(box(), tmp_path / "b.gdf")
    lines = path.read_text().splitlines()
    lines[3] = "5"
    path.write_text("\n".join(lines) + "\n")
    with pytest.raises(MeshFileError, match=r"NPAN = 5.*6 complete panel\(s\)\); wrong NPAN"):
        read_mesh(path)


@pytest.mark.parametrize("suffix", [".stl", ".gdf", ".dat", ".obj"])
def test_empty_file(tmp_path: Path, suffix: str) -> None:
    path = tmp_path / f"empty{suffix}"
    path.write_text("\n  \n")
    with pytest.raises(MeshFileError, match="file is empty"):
        read_mesh(path)


def test_file_without_panels(tmp_path: Path) -> None:
    path = tmp_path / "points.obj"
    path.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\n")
    with pytest.raises(MeshFileError, match="no panels"):
        read_mesh(path)


@pytest.mark.parametrize("case", ["obj", "gdf", "stl"])
def test_non_finite_coordinates(tmp_path: Path, case: str) -> None:
    mesh = box()
    v = mesh.vertices.copy()
    path = _write(mesh, tmp_path, case, frame="z_down")
    if case == "stl":
        data = bytearray(path.read_bytes())
        data[84 + 12 : 84 + 16] = struct.pack("<f", np.nan)  # x of the first vertex
        path.write_bytes(bytes(data))
    else:
        old = repr(float(v[mesh.faces[0, 0], 0]))
        text = path.read_text()
        start = text.index("\n", text.index("v ") if case == "obj" else 20)
        path.write_text(text[:start] + text[start:].replace(old, "inf", 1))
    with pytest.raises(MeshFileError, match="non-finite") as err:
        read_mesh(path, frame="z_down")
    assert str(path) in str(err.value)


def test_not_a_nemoh_file(tmp_path: Path) -> None:
    path = tmp_path / "x.dat"
    path.write_text("1 2 3\n")
    with pytest.raises(MeshFileError, match="'2 0' or '2 1'"):
        read_mesh(path)


# ---------------------------------------------------------------------- atomic writes
def test_failed_write_leaves_old_file_intact(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    path = write_mesh(box(), tmp_path / "hull.gdf")
    before = path.read_bytes()

    def broken_writer(fh, vertices, faces, title, frame) -> None:
        fh.write(b"half a file")
        raise RuntimeError("disk full (simulated)")

    monkeypatch.setitem(mesh_io._WRITERS, "gdf", broken_writer)
    with pytest.raises(RuntimeError, match="simulated"):
        write_mesh(sphere(), path)
    assert path.read_bytes() == before
    assert sorted(p.name for p in tmp_path.iterdir()) == ["hull.gdf"]
    assert read_mesh(path).volume == L * B * H


def test_unwritable_target_leaves_no_debris(tmp_path: Path) -> None:
    target = tmp_path / "taken.obj"
    target.mkdir()
    (target / "keep").write_text("x")
    with pytest.raises(OSError):
        write_mesh(box(), target)
    assert sorted(p.name for p in tmp_path.iterdir()) == ["taken.obj"]
    assert (target / "keep").read_text() == "x"
    with pytest.raises(FileNotFoundError):
        write_mesh(box(), tmp_path / "no_such_dir" / "b.obj")


def test_rewrite_keeps_permissions(tmp_path: Path) -> None:
    path = write_mesh(box(), tmp_path / "hull.stl")
    os.chmod(path, 0o640)
    write_mesh(sphere(), path)
    assert stat.S_IMODE(path.stat().st_mode) == 0o640
    _assert_same_mesh(read_mesh(path), sphere(), triangulated=True)
