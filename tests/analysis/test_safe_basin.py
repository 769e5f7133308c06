"""Safe basins (McCue & Campbell fig. 8) against the energy separatrix, and their erosion."""

from __future__ import annotations

import math

import numpy as np
import pytest

from ship_gym.analysis.safe_basin import (
    integrity_curve,
    plot_basin,
    s175_safe_basin,
    safe_basin,
    write_basin,
    write_integrity_csv,
)
from ship_gym.roll.equation import RollEquation

ET = RollEquation.edith_terkol()
UNDAMPED = RollEquation(c1=ET.c1, c2=ET.c2, c3=ET.c3, c4=ET.c4, c5=ET.c5)
GRID = {"n_roll": 61, "n_rate": 41, "roll_range": (-1.0, 1.0), "roll_rate_range": (-0.6, 0.6)}


def test_undamped_unforced_basin_is_the_energy_separatrix():
    # b = 0, F = 0: ½φ̇² + V(φ) is conserved, so a cell is safe iff its energy is below the
    # barrier V(φᵥ) and it starts inside the well (|φ₀| < φᵥ). Cells whose energy is within the
    # energy change across half a cell diagonal of the barrier (|∇E| · ½ cell diagonal) may go
    # either way — the grid only resolves the boundary to a cell — and, just above the barrier,
    # the time to reach the hilltop grows like log(1/ΔE): those are excluded, every other cell
    # must agree (duration 300 s ≫ the 10 s period).
    basin = safe_basin(UNDAMPED, duration=300.0, dt=0.05, **GRID)
    phi, rate = np.meshgrid(basin.roll, basin.roll_rate)
    pv = UNDAMPED.vanishing_angle()
    e = UNDAMPED.energy(phi, rate)
    barrier = float(UNDAMPED.potential_energy(pv))
    d_roll = basin.roll[1] - basin.roll[0]
    d_rate = basin.roll_rate[1] - basin.roll_rate[0]
    grad = np.hypot(UNDAMPED.restoring(phi), rate)
    band = grad * 0.5 * math.hypot(d_roll, d_rate)
    inside_well = np.abs(phi) < pv
    sure_safe = inside_well & (e < barrier - band)
    sure_capsize = ~inside_well | (e > barrier + band)
    assert np.all(basin.safe[sure_safe])
    assert np.all(basin.capsized[sure_capsize])
    undecided = ~(sure_safe | sure_capsize)
    assert undecided.mean() < 0.08  # the band is a thin strip along the separatrix
    # safe area vs the area inside the separatrix, 2∫√(2(Vᵥ − V)) dφ, to one cell row of the
    # boundary (perimeter ≈ 4 rad → ≈ 4·max(dφ, dφ̇) rad²/s)
    x = np.linspace(-pv, pv, 20001)
    area = np.trapezoid(2 * np.sqrt(np.maximum(2 * (barrier - UNDAMPED.potential_energy(x)), 0)), x)
    assert basin.safe_area == pytest.approx(area, abs=4 * max(d_roll, d_rate) * 0.5)


def test_damped_unforced_basin_strictly_contains_the_undamped_one():
    undamped = safe_basin(UNDAMPED, duration=200.0, **GRID)
    damped = safe_basin(ET, duration=200.0, **GRID)  # F = 0, b₁, b₂ of the Edith Terkol
    assert not np.any(undamped.safe & damped.capsized)  # ⊆: damping only removes energy
    assert damped.safe_fraction > undamped.safe_fraction  # strictly: tails beyond the barrier


def test_integrity_decreases_with_forcing_amplitude():
    # Monotone erosion (Soliman & Thompson): a tolerance of 0.02 for the fractal boundary
    # details; the curve must also fall substantially (to < 5 % by F = 0.08 rad/s²).
    amps = [0.0, 0.01, 0.02, 0.03, 0.04, 0.06, 0.08]
    curve = integrity_curve(
        RollEquation.edith_terkol(), amps, duration=150.0, dt=0.1, n_roll=41, n_rate=31,
        roll_range=(-1.0, 1.0), roll_rate_range=(-0.6, 0.6),
    )  # fmt: skip
    assert curve.integrity[0] == pytest.approx(1.0)
    assert np.all(np.diff(curve.integrity) < 0.02), curve.integrity
    assert curve.integrity[2] < 0.8 and curve.integrity[-1] < 0.05


def test_capsize_time_and_outside_cells():
    b = safe_basin(ET, duration=50.0, n_roll=5, n_rate=3, roll_range=(-1.0, 1.0))
    # |φ₀| = 1 > φᵥ: capsized at t = 0
    assert b.capsized[:, 0].all() and b.capsized[:, -1].all()
    np.testing.assert_array_equal(b.capsize_time[:, 0], 0.0)
    assert np.all(np.isnan(b.capsize_time[b.safe]))
    assert np.all(b.capsize_time[b.capsized] <= 50.0)
    assert b.safe[1, 2]  # upright at rest is safe


def test_bad_arguments_raise():
    with pytest.raises(ValueError, match="grid points"):
        safe_basin(ET, n_roll=1)
    with pytest.raises(ValueError, match="roll range"):
        safe_basin(ET, roll_range=(1.0, -1.0))
    with pytest.raises(ValueError, match="duration"):
        safe_basin(ET, duration=-1.0)
    with pytest.raises(ValueError, match="vanishing"):
        safe_basin(RollEquation(c1=0.4))
    with pytest.raises(ValueError, match="amplitudes"):
        integrity_curve(ET, [-0.1])


def test_files_written(tmp_path):
    b = safe_basin(ET, duration=20.0, n_roll=6, n_rate=4)
    csv = write_basin(b, tmp_path / "b.csv")
    rows = [r for r in csv.read_text().splitlines() if not r.startswith("#")]
    assert rows[0] == "roll_rad,roll_rate_rad_s,capsized,capsize_time_s" and len(rows) == 25
    nc = write_basin(b, tmp_path / "b.nc")
    import xarray as xr

    with xr.open_dataset(nc) as ds:
        np.testing.assert_array_equal(ds["capsized"].values.astype(bool), b.capsized)
    curve = integrity_curve(ET, [0.0, 0.05], duration=20.0, n_roll=6, n_rate=4)
    text = write_integrity_csv(curve, tmp_path / "c.csv").read_text()
    assert "integrity" in text and len(text.splitlines()) == 4
    png = plot_basin(b, tmp_path / "b.png", separatrix_of=ET)
    assert png.read_bytes()[:4] == b"\x89PNG"


@pytest.mark.slow
def test_s175_roll_only_basin_small_grid():
    # Calm water, roll only: upright at rest is safe, cells beyond the GZ vanishing angle
    # (66.2°) are capsized at t = 0, and a large roll rate toward the capsize side capsizes.
    # Slow: building the simulator and 200 steps of 9 ships take ≈ 15 s CPU.
    b = s175_safe_basin(
        n_roll=3, n_rate=3, roll_range=(-1.3, 0.0), roll_rate_range=(-0.9, 0.0), duration=20.0
    )
    assert b.capsize_angle == pytest.approx(math.radians(66.23), abs=0.01)
    assert b.safe[-1, -1]  # (0, 0)
    assert b.capsized[:, 0].all() and np.all(b.capsize_time[:, 0] == 0.0)  # φ₀ = −1.3 rad
    assert b.capsized[0, 1]  # φ₀ = −0.65 rad, φ̇₀ = −0.9 rad/s: thrown over within 20 s


def test_cli_safe_basin_edith_terkol(tmp_path, capsys):
    import argparse
    import json

    from ship_gym.cli import safe_basin as cli_safe_basin

    parser = argparse.ArgumentParser()
    cli_safe_basin.add_commands(parser.add_subparsers())
    args = parser.parse_args(
        [
            "safe-basin", "--model", "edith-terkol", "--forcing", "0.03", "--grid", "11",
            "--duration", "60", "--integrity", "0", "0.03", "--no-progress",
            "--json", str(tmp_path / "b.json"), "--csv", str(tmp_path / "b.csv"),
            "--plot", str(tmp_path / "b.png"),
        ]
    )  # fmt: skip
    assert args.func(args) == 0
    payload = json.loads((tmp_path / "b.json").read_text())
    assert payload["grid"] == [11, 11] and 0.0 < payload["integrity"] < 1.0
    assert payload["integrity_curve"]["integrity"][0] == pytest.approx(1.0)
    # the curve's F = 0.03 point is the basin itself
    assert payload["integrity_curve"]["integrity"][1] == pytest.approx(payload["integrity"])
    assert (tmp_path / "b.png").exists() and (tmp_path / "b.csv").exists()
    assert "integrity" in capsys.readouterr().out
