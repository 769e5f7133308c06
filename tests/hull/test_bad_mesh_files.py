"""Bad mesh files (issue 15, item 6): every case names the file and the format expected."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

import numpy as np
import pytest

from ship_gym.hull.mesh import MeshError, PanelMesh
from ship_gym.hull.mesh_io import MESH_FORMATS, MeshFileError, read_mesh, write_mesh

FORMATS = ("stl", "gdf", "dat", "obj")


def _cube() -> PanelMesh:
    v = np.array([[x, y, z] for z in (0.0, 1.0) for y in (0.0, 1.0) for x in (0.0, 1.0)])
    quads = [
        [0, 2, 3, 1],  # z = 0, normal -z
        [4, 5, 7, 6],  # z = 1, normal +z
        [0, 1, 5, 4],  # y = 0, normal -y
        [2, 6, 7, 3],  # y = 1, normal +y
        [0, 4, 6, 2],  # x = 0, normal -x
        [1, 3, 7, 5],  # x = 1, normal +x
    ]
    return PanelMesh(v, np.array(quads), "cube")


def _good(fmt: str, tmp: Path) -> bytes:
    path = write_mesh(_cube(), tmp / f"good_source.{fmt}")
    data = path.read_bytes()
    path.unlink()
    return data


BAD: dict[str, Callable[[str, Path], bytes]] = {
    "empty": lambda fmt, tmp: b"",
    "whitespace": lambda fmt, tmp: b"  \n\n \t\n",
    "random_bytes": lambda fmt, tmp: np.random.default_rng(11).bytes(777),
    "text": lambda fmt, tmp: b"this is a README file\nnothing else\n",
    "truncated_half": lambda fmt, tmp: _good(fmt, tmp)[: len(_good(fmt, tmp)) // 2],
    "truncated_header": lambda fmt, tmp: _good(fmt, tmp)[:30],
}


@pytest.mark.parametrize("fmt", FORMATS)
@pytest.mark.parametrize("kind", sorted(BAD))
def test_bad_mesh_file_names_the_file_and_the_format(tmp_path: Path, fmt: str, kind: str) -> None:
    path = tmp_path / f"bad_{kind}.{fmt}"
    path.write_bytes(BAD[kind](fmt, tmp_path))
    with pytest.raises(MeshError) as err:
        read_mesh(path)
    message = str(err.value)
    assert path.name in message
    if isinstance(err.value, MeshFileError):
        assert f"expected a {MESH_FORMATS[fmt]}" in message
    else:  # parsed, but the remaining panels do not close the hull
        assert "watertight" in message or "orientation" in message or "normals" in message


@pytest.mark.parametrize("kind", ["empty", "whitespace", "random_bytes", "text"])
@pytest.mark.parametrize("fmt", FORMATS)
def test_unreadable_content_is_a_mesh_file_error(tmp_path: Path, fmt: str, kind: str) -> None:
    path = tmp_path / f"bad_{kind}.{fmt}"
    path.write_bytes(BAD[kind](fmt, tmp_path))
    with pytest.raises(MeshFileError, match=f"expected a {MESH_FORMATS[fmt]}".replace("(", r"\(")
                       .replace(")", r"\)").replace(".", r"\.")):  # fmt: skip
        read_mesh(path)


@pytest.mark.parametrize("fmt", FORMATS)
def test_missing_mesh_and_directory(tmp_path: Path, fmt: str) -> None:
    with pytest.raises(FileNotFoundError) as err:
        read_mesh(tmp_path / f"gone.{fmt}")
    assert f"gone.{fmt}" in str(err.value) and MESH_FORMATS[fmt] in str(err.value)
    folder = tmp_path / f"folder.{fmt}"
    folder.mkdir()
    with pytest.raises(IsADirectoryError) as err2:
        read_mesh(folder)
    assert f"folder.{fmt}" in str(err2.value) and MESH_FORMATS[fmt] in str(err2.value)


@pytest.mark.parametrize("fmt", FORMATS)
def test_good_cube_still_reads(tmp_path: Path, fmt: str) -> None:
    path = write_mesh(_cube(), tmp_path / f"cube.{fmt}")
    assert read_mesh(path).n_faces >= 6
