"""Calm-water resistance (ITTC-57, Holtrop–Mennen) and the B-series propeller.

References
----------
* ITTC-1957 line C_F = 0.075/(log₁₀ Rn − 2)², evaluated here independently with ``math``.
* Holtrop & Mennen (1982), "An approximate power prediction method", ISP 29(335): the worked
  example on the last page (L = 205 m, B = 32 m, T = 10 m, ∇ = 37 500 m³, 25 kn): intermediate
  coefficients and R_F = 869.63 kN, R_APP = 8.83 kN, R_W = 557.11 kN, R_A = 221.98 kN,
  R_T = 1793.26 kN. (1793 kN is the *total*; the 869 kN sometimes quoted is the friction.)
* Wageningen B-series (Oosterveld & van Oossanen 1975, Rn = 2·10⁶): no independent table of
  B4-70 open-water values was available to check against, so the values below are the
  polynomial's own (a regression pin), and the coefficient tables were cross-checked by hand
  against two independent public transcriptions; physics checks (monotone K_T, single zero,
  efficiency peak) complete the test.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from ship_gym.conventions import PITCH, ROLL, SURGE, YAW
from ship_gym.forces.base import ForceContext
from ship_gym.forces.propeller import (
    KQ_TERMS,
    KT_TERMS,
    SHAFT_SPEED_COMMAND,
    Propeller,
    WageningenB,
    design_propeller_for,
    holtrop_propulsion_factors,
    service_speed,
)
from ship_gym.forces.resistance import (
    CalmWaterResistance,
    HoltropMennen,
    HoltropRangeWarning,
    ResistanceParticulars,
    ittc57_friction_coefficient,
    resistance_curve,
)
from ship_gym.hull import load_hull

KNOT = 1852.0 / 3600.0


@pytest.fixture(scope="module")
def s175():
    return load_hull("s175")


@pytest.fixture(scope="module")
def s175_resistance(s175):
    return CalmWaterResistance.from_hull(s175)


@pytest.fixture(scope="module")
def s175_propeller(s175, s175_resistance):
    return design_propeller_for(s175, resistance=s175_resistance)


def _ctx(u: float, n: float | None = None) -> ForceContext:
    nu = np.array([u, 0.0, 0.0, 0.0, 0.0, 0.0])
    commands = {} if n is None else {SHAFT_SPEED_COMMAND: n}
    return ForceContext(t=0.0, eta=np.zeros(6), nu=nu, rotation=np.eye(3), commands=commands)


# ------------------------------------------------------------------------------ ITTC-57
def test_ittc57_friction_line_values():
    for rn in (1e6, 1e7, 1e9, 2.2187e9, 5e9):
        exact = 0.075 / (math.log10(rn) - 2.0) ** 2
        assert ittc57_friction_coefficient(rn) == pytest.approx(exact, rel=1e-14)
    assert ittc57_friction_coefficient(1e9) == pytest.approx(0.075 / 49.0, rel=1e-14)  # 0.0015306
    assert ittc57_friction_coefficient(1e7) == pytest.approx(0.003, rel=1e-14)
    arr = ittc57_friction_coefficient(np.array([1e6, 1e9]))
    assert arr.shape == (2,) and arr[0] > arr[1]


@pytest.mark.parametrize("bad", [100.0, 50.0, 0.0, -1e6, np.nan, np.inf])
def test_ittc57_rejects_bad_reynolds(bad):
    with pytest.raises(ValueError, match="reynolds"):
        ittc57_friction_coefficient(bad)


# ------------------------------------------------------------------------------ Holtrop–Mennen
def _holtrop_example() -> ResistanceParticulars:
    """Holtrop & Mennen (1982) worked example (their S = 7381.45 m² is their own S estimate)."""
    return ResistanceParticulars(
        length=205.0,
        beam=32.0,
        draught_fore=10.0,
        draught_aft=10.0,
        volume=37500.0,
        lcb=-0.75,
        midship_coefficient=0.98,
        waterplane_coefficient=0.75,
        wetted_area=None,
        bulb_area=20.0,
        bulb_centre_height=4.0,
        transom_area=16.0,
        stern_shape=10.0,
        appendage_area=50.0,
        appendage_form_factor=1.5,
    )


def test_holtrop_mennen_1982_worked_example():
    part = _holtrop_example()
    assert part.wetted_area_estimate == pytest.approx(7381.45, abs=0.05)
    assert part.length_of_run == pytest.approx(81.385, abs=0.005)
    assert part.entrance_angle_deg == pytest.approx(12.08, abs=0.01)
    hm = HoltropMennen(part, variant="1982", rho=1025.0, g=9.81)
    c = hm.coefficients
    assert c["c12"] == pytest.approx(0.5102, abs=1e-4)
    assert c["c13"] == pytest.approx(1.03, abs=1e-12)
    assert hm.form_factor == pytest.approx(1.156, abs=5e-4)
    assert c["c7"] == pytest.approx(0.1561, abs=1e-4)
    assert c["c1"] == pytest.approx(1.398, abs=1e-3)
    assert c["c3"] == pytest.approx(0.02119, abs=1e-5)
    assert c["c2"] == pytest.approx(0.7595, abs=1e-4)
    assert c["c5"] == pytest.approx(0.9592, abs=1e-4)
    assert c["c15"] == pytest.approx(-1.69385, abs=1e-12)
    assert c["m1"] == pytest.approx(-2.1274, abs=1e-4)
    assert c["lambda_"] == pytest.approx(0.6513, abs=1e-4)
    assert c["P_B"] == pytest.approx(0.6261, abs=1e-4)
    assert hm.correlation_allowance == pytest.approx(0.000352, abs=1e-6)

    r = hm.components(25.0 * KNOT)
    assert r.froude_number == pytest.approx(0.2868, abs=1e-4)
    assert r.friction_coefficient == pytest.approx(0.00139, abs=5e-6)
    assert r.friction == pytest.approx(869.63e3, rel=3e-3)
    assert r.appendage == pytest.approx(8.83e3, rel=1e-2)
    assert r.wave == pytest.approx(557.11e3, rel=3e-3)
    assert 0.0 < r.bulb < 0.1e3
    assert r.transom == 0.0  # Fn_T = 5.43 > 5
    # the paper's R_A = 221.98 kN apparently takes S + S_APP; we take S as its formula: −0.6 %
    assert r.correlation == pytest.approx(221.98e3, rel=1e-2)
    assert r.total == pytest.approx(1793.26e3, rel=3e-3)


def test_holtrop_1984_variant_and_high_speed_branch():
    part = _holtrop_example()
    hm84 = HoltropMennen(part, variant="1984", rho=1025.0, g=9.81)
    hm82 = HoltropMennen(part, variant="1982", rho=1025.0, g=9.81)
    # 1984 form factor (eq. 3b) differs from 1982 (3a); wave resistance nearly equal at Fn 0.29
    assert hm84.form_factor == pytest.approx(1.185, abs=1e-3)
    u = 25.0 * KNOT
    assert hm84.components(u).wave == pytest.approx(hm82.components(u).wave, rel=0.01)
    # the interpolation between Fn 0.40 and 0.55 joins both branches continuously
    for fn in (0.40, 0.55):
        lo, hi = hm84.wave_resistance(fn - 1e-9), hm84.wave_resistance(fn + 1e-9)
        assert hi == pytest.approx(lo, rel=1e-6)


def test_s175_particulars_from_mesh(s175):
    hm = HoltropMennen.from_hull(s175)
    p = hm.particulars
    assert p.length == pytest.approx(176.66, abs=0.05)  # waterline from the offsets
    assert p.block_coefficient == pytest.approx(0.5624, abs=2e-3)
    assert p.midship_coefficient == pytest.approx(0.964, abs=3e-3)
    assert -2.0 < p.lcb < 0.0  # LCB aft of mid-waterline
    assert hm.wetted_area == pytest.approx(float(s175.immersed_mesh.areas.sum()))
    # within Holtrop & Mennen's cargo-liner range up to Fn = 0.30
    assert hm.range_report(12.0) == ()
    with pytest.warns(HoltropRangeWarning, match="Froude"):
        resistance_curve(hm, [10.0, 13.5])
    with pytest.raises(ValueError, match="outside its range"):
        resistance_curve(s175, [13.5], on_out_of_range="raise")


def test_s175_resistance_physics(s175):
    curve = resistance_curve(s175, np.linspace(0.5, 12.4, 120))
    total = np.asarray(curve.total)
    assert np.all(np.diff(total) > 0.0)
    # low Froude numbers: R_T ≈ U² (only the slow decrease of C_F with Rn): R/U² within 15 %
    low = resistance_curve(s175, [2.0, 3.0, 4.0, 5.0])
    coeff = np.asarray(low.total) / np.asarray(low.speed) ** 2
    assert np.ptp(coeff) / coeff.mean() < 0.15
    assert np.all(np.asarray(low.wave) < 0.02 * np.asarray(low.total))
    # wave resistance rises steeply towards Fn 0.3: local exponent d ln R_W / d ln U >> 2
    g_l = math.sqrt(s175.g * 176.66)
    fn = np.array([0.20, 0.25, 0.28, 0.30])
    c = resistance_curve(s175, fn * g_l)
    rw = np.asarray(c.wave)
    assert np.all(np.diff(rw) > 0.0)
    slope = math.log(rw[3] / rw[2]) / math.log(fn[3] / fn[2])
    slope_f = math.log(c.friction[3] / c.friction[2]) / math.log(fn[3] / fn[2])
    assert slope > 4.0 and slope_f < 2.0
    share = rw / np.asarray(c.total)
    assert share[0] < 0.15 and share[3] > 0.35


def test_resistance_force_model_signs(s175_resistance):
    model = s175_resistance
    assert model.name == "resistance"
    f_ahead, _ = model.evaluate(_ctx(10.0), np.zeros(0))
    f_astern, _ = model.evaluate(_ctx(-10.0), np.zeros(0))
    assert f_ahead[SURGE] < 0.0 and f_astern[SURGE] == -f_ahead[SURGE]
    assert f_ahead[SURGE] == pytest.approx(-model.resistance(10.0), rel=1e-15)
    assert np.all(f_ahead[1:] == 0.0)
    f0, s0 = model.evaluate(_ctx(0.0), np.zeros(0))
    assert np.all(f0 == 0.0) and s0.shape == (0,)
    # low-speed U² extension is continuous at Rn = 1e5 and vanishes at rest
    v = model.holtrop.min_speed
    assert model.resistance(v * (1 - 1e-9)) == pytest.approx(model.resistance(v), rel=1e-7)
    assert model.resistance(0.5 * v) == pytest.approx(0.25 * model.resistance(v), rel=1e-12)
    r3 = model.resistance(3.0)
    np.testing.assert_allclose(model.surge_force([-3.0, 3.0]), [r3, -r3], rtol=1e-15)


def test_resistance_bad_inputs(s175):
    with pytest.raises(ValueError, match="variant"):
        HoltropMennen.from_hull(s175, variant="1999")
    with pytest.raises(ValueError, match="prismatic"):
        ResistanceParticulars(100.0, 10.0, 5.0, 5.0, 4900.0, 0.0, 0.99, 0.9)
    with pytest.raises(ValueError, match="beam"):
        ResistanceParticulars(100.0, -10.0, 5.0, 5.0, 3000.0, 0.0, 0.95, 0.8)
    with pytest.raises(ValueError, match="speed"):
        HoltropMennen.from_hull(s175).components(-1.0)
    with pytest.raises(ValueError, match="callable"):
        CalmWaterResistance(42.0)  # type: ignore[arg-type]


# ------------------------------------------------------------------------------ B-series
def test_b_series_tables():
    assert len(KT_TERMS) == 39 and len(KQ_TERMS) == 47
    for terms in (KT_TERMS, KQ_TERMS):
        exps = [t[1:] for t in terms]
        assert len(set(exps)) == len(exps)  # no term twice
        assert all(s <= 3 and t in (0, 1, 2, 3, 6) and u <= 2 and v <= 2 for s, t, u, v in exps)


def test_b4_70_open_water():
    b = WageningenB(4, 0.70, 1.0)
    assert b.name == "B4-70"
    j = np.array([0.5, 0.6, 0.7, 0.8])
    # regression pin of the Oosterveld–van Oossanen polynomial (see module docstring)
    np.testing.assert_allclose(b.kt(j), [0.27103, 0.22555, 0.17829, 0.12973], atol=2e-5)
    np.testing.assert_allclose(10 * b.kq(j), [0.43433, 0.37270, 0.30768, 0.23973], atol=2e-5)
    # the collapsed cubic equals the full 39/47-term sums
    for jj in (0.0, 0.33, 0.77, 1.0):
        full_kt = sum(c * jj**s * 1.0**t * 0.7**u * 4.0**v for c, s, t, u, v in KT_TERMS)
        full_kq = sum(c * jj**s * 1.0**t * 0.7**u * 4.0**v for c, s, t, u, v in KQ_TERMS)
        assert b.kt(jj) == pytest.approx(full_kt, abs=1e-14)
        assert b.kq(jj) == pytest.approx(full_kq, abs=1e-14)
    # physics of the curves: K_T, K_Q decrease, one zero of K_T with positive torque there
    grid = np.linspace(0.0, b.j_zero_thrust, 200)
    assert np.all(np.diff(b.kt(grid)) < 0.0) and np.all(np.diff(b.kq(grid)) < 0.0)
    assert b.kt(b.j_zero_thrust) == pytest.approx(0.0, abs=1e-12)
    assert 1.0 < b.j_zero_thrust < 1.15 and b.kq(b.j_zero_thrust) > 0.0
    eta = b.efficiency(grid[1:-1])
    assert 0.6 < eta.max() < 0.75 and 0.75 < grid[1:-1][np.argmax(eta)] < 0.95
    # higher pitch: more thrust at the same J
    assert WageningenB(4, 0.70, 1.2).kt(0.6) > b.kt(0.6) > WageningenB(4, 0.70, 0.8).kt(0.6)


def test_b_series_bad_inputs():
    with pytest.raises(ValueError, match="z_blades"):
        WageningenB(8, 0.7, 1.0)
    with pytest.raises(ValueError, match="z_blades"):
        WageningenB(4.5, 0.7, 1.0)  # type: ignore[arg-type]
    with pytest.raises(ValueError, match="p_d"):
        WageningenB(4, 0.7, 1.6)
    with pytest.raises(ValueError, match="ae_a0"):
        WageningenB(4, 0.2, 1.0)
    assert WageningenB(4, 0.7, 1.5, allow_extrapolation=True).p_d == 1.5


# ------------------------------------------------------------------------------ propeller
def test_s175_design_and_propulsion_factors(s175, s175_propeller):
    prop, d = s175_propeller, s175_propeller.design
    assert d.speed == pytest.approx(service_speed(s175))
    assert d.froude_number == pytest.approx(0.25, rel=1e-12)
    assert d.diameter == pytest.approx(0.7 * 9.5)
    assert 0.4 <= d.ae_a0 <= 1.05 and 0.5 <= d.p_d <= 1.4
    assert 80.0 < d.point.rpm < 120.0  # a large slow-speed diesel's range
    assert 0.15 < prop.wake_fraction < 0.35 and 0.12 < prop.thrust_deduction < 0.25
    assert 0.55 < d.point.eta_open_water < 0.75 and 0.6 < d.point.eta_propulsive < 0.8
    # twin-screw regressions exist and differ
    hm = prop.resistance.holtrop
    twin = holtrop_propulsion_factors(
        hm.particulars,
        diameter=5.0,
        viscous_resistance_coefficient=hm.viscous_resistance_coefficient(10.0),
        ae_a0=0.7,
        twin_screw=True,
    )
    assert twin.wake_fraction != pytest.approx(prop.wake_fraction, abs=1e-3)


@pytest.mark.parametrize("speed", [8.0, 10.0, 10.36, 12.0])
def test_self_propulsion_balance(s175_propeller, s175_resistance, speed):
    prop = s175_propeller
    n = prop.shaft_speed_for(speed)
    thrust, _ = prop.thrust_torque(n, (1.0 - prop.wake_fraction) * speed)
    r = s175_resistance.resistance(speed)
    assert (1.0 - prop.thrust_deduction) * thrust == pytest.approx(r, rel=1e-6)
    assert prop.steady_speed_for(n) == pytest.approx(speed, rel=1e-9)
    point = prop.self_propulsion(speed)
    assert point.delivered_power == pytest.approx(2 * math.pi * n * point.torque, rel=1e-12)
    assert prop.shaft_speed_for(0.0) == 0.0


def test_design_for_a_given_rpm(s175):
    prop = design_propeller_for(s175, rpm=90.0)
    assert prop.design.point.rpm == pytest.approx(90.0, rel=1e-6)
    with pytest.raises(ValueError, match="rpm"):
        design_propeller_for(s175, rpm=400.0)


def test_propeller_force_signs_and_moment(s175_propeller):
    prop = s175_propeller
    n = prop.design.point.shaft_speed
    xp, yp, zp = prop.position
    assert yp == 0.0
    f, states = prop.evaluate(_ctx(10.0, n), np.zeros(0))
    assert states.shape == (0,) and prop.name == "propeller"
    assert f[SURGE] > 0.0  # ahead rpm, ship moving ahead: forward force
    assert f[PITCH] == pytest.approx(zp * f[SURGE]) and zp > 0.0  # below WL: bow-up moment
    assert f[ROLL] == 0.0 and f[YAW] == 0.0 and f[1] == 0.0 and f[2] == 0.0
    op = prop.last_operating_point
    assert op.torque > 0.0 and op.delivered_power > 0.0
    # off-centre propeller: yaw moment −y_P X; roll reaction of a right-handed propeller < 0
    twin = Propeller(
        prop.open_water,
        prop.diameter,
        wake_fraction=prop.wake_fraction,
        thrust_deduction=prop.thrust_deduction,
        position=(xp, 5.0, zp),
        roll_reaction=True,
    )
    g, _ = twin.evaluate(_ctx(10.0, n), np.zeros(0))
    assert g[YAW] == pytest.approx(-5.0 * g[SURGE])
    assert g[ROLL] == pytest.approx(-twin.last_operating_point.torque) and g[ROLL] < 0.0
    # stopped shaft: nothing; astern shaft speed while going ahead: backing thrust
    assert np.all(prop.evaluate(_ctx(10.0, 0.0), np.zeros(0))[0] == 0.0)
    assert prop.evaluate(_ctx(10.0, -n), np.zeros(0))[0][SURGE] < 0.0
    with pytest.raises(ValueError, match="shaft_speed"):
        prop.evaluate(_ctx(10.0), np.zeros(0))


def test_propeller_outside_first_quadrant_is_continuous(s175_propeller):
    prop = s175_propeller
    d, j0 = prop.diameter, prop.open_water.j_zero_thrust
    n = 1.5
    # bollard
    t0, q0 = prop.thrust_torque(n, 0.0)
    assert t0 == pytest.approx(prop.rho * n**2 * d**4 * prop.open_water.kt(0.0))
    for j in (0.0, j0):
        va = j * n * d
        lo, hi = prop.thrust_torque(n, va - 1e-9), prop.thrust_torque(n, va + 1e-9)
        assert hi[0] == pytest.approx(lo[0], abs=1e-3) and hi[1] == pytest.approx(lo[1], abs=1e-3)
    # windmilling: beyond J0 the thrust is negative, and vanishes as n -> 0
    assert prop.thrust_torque(n, 1.3 * j0 * n * d)[0] < 0.0
    t_small = [prop.thrust_torque(eps, 8.0)[0] for eps in (1e-6, 1e-7)]
    assert t_small[0] < 0.0 and t_small[1] == pytest.approx(0.1 * t_small[0], rel=1e-5)
    # reversed inflow with ahead rpm: more thrust than at the bollard
    assert prop.thrust_torque(n, -2.0)[0] > t0
    # astern: mirrored and scaled
    ta, qa = prop.thrust_torque(-n, 0.0)
    assert ta == pytest.approx(-prop.astern_thrust_factor * t0) and qa == pytest.approx(-q0)


def test_surge_simulation_reaches_and_holds_commanded_speed(s175, s175_propeller):
    """1-DOF surge: (m + A11) u̇ = X_prop(u, n*) + X_res(u), explicit Euler from rest."""
    from ship_gym.hydro import load_database

    db = load_database("s175")
    a11 = float(db.added_mass.isel(omega=-1).sel(influenced_dof="Surge", radiating_dof="Surge"))
    assert 0.0 < a11 < 0.1 * s175.mass.mass
    mass = s175.mass.mass + a11
    prop = s175_propeller
    res = prop.resistance
    target = 10.0
    n = prop.shaft_speed_for(target)
    u, dt = 0.0, 1.0
    history = []
    for k in range(2000):
        ctx = _ctx(u, n)
        x = prop.evaluate(ctx, np.zeros(0))[0][SURGE] + res.evaluate(ctx, np.zeros(0))[0][SURGE]
        u += dt * x / mass
        history.append(u)
        assert k > 0 or u > 0.0
    history = np.array(history)
    first = int(np.argmax(np.abs(history - target) < 0.01 * target))
    assert 0 < first < 1200  # reached within 1 % in 20 min from rest
    assert np.all(np.abs(history[first:] - target) < 0.01 * target)  # and held
    assert history[-1] == pytest.approx(target, rel=1e-6)
