"""Capsize-map runner: resume, parallel = serial, config mismatch, interrupted runs, criteria."""

from __future__ import annotations

import argparse
import dataclasses
import json
import math
from types import SimpleNamespace
from typing import ClassVar

import numpy as np
import pytest

from ship_gym.analysis import capsize_map as cm
from ship_gym.engine.simulator import SimulationDiverged


def _tiny_config(**kw) -> cm.CapsizeMapConfig:
    base = dict(
        headings_deg=(0.0, 90.0),
        froude_numbers=(0.1, 0.2),
        seeds=(0,),
        duration=20.0,
        dt=0.2,
        capsize_angle_deg=30.0,
    )
    base.update(kw)
    return cm.CapsizeMapConfig(**base)


class CountingRunner:
    """A fake cell runner: deterministic outcome from the cell, counts calls, can fail."""

    def __init__(self, fail_on: str | None = None) -> None:
        self.calls: list[str] = []
        self.fail_on = fail_on

    def __call__(self, config: cm.CapsizeMapConfig, cell: cm.Cell, angle: float) -> dict:
        if cell.key == self.fail_on:
            raise RuntimeError(f"boom in {cell.key}")
        self.calls.append(cell.key)
        roll = 10.0 * cell.heading + cell.froude + cell.seed
        return {
            "capsized": roll > angle,
            "reason": "roll" if roll > angle else "none",
            "time_to_capsize": 5.0 if roll > angle else None,
            "max_abs_roll_deg": roll,
            "rms_roll_deg": roll / 2,
        }


def test_resume_skips_finished_cells_and_interrupt_keeps_them(tmp_path):
    path = tmp_path / "map.jsonl"
    cfg = _tiny_config()
    cells = [c.key for c in cfg.cells()]
    assert len(cells) == 4
    # an exception in the third cell stops the run: the two finished cells stay on disk
    first = CountingRunner(fail_on=cells[2])
    with pytest.raises(RuntimeError, match="boom"):
        cm.run_capsize_map(cfg, path, progress=False, cell_runner=first)
    assert first.calls == cells[:2]
    _, records = cm.load_results(path)
    assert [r["key"] for r in records] == cells[:2]
    # the rerun simulates only the two missing cells
    second = CountingRunner()
    res = cm.run_capsize_map(cfg, path, progress=False, cell_runner=second)
    assert second.calls == cells[2:]
    assert res.n_run == 2
    assert [r["key"] for r in res.records] == cells
    # and a third run simulates nothing
    third = CountingRunner()
    assert cm.run_capsize_map(cfg, path, progress=False, cell_runner=third).n_run == 0
    assert third.calls == []
    assert len(path.read_text().splitlines()) == 1 + 4


def test_config_mismatch_is_a_clear_error(tmp_path):
    path = tmp_path / "map.jsonl"
    cm.run_capsize_map(_tiny_config(), path, progress=False, cell_runner=CountingRunner())
    before = path.read_bytes()
    with pytest.raises(ValueError, match=r"different configuration.*duration"):
        cm.run_capsize_map(
            _tiny_config(duration=40.0), path, progress=False, cell_runner=CountingRunner()
        )
    with pytest.raises(ValueError, match=r"hull_overrides"):
        cm.run_capsize_map(
            _tiny_config(hull_overrides={"kg": 10.1}),
            path,
            progress=False,
            cell_runner=CountingRunner(),
        )
    assert path.read_bytes() == before  # nothing mixed in


def test_torn_last_line_is_cut_and_rerun(tmp_path):
    path = tmp_path / "map.jsonl"
    cfg = _tiny_config()
    cm.run_capsize_map(cfg, path, progress=False, cell_runner=CountingRunner())
    lines = path.read_text().splitlines(keepends=True)
    # simulate a crash in the middle of writing the last record
    path.write_text("".join(lines[:-1]) + lines[-1][:15])
    runner = CountingRunner()
    res = cm.run_capsize_map(cfg, path, progress=False, cell_runner=runner)
    assert runner.calls == [cfg.cells()[-1].key]
    assert len(res.records) == 4
    for line in path.read_text().splitlines():
        json.loads(line)  # every line valid again


def test_summary_probability_over_seeds():
    cfg = _tiny_config(seeds=(0, 1, 2, 3))
    runner = CountingRunner()
    records = [cm._run_keyed(runner, cfg, c, 10.5) for c in cfg.cells()]
    rows = cm.summarise(cfg, records)
    assert len(rows) == 4
    # heading index 1 → roll = 10 + froude + seed > 10.5 for seed ≥ 1 (Fn index 0) → 3/4
    row = next(r for r in rows if r["heading_deg"] == 90.0 and r["froude"] == 0.1)
    assert row["capsize_probability"] == pytest.approx(0.75)
    assert row["n"] == 4 and row["n_roll"] == 3 and row["n_diverged"] == 0
    row0 = next(r for r in rows if r["heading_deg"] == 0.0 and r["froude"] == 0.1)
    assert row0["capsize_probability"] == 0.0 and math.isnan(row0["mean_time_to_capsize"])


def test_bad_config_values():
    with pytest.raises(ValueError, match="froude_numbers"):
        _tiny_config(froude_numbers=(0.0,))
    with pytest.raises(ValueError, match="multiple of dt"):
        _tiny_config(duration=20.05)
    with pytest.raises(ValueError, match="bad sea state"):
        cm.SeaSpec.parse("regular:10")
    sea = cm.SeaSpec.parse("jonswap:7:15")
    assert sea.kind == "irregular" and sea.period == 15.0
    assert cm.CapsizeMapConfig.from_dict(_tiny_config(seas=(sea,)).to_dict()) == _tiny_config(
        seas=(sea,)
    )


class _DivergingSim:
    """Stand-in simulator that diverges at its 4th step (rolling 1° per step)."""

    dt = 0.5
    forces: ClassVar[list] = []
    engine = SimpleNamespace(forces=[], n_ships=1)  # no rudder

    def __init__(self) -> None:
        self.t, self.eta, self.nu, self.commands, self.z = 0.0, np.zeros(6), np.zeros(6), {}, []

    def step(self) -> None:
        if self.t >= 1.5 - 1e-9:
            raise SimulationDiverged("test")
        self.t += self.dt
        self.eta = self.eta + np.radians([0, 0, 0, 1.0, 0, 0])


def test_capsize_reasons_roll_and_diverged():
    # roll beyond the angle: stops at the first step that exceeds 1.5° → t = 1.0 s (2° roll)
    out, series = cm.simulate_until_capsize(_DivergingSim(), 5.0, math.radians(1.5))
    assert out.capsized and out.reason == "roll" and out.time_to_capsize == pytest.approx(1.0)
    assert out.max_abs_roll_deg == pytest.approx(2.0)
    # otherwise the SimulationDiverged at the 4th step counts as capsize "diverged" at t = 2 s
    out, series = cm.simulate_until_capsize(_DivergingSim(), 5.0, math.radians(60.0))
    assert out.capsized and out.reason == "diverged" and out.time_to_capsize == pytest.approx(2.0)
    assert series["t"][-1] == pytest.approx(1.5)  # last valid state kept


@pytest.fixture(scope="module")
def serial_real(tmp_path_factory):
    """A real 2-cell map (following and beam seas, Fn 0.2, 30 s) with a 2° 'capsize' angle."""
    cfg = _tiny_config(froude_numbers=(0.2,), duration=30.0, capsize_angle_deg=2.0)
    path = tmp_path_factory.mktemp("serial") / "map.jsonl"
    return cfg, cm.run_capsize_map(cfg, path, n_jobs=1, progress=False)


def test_real_cells_detect_roll_capsize(serial_real):
    _, res = serial_real
    following, beam = res.records
    # following seas: no excitation of roll at all on a symmetric ship (|φ| < 0.01°)
    assert not following["capsized"] and following["max_abs_roll_deg"] < 0.01
    # beam seas, H = 10.5 m: roll passes 2° during the ramp (≈ 4.6° at 30 s untruncated)
    assert beam["capsized"] and beam["reason"] == "roll"
    assert 0.0 < beam["time_to_capsize"] < 30.0
    # the autopilot holds the heading (deviation < 1°) and the propeller the speed (±5 %)
    assert beam["max_heading_deviation_deg"] < 1.0
    assert abs(beam["mean_speed"] / beam["speed"] - 1.0) < 0.05


def test_parallel_equals_serial(serial_real, tmp_path):
    cfg, serial = serial_real
    parallel = cm.run_capsize_map(cfg, tmp_path / "par.jsonl", n_jobs=2, progress=False)
    # bit-identical physics: same code, same seeds, the process does not matter
    for a, b in zip(serial.records, parallel.records, strict=True):
        a = {k: v for k, v in a.items() if k != "cpu_s"}
        b = {k: v for k, v in b.items() if k != "cpu_s"}
        assert a == b


def test_cli_parses_and_runs(tmp_path, capsys):
    from ship_gym.cli import capsize as cli_capsize

    parser = argparse.ArgumentParser()
    cli_capsize.add_commands(parser.add_subparsers(dest="command"))
    results = tmp_path / "cli.jsonl"
    args = parser.parse_args(
        [
            "capsize-map",
            "--headings",
            "90",
            "--froude",
            "0.2",
            "--duration",
            "10",
            "--dt",
            "0.5",
            "--capsize-angle",
            "45",
            "--results",
            str(results),
            "--plot",
            str(tmp_path / "map.png"),
            "--json",
            str(tmp_path / "map.json"),
            "--no-progress",
        ]
    )
    assert args.func(args) == 0
    payload = json.loads((tmp_path / "map.json").read_text())
    assert payload["summary"][0]["capsize_probability"] == 0.0
    assert (tmp_path / "map.png").stat().st_size > 0
    assert "ran 1 cells" in capsys.readouterr().out


# ----------------------------------------------------------------------------- engine path
_OUTCOME_FLOATS = (
    "max_abs_roll_deg",
    "rms_roll_deg",
    "max_abs_pitch_deg",
    "max_heading_deviation_deg",
    "mean_speed",
    "simulated_time",
    "speed",
)


def _assert_same_outcome(a: dict, b: dict) -> None:
    """Engine vs Simulator: same outcome, statistics to rounding (the paths agree to ≈ 1e-12;
    1e-9 relative leaves room for the growth of rounding over a nonlinear run)."""
    assert a["capsized"] == b["capsized"] and a["reason"] == b["reason"]
    if a["time_to_capsize"] is None:
        assert b["time_to_capsize"] is None
    else:  # the engine finds the exact capsize step (replay), not the chunk end
        assert b["time_to_capsize"] == pytest.approx(a["time_to_capsize"], rel=0, abs=1e-9)
    for k in (k for k in _OUTCOME_FLOATS if k in a):
        assert b[k] == pytest.approx(a[k], rel=1e-9, abs=1e-12), k


def test_engine_cell_equals_simulator_cell(serial_real):
    # the beam-seas cell capsizes (2°) inside a 5-step chunk: the engine replays that chunk step
    # by step, so its time to capsize and statistics are the step-by-step run's
    cfg, res = serial_real
    following, beam = res.records
    assert beam["engine"] == "compiled" and beam["batch_size"] == 1
    assert cfg.record_every == 5 and beam["capsized"]
    cells = cfg.cells()
    for cell, rec in zip(cells, (following, beam), strict=True):
        ref = cm.run_cell(cfg, cell, cfg.capsize_angle_deg, engine="simulator")
        assert ref["engine"] == "simulator"
        _assert_same_outcome(ref, rec)


def test_seeds_in_one_batch_equal_seeds_alone():
    # determinism: a cell's result does not depend on the cells it runs with (3 seeds of beam
    # seas capsizing at different steps: three replays in one batch)
    cfg = _tiny_config(
        headings_deg=(90.0,), froude_numbers=(0.2,), seeds=(0, 1, 2), duration=24.0,
        capsize_angle_deg=2.0,
    )  # fmt: skip
    together = cm.run_cells(cfg, cfg.cells(), 2.0)
    assert {r["batch_size"] for r in together} == {3}
    times = [r["time_to_capsize"] for r in together]
    assert all(r["capsized"] for r in together) and len(set(times)) == 3
    skip = ("cpu_s", "batch_size")
    for cell, rec in zip(cfg.cells(), together, strict=True):
        alone = cm.run_cell(cfg, cell, 2.0)
        assert {k: v for k, v in alone.items() if k not in skip} == {
            k: v for k, v in rec.items() if k not in skip
        }


@pytest.mark.parametrize("every", [1, 5])
def test_engine_divergence_matches_simulator(every):
    # a |ν| limit just above U makes the run "diverge" after a few seconds: both paths stop at
    # the same step, keep the last valid state and report its time + Δt
    from ship_gym.engine.ship import build_simulator

    cfg = _tiny_config(headings_deg=(90.0,), froude_numbers=(0.2,), duration=30.0)
    cell = cfg.cells()[0]
    setup, sea, beta, rng = cm.cell_setup(cfg, cell)
    ref_sim = build_simulator(setup, sea, wave_heading=beta, rng=rng)
    eng_sim = cm.build_cells_simulator(cfg, [cell])
    ref_sim.max_abs_velocity = eng_sim.max_abs_velocity = setup.speed + 1e-3
    angle = math.radians(60.0)
    ref, ref_series = cm.simulate_until_capsize(ref_sim, 30.0, angle, record_every=every)
    out, series = cm.simulate_until_capsize(eng_sim, 30.0, angle, record_every=every)
    assert ref.reason == "diverged" and 0.0 < ref.time_to_capsize < 30.0
    _assert_same_outcome(dataclasses.asdict(ref), dataclasses.asdict(out))
    np.testing.assert_array_equal(series["t"], ref_series["t"])
    np.testing.assert_allclose(series["eta"], ref_series["eta"], rtol=1e-9, atol=1e-12)
    np.testing.assert_allclose(series["rudder"], ref_series["rudder"], rtol=1e-9, atol=1e-12)
    assert eng_sim.diverged[0] and 0 in eng_sim.divergence_messages


def test_engine_choice_and_fallback():
    assert cm.engine_supports("state_space", "holloway") and cm.engine_supports("2b", "rk4")
    assert cm.engine_supports("convolution", "rk4") and not cm.engine_supports("none", "abm")
    assert cm.use_engine("auto", "2a", "rk4") and not cm.use_engine("simulator", "2a", "rk4")
    assert cm.use_engine("auto", "convolution", "rk4")  # batched, on the numpy path
    with pytest.raises(ValueError, match="integrator 'rk4' or 'holloway'"):
        cm.use_engine("engine", "none", "abm")
    with pytest.raises(ValueError, match="engine must be"):
        cm.use_engine("fast", "2a", "rk4")
    cfg = _tiny_config(headings_deg=(90.0,), froude_numbers=(0.2,), seeds=(0, 1))
    with pytest.raises(ValueError, match="share sea, heading and Froude"):
        cm.build_cells_simulator(_tiny_config(), _tiny_config().cells()[:2])
    sim = cm.build_cells_simulator(cfg, cfg.cells())
    sim.advance(1)
    with pytest.raises(ValueError, match="reset state"):
        cm.simulate_ships_until_capsize(sim, 1.0, 1.0)
    with pytest.raises(ValueError, match="one ship"):
        cm.simulate_until_capsize(cm.build_cells_simulator(cfg, cfg.cells()), 1.0, 1.0)


def test_numpy_backend_steps_singly_and_agrees():
    # the engine's numpy backend is not bit-identical across sets of running ships, so it is
    # advanced one step per call (no replay); it agrees with the compiled one to rounding
    cfg = _tiny_config(
        headings_deg=(90.0,), froude_numbers=(0.2,), seeds=(0, 1), duration=24.0,
        capsize_angle_deg=2.0,
    )  # fmt: skip
    out = {}
    for backend in ("numpy", "compiled"):
        sim = cm.build_cells_simulator(cfg, cfg.cells(), backend=backend)
        out[backend] = cm.simulate_ships_until_capsize(sim, 24.0, math.radians(2.0), record_every=5)
        assert sim.compiled == (backend == "compiled")
    for (a, _), (b, _) in zip(out["compiled"], out["numpy"], strict=True):
        assert a.reason == "roll"
        _assert_same_outcome(dataclasses.asdict(a), dataclasses.asdict(b))


def test_a_capsize_through_a_pitch_pole_is_reported_as_such():
    # the roll criterion fires when the zyx Euler angles flip through θ = ±90°: such a run (the
    # surf-riding S175 at Fn 0.4 in docs/capsize_map) is a "pitch" outcome, not a roll capsize
    t = np.arange(5.0)
    eta = np.zeros((5, 6))
    eta[:, 4] = np.radians([0.0, -20.0, -60.0, -95.0, -120.0])
    eta[-1, 3] = np.radians(110.0)
    series = {"t": t, "eta": eta, "nu": np.zeros((5, 6))}
    out = cm._outcome(series, "roll", 4.0, 4.0, heading_command=0.0, stats_after=0.0)
    assert out.capsized and out.reason == "pitch" and out.max_abs_pitch_deg == pytest.approx(120.0)
    eta[:, 4] = np.radians([0.0, 5.0, -8.0, 6.0, -4.0])  # an ordinary roll capsize stays "roll"
    out = cm._outcome(series, "roll", 4.0, 4.0, heading_command=0.0, stats_after=0.0)
    assert out.reason == "roll"


def test_an_initial_heel_disturbs_each_seed_and_keeps_engine_equal_to_simulator():
    """``initial_heel_deg``: each seed starts heeled by its own draw within ± the stated angle
    (so that an instability grows from a stated disturbance, not round-off); the engine batch
    and the single-ship simulator start from the same heel and give the same outcome; the
    option at 0 leaves the results file's configuration as before it existed."""
    cfg = _tiny_config(
        headings_deg=(0.0,), froude_numbers=(0.2,), seeds=(0, 1, 2), duration=4.0,
        initial_heel_deg=5.0, capsize_angle_deg=60.0, record_every=1,
    )  # fmt: skip
    sim = cm.build_cells_simulator(cfg, cfg.cells())
    heels = np.degrees(sim.eta[:, 3])
    assert np.all(np.abs(heels) <= 5.0) and len(set(np.round(heels, 9))) == 3
    assert np.all(np.abs(heels) > 0.0)
    together = cm.run_cells(cfg, cfg.cells(), 60.0)
    for cell, rec in zip(cfg.cells(), together, strict=True):
        ref = cm.run_cell(cfg, cell, 60.0, engine="simulator")
        _assert_same_outcome(ref, rec)
    assert max(r["max_abs_roll_deg"] for r in together) > 1.0  # the heel shows in the roll
    assert "initial_heel_deg" not in _tiny_config().to_dict()
    assert cm.CapsizeMapConfig.from_dict(cfg.to_dict()) == cfg
    with pytest.raises(ValueError, match="initial_heel_deg"):
        _tiny_config(initial_heel_deg=45.0)
