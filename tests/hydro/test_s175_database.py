"""The bundled S175 database: provenance, consistency with the hull, and its kernels."""

import numpy as np
import pytest

from ship_gym.hull import hydrostatics, load_hull
from ship_gym.hydro import as_arrays, load_database, validate_database
from ship_gym.hydro.retardation import (
    compute_kernels,
    fit_added_mass_infinite,
    kernel_decay,
    reconstruction_error,
)


@pytest.fixture(scope="module")
def db():
    return load_database("s175")


@pytest.fixture(scope="module")
def kernels(db):
    arr = as_arrays(db)
    k = compute_kernels(
        arr.omega,
        arr.added_mass,
        arr.radiation_damping,
        arr.added_mass_infinite,
        t_max=60.0,
        dt=0.05,
        tail="power",
    )
    return arr, k


def test_bundled_database_is_valid_and_documented(db):
    report = validate_database(db)
    assert report["has_zero_frequency"] and report["has_infinite_frequency"]
    for key in ("frame", "time_convention", "rho", "g", "n_panels", "source", "built_by"):
        assert key in db.attrs, key
    assert "capytaine" in db.attrs["source"]


def test_database_agrees_with_hull_hydrostatics_and_mass(db):
    hull = load_hull("s175")
    c = db["hydrostatic_stiffness"].values
    np.testing.assert_allclose(c, hydrostatics(hull).stiffness, rtol=1e-9, atol=1.0)
    assert c[2, 2] > 0 and c[3, 3] > 0 and c[4, 4] > 0
    m = db["inertia_matrix"].values
    np.testing.assert_allclose(m, hull.mass.rigid_body_matrix(), rtol=1e-9, atol=1e-3)


def test_kernels_decay_within_truncation(kernels):
    _, k = kernels
    decay = kernel_decay(k.t, k.K)
    assert decay.all_decayed  # |K| over the last 5 % of 60 s below 1 % of its maximum


def test_ogilvie_reconstruction_where_resolved(kernels):
    # Where the database is resolved (0.2–1.4 rad/s: above the 2π/60 s window, below ω_max
    # 1.67 rad/s), B(ω) comes back within 1 % (measured ≤ 0.2 %).
    # A(ω) carries a nearly constant offset: K only knows B up to ω_max plus the ω⁻⁴ tail, and
    # Kramers–Kronig feels the missing high-frequency damping everywhere. With the BEM A(∞) the
    # offset is ≤ 3.1 % of max|A_ii| (surge/sway/yaw worst); with the A(∞) fitted to the band
    # (fit_added_mass_infinite) the residual is ≤ 0.7 %: bound them at 5 % and 1 %.
    arr, k = kernels
    band = dict(omega_min=0.2, omega_max=1.4)
    diag = np.arange(6)
    sel = (arr.omega >= 0.2) & (arr.omega <= 1.4)
    a_db = arr.added_mass[sel][:, diag, diag]
    for a_inf, bound in (
        (arr.added_mass_infinite, 0.05),
        (fit_added_mass_infinite(k.t, k.K, arr.omega, arr.added_mass, **band), 0.01),
    ):
        err = reconstruction_error(
            k.t, k.K, arr.omega, arr.added_mass, arr.radiation_damping, a_inf, **band
        )
        assert np.all(err.damping[diag, diag] < 0.01)
        a_rec = np.stack(
            [
                np.interp(arr.omega[sel], err.omega, err.added_mass_reconstructed[:, i, i])
                for i in diag
            ],
            axis=1,
        )
        rel = np.max(np.abs(a_rec - a_db), axis=0) / np.max(np.abs(a_db), axis=0)
        assert np.all(rel < bound), rel
