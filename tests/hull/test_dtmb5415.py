"""The DTMB 5415 surface combatant: hydrostatics of the meshed offsets vs the published data.

Published values: SIMMAN 2014, "Geometry and conditions, US Navy combatant" (full scale);
see ``ship_gym/data/dtmb5415/README.md``.
"""

from __future__ import annotations

import numpy as np
import pytest

from ship_gym.hull import hydrostatics, load_hull


@pytest.fixture(scope="module")
def hull():
    return load_hull("dtmb5415")


@pytest.fixture(scope="module")
def hs(hull):
    return hydrostatics(hull)


def test_mesh_is_closed_and_spans_the_ship(hull):
    hull.mesh.check(closed=True)
    lo, hi = hull.mesh.bounds
    # hull from the transom (0.5 m forward of the AP) to the sonar-dome nose at the FP
    assert lo[0] == pytest.approx(-70.52, abs=0.05)
    assert hi[0] == pytest.approx(70.93, abs=0.05)
    # sonar dome 3.0 m below the keel; deck at the assumed D = 12.5 m
    assert hi[2] == pytest.approx(9.16, abs=0.05)
    assert lo[2] == pytest.approx(6.15 - 12.5, abs=1e-9)
    assert hi[1] == pytest.approx(-lo[1])


def test_displacement_and_form_coefficients(hull, hs):
    ref = hull.particulars.reference
    # the offsets are sliced from the benchmark surface model: 0.1 % on volume, which is the
    # published rounding of Cb (0.507 ± 0.0005) and the IGES/table scale mismatch (0.2 %)
    assert hs.volume == pytest.approx(ref["volume_m3"], rel=2e-3)
    cb = hs.volume / (142.0 * 19.06 * 6.15)
    assert cb == pytest.approx(ref["Cb"], abs=2e-3)
    # no published Cw; the waterplane of a transom-stern combatant: 0.77 on Lpp × Bwl
    assert hs.waterplane_area / (142.0 * 19.06) == pytest.approx(0.774, abs=5e-3)


def test_buoyancy_centre_and_stability(hull, hs):
    ref = hull.particulars.reference
    # LCB −0.683 % Lpp: within 0.2 % Lpp (the transom cut and the dome nose, 0.2 m)
    assert hs.centre_of_buoyancy[0] == pytest.approx(ref["LCB_fwd_of_midship_m"], abs=0.3)
    # KB of a fine hull with a dome: T/2 + ~0.5 m; GM of the SIMMAN condition with KG 7.555 m
    assert hs.kb == pytest.approx(3.659, abs=0.02)
    assert hs.gmt == pytest.approx(ref["GMt_m"], abs=0.02)
    assert hs.bmt == pytest.approx(5.846, abs=0.05)
    assert hs.gml == pytest.approx(293.0, rel=0.02)


def test_midship_section_coefficient():
    from importlib import resources

    from ship_gym.hull.offsets import read_offsets_csv

    path = resources.files("ship_gym.data").joinpath("dtmb5415/offsets.csv")
    st = min(read_offsets_csv(str(path)), key=lambda s: abs(s.x))
    below = st.height <= 6.15
    z = np.append(st.height[below], 6.15)
    y = np.append(st.half_breadth[below], np.interp(6.15, st.height, st.half_breadth))
    area = 2.0 * float(np.sum(0.5 * (y[1:] + y[:-1]) * np.diff(z)))
    assert area / (19.06 * 6.15) == pytest.approx(0.821, abs=5e-3)
    assert 2.0 * y[-1] == pytest.approx(19.06, rel=3e-3)


def test_bundled_database_loads_with_plausible_natural_periods(hull):
    from ship_gym.hydro import load_database

    try:
        ds = load_database("dtmb5415")
    except FileNotFoundError:
        pytest.skip("dtmb5415 database not built (scripts/build_hull_database.py dtmb5415)")
    omega = ds.omega.values
    finite = np.isfinite(omega) & (omega > 0)
    k = ds.hydrostatic_stiffness.values
    m = ds.inertia_matrix.values
    a = ds.added_mass.values
    periods = {}
    for i, dof in ((2, "heave"), (4, "pitch")):
        # fixed point T = 2π sqrt((M + A(ω)) / C) on the stored grid
        w = np.sqrt(k[i, i] / m[i, i])
        for _ in range(50):
            w = np.sqrt(k[i, i] / (m[i, i] + np.interp(w, omega[finite], a[finite, i, i])))
        periods[dof] = 2 * np.pi / w
    # strip-theory estimates for a 142 m combatant: heave and pitch both ≈ 2.4 sqrt(T)… 6–7 s
    # (heave 2π sqrt(2 T / g·(1 + Cb)/(3 Cw)) ≈ 6.0 s with A33 ≈ M): wide band, order-of-magnitude
    assert 5.0 < periods["heave"] < 8.0
    assert 5.0 < periods["pitch"] < 8.0
