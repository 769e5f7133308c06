"""A user's own ship from an STL, end to end (issue 14's acceptance test): ship file → ``ship-gym
ship check|build`` (BEM once, cached) → ``simulate``, a capsize-map cell and every ship
environment id (``check_env``, the vector env), with the database checked against the hull."""

from __future__ import annotations

import json
import threading
from pathlib import Path

import gymnasium as gym
import numpy as np
import pytest
from gymnasium.utils.env_checker import check_env

import ship_gym  # noqa: F401  (registers the ids)
from ship_gym.cli import main
from ship_gym.ship import DatabaseMismatchError, load_ship
from ship_gym.ship.database_cache import cache_path, cached_database

SHIP_ENV_IDS = (
    "ship_gym/CourseKeeping-v2",
    "ship_gym/RollStabilization-v2",
    "ship_gym/RideControl-v2",
    "ship_gym/CapsizeAvoidance-v2",
)
"""Every registered id built on the 6-DOF ship model (RollOneDOF is the 1-DOF Edith Terkol
equation, with no hull to choose)."""


def test_own_ship_from_an_stl_runs_everywhere(
    patrol_ship: Path, ship_cache: Path, tmp_path: Path, capsys: pytest.CaptureFixture
):
    ship_file = str(patrol_ship)
    assert main(["ship", "check", ship_file, "--plot", "", "--json", str(tmp_path / "c.json")]) == 0
    report = json.loads((tmp_path / "c.json").read_text())
    assert report["hydrostatics"]["gmt_m"] == pytest.approx(1.2, abs=1e-9)
    assert report["database"]["state"].startswith("not built")
    assert report["appendages"]["provenance"]["rudder.area"] == "estimated"

    # the database is built once, cached by content, then reused
    assert main(["ship", "build", ship_file]) == 0
    ship = load_ship(patrol_ship)
    path = cache_path(ship.hull, ship.description)
    assert path.is_file() and path.parent.parent == ship_cache
    stamp = path.stat().st_mtime_ns
    capsys.readouterr()
    assert main(["ship", "build", ship_file]) == 0
    assert "already built" in capsys.readouterr().out
    assert path.stat().st_mtime_ns == stamp
    ds = ship.database()
    assert ds.attrs["ship"] == "patrol60"
    # an exactly symmetric mesh gives an exactly symmetric database (no sway-heave coupling)
    a = ds["added_mass"].sel(influenced_dof="Heave", radiating_dof="Sway").values
    assert np.max(np.abs(a)) == 0.0

    out = tmp_path / "out"
    assert main(["simulate", "--ship", ship_file, "--regular", "1.5", "50", "--heading-deg",
                 "45", "--speed", "6", "--duration", "30", "--hold", "surge,sway,yaw",
                 "--output", str(out / "s.nc"), "--plot", ""]) == 0  # fmt: skip
    assert main(["capsize-map", "--ship", ship_file, "--headings", "45", "--froude", "0.3",
                 "--sea", "regular:2:60", "--seeds", "1", "--duration", "30",
                 "--capsize-angle", "60", "--results", str(out / "cm.jsonl"), "--plot", "",
                 "--no-progress"]) == 0  # fmt: skip
    assert (out / "cm.jsonl").read_text().strip()

    for env_id in SHIP_ENV_IDS:
        env = gym.make(env_id, ship=ship_file, hs_range_m=(1.0, 2.0)) if "Capsize" not in env_id \
            else gym.make(env_id, ship=ship_file)  # fmt: skip
        check_env(env.unwrapped, skip_render_check=True)
        obs, info = env.reset(seed=3)
        for _ in range(4):
            obs, reward, _, _, info = env.step(env.action_space.sample())
        assert np.all(np.isfinite(obs)) and np.isfinite(reward)
        assert not info["diverged"]
        assert env.unwrapped.task.sim.hull.name == "patrol60"
        env.close()
        vec = gym.make_vec(env_id, num_envs=2, vectorization_mode="vector_entry_point",
                           ship=ship_file)  # fmt: skip
        vec.reset(seed=0)
        obs, *_ = vec.step(vec.action_space.sample())
        assert obs.shape[0] == 2 and np.all(np.isfinite(obs))
        vec.close()


def test_a_foreign_database_is_refused_for_the_own_ship(patrol_ship: Path, ship_cache: Path):
    foreign = patrol_ship.parent / "foreign.toml"
    foreign.write_text(patrol_ship.read_text().replace("n_omega = 10", 'database = "s175"'))
    ship = load_ship(foreign)
    with pytest.raises(DatabaseMismatchError, match="does not belong to hull 'patrol60'"):
        ship.database()
    code = main(["simulate", "--ship", str(patrol_ship), "--database", "s175", "--duration", "1",
                 "--output", "", "--plot", ""])  # fmt: skip
    assert code == 1


def test_concurrent_builds_of_one_database_build_it_once(
    patrol_ship: Path, ship_cache: Path, monkeypatch: pytest.MonkeyPatch
):
    """Two builders of the same key: the second waits on the file lock and reads the first's
    database (the BEM runs once); a missing database without ``build`` names the command."""
    import ship_gym.hydro.bem as bem

    ship = load_ship(patrol_ship)
    with pytest.raises(FileNotFoundError, match="ship-gym ship build"):
        cached_database(ship.hull, ship.description, build=False)
    calls = []
    real = bem.compute_hull_database

    def counting(*args, **kwargs):
        calls.append(threading.get_ident())
        return real(*args, **kwargs)

    monkeypatch.setattr(bem, "compute_hull_database", counting)
    paths: list[Path] = []
    workers = [
        threading.Thread(
            target=lambda: paths.append(
                cached_database(ship.hull, ship.description, progress=False)
            )
        )
        for _ in range(2)
    ]
    for w in workers:
        w.start()
    for w in workers:
        w.join()
    assert len(calls) == 1
    assert len(paths) == 2 and paths[0] == paths[1] and paths[0].is_file()


def test_ship_check_reports_a_form_outside_the_resistance_regressions(tmp_path, capsys):
    """The bundled box barge (C_B = 1) is outside Holtrop–Mennen's and the B-series design's
    regressions: ``ship check`` says so and still reports everything else (issue #35 item 0),
    and a GZ curve that does not vanish within the heels computed is said in words, not nan."""
    out = tmp_path / "barge.json"
    assert main(["ship", "check", "box_barge", "--plot", "", "--json", str(out)]) == 0
    text = capsys.readouterr().out
    assert "not estimated" in text and "block coefficient" in text
    assert "nan deg" not in text
    report = json.loads(out.read_text())
    assert (
        report["speed"]["propeller"] is None
        and "block coefficient" in (report["speed"]["not_estimated"])
    )
    assert report["appendages"]["rudder"] is not None and report["manoeuvring"]
