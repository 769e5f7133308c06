"""Compiled Holtrop–Mennen kernel (ship_gym.forces.resistance): one implementation of R_T(U).

:func:`holtrop_total` / :func:`holtrop_components` / :func:`holtrop_wave_resistance` evaluate
Holtrop & Mennen (1982) / Holtrop (1984), eqs. (1)–(10) of the module docstring, from the
packed record :meth:`HoltropMennen.kernel_parameters`; the model's Python methods call them.

Reference values: recorded with the pure-Python implementation of ``HoltropMennen._scalar`` /
``wave_resistance`` as it was before the kernel existed (same arithmetic, CPython ``math``), for

* the S175 (``HoltropMennen.from_hull(load_hull("s175"), variant=...)``), also with an air
  frontal area of 600 m² (eq. 10);
* Holtrop & Mennen's (1982) worked example with bulb, transom and appendages (eqs. 5, 7, 8),
  ``rho=1025, g=9.81``, up to Fn = 0.67 (Holtrop's 1984 interpolation and high-speed branch);
* the Wigley hull (``load_hull("wigley")``; the box barge has C_B = 1, outside the method).

Tolerance: the kernel repeats the old operations in the same order, and numba lowers
``math.exp/log10/cos`` and float ``**`` to the same C library functions CPython calls, so here
every recorded value is reproduced bit for bit. ``rel=1e-14`` (≈ 45 ulp) still passes on a
platform where numba's and CPython's libm differ by an ulp: an ulp in the argument of the
exponential of eq. (6), |m1 Fn^−0.9 + m cos λFn^−2| ≲ 30, becomes ≲ 30 ulp of R_W; anything
beyond that is a change of the arithmetic, not of the library.
"""

from __future__ import annotations

import numba as nb
import numpy as np
import pytest

from ship_gym.forces.resistance import (
    _HM_SIZE,
    _HM_VARIANT_1984,
    CalmWaterResistance,
    HoltropMennen,
    ResistanceParticulars,
    holtrop_components,
    holtrop_total,
    holtrop_wave_resistance,
)
from ship_gym.hull import load_hull

RTOL = 1e-14  # see the module docstring


def _example() -> ResistanceParticulars:
    """Holtrop & Mennen's (1982) worked example (as in tests/forces/test_propulsion.py)."""
    return ResistanceParticulars(
        length=205.0,
        beam=32.0,
        draught_fore=10.0,
        draught_aft=10.0,
        volume=37500.0,
        lcb=-0.75,
        midship_coefficient=0.98,
        waterplane_coefficient=0.75,
        bulb_area=20.0,
        bulb_centre_height=4.0,
        transom_area=16.0,
        stern_shape=10.0,
        appendage_area=50.0,
        appendage_form_factor=1.5,
    )


@pytest.fixture(scope="module")
def models() -> dict[tuple[str, str], HoltropMennen]:
    s175, wigley = load_hull("s175"), load_hull("wigley")
    out = {}
    for variant in ("1982", "1984"):
        out["s175", variant] = HoltropMennen.from_hull(s175, variant=variant)
        out["s175air", variant] = HoltropMennen.from_hull(
            s175, variant=variant, air_frontal_area=600.0
        )
        out["example", variant] = HoltropMennen(_example(), variant=variant, rho=1025.0, g=9.81)
        out["wigley", variant] = HoltropMennen.from_hull(wigley, variant=variant)
    return out


def _close(got: float, want: float) -> bool:
    return abs(got - want) <= RTOL * abs(want)


# R_T [N] of the pre-kernel implementation at speeds U [m/s] (3e-4 m/s: below U_min, Rn < 1e5)
_TOTAL_N = {
    ("s175", "1982"): {
        0.0: 0.0,
        0.0003: 0.0023896330036171486,
        0.3: 743.1223346916382,
        1.0: 7091.079719570703,
        3.0: 56324.079694439584,
        7.5: 335488.2096313059,
        10.36: 793525.6222178844,
        12.0: 1229178.7226955253,
        15.0: 2617161.9339208207,
    },
    ("s175", "1984"): {
        0.0: 0.0,
        0.0003: 0.002466187056136746,
        0.3: 764.7104804324692,
        1.0: 7292.028619751734,
        3.0: 57882.38904324177,
        7.5: 344470.7885546646,
        10.36: 797533.9861676308,
        12.0: 1258155.577249281,
        15.0: 2652072.1595805436,
    },
    ("s175air", "1982"): {
        0.0: 0.0,
        0.0003: 0.0024160930036171485,
        0.3: 769.5823346916383,
        1.0: 7385.079719570703,
        3.0: 58970.079694439584,
        7.5: 352025.7096313059,
        10.36: 825080.5246178844,
        12.0: 1271514.7226955253,
        15.0: 2683311.9339208207,
    },
    ("s175air", "1984"): {
        0.0: 0.0,
        0.0003: 0.002492647056136746,
        0.3: 791.1704804324693,
        1.0: 7586.028619751734,
        3.0: 60528.38904324177,
        7.5: 361008.2885546646,
        10.36: 829088.8885676308,
        12.0: 1300491.577249281,
        15.0: 2718222.1595805436,
    },
    ("example", "1982"): {
        0.0: 0.0,
        0.0003: 0.0035775487268066377,
        0.3: 1176.2867506555388,
        1.0: 11344.362983175675,
        3.0: 89109.57403483847,
        7.5: 486199.28381224716,
        10.36: 964798.5979817744,
        12.0: 1496162.6014863662,
        15.0: 2695112.626712518,
        20.0: 9522201.539961822,
        22.0: 12988275.05931361,
        26.0: 18586849.22707053,
        30.0: 23366255.316993747,
    },
    ("example", "1984"): {
        0.0: 0.0,
        0.0003: 0.003658797720726847,
        0.3: 1198.683643854696,
        1.0: 11553.239920245655,
        3.0: 90731.77413188262,
        7.5: 495194.3608597499,
        10.36: 990837.3178126959,
        12.0: 1483419.3690394321,
        15.0: 2767541.773885565,
        20.0: 9642097.839378743,
        22.0: 13182269.48619806,
        26.0: 19279382.198528558,
        30.0: 22576813.026024092,
    },
    ("wigley", "1982"): {
        0.0: 0.0,
        0.0003: 0.0006588003937664483,
        0.3: 227.8470669015466,
        1.0: 2171.4140553868983,
        3.0: 17256.9999239155,
        7.5: 122840.44054872644,
        10.36: 283302.8283870806,
        12.0: 507970.2074623224,
        15.0: 1236356.2663689493,
    },
    ("wigley", "1984"): {
        0.0: 0.0,
        0.0003: 0.0006936080274933796,
        0.3: 238.58143468698987,
        1.0: 2270.5627400430503,
        3.0: 18021.29162153027,
        7.5: 128735.74722153123,
        10.36: 303375.8634453941,
        12.0: 514450.4748691139,
        15.0: 954710.9699099797,
    },
}
_WAVE_N = {
    "1982": {
        0.0: 0.0,
        0.005: 0.0,
        0.05: 7.749834991293402e-06,
        0.2: 46630.01347401726,
        0.3: 639971.2328382022,
        0.4: 3605047.9774895846,
        0.45: 6934376.939785735,
        0.5: 10101314.028635781,
        0.55: 12611925.37998247,
        0.6: 14650000.723982645,
        0.8: 21997084.093971517,
    },
    "1984": {
        0.0: 0.0,
        0.005: 0.0,
        0.05: 7.749834991293402e-06,
        0.2: 44843.02089628032,
        0.3: 668796.3346213152,
        0.4: 3671141.5594579405,
        0.45: 6987720.739150372,
        0.5: 10304299.918842804,
        0.55: 13620879.098535236,
        0.6: 14926237.749754708,
        0.8: 18906773.85174821,
    },
}
_COMPONENTS = {
    ("example", "1984", 7.5): (
        0.1672437239207213,
        1293865185.5592024,
        0.0014828298523659623,
        315536.31178475026,
        3206.040325330313,
        9215.16709272788,
        23.44251220597503,
        33805.70091802378,
        75007.97536549786,
        0.0,
        495194.3608597499,
    ),
    ("example", "1984", 26.0): (
        0.5797782429251671,
        4485399309.938568,
        0.001280955129199343,
        3275790.4344211663,
        33284.01783833343,
        14462510.714703673,
        81.83559814303017,
        0.0,
        901429.179503583,
        0.0,
        19279382.198528558,
    ),
    ("example", "1982", 0.0003): (
        6.68974895682885e-06,
        51754.60742236809,
        0.008333333333333333,
        0.002837244487008308,
        2.8828124999999998e-05,
        0.0,
        7.390390649689613e-12,
        0.0001475927727494661,
        0.00012001276058479655,
        0.0,
        0.0035775487268066377,
    ),
    ("s175", "1982", 10.36): (
        0.2488588361666796,
        1540203231.507195,
        0.0014517643192204198,
        427853.92335936823,
        0.0,
        202083.91531983417,
        0.0,
        0.0,
        115017.62723139892,
        0.0,
        793525.6222178844,
    ),
}


@pytest.mark.parametrize("key", sorted(_TOTAL_N))
def test_total_matches_recorded_values(models, key):
    hm = models[key]
    params = hm.kernel_parameters()
    force = CalmWaterResistance(hm)
    speeds = np.array(sorted(_TOTAL_N[key]))
    for u, want in _TOTAL_N[key].items():
        got = holtrop_total(params, u)
        assert _close(got, want), (key, u, got, want)
        assert holtrop_total(params, -u) == got  # R_T(|U|)
        assert hm.total_scalar(u) == got and hm.total(u) == got
        assert force.resistance(-u) == got and force.curve(u) == got
    np.testing.assert_array_equal(hm.total(speeds), [holtrop_total(params, u) for u in speeds])


@pytest.mark.parametrize("key", sorted(_COMPONENTS))
def test_components_match_recorded_values(models, key):
    hull, variant, u = key
    hm = models[hull, variant]
    got = holtrop_components(hm.kernel_parameters(), u)
    assert len(got) == 11
    for g, w in zip(got, _COMPONENTS[key], strict=True):
        assert _close(g, w), (key, got, _COMPONENTS[key])
    assert hm._scalar(u) == got
    c = hm.components(u)
    fields = (
        "froude_number", "reynolds_number", "friction_coefficient", "friction", "appendage",
        "wave", "bulb", "transom", "correlation", "air", "total",
    )  # fmt: skip
    assert tuple(getattr(c, f) for f in fields) == got


@pytest.mark.parametrize("variant", ["1982", "1984"])
def test_wave_resistance_matches_recorded_values(models, variant):
    hm = models["example", variant]
    params = hm.kernel_parameters()
    for fn, want in _WAVE_N[variant].items():
        got = holtrop_wave_resistance(params, fn)
        assert _close(got, want), (variant, fn, got, want)
        assert hm.wave_resistance(fn) == got
    assert hm.wave_resistance(np.float64(0.3)) == holtrop_wave_resistance(params, 0.3)
    with pytest.raises(ValueError):  # float("fast"), as before the kernel
        hm.wave_resistance("fast")  # type: ignore[arg-type]


def test_kernel_parameters_record(models):
    for (_, variant), hm in models.items():
        params = hm.kernel_parameters()
        assert params.shape == (_HM_SIZE,) and params.dtype == np.float64
        assert np.all(np.isfinite(params))
        assert params[_HM_VARIANT_1984] == (1.0 if variant == "1984" else 0.0)
    hm = models["s175", "1984"]
    params = hm.kernel_parameters()
    params[:] = 0.0  # a copy: the model is unaffected
    # the frozen value to round-off (1 ulp apart between CPU/numpy builds): zeroing the model's
    # own parameters would change it entirely
    assert hm.total_scalar(10.36) == pytest.approx(_TOTAL_N["s175", "1984"][10.36], rel=1e-13)
    np.testing.assert_array_equal(CalmWaterResistance(hm).kernel_parameters(), hm._params)


@nb.njit
def _surge_forces(records, u):  # pragma: no cover - compiled
    """X = −R_T(|u|) sign(u) per ship, as the compiled engine would evaluate it."""
    out = np.zeros(u.shape[0])
    for i in range(u.shape[0]):
        if u[i] != 0.0:
            out[i] = -np.sign(u[i]) * holtrop_total(records[i], u[i])
    return out


def test_callable_from_njit(models):
    keys = [("s175", "1982"), ("example", "1984"), ("wigley", "1984")]
    records = np.stack([models[k].kernel_parameters() for k in keys])
    u = np.array([7.5, -12.0, 3.0])
    got = _surge_forces(records, u)
    want = [-_TOTAL_N[keys[0]][7.5], _TOTAL_N[keys[1]][12.0], -_TOTAL_N[keys[2]][3.0]]
    np.testing.assert_array_equal(got, want)
    assert _surge_forces(records, np.zeros(3)).tolist() == [0.0, 0.0, 0.0]


def test_generic_curve_has_no_kernel():
    curve = lambda u: 1.0e3 * u * u  # noqa: E731
    model = CalmWaterResistance(curve)
    assert model.holtrop is None and model.curve is curve
    with pytest.raises(NotImplementedError, match="generic callable curve"):
        model.kernel_parameters()
    with pytest.raises(AttributeError):
        model.curve = abs  # type: ignore[misc]
