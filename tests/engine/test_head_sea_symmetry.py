"""A port–starboard symmetric ship in head or following seas stays upright (issue #13, item 5).

Nothing in the physics can roll, sway or yaw a symmetric hull heading into (or away from) the
waves: the Froude–Krylov triangulation is mirror-symmetric (tests/forces/
test_froude_krylov_symmetry.py) and the bundled database is symmetrised
(:func:`ship_gym.hydro.database.symmetrise`; the BEM's round-off couplings of ≈ 2e-5 rolled the
ship by ≈ 1e-5 rad before). Criterion: |roll|, |yaw| < 1e-12 rad and |sway| < 1e-12 L over the
run (measured ≤ 9e-14 rad and ≤ 6e-11 m at 8 m/s: round-off of the 6-DOF integration), with the
default force set: nonlinear FK, state-space radiation with the forward-speed terms,
diffraction, viscous roll damping.
"""

from __future__ import annotations

import numpy as np
import pytest

from ship_gym.engine.ship import ShipSetup, build_simulator
from ship_gym.hydro import load_database, symmetrise
from ship_gym.hydro.database import as_arrays
from ship_gym.waves.sea_state import IrregularSea, RegularWave

SEAS = {
    "regular-head": (RegularWave(6.0, period=10.6), 180.0),
    "irregular-following": (IrregularSea(hs=5.0, tp=11.0, n_components=30), 0.0),
}


@pytest.mark.parametrize("speed", [0.0, 8.0])
@pytest.mark.parametrize("case", sorted(SEAS))
def test_symmetric_ship_stays_upright(case, speed):
    sea, beta = SEAS[case]
    sim = build_simulator(
        ShipSetup(speed=speed), sea, wave_heading=np.radians(beta), rng=np.random.default_rng(1)
    )
    res = sim.run(60.0)
    assert np.abs(res.eta[:, 2] - res.eta[0, 2]).max() > 0.1  # the ship does move
    assert np.abs(res.eta[:, 3]).max() < 1e-12
    assert np.abs(res.eta[:, 5]).max() < 1e-12
    assert np.abs(res.eta[:, 1]).max() < 1e-12 * 175.0


def test_symmetrise_removes_exactly_what_symmetry_forbids():
    raw = load_database("s175")  # bundled: already symmetrised
    assert "port_starboard_symmetrised" in raw.attrs
    arr = as_arrays(raw)
    sym, anti = [0, 2, 4], [1, 3, 5]
    for matrix in (arr.added_mass, arr.radiation_damping):
        assert np.all(matrix[:, sym][:, :, anti] == 0.0)
        assert np.all(matrix[:, anti][:, :, sym] == 0.0)
    beta = np.degrees(arr.wave_direction)
    for b in (0.0, 180.0):
        j = int(np.argmin(np.abs(beta - b)))
        assert np.all(arr.excitation_force[:, j][:, anti] == 0.0)
    # idempotent, and the symmetric parts untouched
    again = symmetrise(raw)
    np.testing.assert_array_equal(as_arrays(again).added_mass, arr.added_mass)
    np.testing.assert_array_equal(as_arrays(again).excitation_force, arr.excitation_force)


def test_symmetrise_refuses_an_asymmetric_hull():
    ds = load_database("s175").copy(deep=True)
    a = ds["added_mass"]
    a.loc[{"influenced_dof": "Heave", "radiating_dof": "Roll"}] = 0.1 * a.sel(
        influenced_dof="Heave", radiating_dof="Heave"
    )
    with pytest.raises(ValueError, match="not look port/starboard symmetric"):
        symmetrise(ds)
