"""BEM adapter against analytic and published results, and the signs of the change of frame.

* Floating hemisphere in heave vs Hulme (1982), J. Fluid Mech. 121, 443–463
  (``tests/data/hulme1982_hemisphere_heave.csv``), and A33(∞)/(ρV) = 1/2.
* Long-wave limits that fix every sign of the capytaine → ship_gym conversion (our frame is
  z down, y starboard; β = 0 following seas, π/2 waves travelling toward starboard; complex
  amplitudes x(t) = Re(X e^{-iωt}), incident crest at O at t = 0):

  - heave: a crest over the body pushes it up, i.e. F3 ≈ −C33·a (negative = upward);
  - sway, beam sea travelling toward starboard: the Froude–Krylov force is the pressure-gradient
    force ρV·u̇ of the undisturbed flow, F2 ≈ −i ρ g k V a. In time, Re(−i e^{−iωt}) = −sin ωt: the
    force points to starboard a quarter period *before* the crest reaches O, when the water
    surface over the body slopes down toward starboard (more water on the port side);
  - roll and pitch of a box: the hull follows the wave slope; with p ≈ ρga(1 − kz + ik·r) the
    Froude–Krylov moments are M4 ≈ −i ρ g k a (I_T − V z_B) (β = 90°) and
    M5 ≈ −i ρ g k a (I_L − V z_B) (β = 180°), z_B > 0 the depth of the centre of buoyancy: the
    starboard side goes down / the bow goes up when the surface slopes down that way.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
import xarray as xr

from ship_gym.hull.mesh import PanelMesh
from ship_gym.hydro import bem
from ship_gym.hydro.checks import validate_database
from ship_gym.hydro.database import open_database, save_database, split_frequencies

RHO, G = 1000.0, 9.81
A_RADIUS = 1.0
HULME = Path(__file__).resolve().parents[1] / "data" / "hulme1982_hemisphere_heave.csv"
KA_LOW = 0.05


def hemisphere_mesh(a: float = A_RADIUS, n_theta: int = 20, n_phi: int = 64) -> PanelMesh:
    """Immersed hemisphere (our frame, z down): quads on latitude rings, triangles at the pole.

    Rings at polar angle θ ∈ [0, π/2) from the waterline, n_phi meridians (a multiple of 4 so
    that the mesh is exactly symmetric about both vertical planes); outward normals.
    """
    theta = np.linspace(0.0, 0.5 * np.pi, n_theta + 1)[:-1]
    phi = 2.0 * np.pi * np.arange(n_phi) / n_phi
    c, s = np.cos(phi), np.sin(phi)
    c[np.abs(c) < 1e-12] = 0.0
    s[np.abs(s) < 1e-12] = 0.0
    rings = [np.column_stack([a * np.cos(t) * c, a * np.cos(t) * s, np.full(n_phi, a * np.sin(t))])
             for t in theta]  # fmt: skip
    vertices = np.concatenate([*rings, [[0.0, 0.0, a]]])
    pole = len(vertices) - 1

    def v(i: int, j: int) -> int:
        return i * n_phi + j % n_phi

    faces = []
    for i in range(n_theta):
        for j in range(n_phi):
            if i == n_theta - 1:
                faces.append([v(i, j), v(i, j + 1), pole, pole])
            else:
                faces.append([v(i, j), v(i, j + 1), v(i + 1, j + 1), v(i + 1, j)])
    return PanelMesh(vertices, np.array(faces), "hemisphere")


def box_mesh(length: float, beam: float, draught: float, size: float) -> PanelMesh:
    """Immersed box barge (our frame): bottom at z = T, open at z = 0, outward normals."""
    nx, ny, nz = round(length / size), round(beam / size), max(1, round(draught / size))
    x = np.linspace(-length / 2, length / 2, nx + 1)
    y = np.linspace(-beam / 2, beam / 2, ny + 1)
    z = np.linspace(0.0, draught, nz + 1)
    quads: list[np.ndarray] = []

    def grid(p0, du, dv, nu, nv):
        for i in range(nu):
            for j in range(nv):
                q = [p0 + i * du + j * dv, p0 + (i + 1) * du + j * dv,
                     p0 + (i + 1) * du + (j + 1) * dv, p0 + i * du + (j + 1) * dv]  # fmt: skip
                quads.append(np.array(q))

    dx, dy, dz = x[1] - x[0], y[1] - y[0], z[1] - z[0]
    ex, ey, ez = np.eye(3)
    grid(np.array([x[0], y[0], draught]), dx * ex, dy * ey, nx, ny)  # bottom, normal +z
    grid(np.array([x[0], y[-1], 0.0]), dz * ez, dx * ex, nz, nx)  # starboard side, normal +y
    grid(np.array([x[0], y[0], 0.0]), dx * ex, dz * ez, nx, nz)  # port side, normal -y
    grid(np.array([x[-1], y[0], 0.0]), dy * ey, dz * ez, ny, nz)  # bow, normal +x
    grid(np.array([x[0], y[0], 0.0]), dz * ez, dy * ey, nz, ny)  # stern, normal -x
    pts = np.concatenate(quads)
    key = np.round(pts / (1e-9 * size)).astype(np.int64)
    _, first, inverse = np.unique(key, axis=0, return_index=True, return_inverse=True)
    mesh = PanelMesh(pts[first], inverse.reshape(-1, 4), "box")
    assert mesh.volume > 0.0, "box normals must point outward"
    return mesh


def rigid_body_matrix(mass: float, cog: np.ndarray, radii: np.ndarray) -> np.ndarray:
    """6×6 mass matrix about O for G at ``cog`` (Fossen eq. 3.44), diagonal inertia about G."""
    x, y, z = cog
    s = np.array([[0.0, -z, y], [z, 0.0, -x], [-y, x, 0.0]])
    inertia_g = np.diag(mass * np.asarray(radii) ** 2)
    m = np.zeros((6, 6))
    m[:3, :3] = mass * np.eye(3)
    m[:3, 3:] = -mass * s
    m[3:, :3] = mass * s
    m[3:, 3:] = inertia_g - mass * s @ s
    return m


@pytest.fixture(scope="module")
def hulme() -> np.ndarray:
    return np.loadtxt(HULME, delimiter=",", skiprows=1)


@pytest.fixture(scope="module")
def hemisphere_db(hulme: np.ndarray) -> xr.Dataset:
    mesh = hemisphere_mesh()
    ka = np.concatenate([[KA_LOW], hulme[(hulme[:, 0] >= 0.5) & (hulme[:, 0] <= 2.0), 0]])
    omega = np.sqrt(ka * G / A_RADIUS)
    volume = mesh.volume
    cog = np.array([0.0, 0.0, 0.5 * A_RADIUS])  # G below the centre: GM = a/2 > 0
    m6 = rigid_body_matrix(RHO * volume, cog, np.sqrt(0.4) * A_RADIUS * np.ones(3))
    return bem.compute_database(
        mesh,
        omega=omega,
        wave_directions=np.deg2rad([0.0, 90.0]),
        rho=RHO,
        g=G,
        mass_matrix=m6,
        progress=False,
    )


def _heave(ds: xr.Dataset, var: str) -> xr.DataArray:
    return ds[var].sel(influenced_dof="Heave", radiating_dof="Heave")


# ---------------------------------------------------------------------------- Hulme (1982)
def test_heave_added_mass_and_damping_match_hulme(hemisphere_db, hulme) -> None:
    ds = hemisphere_db
    volume = 2.0 / 3.0 * np.pi * A_RADIUS**3
    finite, a0, ainf = split_frequencies(ds, require_infinite=True)
    omega = finite.omega.values
    ka = omega**2 * A_RADIUS / G
    sel = ka >= 0.5
    a_nd = _heave(finite, "added_mass").values / (RHO * volume)
    b_nd = _heave(finite, "radiation_damping").values / (RHO * volume * omega)
    a_ref = np.interp(ka, hulme[:, 0], hulme[:, 1])
    b_ref = np.interp(ka, hulme[:, 0], hulme[:, 2])
    np.testing.assert_allclose(a_nd[sel], a_ref[sel], rtol=0.03)
    np.testing.assert_allclose(b_nd[sel], b_ref[sel], rtol=0.03)
    assert ainf.sel(influenced_dof="Heave", radiating_dof="Heave") / (RHO * volume) == (
        pytest.approx(0.5, rel=0.03)
    )
    assert a0.sel(influenced_dof="Heave", radiating_dof="Heave") / (RHO * volume) == (
        pytest.approx(hulme[0, 1], rel=0.03)
    )
    # the limits sit on the omega axis, with zero damping and no wave forces
    assert ds.omega.values[0] == 0.0 and np.isinf(ds.omega.values[-1])
    assert np.all(ds.radiation_damping.values[[0, -1]] == 0.0)
    assert np.all(np.isnan(ds.excitation_force.values[[0, -1]]))


def test_database_schema_attributes_and_file_round_trip(hemisphere_db, tmp_path) -> None:
    ds = hemisphere_db
    assert ds.added_mass.dims == ("omega", "influenced_dof", "radiating_dof")
    assert ds.excitation_force.dims == ("omega", "wave_direction", "influenced_dof")
    assert ds.attrs["symmetry"] == "xOz+yOz" and ds.attrs["n_panels"] == 1280
    assert 0.0 < ds.attrs["lid_z"] < 0.05 * A_RADIUS
    assert ds.attrs["rho"] == RHO and ds.attrs["g"] == G
    assert "capytaine 3" in ds.attrs["source"]
    np.testing.assert_allclose(ds.wave_direction.values, [0.0, 0.5 * np.pi])
    report = validate_database(ds, min_frequencies=10, min_omega_ratio=1.0)
    assert report["max_asymmetry_added_mass"] < 0.01
    save_database(ds, tmp_path / "hemisphere.nc")
    xr.testing.assert_identical(open_database(tmp_path / "hemisphere.nc"), ds)


# ---------------------------------------------------------------------------- hydrostatics
def test_hydrostatic_stiffness_is_positive_in_our_frame(hemisphere_db) -> None:
    c = hemisphere_db.hydrostatic_stiffness.values
    volume = hemisphere_mesh().volume
    # a 64-gon waterplane has 0.16 % less area than the circle
    assert c[2, 2] == pytest.approx(RHO * G * np.pi * A_RADIUS**2, rel=0.003)
    # GM = z_G for a hemisphere (metacentre at the centre O): C44 = C55 = ρ g V z_G
    assert c[3, 3] == pytest.approx(RHO * G * volume * 0.5 * A_RADIUS, rel=0.01)
    assert c[4, 4] == pytest.approx(c[3, 3], rel=1e-6)


# ---------------------------------------------------------------------------- wave-force signs
def _low(ds: xr.Dataset) -> xr.Dataset:
    finite, _, _ = split_frequencies(ds)
    return finite.isel(omega=0)


def test_a_crest_pushes_the_hemisphere_up(hemisphere_db) -> None:
    low = _low(hemisphere_db)
    omega = float(low.omega)
    assert omega**2 * A_RADIUS / G == pytest.approx(KA_LOW)
    c33 = float(_heave(hemisphere_db, "hydrostatic_stiffness"))
    f3 = complex(low.excitation_force.sel(wave_direction=0.0, influenced_dof="Heave"))
    assert f3.real == pytest.approx(-c33, rel=0.10)  # upward = negative z
    assert abs(f3.imag) < 0.01 * abs(f3.real)
    # sharper, long-wave theory: F3 = -C33 + (ρV + A33) ω² (vertical fluid acceleration)
    a33 = float(_heave(low, "added_mass"))
    volume = hemisphere_mesh().volume
    assert f3.real == pytest.approx(-c33 + (RHO * volume + a33) * omega**2, rel=0.01)


def test_a_beam_sea_toward_starboard_pushes_the_hemisphere_to_starboard(hemisphere_db) -> None:
    low = _low(hemisphere_db)
    omega = float(low.omega)
    k = omega**2 / G
    volume = hemisphere_mesh().volume
    beam = np.deg2rad(90.0)
    fk2 = complex(low.Froude_Krylov_force.sel(wave_direction=beam, influenced_dof="Sway"))
    # F2 = -i ρ g k V a: starboard force a quarter period before the crest reaches O
    assert fk2.imag == pytest.approx(-RHO * G * k * volume, rel=0.05)
    assert abs(fk2.real) < 0.02 * abs(fk2.imag)
    # with diffraction: G. I. Taylor's long-wave force (ρV + A22) u̇, u̇ = -i ω² a
    f2 = complex(low.excitation_force.sel(wave_direction=beam, influenced_dof="Sway"))
    a22 = float(low.added_mass.sel(influenced_dof="Sway", radiating_dof="Sway"))
    assert f2.imag == pytest.approx(-(RHO * volume + a22) * omega**2, rel=0.03)
    # no sideways force in following seas, no surge force in beam seas
    assert abs(complex(low.excitation_force.sel(wave_direction=0.0, influenced_dof="Sway"))) < (
        1e-6 * abs(f2)
    )
    # axisymmetry: sway in beam seas toward starboard equals surge in following seas (the lid
    # grid, stations along x, is not invariant under a quarter turn: measured 3e-5 at ka = 0.05,
    # rising to 2.3e-3 at ka = 2, where the lid matters most; hence 1e-4 and 5e-3)
    f1 = complex(low.excitation_force.sel(wave_direction=0.0, influenced_dof="Surge"))
    assert f2 == pytest.approx(f1, rel=1e-4)
    for w in hemisphere_db.omega.values[1:-1]:
        fx = hemisphere_db.excitation_force.sel(omega=w)
        assert complex(fx.sel(wave_direction=beam, influenced_dof="Sway")) == pytest.approx(
            complex(fx.sel(wave_direction=0.0, influenced_dof="Surge")), rel=5e-3
        )


def test_box_follows_the_wave_slope_in_roll_and_pitch() -> None:
    # a shallow, wide box, so that I_T and I_L dominate V z_B: the Froude-Krylov moments are
    # then not a small difference, and the one-point panel quadrature of ∫y² dA (relative error
    # Δy²/B² ≈ 0.4 %) does not blur the comparison
    length, beam, draught = 6.0, 4.0, 0.25
    mesh = box_mesh(length, beam, draught, size=0.25)
    volume = length * beam * draught
    assert mesh.volume == pytest.approx(volume)
    k = 0.02
    m6 = rigid_body_matrix(RHO * volume, np.zeros(3), np.array([1.2, 1.8, 2.0]))
    ds = bem.compute_database(
        mesh,
        omega=[np.sqrt(k * G)],
        wave_directions=np.deg2rad([90.0, 180.0]),
        rho=RHO,
        g=G,
        mass_matrix=m6,
        zero_frequency=False,
        infinite_frequency=False,
        progress=False,
    )
    fk = ds.Froude_Krylov_force.isel(omega=0)
    z_b = 0.5 * draught
    i_t = length * beam**3 / 12.0
    i_l = beam * length**3 / 12.0
    m4 = complex(fk.sel(wave_direction=np.deg2rad(90.0), influenced_dof="Roll"))
    m5 = complex(fk.sel(wave_direction=np.deg2rad(180.0), influenced_dof="Pitch"))
    assert m4.imag == pytest.approx(-RHO * G * k * (i_t - volume * z_b), rel=0.03)
    assert m5.imag == pytest.approx(-RHO * G * k * (i_l - volume * z_b), rel=0.03)
    assert abs(m4.real) < 0.02 * abs(m4.imag) and abs(m5.real) < 0.02 * abs(m5.imag)
    # head seas push the box aft-ward at the crest's approach: F1 = -i ρ g k V a cos β, β = π
    f1 = complex(fk.sel(wave_direction=np.pi, influenced_dof="Surge"))
    assert f1.imag == pytest.approx(RHO * G * k * volume, rel=0.03)
    c = ds.hydrostatic_stiffness.values
    assert c[2, 2] == pytest.approx(RHO * G * length * beam)
    gm_t = beam**2 / (12 * draught) - z_b  # BM - depth of B, G at O
    assert c[3, 3] == pytest.approx(RHO * G * volume * gm_t, rel=0.01)  # panel quadrature


# ---------------------------------------------------------------------------- API behaviour
def test_compute_database_rejects_bad_input() -> None:
    mesh = hemisphere_mesh(n_theta=4, n_phi=8)
    m6 = rigid_body_matrix(RHO * mesh.volume, np.zeros(3), np.ones(3))
    kw = dict(omega=[1.0], wave_directions=[0.0], rho=RHO, g=G, mass_matrix=m6, progress=False)
    with pytest.raises(ValueError, match="omega"):
        bem.compute_database(mesh, **{**kw, "omega": [-1.0]})
    with pytest.raises(ValueError, match="duplicate headings"):
        bem.compute_database(mesh, **{**kw, "wave_directions": [0.0, 2 * np.pi]})
    with pytest.raises(ValueError, match="mass_matrix"):
        bem.compute_database(mesh, **{**kw, "mass_matrix": np.eye(3)})
    with pytest.raises(ValueError, match="above the waterline"):
        bem.compute_database(mesh.translated([0.0, 0.0, -0.5]), **kw)
    with pytest.raises(ValueError, match="normals point"):
        bem.compute_database(mesh.flipped(), **kw)
    with pytest.raises(ValueError, match="n_jobs"):
        bem.compute_database(mesh, **{**kw, "n_jobs": 0})
    with pytest.raises(ValueError, match="not port/starboard symmetric"):
        bem.compute_database(mesh.translated([0.0, 0.3, 0.0]), **{**kw, "symmetry": True})


def test_symmetry_detection() -> None:
    mesh = hemisphere_mesh(n_theta=4, n_phi=8)
    v, f = mesh.vertices, mesh.faces
    assert bem.is_mirror_symmetric(v, f, axis=1) and bem.is_mirror_symmetric(v, f, axis=0)
    shifted = mesh.translated([0.2, 0.0, 0.0])
    assert bem.is_mirror_symmetric(shifted.vertices, f, axis=1)
    assert not bem.is_mirror_symmetric(shifted.vertices, f, axis=0)


@pytest.mark.filterwarnings("ignore:.*not in equilibrium")
def test_smoke_compute_hull_database_with_a_library_hull() -> None:
    """Smoke test: the Hull wrapper runs (coarse mesh, one frequency); no physics checked."""
    library = pytest.importorskip("ship_gym.hull.library")
    hull = library.hemisphere(n_theta=5, n_phi=12)
    ds = bem.compute_hull_database(hull, omega=[2.0], wave_directions=[np.pi], progress=False)
    assert ds.sizes["omega"] == 3 and ds.attrs["mesh_name"] == hull.name
    np.testing.assert_allclose(ds.inertia_matrix.values, hull.mass.rigid_body_matrix())
