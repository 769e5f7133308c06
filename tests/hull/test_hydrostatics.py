"""Hydrostatics by pressure integration against closed forms and the S175 ShipX data check."""

import numpy as np
import pytest

from ship_gym.hull import (
    equilibrium,
    hydrostatics,
    load_hull,
    pressure_integral,
    righting_arm,
)


@pytest.fixture(scope="module")
def barge():
    return load_hull("box_barge", length=100.0, beam=20.0, draught=5.0, depth=10.0, kg=6.0)


@pytest.fixture(scope="module")
def s175():
    return load_hull("s175")


def test_box_barge_hydrostatics_exact(barge):
    # A box is meshed exactly and p is linear on each panel: only round-off remains.
    hs = hydrostatics(barge)
    assert hs.volume == pytest.approx(100 * 20 * 5, rel=1e-12)
    assert hs.kb == pytest.approx(2.5, rel=1e-12)
    assert hs.bmt == pytest.approx(20**2 / (12 * 5), rel=1e-12)
    assert hs.gmt == pytest.approx(2.5 + 20**2 / 60 - 6.0, rel=1e-12)
    assert hs.bml == pytest.approx(100**2 / (12 * 5), rel=1e-12)
    assert hs.waterplane_area == pytest.approx(2000.0, rel=1e-12)


def test_box_barge_gz_wall_sided(barge):
    # Wall-sided formula GZ = sin φ (GM + ½ BM tan² φ) is exact for a box until the deck edge
    # immerses or the bilge emerges: atan((D − T)/(B/2)) = atan(T/(B/2)) = 26.57°.
    heel = np.arange(0.0, 26.0, 2.5)
    curve = righting_arm(barge, heel)
    hs = hydrostatics(barge)
    phi = np.radians(heel)
    expected = np.sin(phi) * (hs.gmt + 0.5 * hs.bmt * np.tan(phi) ** 2)
    np.testing.assert_allclose(curve.gz, expected, rtol=1e-9, atol=1e-10)
    # beyond deck-edge immersion the wall-sided formula overestimates GZ (deck edge in water)
    late = righting_arm(barge, [45.0]).gz[0]
    phi45 = np.radians(45.0)
    assert late < np.sin(phi45) * (hs.gmt + 0.5 * hs.bmt * np.tan(phi45) ** 2) - 0.5


def test_s175_matches_shipx_data_check(s175):
    ref = s175.particulars.reference
    hs = hydrostatics(s175)  # design waterline, even keel, as in the ShipX data check
    assert hs.displacement / 1e3 == pytest.approx(ref["displacement_t"], rel=0.01)
    assert hs.kb == pytest.approx(ref["KB_m"], rel=0.02)
    assert hs.gmt == pytest.approx(ref["GMt_m"], rel=0.03)
    assert hs.gml == pytest.approx(ref["GMl_m"], rel=0.03)
    assert hs.waterplane_area / (175.0 * 25.4) == pytest.approx(ref["Cw"], rel=0.02)


def test_s175_mesh_is_closed_symmetric_and_to_the_deck(s175):
    s175.mesh.check(closed=True)
    assert s175.mesh.n_faces >= 1500
    lo, hi = s175.mesh.bounds
    assert lo[2] == pytest.approx(9.5 - 15.4)  # deck at D = 15.4 m above the keel
    assert hi[2] == pytest.approx(9.5)
    # mirror symmetry: buoyancy has no transverse moment upright
    r = pressure_integral(s175)
    assert abs(r.moment[0]) < 1e-9 * s175.mass.mass * s175.g


def test_stiffness_matches_finite_differences(s175):
    # C = −∂(buoyancy + weight)/∂η at the design waterline. The waterline is a mesh line where
    # the panel slopes change, so the second derivative jumps there and central differences
    # are only O(h) accurate: h = 1e-5 m / rad keeps that error near 1e-5.
    hs = hydrostatics(s175)
    c = hs.stiffness
    h = 1e-5
    fz = [pressure_integral(s175, heave=s).force[2] for s in (-h, h)]
    assert -(fz[1] - fz[0]) / (2 * h) == pytest.approx(c[2, 2], rel=1e-4)
    fz_t = [pressure_integral(s175, trim=s).force[2] for s in (-h, h)]
    assert -(fz_t[1] - fz_t[0]) / (2 * h) == pytest.approx(c[2, 4], rel=1e-3)
    # z down: LCF aft of amidships (∫x dA < 0) gives C35 = −ρg∫x dA > 0 (bow-up trim sinks O)
    assert hs.centre_of_flotation[0] < 0 and c[2, 4] > 0
    assert c[3, 3] > 0 and c[4, 4] > 0 and c[2, 2] > 0


def test_equilibrium_balances_weight_and_trim(s175):
    eq = equilibrium(s175)
    r = pressure_integral(s175, eq.heave, 0.0, eq.trim)
    assert r.volume * s175.rho == pytest.approx(s175.mass.mass, rel=1e-8)
    # LCB under LCG at equilibrium (trim is small, so horizontal positions compare directly)
    assert r.centre_of_buoyancy[0] == pytest.approx(s175.mass.cog[0], abs=1e-3)
    assert abs(eq.heave) < 0.1 and abs(np.degrees(eq.trim)) < 0.1


def test_s175_gz_curve(s175):
    curve = righting_arm(s175, [-30.0, -10.0, 0.0, 2.0, 10.0, 30.0, 60.0, 90.0])
    gz = dict(zip(curve.heel_deg, curve.gz, strict=True))
    assert abs(gz[0.0]) < 1e-9
    assert gz[10.0] == pytest.approx(-gz[-10.0], abs=1e-9)  # port/starboard symmetry
    assert gz[30.0] == pytest.approx(-gz[-30.0], abs=1e-9)
    # initial slope dGZ/dφ = GM at the free-floating equilibrium (2° chord: ~0.1 % curvature error)
    eq = equilibrium(s175)
    gm = hydrostatics(s175, heave=eq.heave, trim=eq.trim).gmt
    assert gz[2.0] / np.radians(2.0) == pytest.approx(gm, rel=0.01)
    assert gz[90.0] < 0.0
    assert 30.0 < curve.vanishing_angle_deg < 90.0
    # the refined vanishing angle is a zero of GZ
    at_vanishing = righting_arm(s175, [curve.vanishing_angle_deg]).gz[0]
    assert abs(at_vanishing) < 1e-4


def test_wigley_converges_to_closed_forms():
    # Polygonal sections are inscribed in the parabolic ones: O(h²) volume deficit.
    errs = []
    for n in (1, 2):
        w = load_hull("wigley", n_sections=20 * n, n_below=4 * n)
        hs = hydrostatics(w)
        errs.append(abs(hs.volume / w.particulars.reference["volume_m3"] - 1.0))
        assert hs.waterplane_area == pytest.approx(
            w.particulars.reference["waterplane_area_m2"], rel=0.01
        )
    assert errs[1] < 0.01
    assert errs[0] / errs[1] > 3.0  # second-order convergence (ratio 4 ideal)


def test_hemisphere_hydrostatics():
    a = 2.0
    hm = load_hull("hemisphere", radius=a, n_theta=24, n_phi=96)
    hs = hydrostatics(hm)
    assert hs.volume == pytest.approx(2 / 3 * np.pi * a**3, rel=0.01)
    assert hs.kb == pytest.approx(5 * a / 8, rel=0.01)
    # metacentre on the waterline: GM = z_G (G below the waterline by a/2 by default)
    assert hs.gmt == pytest.approx(a / 2, rel=0.02)


def test_load_hull_rejects_bad_input():
    with pytest.raises(ValueError, match="unknown hull 'titanic'"):
        load_hull("titanic")
    with pytest.raises(ValueError, match="bad override"):
        load_hull("s175", colour="red")
    with pytest.raises(ValueError, match="draught"):
        load_hull("box_barge", draught=12.0, depth=10.0)
    with pytest.raises(ValueError, match="heel angles"):
        righting_arm(load_hull("box_barge"), [200.0])
