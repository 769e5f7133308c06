"""``ship-gym hydro`` end to end (issue #14): a library hull other than the S175 builds, and a
database that fails validation is kept next to the output instead of being thrown away."""

from __future__ import annotations

from pathlib import Path

import pytest

from ship_gym.cli import main
from ship_gym.hydro.checks import validate_database
from ship_gym.hydro.database import load_database, open_database
from tests.hydro.test_database_io import synthetic_database

# ω_max resolved by this mesh (2.0 rad/s) is above 1.5 x its heave natural frequency (1.3 rad/s)
WIGLEY = ["--set", "n_sections=50", "n_below=4", "n_above=1"]


@pytest.mark.filterwarnings("ignore:.*not in equilibrium")
def test_hydro_builds_a_valid_wigley_database(tmp_path, capsys) -> None:
    output = tmp_path / "tmp" / "x.nc"
    argv = ["hydro", "wigley", *WIGLEY, "--n-omega", "10", "--headings", "180"]
    assert main([*argv, "--output", str(output)]) == 0
    out = capsys.readouterr().out
    assert "wigley" in out and str(output) in out
    ds = load_database(output)
    assert ds.sizes["omega"] == 12 and ds.sizes["wave_direction"] == 1
    validate_database(ds)


def test_a_rejected_database_is_saved_next_to_the_output(tmp_path, monkeypatch, capsys) -> None:
    import ship_gym.hydro.bem as bem

    broken = synthetic_database()
    broken["radiation_damping"].values[5, 2, 2] = -1e6  # a negative heave damping
    monkeypatch.setattr(bem, "compute_hull_database", lambda hull, **kwargs: broken)
    output = tmp_path / "db.nc"
    assert main(["hydro", "box_barge", "--output", str(output)]) == 1
    err = capsys.readouterr().err
    rejected = tmp_path / "db.rejected.nc"
    assert str(rejected) in err and "failed validation" in err
    assert "negative radiation damping" in err and "Traceback" not in err
    assert not output.exists() and rejected.is_file()
    kept = open_database(rejected, validate="none")
    assert float(kept["radiation_damping"].values[5, 2, 2]) == -1e6


def test_hydro_passes_the_checkpoint_folder(tmp_path, monkeypatch) -> None:
    import ship_gym.hydro.bem as bem

    seen: list[Path | None] = []

    def fake(hull, **kwargs):
        seen.append(kwargs.get("checkpoint"))
        return synthetic_database()

    monkeypatch.setattr(bem, "compute_hull_database", fake)
    checkpoint = tmp_path / "new" / "ckpt"
    argv = ["hydro", "box_barge", "--output", str(tmp_path / "db.nc")]
    assert main([*argv, "--checkpoint", str(checkpoint)]) == 0
    assert seen == [checkpoint] and checkpoint.is_dir()  # created before the BEM
