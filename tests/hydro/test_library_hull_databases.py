"""BEM databases of the library hulls (issue #14): every hull builds, validates and is checked.

Small databases (coarse meshes through the builders' own parameters, 10 frequencies up to the
resolved ω_max, 2 headings) so that each takes seconds. What is checked:

* each database passes :func:`validate_database` with its default tolerances;
* closed forms: the box barge's heave stiffness is ρ g L B (a flat waterplane: exact to
  rounding, 1e-9), the hemisphere's A33(∞) is half the displaced mass, 0.5 ρ (2/3) π a³ (to 4 %:
  the coarse 8 × 24 mesh holds 2 % less volume than the sphere and the one-point panels of
  the curved surface add about as much; finite frequencies against Hulme 1982 are in
  ``tests/validation/test_bem_hemisphere.py``);
* the Wigley hull, whose mesh made capytaine fail with an IndexError (folded panels with three
  vertices on the centre plane at the stem and stern foot, cut by capytaine's clipper into a
  triangle lying in the symmetry plane): the symmetric split keeps every panel, and the
  symmetric solve equals the full-mesh solve (to solver precision with flat panels, to the
  non-planar-panel error on the Wigley hull);
* the box barge's lid covers its waterplane (capytaine's ``generate_lid`` covered 40 % of it);
* broken databases are still refused: wrong damping sign, NaN, a flipped coupling;
* partial results survive a failure: with ``checkpoint=`` a run stopped at the 3rd frequency
  leaves 2 files, and the rerun solves only the others and equals an uninterrupted run;
* capytaine's exceptions come back as :class:`BEMError` naming the hull, ω and a hint.
"""

from __future__ import annotations

import warnings

import numpy as np
import pytest
import xarray as xr

from ship_gym.hull import load_hull
from ship_gym.hydro import bem, frames
from ship_gym.hydro.checks import DatabaseError, validate_database

HEADINGS = np.deg2rad([90.0, 180.0])
SMALL = {
    # 80 immersed panels, 2 over the draught; G low enough for GM > 0 (GM = 1.17 m)
    "box_barge": {"length": 20.0, "beam": 10.0, "draught": 5.0, "kg": 3.0, "panel_size": 2.5},
    "hemisphere": {"n_theta": 8, "n_phi": 24},  # 192 immersed panels
    # ω_max ≥ 1.5 × the heave natural frequency 1.3 rad/s needs panels ≤ 1.9 m in radius
    "wigley": {"n_sections": 50, "n_below": 4, "n_above": 1},  # 392 immersed panels
}


def _database(name: str, **kwargs) -> xr.Dataset:
    hull = load_hull(name, **SMALL[name])
    with warnings.catch_warnings():
        # the coarse hemisphere displaces 2 % less than the sphere's mass: not in equilibrium
        warnings.filterwarnings("ignore", message=".*not in equilibrium")
        return bem.compute_hull_database(
            hull, n_omega=10, wave_directions=HEADINGS, progress=False, **kwargs
        )


class _Databases(dict):
    """Each hull's database, built on first use (one hull per test set-up, < 20 s each)."""

    def __missing__(self, name: str) -> xr.Dataset:
        self[name] = _database(name)
        return self[name]


@pytest.fixture(scope="module")
def databases() -> dict[str, xr.Dataset]:
    return _Databases()


@pytest.mark.parametrize("name", sorted(SMALL))
def test_library_hull_database_is_valid(databases, name) -> None:
    ds = databases[name]
    report = validate_database(ds)
    assert report["n_frequencies"] == 10 and report["has_infinite_frequency"]
    assert ds.attrs["symmetry"] == bem.SYMMETRY_XY  # all three are symmetric fore/aft too
    assert ds.attrs["n_lid_panels"] > 0 and ds.attrs["lid_source"].startswith("conforming")
    # measured (A, B): box 0.012, 0.090; Wigley 0.009, 0.021; hemisphere 0 (only its
    # translations are judged, and they do not couple)
    assert report["max_asymmetry_added_mass"] < 0.05
    assert report["max_asymmetry_damping"] < 0.15


def test_box_barge_heave_stiffness_is_rho_g_l_b(databases) -> None:
    hull = load_hull("box_barge", **SMALL["box_barge"])
    p = SMALL["box_barge"]
    c33 = databases["box_barge"]["hydrostatic_stiffness"].sel(
        influenced_dof="Heave", radiating_dof="Heave"
    )
    assert float(c33) == pytest.approx(hull.rho * hull.g * p["length"] * p["beam"], rel=1e-9)


def test_hemisphere_heave_added_mass_at_infinity_is_half_the_displaced_mass(databases) -> None:
    hull = load_hull("hemisphere", **SMALL["hemisphere"])
    a33 = databases["hemisphere"]["added_mass"].sel(
        omega=np.inf, influenced_dof="Heave", radiating_dof="Heave"
    )
    assert float(a33) == pytest.approx(0.5 * hull.rho * 2.0 / 3.0 * np.pi, rel=0.04)  # 1.8 %


def test_hemisphere_rotations_are_recognised_as_noise(databases) -> None:
    # roll/pitch/yaw about the centre O of a hemisphere displace no water: their damping is BEM
    # noise (1e-5 of the translations'), skipped by the sign check; a real negative damping of
    # a translation is still refused
    ds = databases["hemisphere"]
    report = validate_database(ds)
    assert all(report["min_damping_ratio"][dof] == 0.0 for dof in ("Roll", "Pitch", "Yaw"))
    bad = ds.copy(deep=True)
    bad["radiation_damping"].loc[{"influenced_dof": "Sway", "radiating_dof": "Sway"}] *= -1.0
    with pytest.raises(DatabaseError, match=r"negative radiation damping B\[Sway,Sway\]"):
        validate_database(bad)


def test_wigley_symmetric_split_keeps_every_panel() -> None:
    hull = load_hull("wigley", **SMALL["wigley"])
    mesh = hull.immersed_mesh
    v = frames.points_to_capytaine(mesh.vertices)
    hv, hf = bem._positive_side(v, mesh.faces, 1, name="wigley")
    _, qf = bem._positive_side(hv, hf, 0, name="wigley")
    assert len(hf) == mesh.n_faces // 2  # no panel cut or duplicated
    assert not np.any(np.all(np.abs(hv[hf, 1]) < 1e-9, axis=1))  # none in the plane y = 0
    assert len(qf) >= mesh.n_faces // 4  # even n_sections: the midship panels are cut at x = 0
    # the folded stem/stern-foot panels that broke capytaine's clipper are there
    on_plane = np.sum(np.abs(mesh.vertices[mesh.faces][:, :, 1]) < 1e-9, axis=1)
    assert np.any(on_plane == 3)


@pytest.mark.filterwarnings("ignore:.*not in equilibrium")
@pytest.mark.parametrize(("name", "tolerance"), [("box_barge", 1e-4), ("wigley", 0.03)])
def test_the_symmetric_solve_equals_the_full_mesh_solve(name, tolerance) -> None:
    # Box: flat panels, equal to solver precision (measured 8e-6 of the largest entry). Wigley:
    # capytaine represents a non-planar quad by the two triangles on one of its diagonals,
    # chosen by the vertex order, which a mirror image reverses; the coarse Wigley quads are
    # curved enough for that to move A by up to 1.2 % and B by 1.9 % of their largest entry
    # (measured, lid off or on alike): a discretisation error, not a split error.
    hull = load_hull(name, **SMALL[name])
    kwargs = dict(
        omega=[0.8], wave_directions=[np.pi], zero_frequency=False, infinite_frequency=False,
        progress=False,
    )  # fmt: skip
    sym = bem.compute_hull_database(hull, **kwargs)
    full = bem.compute_hull_database(hull, symmetry=False, **kwargs)
    assert sym.attrs["symmetry"] == bem.SYMMETRY_XY and full.attrs["symmetry"] == "none"
    # the lid is split like the hull: its panels straddling x = 0 (no section at midship with an
    # even n_sections) are cut there, so the symmetric lid may count a few more panels
    assert sym.attrs["n_lid_panels"] >= full.attrs["n_lid_panels"] > 0
    for var in ("added_mass", "radiation_damping", "excitation_force"):
        scale = float(np.abs(full[var]).max())
        np.testing.assert_allclose(
            sym[var].values, full[var].values, rtol=0, atol=tolerance * scale, err_msg=var
        )


def test_box_barge_lid_covers_the_waterplane() -> None:
    hull = load_hull("box_barge", **SMALL["box_barge"])
    mesh = hull.immersed_mesh
    v = frames.points_to_capytaine(mesh.vertices)
    lid = bem._conforming_lid(v, mesh.faces, -bem.lid_depth(mesh))
    assert lid is not None
    lv, lf = lid
    q = lv[lf]
    area = 0.5 * np.abs(np.cross(q[:, 2] - q[:, 0], q[:, 3] - q[:, 1])[:, 2]).sum()
    p = SMALL["box_barge"]
    assert area == pytest.approx(p["length"] * p["beam"], rel=1e-9)


def test_a_broken_database_is_still_refused(databases) -> None:
    ds = databases["box_barge"]
    validate_database(ds)

    def broken(edit) -> xr.Dataset:
        out = ds.copy(deep=True)
        edit(out)
        return out

    def heave_sign(d):
        d["radiation_damping"].loc[{"influenced_dof": "Heave", "radiating_dof": "Heave"}] *= -1

    def nan(d):
        d["added_mass"].values[3, 1, 1] = np.nan

    def coupling_sign(d):  # B[Roll, Sway] of the wrong sign (a frame error in one term)
        d["radiation_damping"].loc[{"influenced_dof": "Roll", "radiating_dof": "Sway"}] *= -1

    def transposed_couplings(d):  # A[Surge, Pitch] entered as A[Pitch, Surge] x 3
        d["added_mass"].loc[{"influenced_dof": "Pitch", "radiating_dof": "Surge"}] *= 3

    for edit, message in (
        (heave_sign, r"negative radiation damping B\[Heave,Heave\]"),
        (nan, "non-finite"),
        (coupling_sign, r"radiation_damping is not symmetric.*\(Sway, Roll\)"),
        (transposed_couplings, r"added_mass is not symmetric.*\(Surge, Pitch\)"),
    ):
        with pytest.raises(DatabaseError, match=message):
            validate_database(broken(edit))


# ------------------------------------------------------------------- checkpoints and errors
BOX_OMEGA = [0.4, 0.8, 1.2, 1.6]  # + 0 and inf: 6 frequencies


def _box(**kwargs) -> xr.Dataset:
    hull = load_hull("box_barge", **SMALL["box_barge"])
    return bem.compute_hull_database(
        hull, omega=BOX_OMEGA, wave_directions=HEADINGS, progress=False, **kwargs
    )


def test_an_interrupted_run_resumes_from_its_checkpoint(tmp_path, monkeypatch) -> None:
    reference = _box()
    real = bem._solve_frequency
    calls: list[float] = []
    stop = [True]

    def stop_at_the_third(*args, **kwargs):
        calls.append(args[2])
        if stop[0] and len(calls) == 3:
            raise KeyboardInterrupt("stopped by the test")  # not an Exception: not wrapped
        return real(*args, **kwargs)

    monkeypatch.setattr(bem, "_solve_frequency", stop_at_the_third)
    checkpoint = tmp_path / "ckpt"
    with pytest.raises(KeyboardInterrupt):
        _box(checkpoint=checkpoint)
    assert len(list(checkpoint.glob("*.npz"))) == 2
    assert not list(checkpoint.glob("*.tmp"))  # atomic writes leave no partial file

    calls.clear()
    stop[0] = False
    resumed = _box(checkpoint=checkpoint)
    assert len(calls) == 4  # 6 frequencies, 2 read back
    assert resumed.attrs["checkpoint_frequencies_reused"] == 2
    assert len(list(checkpoint.glob("*.npz"))) == 6
    for var in reference.data_vars:
        np.testing.assert_allclose(resumed[var].values, reference[var].values, rtol=1e-12)
    xr.testing.assert_equal(resumed.coords.to_dataset(), reference.coords.to_dataset())

    calls.clear()  # a third run solves nothing; another rho solves everything again
    _box(checkpoint=checkpoint)
    assert calls == []
    hull = load_hull("box_barge", **SMALL["box_barge"], rho=1000.0)
    bem.compute_hull_database(
        hull, omega=BOX_OMEGA, wave_directions=HEADINGS, progress=False, checkpoint=checkpoint
    )
    assert len(calls) == 6


def test_the_checkpoint_key_covers_the_problem_definition() -> None:
    hull = load_hull("box_barge", **SMALL["box_barge"])
    mesh = hull.immersed_mesh
    base = dict(
        rho=1025.0, g=9.81, mass_matrix=hull.mass.rigid_body_matrix(), omega=0.5,
        wave_directions=HEADINGS, lid=True, lid_z=0.3, symmetry="xOz+yOz",
        capytaine_version="3.0",
    )  # fmt: skip
    key = bem._checkpoint_key(mesh.vertices, mesh.faces, **base)
    assert key == bem._checkpoint_key(mesh.vertices.copy(), mesh.faces.copy(), **base)
    moved = mesh.vertices + np.array([0.0, 0.0, 1e-9])
    assert bem._checkpoint_key(moved, mesh.faces, **base) != key
    for change in (
        {"rho": 1000.0}, {"g": 9.80665}, {"omega": 0.5000001}, {"lid": False}, {"lid_z": 0.2},
        {"symmetry": "none"}, {"capytaine_version": "3.1"}, {"wave_directions": HEADINGS[:1]},
        {"lid_source": "capytaine generate_lid"},
        {"mass_matrix": 1.01 * base["mass_matrix"]},
    ):  # fmt: skip
        assert bem._checkpoint_key(mesh.vertices, mesh.faces, **{**base, **change}) != key


def test_a_checkpoint_that_is_a_file_is_refused(tmp_path) -> None:
    (tmp_path / "f").write_text("")
    with pytest.raises(ValueError, match="checkpoint must be a directory"):
        _box(checkpoint=tmp_path / "f")


def test_a_capytaine_failure_names_the_hull_the_frequency_and_a_hint(monkeypatch) -> None:
    def broken(solver, body, omega, beta_c, **kwargs):
        if omega == BOX_OMEGA[1]:
            raise IndexError("list index out of range")
        return real(solver, body, omega, beta_c, **kwargs)

    real = bem._solve_frequency
    monkeypatch.setattr(bem, "_solve_frequency", broken)
    with pytest.raises(bem.BEMError) as info:
        _box()
    err = info.value
    assert isinstance(err, RuntimeError) and err.hull == "box_barge" and err.omega == 0.8
    message = str(err)
    assert "box_barge" in message and "omega = 0.8 rad/s" in message
    assert "IndexError" in message and "check the mesh" in message
