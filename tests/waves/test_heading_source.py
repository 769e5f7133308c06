"""One source of truth for the wave heading, and no silent heading extrapolation (issue 15,
item 9)."""

from __future__ import annotations

import dataclasses
import math
import pickle
import warnings

import numpy as np
import pytest

from ship_gym.engine.ship import resolve_wave_heading, wave_field_for
from ship_gym.forces.diffraction import (
    Diffraction,
    covered_heading_arcs,
    describe_arcs,
    heading_distance_to_arcs,
)
from ship_gym.hydro import load_database
from ship_gym.waves.sea_state import DEFAULT_HEADING, IrregularSea, RegularWave, heading_is_set

RNG = np.random.default_rng


# ---------------------------------------------------------------------- the sea's heading
def test_default_heading_is_zero_but_marked_as_unset() -> None:
    for sea in (IrregularSea(hs=2.0, tp=8.0), RegularWave(2.0, period=9.0)):
        assert sea.heading == 0.0 and not heading_is_set(sea)
        assert repr(sea.heading) == "0.0" and DEFAULT_HEADING == 0.0
        assert not heading_is_set(pickle.loads(pickle.dumps(sea)))
        assert not heading_is_set(dataclasses.replace(sea, ramp_time=10.0))
        assert heading_is_set(dataclasses.replace(sea, heading=0.0))
    assert heading_is_set(IrregularSea(hs=2.0, tp=8.0, heading=0.0))
    assert heading_is_set(RegularWave(2.0, period=9.0, heading=1.0))
    assert IrregularSea(hs=2.0, tp=8.0) == IrregularSea(hs=2.0, tp=8.0, heading=0.0)


@pytest.mark.parametrize(
    ("sea_heading", "wave_heading"),
    [(0.0, math.pi), (1.0, 2.0), (math.pi, 0.0), (-0.5, 0.5), (0.3, 0.3 + 1e-6)],
)
@pytest.mark.parametrize("kind", ["irregular", "regular"])
def test_conflicting_headings_raise_naming_both(sea_heading, wave_heading, kind) -> None:
    if kind == "irregular":
        sea: IrregularSea | RegularWave = IrregularSea(hs=2.0, tp=8.0, heading=sea_heading)
    else:
        sea = RegularWave(2.0, period=9.0, heading=sea_heading)
    with pytest.raises(ValueError) as err:
        wave_field_for(sea, wave_heading, RNG(0))
    message = str(err.value)
    assert f"heading={sea_heading!r}" in message and f"wave_heading={wave_heading!r}" in message
    assert "give only one" in message


def test_which_heading_wins() -> None:
    explicit = IrregularSea(hs=2.0, tp=8.0, heading=0.7)
    unset = IrregularSea(hs=2.0, tp=8.0)
    # only the sea's heading
    np.testing.assert_allclose(wave_field_for(explicit, None, RNG(0)).direction, 0.7)
    # only wave_heading
    np.testing.assert_allclose(wave_field_for(unset, 1.3, RNG(0)).direction, 1.3)
    # both, equal (also modulo 2π)
    np.testing.assert_allclose(wave_field_for(explicit, 0.7, RNG(0)).direction, 0.7)
    wave_field_for(explicit, 0.7 + 2.0 * math.pi, RNG(0))
    # neither: the default of the caller (0 for wave_field_for, π for build_simulator)
    np.testing.assert_allclose(wave_field_for(unset, None, RNG(0)).direction, 0.0)
    assert resolve_wave_heading(unset, None, default=math.pi) == math.pi
    assert resolve_wave_heading(explicit, None, default=math.pi) == 0.7
    assert resolve_wave_heading(None, None, default=math.pi) == math.pi
    assert wave_field_for(None, 1.0) is None
    # the same sea realisation as before when the heading comes from wave_heading only
    a = wave_field_for(unset, 1.3, RNG(5))
    b = wave_field_for(dataclasses.replace(unset, heading=1.3), None, RNG(5))
    np.testing.assert_array_equal(a.phase, b.phase)
    np.testing.assert_array_equal(a.direction, b.direction)


@pytest.mark.parametrize("bad", [float("nan"), float("inf"), "south", [1.0, 2.0]])
def test_bad_wave_heading_values(bad) -> None:
    sea = IrregularSea(hs=2.0, tp=8.0)
    with pytest.raises(ValueError, match="wave_heading"):
        wave_field_for(sea, bad, RNG(0))


# ---------------------------------------------------------------------- coverage
def test_covered_arcs() -> None:
    deg = np.radians
    assert covered_heading_arcs(deg(np.arange(0, 360, 15)), deg(90)) == [(0.0, 2 * math.pi)]
    assert describe_arcs(covered_heading_arcs(deg([0, 90, 180, 270]), deg(90))) == "all headings"
    arcs = covered_heading_arcs(deg([135, 180, 225]), deg(90))
    np.testing.assert_allclose(np.degrees(arcs), [[135, 225]])
    np.testing.assert_allclose(np.degrees(covered_heading_arcs(deg([350, 0, 10]), deg(90))),
                               [[350, 370]])  # fmt: skip
    d = heading_distance_to_arcs(deg([45, 135, 200, 230, 0, 355]), arcs)
    np.testing.assert_allclose(np.degrees(d), [90, 0, 0, 5, 135, 130], atol=1e-9)
    two = covered_heading_arcs(deg([0, 10, 180, 190]), deg(30))
    assert len(two) == 2 and "0-10 deg" in describe_arcs(two) and "180-190" in describe_arcs(two)


@pytest.fixture(scope="module")
def s175():
    return load_database("s175")


@pytest.fixture(scope="module")
def head_only(s175):
    """Only 135° and 180° (mirrored to 225° by the hull's symmetry)."""
    return s175.sel(wave_direction=s175.wave_direction.values[[9, 12]])


@pytest.mark.parametrize("deg", [0.0, 20.0, 45.0, 90.0, 100.0, 270.0, 315.0])
def test_partial_database_refuses_uncovered_heading(head_only, deg) -> None:
    field = wave_field_for(RegularWave(2.0, period=9.0), math.radians(deg))
    with pytest.raises(ValueError) as err:
        Diffraction(head_only, field)
    message = str(err.value)
    assert f"wave heading {deg:g} deg" in message
    assert "135-225 deg" in message and "database headings 135, 180" in message
    assert "heading_extrapolation='warn'" in message


@pytest.mark.parametrize("deg", [135.0, 150.0, 180.0, 210.0, 225.0])
def test_partial_database_accepts_covered_heading_silently(head_only, deg) -> None:
    field = wave_field_for(RegularWave(2.0, period=9.0), math.radians(deg))
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        Diffraction(head_only, field)


def test_within_tolerance_warns_and_options(head_only) -> None:
    near = wave_field_for(RegularWave(2.0, period=9.0), math.radians(228.0))
    with pytest.warns(UserWarning, match="wave heading 228 deg"):
        Diffraction(head_only, near)
    far = wave_field_for(RegularWave(2.0, period=9.0), math.radians(45.0))
    with pytest.warns(UserWarning, match=r"wave heading 45 deg.*135-225 deg"):
        Diffraction(head_only, far, heading_extrapolation="warn")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        Diffraction(head_only, far, heading_extrapolation="allow")
    with pytest.warns(UserWarning, match="90 deg outside"):  # within the tolerance: warns only
        Diffraction(head_only, far, heading_extrapolation_tolerance_deg=95.0)
    for bad in ({"heading_extrapolation": "maybe"}, {"max_heading_gap_deg": -1.0},
                {"heading_extrapolation_tolerance_deg": float("nan")}):  # fmt: skip
        with pytest.raises(ValueError, match=next(iter(bad))):
            Diffraction(head_only, far, **bad)


def test_short_crested_sea_edges_are_checked(head_only) -> None:
    sea = IrregularSea(hs=3.0, tp=10.0, spreading_s=1.0, n_directions=7, n_components=10)
    field = wave_field_for(sea, math.pi, RNG(1))
    with pytest.raises(ValueError, match="outside the headings"):
        Diffraction(head_only, field)
    Diffraction(head_only, field, heading_extrapolation="allow")


def test_symmetric_half_circle_database_is_never_flagged(s175) -> None:
    # 0–180° on a port–starboard symmetric hull covers 180–360° by mirroring
    for deg in (0.0, 45.0, 200.0, 270.0, 330.0, 359.0):
        field = wave_field_for(RegularWave(2.0, period=9.0), math.radians(deg))
        with warnings.catch_warnings():
            warnings.simplefilter("error")
            model = Diffraction(s175, field)
        assert model.covered_headings == [(0.0, 2 * math.pi)]
    sea = IrregularSea(hs=4.0, tp=10.0, spreading_s=2.0, n_directions=5, n_components=10)
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        Diffraction(s175, wave_field_for(sea, 0.3, RNG(0)))
