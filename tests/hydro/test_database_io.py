"""NetCDF storage of hydrodynamic databases, loading, accessors and validation errors."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from ship_gym.conventions import BODY_FRAME, DOF_NAMES, TIME_CONVENTION, WAVE_HEADING
from ship_gym.hydro import database, frames
from ship_gym.hydro.checks import DatabaseError, validate_database

RHO, G = 1025.0, 9.81


def synthetic_database(n_omega: int = 24, seed: int = 0) -> xr.Dataset:
    """A physically plausible database in our frame (diagonal-dominant, symmetric, B ≥ 0).

    Heave/pitch/roll added mass and damping follow smooth analytic shapes; couplings are small
    symmetric perturbations; the omega axis holds 0 and inf. Mass 1e6 kg, GM_T 1 m.
    """
    rng = np.random.default_rng(seed)
    w = np.linspace(0.1, 3.0, n_omega)
    omega = np.concatenate([[0.0], w, [np.inf]])
    scale = np.array([1e5, 1e6, 1e6, 1e7, 1e8, 1e8])  # diagonal magnitudes [SI]
    a = np.zeros((len(omega), 6, 6))
    b = np.zeros_like(a)
    shape_a = 1.0 + 0.5 / (1.0 + w**2)  # A(ω) → A(∞) = scale
    shape_b = w**2 * np.exp(-(w**2))  # B(ω) ≥ 0, vanishing at 0 and ∞
    coupling = rng.normal(scale=0.05, size=(6, 6))
    coupling = 0.5 * (coupling + coupling.T)
    np.fill_diagonal(coupling, 1.0)
    base = coupling * np.sqrt(np.outer(scale, scale))
    a[0] = 1.5 * base
    a[1:-1] = shape_a[:, None, None] * base
    a[-1] = base
    b[1:-1] = shape_b[:, None, None] * base
    beta = np.deg2rad([0.0, 45.0, 90.0, 135.0, 180.0])
    f = np.full((len(omega), len(beta), 6), np.nan + 0j)
    phase = rng.uniform(0, 2 * np.pi, size=(len(w), len(beta), 6))
    f[1:-1] = np.sqrt(scale)[None, None, :] * 1e3 * np.exp(1j * phase)
    c = np.diag([0.0, 0.0, 3.0e6, G * 1e6, 5.0e8, 0.0])  # GM_T = C44 / (m g) = 1 m
    m = np.diag([1e6, 1e6, 1e6, 5e7, 8e8, 8e8])
    dims3 = ("omega", "influenced_dof", "radiating_dof")
    dimsf = ("omega", "wave_direction", "influenced_dof")
    ds = xr.Dataset(
        {
            "added_mass": (dims3, a),
            "radiation_damping": (dims3, b),
            "excitation_force": (dimsf, f),
            "Froude_Krylov_force": (dimsf, 0.5 * f),
            "diffraction_force": (dimsf, 0.5 * f),
            "hydrostatic_stiffness": (("influenced_dof", "radiating_dof"), c),
            "inertia_matrix": (("influenced_dof", "radiating_dof"), m),
        },
        coords={
            "omega": omega,
            "wave_direction": beta,
            "influenced_dof": list(DOF_NAMES),
            "radiating_dof": list(DOF_NAMES),
        },
        attrs={
            "frame": BODY_FRAME,
            "time_convention": TIME_CONVENTION,
            "wave_heading": WAVE_HEADING,
            "rho": RHO,
            "g": G,
            "n_panels": 1234,
            "cog": np.array([0.0, 0.0, -1.0]),
            "source": "synthetic",
        },
    )
    with np.errstate(divide="ignore"):
        ds = ds.assign_coords(period=("omega", 2 * np.pi / omega))
    ds["added_mass"].attrs["units"] = "kg, kg m, kg m^2"
    return ds


# ------------------------------------------------------------------------------ round trips
def test_round_trip_of_our_format(tmp_path: Path) -> None:
    ds = synthetic_database()
    path = database.save_database(ds, tmp_path / "db.nc")
    back = database.open_database(path)
    xr.testing.assert_identical(back, ds)
    assert np.isinf(back.omega.values[-1]) and back.omega.values[0] == 0.0
    # the file itself holds only real numbers, readable without ship_gym
    with xr.open_dataset(path) as raw:
        assert "excitation_force_real" in raw and "excitation_force_imag" in raw
        assert "excitation_force" not in raw
        assert not any(np.iscomplexobj(raw[v].values) for v in raw.data_vars)
        assert raw.attrs["ship_gym_format"] == database.FORMAT_VERSION


def test_reads_capytaine_netcdf_export_and_converts_the_frame(tmp_path: Path) -> None:
    from capytaine.io.xarray import export_dataset

    ours = synthetic_database(n_omega=5)
    capy = frames.dataset_to_capytaine(ours)
    capy.attrs = {"capytaine_version": "3.0.0"}  # capytaine files carry no 'frame' attribute
    capy = capy.assign_coords(rho=RHO, g=G, forward_speed=0.0, water_depth=np.inf)
    export_dataset(str(tmp_path / "capy.nc"), capy)
    with xr.open_dataset(tmp_path / "capy.nc") as raw:
        assert "complex" in raw.dims  # capytaine's own layout
    back = database.open_database(tmp_path / "capy.nc")
    assert back.attrs["frame"] == BODY_FRAME
    for name in ours.data_vars:
        scalars = ["rho", "g", "forward_speed", "water_depth"]
        xr.testing.assert_allclose(back[name].drop_vars(scalars), ours[name])


def test_reads_a_real_capytaine_run(tmp_path: Path) -> None:
    """A tiny BEM run exported by capytaine itself opens as frames.dataset_from_capytaine says."""
    import capytaine as cpt
    from capytaine.io.xarray import export_dataset

    mesh = cpt.mesh_sphere(radius=1.0, center=(0, 0, 0), resolution=(6, 12)).immersed_part()
    body = cpt.FloatingBody(
        mesh=mesh, dofs=cpt.rigid_body_dofs(rotation_center=(0, 0, 0)), center_of_mass=(0, 0, 0)
    )
    problems = [cpt.RadiationProblem(body=body, omega=1.0, radiating_dof=d) for d in DOF_NAMES]
    problems += [
        cpt.DiffractionProblem(body=body, omega=1.0, wave_direction=b) for b in (0.0, 0.5 * np.pi)
    ]
    results = cpt.BEMSolver().solve_all(problems, progress_bar=False)
    ds_c = cpt.assemble_dataset(results)
    export_dataset(str(tmp_path / "run.nc"), ds_c)
    back = database.open_database(tmp_path / "run.nc")
    expected = frames.dataset_from_capytaine(ds_c)
    for name in ("added_mass", "radiation_damping", "excitation_force", "hydrostatic_stiffness"):
        xr.testing.assert_allclose(back[name], expected[name].transpose(*back[name].dims))
    # capytaine direction π/2 (toward port) is our 3π/2
    np.testing.assert_allclose(back.wave_direction.values, [0.0, 1.5 * np.pi])


def test_failed_save_leaves_existing_file_untouched(tmp_path: Path, monkeypatch) -> None:
    path = tmp_path / "db.nc"
    database.save_database(synthetic_database(), path)
    before = path.read_bytes()

    bad = synthetic_database()
    bad.attrs["nested"] = {"not": "storable"}
    with pytest.raises(ValueError, match="'nested'"):
        database.save_database(bad, path)
    assert path.read_bytes() == before

    def explode(self, *args, **kwargs):  # fails after the temporary file exists
        Path(args[0]).write_bytes(b"partial garbage")
        raise OSError("disk full")

    monkeypatch.setattr(xr.Dataset, "to_netcdf", explode)
    with pytest.raises(OSError, match="disk full"):
        database.save_database(synthetic_database(seed=3), path)
    assert path.read_bytes() == before
    assert sorted(os.listdir(tmp_path)) == ["db.nc"]  # no temporary file left behind


def test_save_and_open_errors(tmp_path: Path) -> None:
    with pytest.raises(ValueError, match=r"xarray\.Dataset"):
        database.save_database(synthetic_database().added_mass, tmp_path / "x.nc")  # type: ignore[arg-type]
    with pytest.raises(FileNotFoundError, match="does not exist"):
        database.save_database(synthetic_database(), tmp_path / "missing" / "x.nc")
    with pytest.raises(FileNotFoundError, match="not found"):
        database.open_database(tmp_path / "nothing.nc")
    odd = synthetic_database()
    odd.attrs["frame"] = "some other frame"
    database.save_database(odd, tmp_path / "odd.nc")
    with pytest.raises(ValueError, match="some other frame"):
        database.open_database(tmp_path / "odd.nc")


def test_load_database_by_name_and_by_path(tmp_path: Path, monkeypatch) -> None:
    target = tmp_path / "demo" / "demo_hydro.nc"
    monkeypatch.setattr(
        database, "bundled_database_path", lambda name: tmp_path / name / f"{name}_hydro.nc"
    )
    with pytest.raises(FileNotFoundError, match="bundled hydrodynamic database 'demo'"):
        database.load_database("demo")
    target.parent.mkdir()
    database.save_database(synthetic_database(), target)
    # a bundled database is symmetrised only if its hull is symmetric (this one is not); a path
    # is returned as stored
    xr.testing.assert_identical(database.load_database("demo"), synthetic_database())
    xr.testing.assert_identical(database.load_database(target), synthetic_database())
    xr.testing.assert_identical(database.load_database(str(target)), synthetic_database())


def test_bundled_s175_path() -> None:
    path = database.bundled_database_path("s175")
    assert path.parts[-3:] == ("data", "s175", "s175_hydro.nc")
    if not path.is_file():
        with pytest.raises(FileNotFoundError, match="not available"):
            database.load_database("s175")


# ------------------------------------------------------------------------------ accessors
def test_split_frequencies_and_as_arrays() -> None:
    ds = synthetic_database()
    finite, a0, ainf = database.split_frequencies(ds)
    assert finite.sizes["omega"] == ds.sizes["omega"] - 2
    np.testing.assert_array_equal(a0.values, ds.added_mass.values[0])
    np.testing.assert_array_equal(ainf.values, ds.added_mass.values[-1])
    arr = database.as_arrays(ds)
    assert arr.added_mass.shape == (24, 6, 6) and arr.excitation_force.shape == (24, 5, 6)
    np.testing.assert_array_equal(arr.added_mass_infinite, ds.added_mass.values[-1])
    no_inf = ds.isel(omega=slice(0, -1))
    assert database.split_frequencies(no_inf)[2] is None
    with pytest.raises(ValueError, match="infinite-frequency"):
        database.split_frequencies(no_inf, require_infinite=True)


def test_mirror_headings_uses_port_starboard_symmetry() -> None:
    ds = synthetic_database()
    # make the hull symmetric: no coupling between (surge, heave, pitch) and (sway, roll, yaw)
    m = frames.mirror_signs()
    odd = np.outer(m, m) < 0
    for v in ("added_mass", "radiation_damping"):
        ds[v].values[:, odd] = 0.0
    full = database.mirror_headings(ds)
    np.testing.assert_allclose(
        np.rad2deg(full.wave_direction.values), [0, 45, 90, 135, 180, 225, 270, 315]
    )
    f45 = full.excitation_force.sel(wave_direction=np.deg2rad(45)).values
    f315 = full.excitation_force.sel(wave_direction=np.deg2rad(315)).values
    np.testing.assert_allclose(f315, f45 * m)
    asym = synthetic_database()
    asym["added_mass"].values[:, 1, 2] = asym["added_mass"].values[:, 2, 1] = 5e5
    with pytest.raises(ValueError, match="port/starboard symmetric"):
        database.mirror_headings(asym)


# ------------------------------------------------------------------------------ validation
def test_validate_accepts_a_sound_database_and_reports() -> None:
    report = validate_database(synthetic_database())
    assert report["n_frequencies"] == 24
    assert report["has_infinite_frequency"] and report["has_zero_frequency"]
    assert report["max_asymmetry_added_mass"] < 1e-12
    assert report["C33"] > 0 and report["GM_T"] == pytest.approx(1.0)
    assert set(report["natural_periods"]) == {"Heave", "Roll", "Pitch"}


def _corrupt(action) -> xr.Dataset:
    ds = synthetic_database()
    action(ds)
    return ds


@pytest.mark.parametrize(
    ("action", "message"),
    [
        (lambda ds: ds["hydrostatic_stiffness"].values.__setitem__((2, 2), -1.0), "C33"),
        (lambda ds: ds["hydrostatic_stiffness"].values.__setitem__((3, 3), 0.0), "C44"),
        (lambda ds: ds["hydrostatic_stiffness"].values.__setitem__((4, 4), -5.0), "C55"),
        (lambda ds: ds["added_mass"].values.__setitem__((5, 2, 4), 1e9), "added_mass is not sym"),
        (lambda ds: ds["radiation_damping"].values.__setitem__((5, 2, 2), -1e6), "negative"),
        (lambda ds: ds["added_mass"].values.__setitem__((4, 0, 0), np.nan), "non-finite"),
        (lambda ds: ds["excitation_force"].values.__setitem__((3, 0, 0), np.nan), "excitation"),
        (lambda ds: ds.attrs.__setitem__("frame", "z up"), "frame"),
        (lambda ds: ds["radiation_damping"].values.__setitem__((0, 2, 2), 1.0), "omega = 0"),
    ],
)
def test_validate_names_the_problem(action, message) -> None:
    with pytest.raises(DatabaseError, match=message):
        validate_database(_corrupt(action))


def test_validate_structural_problems() -> None:
    ds = synthetic_database()
    with pytest.raises(DatabaseError, match="'inertia_matrix'"):
        validate_database(ds.drop_vars("inertia_matrix"))
    with pytest.raises(DatabaseError, match=r"A\(inf\) is missing"):
        validate_database(ds.isel(omega=slice(0, -1)))
    with pytest.raises(DatabaseError, match="only 5 finite frequencies"):
        validate_database(ds.isel(omega=[0, 1, 2, 3, 4, 5, -1]))
    with pytest.raises(DatabaseError, match="natural frequency"):
        validate_database(ds.isel(omega=[0, 1, 2, 3, 4, 5, -1]), min_frequencies=3)
    swapped = ds.assign_coords(influenced_dof=list(reversed(DOF_NAMES)))
    with pytest.raises(DatabaseError, match="influenced_dof"):
        validate_database(swapped)
    z_up = frames.dataset_to_capytaine(ds)
    with pytest.raises(DatabaseError, match="frame"):
        validate_database(z_up)
    with pytest.raises(DatabaseError, match=r"xarray\.Dataset"):
        validate_database(ds.added_mass)  # type: ignore[arg-type]
    # every problem is listed, not only the first
    two = _corrupt(lambda d: d["hydrostatic_stiffness"].values.__setitem__((2, 2), -1.0))
    two["hydrostatic_stiffness"].values[4, 4] = -1.0
    with pytest.raises(DatabaseError, match=r"(?s)C33.*C55"):
        validate_database(two)


def test_hydro_modules_do_not_import_capytaine_at_import_time() -> None:
    code = (
        "import sys\n"
        "import ship_gym.hydro.frames, ship_gym.hydro.database, ship_gym.hydro.checks\n"
        "import ship_gym.hydro.wamit, ship_gym.hydro.bem\n"
        "assert 'capytaine' not in sys.modules, 'capytaine imported'\n"
    )
    subprocess.run([sys.executable, "-c", code], check=True)
