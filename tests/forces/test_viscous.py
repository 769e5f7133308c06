"""Viscous roll damping (ship_gym.forces.viscous): Ikeda components, fit, force model.

No published table of component values for the S175 was at hand, so the components are checked
against (i) worked examples of the short closed-form formulas (Kato friction, Ikeda hull lift;
Himeno 1981, ITTC 7.5-02-07-04.5 §2.2.2–2.2.3), (ii) the scalings the method is built on
(friction ∝ wetted area and independent of φa in Kato's laminar form, eddy ∝ ω φa at zero speed,
lift ∝ U, bilge keels add damping growing with their size), and (iii) the order of magnitude
expected for a container ship: a few per cent of critical at the roll resonance.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import replace

import numpy as np
import pytest

from ship_gym.forces.base import ForceContext
from ship_gym.forces.viscous import (
    BilgeKeel,
    IkedaRangeWarning,
    RollDampingCoefficients,
    RollDampingParticulars,
    ViscousRollDamping,
    critical_roll_damping,
    dimensional_roll_damping,
    fit_linear_quadratic,
    ikeda_roll_damping,
    imo_roll_period,
    linear_quadratic_from_equivalent,
    midship_section_area,
    nondimensional_roll_damping,
)
from ship_gym.hull import load_hull
from ship_gym.hydro.database import as_arrays, load_database
from ship_gym.hydro.rao import natural_frequency

PHI10 = math.radians(10.0)
BK = BilgeKeel(length=0.25 * 175.0, breadth=0.45)


@pytest.fixture(scope="module")
def hull():
    return load_hull("s175")


@pytest.fixture(scope="module")
def ship(hull):
    return RollDampingParticulars.from_hull(hull)


@pytest.fixture(scope="module")
def roll_resonance():
    ds = load_database("s175")
    a = as_arrays(ds)
    w = natural_frequency(ds, "Roll")
    inertia = a.inertia_matrix[3, 3] + np.interp(w, a.omega, a.added_mass[:, 3, 3])
    return w, critical_roll_damping(inertia, a.hydrostatic_stiffness[3, 3])


def _ikeda(ship, **kw):
    kw.setdefault("omega", 0.35)
    kw.setdefault("roll_amplitude", PHI10)
    return ikeda_roll_damping(ship, **kw)


# ------------------------------------------------------------------------------ particulars
def test_s175_particulars_from_hull(ship):
    assert ship.block_coefficient == pytest.approx(0.570, abs=0.005)  # ShipX: 0.570 (0.569)
    assert ship.midship_coefficient == pytest.approx(0.967, rel=0.01)  # ShipX: 0.967
    assert ship.og == pytest.approx(-0.05)  # KG 9.55 m, T 9.5 m: G 5 cm above the waterline
    assert ship.friction_area == pytest.approx(175 * (1.75 * 9.5 + 0.5678 * 25.4), rel=0.03)


def test_box_midship_section_is_exact():
    box = load_hull("box_barge", length=60.0, beam=12.0, draught=4.0, depth=8.0, kg=4.0)
    assert midship_section_area(box) == pytest.approx(48.0, rel=1e-9)
    assert midship_section_area(box, x=20.0) == pytest.approx(48.0, rel=1e-9)


def test_imo_roll_period_of_the_s175(roll_resonance):
    # IS Code 2008: C = 0.373 + 0.023 B/d − 0.043 L/100 = 0.359245, T = 2 C B/√GM
    t = imo_roll_period(25.4, 9.5, 175.0, 0.996)
    assert t == pytest.approx(2 * 0.359245 * 25.4 / math.sqrt(0.996), rel=1e-5)
    w_phi, _ = roll_resonance
    assert t == pytest.approx(2 * math.pi / w_phi, rel=0.05)  # BEM + hydrostatics: 17.9 s


# ------------------------------------------------------------------------------ components
def test_friction_worked_example(ship):
    # Kato's laminar C_f, Ikeda's lever r_f, zero speed, S175 at ω = 0.35 rad/s, φa = 10°
    d, b, cb, og, nu = 9.5, 25.4, ship.block_coefficient, ship.og, ship.kinematic_viscosity
    r_f = d * ((0.887 + 0.145 * cb) * (1.7 + cb * b / d) - 2 * og / d) / math.pi
    assert r_f == pytest.approx(9.465, abs=0.001)
    rn = 0.512 * (r_f * PHI10) ** 2 * 0.35 / nu
    c_f = 1.328 / math.sqrt(rn)
    expected = 4 / (3 * math.pi) * 1025 * ship.friction_area * r_f**3 * PHI10 * 0.35 * c_f
    got = _ikeda(ship, turbulent_friction=False).friction
    assert got == pytest.approx(expected, rel=1e-12)
    # Himeno's turbulent term adds 0.014 Rn^-0.114 (larger than the laminar part at full scale)
    turb = _ikeda(ship).friction
    assert turb / got == pytest.approx(1 + 0.014 * rn**-0.114 / c_f, rel=1e-12)


def test_friction_scalings(ship):
    base = _ikeda(ship, turbulent_friction=False).friction
    double_area = replace(ship, wetted_area=2 * ship.friction_area)
    assert _ikeda(double_area, turbulent_friction=False).friction == pytest.approx(2 * base)
    # laminar Kato: B_F ∝ φa ω C_f ∝ φa ω (φa² ω)^(−1/2) — independent of φa, ∝ √ω
    phi20 = _ikeda(ship, roll_amplitude=2 * PHI10, turbulent_friction=False).friction
    assert phi20 == pytest.approx(base, rel=1e-12)
    w4 = _ikeda(ship, omega=4 * 0.35, turbulent_friction=False, on_out_of_range="ignore")
    assert w4.friction == pytest.approx(2 * base, rel=1e-12)
    # forward speed: factor 1 + 4.1 U/(ω L)
    fast = _ikeda(ship, forward_speed=6.0, turbulent_friction=False).friction
    assert fast / base == pytest.approx(1 + 4.1 * 6.0 / (0.35 * 175.0), rel=1e-12)


def test_eddy_is_quadratic_at_zero_speed(ship):
    e = _ikeda(ship).eddy
    assert e > 0
    # B_E ∝ ω φa: a moment ∝ |p| p
    assert _ikeda(ship, roll_amplitude=2 * PHI10).eddy == pytest.approx(2 * e, rel=1e-12)
    assert _ikeda(ship, omega=0.7).eddy == pytest.approx(2 * e, rel=1e-12)
    # forward speed suppresses it: factor (0.04K)²/(1 + (0.04K)²), K = ωL/U
    k = 0.04 * 0.35 * 175.0 / 10.0
    assert _ikeda(ship, forward_speed=10.0).eddy / e == pytest.approx(k**2 / (1 + k**2))
    # a fuller midship section (sharper bilge) sheds stronger vortices
    sharp = replace(ship, midship_coefficient=0.985)
    round_ = replace(ship, midship_coefficient=0.92)
    assert _ikeda(round_).eddy < e < _ikeda(sharp).eddy


def test_lift_worked_example(ship):
    # Ikeda: ½ ρ L d U k_N l_o l_R (1 − 1.4 OG/l_R + 0.7 OG²/(l_o l_R)), κ = 0.1 for C_m 0.964
    u = 10.0
    k_n = 2 * math.pi * 9.5 / 175 + 0.1 * (4.1 * 25.4 / 175 - 0.045)
    assert k_n == pytest.approx(0.39610, abs=1e-5)
    l_o, l_r, og = 0.3 * 9.5, 0.5 * 9.5, -0.05
    expected = (
        0.5 * 1025 * 175 * 9.5 * u * k_n * l_o * l_r
        * (1 - 1.4 * og / l_r + 0.7 * og**2 / (l_o * l_r))
    )  # fmt: skip
    assert expected == pytest.approx(4.637e7, rel=1e-3)
    assert _ikeda(ship, forward_speed=u).lift == pytest.approx(expected, rel=1e-9)
    assert _ikeda(ship).lift == 0.0
    assert _ikeda(ship, forward_speed=2 * u).lift == pytest.approx(2 * expected, rel=1e-12)
    # a roll axis deeper below the waterline (toward the lift centre) lowers the lift damping
    assert _ikeda(replace(ship, og=1.5), forward_speed=u).lift < expected


def test_bilge_keels_add_damping(ship):
    bare = _ikeda(ship)
    assert bare.bilge_keel == 0.0
    with_bk = _ikeda(ship, bilge_keel=BK)
    assert with_bk.bilge_keel > 0.5 * bare.eddy
    assert with_bk.total > bare.total
    for field_name, value in (("breadth", 0.8), ("length", 60.0)):
        bigger = _ikeda(ship, bilge_keel=replace(BK, **{field_name: value}))
        assert bigger.bilge_keel > with_bk.bilge_keel
    # speed-independent, friction/eddy unchanged by the keels
    assert _ikeda(ship, bilge_keel=BK, forward_speed=5.0).bilge_keel == with_bk.bilge_keel
    assert with_bk.friction == bare.friction and with_bk.eddy == bare.eddy


def test_s175_damping_is_a_few_percent_of_critical(hull, roll_resonance):
    w_phi, critical = roll_resonance
    bare = ikeda_roll_damping(hull, omega=w_phi, roll_amplitude=PHI10)
    keels = ikeda_roll_damping(hull, omega=w_phi, roll_amplitude=PHI10, bilge_keel=BK)
    speed = ikeda_roll_damping(
        hull, omega=w_phi, roll_amplitude=PHI10, bilge_keel=BK, forward_speed=10.0
    )
    assert bare.out_of_range == keels.out_of_range == speed.out_of_range == ()
    assert 0.005 < bare.total / critical < 0.03
    assert 0.015 < keels.total / critical < 0.06
    assert keels.total < speed.total < 0.10 * critical  # lift grows more than eddy is lost
    assert bare.eddy > 10 * bare.friction  # eddy making dominates the bare hull at U = 0
    nd = keels.nondimensional()
    assert nd["total"] == pytest.approx(sum(nd[k] for k in ("friction", "eddy", "bilge_keel")))


# ------------------------------------------------------------------------------ validity
def test_out_of_range_is_reported():
    wide = RollDampingParticulars(
        lpp=100.0, beam=20.0, draught=4.0, block_coefficient=0.95, midship_coefficient=1.0,
        og=-1.0,
    )  # fmt: skip
    with pytest.warns(IkedaRangeWarning, match="Cb"):
        r = ikeda_roll_damping(wide, omega=0.5, roll_amplitude=PHI10)
    keys = {m.split(" ")[0] for m in r.out_of_range}
    assert keys == {"Cb", "B/d", "Cm"}
    with pytest.raises(ValueError, match="validity"):
        ikeda_roll_damping(wide, omega=0.5, roll_amplitude=PHI10, on_out_of_range="raise")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        ikeda_roll_damping(wide, omega=0.5, roll_amplitude=PHI10, on_out_of_range="ignore")
    small_bk = BilgeKeel(length=2.0, breadth=0.1)  # lBK/L = 0.02, bBK/B = 0.005
    r = ikeda_roll_damping(
        wide, omega=3.0, roll_amplitude=PHI10, bilge_keel=small_bk, on_out_of_range="ignore"
    )
    keys = {m.split(" ")[0] for m in r.out_of_range}
    assert {"omega_hat", "bBK/B", "lBK/L"} <= keys


def test_bad_inputs_raise(ship, hull):
    for kwargs in (
        {"omega": 0.0},
        {"omega": float("nan")},
        {"roll_amplitude": -0.1},
        {"roll_amplitude": 2.0},
        {"forward_speed": -1.0},
        {"bilge_keel": BilgeKeel(length=150.0, breadth=0.4, x_centre=30.0)},
        {"bilge_keel": (40.0, 0.4)},
        {"on_out_of_range": "shout"},
    ):
        with pytest.raises(ValueError):
            _ikeda(ship, **kwargs)
    with pytest.raises(ValueError):
        ikeda_roll_damping("s175", omega=0.35, roll_amplitude=PHI10)
    for kwargs in ({"length": 0.0, "breadth": 0.4}, {"length": 40.0, "breadth": -1.0}):
        with pytest.raises(ValueError):
            BilgeKeel(**kwargs)
    with pytest.raises(ValueError):
        replace(ship, block_coefficient=1.2)
    with pytest.raises(ValueError):
        replace(ship, draught=-1.0)
    with pytest.raises(ValueError):
        RollDampingCoefficients(-1.0, 0.0)
    with pytest.raises(ValueError):
        RollDampingCoefficients(1.0, float("inf"))
    with pytest.raises(ValueError):
        fit_linear_quadratic(ship, omega=0.35, roll_amplitudes=[PHI10])
    with pytest.raises(ValueError):
        linear_quadratic_from_equivalent([0.1, 0.1], [1.0, 2.0], 0.35)
    with pytest.raises(ValueError):
        ViscousRollDamping((1.0, 2.0))
    with pytest.raises(ValueError):
        nondimensional_roll_damping(1.0, rho=1025.0, volume=1.0, beam=1.0, order=3)


# ------------------------------------------------------------------------------ coefficients
def test_nondimensional_round_trip(ship):
    c = RollDampingCoefficients(3.2e6, 8.5e8)
    kw = {"rho": ship.rho, "volume": ship.volume, "beam": ship.beam, "g": ship.g}
    b1_hat, b2_hat = c.nondimensional(**kw)
    back = RollDampingCoefficients.from_nondimensional(b1_hat, b2_hat, **kw)
    assert back.b1 == pytest.approx(c.b1, rel=1e-14) and back.b2 == pytest.approx(c.b2, rel=1e-14)
    # B̂_eq = B̂1 + (8/3π) ω̂ φa B̂2 with ω̂ = ω √(B/2g)
    w = 0.35
    w_hat = w * math.sqrt(ship.beam / (2 * ship.g))
    b_eq_hat = nondimensional_roll_damping(c.equivalent_linear(PHI10, w), order=1, **kw)
    assert b_eq_hat == pytest.approx(b1_hat + 8 / (3 * math.pi) * w_hat * PHI10 * b2_hat)
    assert dimensional_roll_damping(b1_hat, **kw) == pytest.approx(c.b1, rel=1e-14)
    # and Ikeda's nondimensional output is consistent with the same scale
    r = _ikeda(ship, bilge_keel=BK)
    assert r.nondimensional()["total"] == pytest.approx(
        nondimensional_roll_damping(r.total, order=1, **kw), rel=1e-14
    )


def test_fit_recovers_exact_coefficients():
    true = RollDampingCoefficients(2.0e6, 7.0e8)
    phis = np.radians([4.0, 8.0, 12.0, 20.0])
    b_eq = [true.equivalent_linear(p, 0.35) for p in phis]
    fit = linear_quadratic_from_equivalent(phis, b_eq, 0.35)
    assert fit.b1 == pytest.approx(true.b1, rel=1e-9)
    assert fit.b2 == pytest.approx(true.b2, rel=1e-9)
    # a decreasing B_eq(φa) cannot have B2 < 0: constrained to a constant
    dec = linear_quadratic_from_equivalent(phis, [4.0, 3.0, 2.0, 1.0], 0.35)
    assert dec.b2 == 0.0 and dec.b1 == pytest.approx(2.5)


def test_fit_of_ikeda_components(ship):
    w = 0.35
    phis = np.radians([5.0, 10.0, 15.0, 20.0])
    # bare hull at zero speed, laminar friction: friction → B1 exactly, eddy (∝ φa) → B2 exactly
    fit = fit_linear_quadratic(ship, omega=w, roll_amplitudes=phis, turbulent_friction=False)
    r = _ikeda(ship, omega=w, turbulent_friction=False)
    assert fit.b1 == pytest.approx(r.friction, rel=1e-9)
    assert fit.equivalent_linear(PHI10, w) - fit.b1 == pytest.approx(r.eddy, rel=1e-9)
    # with bilge keels the equivalent damping is reproduced within a few per cent
    fit = fit_linear_quadratic(ship, omega=w, roll_amplitudes=phis, bilge_keel=BK)
    for phi in phis:
        b_eq = _ikeda(ship, omega=w, roll_amplitude=phi, bilge_keel=BK).total
        assert fit.equivalent_linear(phi, w) == pytest.approx(b_eq, rel=0.05)
    assert fit.b1 > 0 and fit.b2 > 0


# ------------------------------------------------------------------------------ force model
def _ctx(p: float) -> ForceContext:
    nu = np.array([5.0, 0.3, -0.2, p, 0.01, -0.02])
    return ForceContext(t=0.0, eta=np.zeros(6), nu=nu, rotation=np.eye(3))


def test_force_model_moment():
    model = ViscousRollDamping(RollDampingCoefficients(2.0e6, 5.0e8))
    assert model.name == "viscous_roll" and model.n_states == 0 and model.added_mass is None
    for p in (0.05, -0.05, 0.0, 0.2):
        force, states_dot = model.evaluate(_ctx(p), np.zeros(0))
        expected = -(2.0e6 * p + 5.0e8 * abs(p) * p)
        np.testing.assert_array_equal(force[[0, 1, 2, 4, 5]], 0.0)
        assert force[3] == pytest.approx(expected, rel=1e-15)
        assert force[3] * p <= 0.0  # always opposes the roll rate (dissipative)
        assert states_dot.shape == (0,)
    assert model.coefficients.moment(0.2) == pytest.approx(-(2.0e6 * 0.2 + 5.0e8 * 0.04))
    np.testing.assert_allclose(
        model.coefficients.moment(np.array([0.1, -0.1])), [-5.2e6, 5.2e6], rtol=1e-15
    )


def test_force_model_from_hull(hull, roll_resonance):
    w_phi, critical = roll_resonance
    model = ViscousRollDamping.from_hull(hull, omega=w_phi, bilge_keel=BK)
    direct = fit_linear_quadratic(hull, omega=w_phi, bilge_keel=BK)
    assert model.coefficients == direct
    b_eq = model.coefficients.equivalent_linear(PHI10, w_phi)
    assert 0.015 < b_eq / critical < 0.06
    # default frequency: the IMO roll period (18.3 s vs 17.9 s from the BEM) — close
    default = ViscousRollDamping.from_hull(hull, bilge_keel=BK)
    assert default.coefficients.equivalent_linear(PHI10, w_phi) == pytest.approx(b_eq, rel=0.05)
    with pytest.raises(ValueError):
        ViscousRollDamping.from_hull(RollDampingParticulars.from_hull(hull))
