"""Bad input files of the hydrodynamic readers (issue 15, item 6).

Every case asserts the error type and that the message names the file and what was expected
(or the variable and the problem, for a database that opens but fails validation).
"""

from __future__ import annotations

import os
import warnings
from collections.abc import Callable
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from ship_gym.hydro import database, frames, load_database, open_database
from ship_gym.hydro.checks import DatabaseError
from ship_gym.hydro.database import DatabaseFileError, save_database
from ship_gym.hydro.wamit import WamitFileError, read_wamit
from tests.hydro.test_database_io import synthetic_database

EXPECTED = "expected a hydrodynamic database written by ship-gym hydro"


# ====================================================================== not a database at all
def _good_bytes(tmp_path: Path) -> bytes:
    path = save_database(synthetic_database(), tmp_path / "good_source.nc")
    data = path.read_bytes()
    path.unlink()
    return data


def _write(path: Path, data: bytes) -> Path:
    path.write_bytes(data)
    return path


def _random(n: int, seed: int) -> Callable[[Path], bytes]:
    return lambda tmp: np.random.default_rng(seed).bytes(n)


def _truncated(fraction: float) -> Callable[[Path], bytes]:
    def make(tmp: Path) -> bytes:
        data = _good_bytes(tmp)
        return data[: max(9, int(len(data) * fraction))]

    return make


def _hdf5_signature_garbage(tmp: Path) -> bytes:
    return b"\x89HDF\r\n\x1a\n" + np.random.default_rng(7).bytes(2000)


UNREADABLE: dict[str, Callable[[Path], bytes]] = {
    "empty": lambda tmp: b"",
    "one_space": lambda tmp: b" ",
    "random_16": _random(16, 0),
    "random_1k": _random(1024, 1),
    "random_64k": _random(65536, 2),
    "text_hello": lambda tmp: b"hello, this is not a database\n",
    "text_csv": lambda tmp: b"t,roll,pitch\n0.0,0.1,0.2\n0.1,0.2,0.3\n",
    "json": lambda tmp: b'{"added_mass": [1, 2, 3]}',
    "png_header": lambda tmp: b"\x89PNG\r\n\x1a\n" + bytes(100),
    "gzip_header": lambda tmp: b"\x1f\x8b\x08\x00" + bytes(100),
    "zip_header": lambda tmp: b"PK\x03\x04" + bytes(100),
    "hdf5_signature_then_garbage": _hdf5_signature_garbage,
    "netcdf3_magic_only": lambda tmp: b"CDF\x01",
    "truncated_1pct": _truncated(0.01),
    "truncated_10pct": _truncated(0.10),
    "truncated_50pct": _truncated(0.50),
    "truncated_90pct": _truncated(0.90),
    "truncated_99pct": _truncated(0.99),
}


@pytest.mark.parametrize("kind", sorted(UNREADABLE))
def test_unreadable_file_names_the_file_and_the_expected_content(tmp_path: Path, kind) -> None:
    path = _write(tmp_path / f"bad_{kind}.nc", UNREADABLE[kind](tmp_path))
    with pytest.raises(DatabaseFileError) as err:
        open_database(path)
    message = str(err.value)
    assert path.name in message
    assert EXPECTED in message
    assert isinstance(err.value, ValueError)  # caught by the CLI's ValueError handler
    # the same through load_database, with a str and a Path
    with pytest.raises(DatabaseFileError, match=path.name):
        load_database(str(path))


def test_missing_path_and_directory(tmp_path: Path) -> None:
    with pytest.raises(FileNotFoundError) as err:
        open_database(tmp_path / "nowhere.nc")
    assert "nowhere.nc" in str(err.value) and "added_mass" in str(err.value)
    with pytest.raises(FileNotFoundError, match=r"nowhere\.nc"):
        load_database(tmp_path / "nowhere.nc")
    folder = tmp_path / "folder.nc"
    folder.mkdir()
    with pytest.raises(IsADirectoryError) as err:
        open_database(folder)
    assert "folder.nc" in str(err.value) and "directory" in str(err.value)
    with pytest.raises(IsADirectoryError, match=r"folder\.nc"):
        load_database(folder)


def test_wrong_argument_types_are_refused() -> None:
    with pytest.raises(TypeError, match="bundled name"):
        load_database(3.5)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="validate must be"):
        open_database("x.nc", validate="sometimes")  # type: ignore[arg-type]
    with pytest.raises(TypeError, match="bogus"):
        open_database("x.nc", bogus=1)


# ====================================================================== NetCDF, but not a database
def _simulation_output() -> xr.Dataset:
    t = np.arange(0.0, 10.0, 0.1)
    return xr.Dataset(
        {
            "eta": (("t", "dof"), np.zeros((t.size, 6))),
            "nu": (("t", "dof"), np.zeros((t.size, 6))),
            "elevation": (("t",), np.zeros(t.size)),
        },
        coords={"t": t, "dof": ["Surge", "Sway", "Heave", "Roll", "Pitch", "Yaw"]},
        attrs={"title": "ship-gym simulate"},
    )


def _weather() -> xr.Dataset:
    return xr.Dataset(
        {"temperature": (("lat", "lon"), np.ones((3, 4)))},
        coords={"lat": [0.0, 1.0, 2.0], "lon": [0.0, 1.0, 2.0, 3.0]},
    )


FOREIGN: dict[str, tuple[Callable[[], xr.Dataset], str | None]] = {
    "simulation_output": (_simulation_output, "simulation output"),
    "weather_grid": (_weather, "temperature"),
    "empty_dataset": (lambda: xr.Dataset(attrs={"title": "nothing"}), "none"),
    "damping_only": (
        lambda: synthetic_database()[["radiation_damping"]],
        "'added_mass'",
    ),
    "added_mass_only": (
        lambda: synthetic_database()[["added_mass"]],
        "'radiation_damping'",
    ),
}


@pytest.mark.parametrize("kind", sorted(FOREIGN))
@pytest.mark.parametrize("engine", ["default", "netcdf3"])
def test_netcdf_that_is_not_a_database_is_refused_on_open(tmp_path: Path, kind, engine) -> None:
    make, needle = FOREIGN[kind]
    path = tmp_path / f"foreign_{kind}.nc"
    ds = make()
    if engine == "netcdf3":
        ds.to_netcdf(path, engine="scipy")
    else:
        ds.to_netcdf(path, engine=database.netcdf_engine())
    with pytest.raises(DatabaseFileError) as err:
        open_database(path)
    message = str(err.value)
    assert path.name in message and "Expected a hydrodynamic database" in message
    if needle is not None:
        assert needle in message


def test_a_real_simulation_output_is_refused(tmp_path: Path) -> None:
    """What ``ship-gym simulate --output x.nc`` writes: ``SimulationResult.to_dataset()``."""
    from ship_gym.engine.ship import ShipSetup, build_simulator

    sim = build_simulator(ShipSetup(radiation="none", viscous_roll=False, dt=0.1), None)
    ds = sim.run(0.5).to_dataset()
    path = tmp_path / "simulation.nc"
    ds.to_netcdf(path, engine=database.netcdf_engine())
    with pytest.raises(DatabaseFileError) as err:
        open_database(path)
    assert "simulation.nc" in str(err.value) and "simulation output" in str(err.value)
    assert "Expected a hydrodynamic database" in str(err.value)


# ============================================================ databases that fail validation
def _set(var: str, index: tuple, value: float) -> Callable[[xr.Dataset], xr.Dataset]:
    def f(ds: xr.Dataset) -> xr.Dataset:
        ds[var].values.__setitem__(index, value)
        return ds

    return f


def _nan_everywhere(var: str) -> Callable[[xr.Dataset], xr.Dataset]:
    def f(ds: xr.Dataset) -> xr.Dataset:
        ds[var].values[1:-1] = np.nan
        return ds

    return f


def _negative_damping_everywhere(ds: xr.Dataset) -> xr.Dataset:
    ds["radiation_damping"].values[1:-1, 3, 3] *= -1.0
    return ds


def _asymmetric_damping(ds: xr.Dataset) -> xr.Dataset:
    ds["radiation_damping"].values[5:10, 2, 4] = 5.0 * np.abs(ds["radiation_damping"].values).max()
    return ds


def _wrong_dims(ds: xr.Dataset) -> xr.Dataset:
    return ds.assign(
        added_mass=ds["added_mass"].rename(influenced_dof="dof_a", radiating_dof="dof_b")
    )


def _transposed_excitation_dims(ds: xr.Dataset) -> xr.Dataset:
    ex = ds["excitation_force"].isel(wave_direction=0, drop=True)
    return ds.drop_vars(["excitation_force", "Froude_Krylov_force", "diffraction_force"]).assign(
        excitation_force=ex
    )


def _swapped_dofs(ds: xr.Dataset) -> xr.Dataset:
    return ds.assign_coords(influenced_dof=["Sway", "Surge", "Heave", "Roll", "Pitch", "Yaw"])


INVALID: dict[str, tuple[Callable[[xr.Dataset], xr.Dataset], tuple[str, ...]]] = {
    "nan_damping_one": (
        _set("radiation_damping", (4, 2, 2), np.nan),
        ("radiation_damping", "non-finite"),
    ),
    "nan_damping_all": (_nan_everywhere("radiation_damping"), ("radiation_damping", "non-finite")),
    "inf_added_mass": (_set("added_mass", (3, 0, 0), np.inf), ("added_mass", "non-finite")),
    "nan_added_mass_inf": (_set("added_mass", (-1, 3, 3), np.nan), ("added_mass", "non-finite")),
    "negative_heave_damping": (
        _set("radiation_damping", (6, 2, 2), -1e6),
        ("B[Heave,Heave]", "negative"),
    ),
    "negative_roll_damping": (_negative_damping_everywhere, ("B[Roll,Roll]", "negative")),
    "damping_at_zero_frequency": (_set("radiation_damping", (0, 2, 2), 1.0), ("omega = 0",)),
    "asymmetric_added_mass": (_set("added_mass", (5, 2, 4), 1e9), ("added_mass", "not symmetric")),
    "asymmetric_damping": (_asymmetric_damping, ("radiation_damping", "not symmetric")),
    "missing_a_inf": (lambda ds: ds.isel(omega=slice(0, -1)), ("A(inf) is missing",)),
    "one_frequency": (lambda ds: ds.isel(omega=[0, 1, -1]), ("only 1 finite frequencies",)),
    "missing_inertia": (lambda ds: ds.drop_vars("inertia_matrix"), ("'inertia_matrix'",)),
    "missing_stiffness": (
        lambda ds: ds.drop_vars("hydrostatic_stiffness"),
        ("'hydrostatic_stiffness'",),
    ),
    "missing_excitation": (lambda ds: ds.drop_vars("excitation_force"), ("'excitation_force'",)),
    "wrong_dims_added_mass": (_wrong_dims, ("'added_mass'", "dims")),
    "excitation_without_heading": (_transposed_excitation_dims, ("'excitation_force'", "dims")),
    "swapped_dof_labels": (_swapped_dofs, ("influenced_dof",)),
    "negative_c33": (_set("hydrostatic_stiffness", (2, 2), -1.0), ("C33",)),
    "zero_c44": (_set("hydrostatic_stiffness", (3, 3), 0.0), ("C44",)),
    "nan_excitation": (
        _set("excitation_force", (3, 0, 0), np.nan),
        ("excitation_force", "non-finite"),
    ),
    "nan_inertia": (_set("inertia_matrix", (0, 0), np.nan), ("inertia_matrix", "non-finite")),
}


@pytest.mark.parametrize("kind", sorted(INVALID))
def test_invalid_database_is_refused_on_open_naming_file_variable_problem(
    tmp_path: Path, kind
) -> None:
    corrupt, needles = INVALID[kind]
    path = save_database(corrupt(synthetic_database()), tmp_path / f"db_{kind}.nc")
    with pytest.raises(DatabaseFileError) as err:
        open_database(path)
    message = str(err.value)
    assert path.name in message and "is invalid" in message
    for needle in needles:
        assert needle in message, (needle, message)
    assert isinstance(err.value, DatabaseError) and isinstance(err.value, ValueError)
    with pytest.raises(DatabaseFileError, match=path.name):
        load_database(path)


def test_validation_can_be_skipped_or_relaxed(tmp_path: Path) -> None:
    path = save_database(synthetic_database().isel(omega=slice(0, -1)), tmp_path / "no_inf.nc")
    assert open_database(path, validate="none").sizes["omega"] == 25
    assert open_database(path, validate="data").sizes["omega"] == 25
    assert open_database(path, require_infinite=False).sizes["omega"] == 25
    with pytest.raises(DatabaseFileError, match="A\\(inf\\)"):
        open_database(path, validate="full")


def test_short_frequency_coverage_warns_unless_its_limits_are_given(tmp_path: Path) -> None:
    path = save_database(
        synthetic_database().isel(omega=[0, 1, 2, 3, 4, 5, -1]), tmp_path / "few.nc"
    )
    with pytest.warns(UserWarning, match=r"few\.nc.*(?s:.*)only 5 finite frequencies"):
        open_database(path)
    with pytest.raises(DatabaseFileError, match=r"few\.nc(?s:.*)only 5 finite frequencies"):
        open_database(path, min_frequencies=10)
    with pytest.raises(DatabaseFileError, match="natural frequency"):
        open_database(path, min_frequencies=3, min_omega_ratio=1.5)


def test_negative_damping_within_tolerance_is_accepted(tmp_path: Path) -> None:
    ds = synthetic_database()
    peak = ds["radiation_damping"].values[:, 2, 2].max()
    ds["radiation_damping"].values[1, 2, 2] = -1e-3 * peak  # BEM noise, below the 1 % tolerance
    path = save_database(ds, tmp_path / "noise.nc")
    open_database(path)
    with pytest.raises(DatabaseFileError, match="negative radiation damping"):
        open_database(path, damping_tolerance=1e-4)


def test_capytaine_export_with_nan_damping_is_refused(tmp_path: Path) -> None:
    from capytaine.io.xarray import export_dataset

    ours = synthetic_database(n_omega=12)
    ours["radiation_damping"].values[3, 2, 2] = np.nan
    capy = frames.dataset_to_capytaine(ours)
    capy.attrs = {"capytaine_version": "3.0.0"}
    export_dataset(str(tmp_path / "capy_nan.nc"), capy)
    with pytest.raises(DatabaseFileError) as err:
        open_database(tmp_path / "capy_nan.nc")
    assert "capy_nan.nc" in str(err.value) and "radiation_damping" in str(err.value)


def test_incomplete_capytaine_export_opens_with_a_warning(tmp_path: Path) -> None:
    from capytaine.io.xarray import export_dataset

    capy = frames.dataset_to_capytaine(synthetic_database(n_omega=12).isel(omega=slice(0, -1)))
    capy.attrs = {"capytaine_version": "3.0.0"}
    export_dataset(str(tmp_path / "capy_partial.nc"), capy)
    with pytest.warns(UserWarning, match=r"capy_partial\.nc.*(?s:.*)A\(inf\) is missing"):
        ds = open_database(tmp_path / "capy_partial.nc")
    assert ds.sizes["omega"] == 13
    with pytest.raises(DatabaseFileError, match="A\\(inf\\)"):
        open_database(tmp_path / "capy_partial.nc", validate="full")


def test_bundled_database_passes_and_validation_is_cached(monkeypatch) -> None:
    path = database.bundled_database_path("s175")
    if not path.is_file():
        pytest.skip("bundled S175 database not built")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        load_database("s175")
    calls = []
    real = database.validate_database
    monkeypatch.setattr(
        database, "validate_database", lambda ds, **kw: calls.append(1) or real(ds, **kw)
    )
    for _ in range(3):
        load_database("s175")
    assert calls == []  # validated once per file version (the first load above)


def test_a_rewritten_file_is_validated_again(tmp_path: Path) -> None:
    path = save_database(synthetic_database(), tmp_path / "db.nc")
    open_database(path)
    bad = synthetic_database()
    bad["radiation_damping"].values[4, 2, 2] = np.nan
    save_database(bad, path)
    os.utime(path, ns=(1, 1))  # a different modification time even on coarse clocks
    with pytest.raises(DatabaseFileError, match="non-finite"):
        open_database(path)


# ====================================================================== WAMIT files
GOOD_1 = "".join(
    f"  {per:.4f}  {i}  {j}  {1.0 + 0.1 * i:.4f}  {0.5:.4f}\n"
    for per in (20.0, 10.0, 5.0)
    for i in (1, 2, 3)
    for j in (1, 2, 3)
)
GOOD_3 = "".join(
    f"  {per:.4f}  {beta:.1f}  {i}  1.0  0.0  1.0  0.0\n"
    for per in (20.0, 10.0)
    for beta in (0.0, 180.0)
    for i in (1, 2, 3)
)

WAMIT_1: dict[str, tuple[bytes, str]] = {
    "empty": (b"", "is empty"),
    "blank_lines": (b"\n\n   \n", "is empty"),
    "random_bytes": (np.random.default_rng(3).bytes(500), "binary"),
    "nul_bytes": (b"  20.0  1  1  1.0\x00\x00 0.5\n", "binary"),
    "only_text": (b"this is a README, not WAMIT output\nsecond line\n", "no numeric data"),
    "garbage_after_data": ((GOOD_1 + "Traceback (most recent call last)\n").encode(), "line 28"),
    "truncated_mid_row": (GOOD_1[: GOOD_1.rindex("\n", 0, -1) + 8].encode(), "columns"),
    "truncated_at_line": ("".join(GOOD_1.splitlines(True)[:-4]).encode(), "truncated"),
    "nan_value": (GOOD_1.replace("0.5000", "nan", 1).encode(), "non-finite"),
    "mode_out_of_range": (b"  20.0  9  1  1.0  0.5\n", "mode index 9"),
}


@pytest.mark.parametrize("kind", sorted(WAMIT_1))
def test_bad_wamit_1_file(tmp_path: Path, kind) -> None:
    content, needle = WAMIT_1[kind]
    path = _write(tmp_path / f"bad_{kind}.1", content)
    with pytest.raises(WamitFileError) as err:
        read_wamit(file_1=path)
    message = str(err.value)
    assert path.name in message and needle in message, message
    if kind != "mode_out_of_range":
        assert "expected a WAMIT .1 file" in message


WAMIT_3: dict[str, tuple[bytes, str]] = {
    "empty": (b"", "is empty"),
    "random_bytes": (np.random.default_rng(4).bytes(300), "binary"),
    "truncated_mid_row": (GOOD_3[:-9].encode(), "columns"),
    "truncated_at_line": ("".join(GOOD_3.splitlines(True)[:-1]).encode(), "truncated"),
    "text": (b"no numbers here\n", "no numeric data"),
}


@pytest.mark.parametrize("kind", sorted(WAMIT_3))
def test_bad_wamit_3_file(tmp_path: Path, kind) -> None:
    content, needle = WAMIT_3[kind]
    good = _write(tmp_path / "good.1", GOOD_1.encode())
    path = _write(tmp_path / f"bad_{kind}.3", content)
    with pytest.raises(WamitFileError) as err:
        read_wamit(file_1=good, file_3=path)
    message = str(err.value)
    assert path.name in message and needle in message and "expected a WAMIT .3 file" in message


@pytest.mark.parametrize(
    ("content", "needle"),
    [(b"", "is empty"), (b"1 1\n", "columns"), (np.random.default_rng(5).bytes(64), "binary")],
    ids=["empty", "short_row", "random"],
)
def test_bad_wamit_hst_file(tmp_path: Path, content: bytes, needle: str) -> None:
    good = _write(tmp_path / "good.1", GOOD_1.encode())
    path = _write(tmp_path / "bad.hst", content)
    with pytest.raises(WamitFileError) as err:
        read_wamit(file_1=good, file_hst=path)
    assert "bad.hst" in str(err.value) and needle in str(err.value)
    assert "expected a WAMIT .hst file" in str(err.value)


def test_wamit_missing_file_and_directory(tmp_path: Path) -> None:
    with pytest.raises(FileNotFoundError) as err:
        read_wamit(file_1=tmp_path / "gone.1")
    assert "gone.1" in str(err.value) and "WAMIT .1 file" in str(err.value)
    (tmp_path / "dir.1").mkdir()
    with pytest.raises(IsADirectoryError) as err2:
        read_wamit(file_1=tmp_path / "dir.1")
    assert "dir.1" in str(err2.value) and "WAMIT .1 file" in str(err2.value)


def test_good_wamit_text_still_reads(tmp_path: Path) -> None:
    path = _write(tmp_path / "good.1", GOOD_1.encode())
    ds = read_wamit(file_1=path)
    assert ds.sizes["omega"] == 3
