"""Fixtures of the ship-file tests: a hull that is not in the library, as an STL and a ship file."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from ship_gym.hull.mesh_io import write_mesh
from ship_gym.hull.offsets import Station, hull_mesh_from_stations

PATROL = dict(length=60.0, beam=9.0, draught=3.0, depth=5.0)
"""Main dimensions [m] of the test hull (a 60 m patrol-boat-like form)."""


def patrol_mesh(n_sections: int = 20, n_below: int = 5):
    """A 60 m hull with a fine bow, a transom and cubic sections, closed to the deck."""
    length, beam, draught, depth = (PATROL[k] for k in ("length", "beam", "draught", "depth"))
    stations = []
    zeta = np.linspace(0.0, 1.0, 21)  # fraction of the draught below the waterline
    for x in np.linspace(-length / 2, length / 2, 21):
        xi = 2 * x / length
        fore = 1 - 0.97 * max(xi, 0.0) ** 2
        aft = 1 - 0.6 * max(-xi, 0.0) ** 4
        half = 0.5 * beam * fore * aft * (1 - zeta**3)
        stations.append(Station(float(x), half[::-1], (draught * (1 - zeta))[::-1]))
    return hull_mesh_from_stations(
        stations, draught=draught, depth=depth, n_sections=n_sections, n_below=n_below,
        n_above=3, n_deck=2, name="patrol",
    )  # fmt: skip


SHIP_FILE = """\
schema = 1
name = "patrol60"
description = "60 m test hull, not in the library"

[hull]
mesh = "patrol.stl"          # z up, as CAD writes it

[loading]
gm_m = 1.2

[speed]
service_froude = 0.3

[hydrodynamics]
n_omega = 10
omega_max_rad_s = 2.4
headings_deg = [0, 90, 180]
"""


@pytest.fixture
def patrol_ship(tmp_path: Path) -> Path:
    """The test hull as an STL (z-up frame, triangles) and its ship file; returns the file."""
    write_mesh(patrol_mesh(), tmp_path / "patrol.stl", frame="z_up")
    path = tmp_path / "patrol.toml"
    path.write_text(SHIP_FILE)
    return path


@pytest.fixture
def ship_cache(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> Path:
    """An empty database cache for the test."""
    cache = tmp_path / "cache"
    monkeypatch.setenv("SHIP_GYM_CACHE", str(cache))
    return cache
