"""Smoke and consistency checks of :mod:`ship_gym.analysis.accuracy` on tiny configurations
(the full study: ``scripts/accuracy_study.py``, ``docs/accuracy/results.md``)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from ship_gym.analysis import accuracy as acc


def test_combinations_hold_the_baselines() -> None:
    quick = acc.combinations(quick=True)
    assert list(quick) == [acc.REFERENCE, acc.CURRENT, acc.CANDIDATE, acc.RECOMMENDED]
    full = acc.combinations(quick=False)
    assert set(quick) <= set(full)
    assert all(c.mesh in acc.MESHES for c in full)
    assert acc.REFERENCE.label == "9600/fast/rk4/0.025"


@pytest.fixture(scope="module")
def hydro() -> dict:
    # three small meshes, 5400 faces standing in for the 9600-face reference; 4 heels
    return acc.hydrostatics_study(
        ["1500", "2400", "5400"], np.array([0.0, 20.0, 40.0, 60.0]), reference="5400"
    )


def test_hydrostatics_reference_has_zero_error(hydro: dict) -> None:
    ref = hydro["meshes"]["5400"]["vs_reference"]
    assert ref["gz_max_abs_mm"] == 0.0
    assert ref["gmt_mm"] == 0.0
    assert ref["displacement_rel"] == 0.0
    for m in hydro["meshes"].values():
        assert all(np.isfinite(m["vs_reference"]["gz_mm"]))


def test_coarser_mesh_has_larger_gz_error(hydro: dict) -> None:
    m = hydro["meshes"]
    assert m["1500"]["faces"] < m["2400"]["faces"] < m["5400"]["faces"]
    assert m["1500"]["vs_reference"]["gz_max_abs_mm"] > m["2400"]["vs_reference"]["gz_max_abs_mm"]
    assert m["2400"]["vs_reference"]["gz_max_abs_mm"] > 0.0


def _run(amplitude: float, phase: float = 0.0, diverged: bool = False) -> dict:
    t = np.arange(0.0, 200.0, 0.1)
    x = amplitude * np.sin(0.2 * math.pi * t + phase)  # 10 s period: whole periods after 100 s
    return {"t": t, "x": {k: x for k in acc.DOFS}, "diverged": diverged, "wall_s": 0.0}


def test_wave_statistics_and_errors() -> None:
    ref = _run(2.0)
    stats = acc.wave_statistics(ref, 100.0)
    assert stats["roll"]["rms"] == pytest.approx(2.0 / math.sqrt(2.0), rel=1e-3)
    assert stats["roll"]["amplitude"] == pytest.approx(2.0, rel=1e-3)
    # the reference against itself: zero error
    for e in acc.wave_errors(ref, ref, 100.0).values():
        assert e == {"rms_rel": 0.0, "amplitude_rel": 0.0, "series_rel": 0.0}
    # 1 % larger amplitude: +1 % RMS and amplitude, 1 % series error
    e = acc.wave_errors(_run(2.02), ref, 100.0)["heave"]
    assert e["rms_rel"] == pytest.approx(0.01, rel=1e-6)
    assert e["amplitude_rel"] == pytest.approx(0.01, rel=1e-3)
    assert e["series_rel"] == pytest.approx(0.01, rel=1e-3)
    # a phase shift leaves the RMS but not the time series
    e = acc.wave_errors(_run(2.0, phase=0.1), ref, 100.0)["pitch"]
    assert abs(e["rms_rel"]) < 1e-3
    assert e["series_rel"] == pytest.approx(0.1, rel=0.01)
    # a diverged run: NaN errors
    assert all(
        math.isnan(v)
        for v in acc.wave_errors(_run(2.0, diverged=True), ref, 100.0)["roll"].values()
    )


def test_summary_and_criteria() -> None:
    fine, coarse = acc.REFERENCE, acc.CANDIDATE
    hydro = {
        "meshes": {
            fine.mesh: {"vs_reference": {"gz_max_abs_mm": 0.0, "gmt_mm": 0.0}},
            coarse.mesh: {"vs_reference": {"gz_max_abs_mm": 4.0, "gmt_mm": 1.0}},
        }
    }
    decay = {
        fine.label: {"period_rel": 0.0, "amplitude_rel": 0.0},
        coarse.label: {"period_rel": 0.005, "amplitude_rel": 0.01},
    }
    ref, run = _run(2.0), _run(2.05)
    waves = {
        name: {
            "runs": {
                fine.label: {"errors": acc.wave_errors(ref, ref, 100.0)},
                coarse.label: {"errors": acc.wave_errors(run, ref, 100.0)},
            }
        }
        for name in ("regular", "irregular")
    }
    cost = {
        fine.label: {"cpu_ratio_to_current": 5.0, "wall_ratio_to_current": 5.0},
        coarse.label: {"cpu_ratio_to_current": 0.3, "wall_ratio_to_current": 0.3},
    }
    summary = acc.summarise([fine, coarse], hydro, decay, waves, cost)
    assert summary[fine.label]["rms_max"] == 0.0
    assert summary[coarse.label]["rms_max"] == pytest.approx(0.025, rel=1e-6)
    assert summary[coarse.label]["passes_3pct"] and not summary[coarse.label]["passes_2pct"]
    assert acc.cheapest_passing(summary, acc.CRITERIA["rms_loose"]) == coarse.label
    assert acc.cheapest_passing(summary, acc.CRITERIA["rms_strict"]) == fine.label


def test_roll_decay_of_the_fast_setting() -> None:
    """Calm-water roll decay of the candidate fast setting: the period of the S175 at
    KG 9.55 m (the full study: 17.68 s for this setting, 17.75 s for the reference)."""
    d = acc.roll_decay(acc.CANDIDATE, 75.0)
    assert not d["diverged"]
    assert d["period_s"] == pytest.approx(17.7, abs=0.3)
    assert 0.0 < d["amplitude_3_cycles_deg"] < acc.ROLL0_DEG
