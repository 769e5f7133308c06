"""Capsize campaigns (issue #17): TOML spec, stable cell ids, serial == 2 workers == resumed,
extension runs only new cells, the Parquet store, the statistics and the CLI."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

pytest.importorskip("pyarrow")

from ship_gym.analysis import campaign as cp
from ship_gym.analysis import campaign_store as st
from ship_gym.analysis import capsize_statistics as cs

# S175 at its default mesh: ~3 s to build, ~0.2 s per batch of 2 ships over 20 s at dt 0.2.
# A 1° capsize angle in beam seas makes some seeds capsize (time to capsize tested too).
TINY = """
name = "tiny"
ships = ["s175"]
headings_deg = {headings}
froude_numbers = [0.2]
seeds = {seeds}
duration_s = 20.0
dt_s = 0.2
capsize_angle_deg = 1.0
batch_seeds = 2

[[seas]]
kind = "regular"
height_m = 2.0
wavelength_m = 100.0
ramp_s = 10.0
"""


def _write(tmp_path: Path, name: str = "c.toml", headings="[90, 60]", seeds=2, extra="") -> Path:
    path = tmp_path / name
    path.write_text(TINY.format(headings=headings, seeds=seeds) + extra)
    return path


def _outputs(records: list[dict]) -> list[tuple]:
    return sorted(tuple(r[c] for c in st.OUTPUT_COLUMNS) for r in records)


@pytest.fixture(scope="module")
def serial(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("serial")
    spec = cp.read_campaign(_write(tmp))
    return spec, cp.run_campaign(spec, tmp / "store", progress=False)


def test_serial_run_fills_the_store(serial):
    spec, res = serial
    assert res.n_cells == res.n_run == 4 and res.n_tasks == 2
    assert len(list(res.store.glob("part-*.parquet"))) == 2
    assert [r["cell_id"] for r in res.records] == [c.cell_id for c in cp.cells(spec)]
    rec = res.records[0]
    assert set(rec) == {name for name, _ in st.COLUMNS}
    assert rec["ship"] == "s175" and rec["ship_digest"].startswith("sha256:")
    assert rec["engine"] == "compiled" and rec["batch_size"] == 2 and rec["cpu_s"] > 0
    capsized = [r for r in res.records if r["capsized"]]
    assert capsized, "the 1° criterion should capsize some seed in beam seas"
    for r in capsized:
        assert 0.0 < r["time_to_capsize_s"] < 20.0 and r["reason"] == "roll"
    for r in res.records:
        if not r["capsized"]:
            assert r["time_to_capsize_s"] is None


def test_two_workers_and_resume_and_extension_are_bit_identical(serial, tmp_path):
    _, ref = serial
    # 2 local worker processes
    spec = cp.read_campaign(_write(tmp_path))
    par = cp.run_campaign(spec, tmp_path / "par", executor="processes", workers=2, progress=False)
    assert par.n_run == 4
    assert _outputs(par.records) == _outputs(ref.records)
    # a smaller campaign first (one heading, one seed), then the full one: only new cells run
    small = cp.read_campaign(_write(tmp_path, "small.toml", headings="[90]", seeds=1))
    store = tmp_path / "resumed"
    first = cp.run_campaign(small, store, progress=False)
    assert first.n_run == 1
    full = cp.run_campaign(spec, store, progress=False)
    assert full.n_run == 3
    # a kill that lost a task: delete one shard, resume runs exactly its cells
    shards = sorted(store.glob("part-*.parquet"))
    lost = st.read_store(store)
    victim = shards[-1]
    import pyarrow.parquet as pq

    n_lost = pq.read_table(victim).num_rows
    victim.unlink()
    again = cp.run_campaign(spec, store, progress=False)
    assert again.n_run == n_lost
    assert _outputs(again.records) == _outputs(ref.records) == _outputs(lost)
    assert cp.run_campaign(spec, store, progress=False).n_run == 0


def test_ray_with_two_local_workers_is_bit_identical(serial, tmp_path):
    """The same campaign as Ray tasks on a local 2-CPU cluster (started and shut down by the
    executor) gives the serial results bit for bit."""
    pytest.importorskip("ray")
    _, ref = serial
    spec = cp.read_campaign(_write(tmp_path))
    res = cp.run_campaign(spec, tmp_path / "ray", executor="ray", workers=2, progress=False)
    assert res.n_run == 4
    assert _outputs(res.records) == _outputs(ref.records)


def test_an_unsteered_ship_has_no_rudder_and_its_own_cells(serial, tmp_path):
    """``controller = "none"``: the same seas without a rudder, other cell ids, other runs."""
    _, ref = serial
    path = tmp_path / "free.toml"
    path.write_text(TINY.format(headings="[90, 60]", seeds=2).replace(
        'name = "tiny"', 'name = "tiny"\ncontroller = "none"'))  # fmt: skip
    free = cp.read_campaign(path)
    res = cp.run_campaign(free, tmp_path / "free", progress=False)
    assert res.n_run == 4
    assert {c.cell_id for c in cp.cells(free)}.isdisjoint(r["cell_id"] for r in ref.records)
    assert _outputs(res.records) != _outputs(ref.records)
    from ship_gym.analysis import capsize_map as cm

    with pytest.raises(ValueError, match="engine only"):
        cm.run_cells(cm.CapsizeMapConfig(), [cm.Cell(0, 0, 0, 0)], 30.0, engine="simulator",
                     steered=False)  # fmt: skip


def test_cell_ids_stable_and_independent_of_list_order(tmp_path):
    a = cp.cells(cp.read_campaign(_write(tmp_path, "a.toml", headings="[90, 60]")))
    b = cp.cells(cp.read_campaign(_write(tmp_path, "b.toml", headings="[60.0, 90]")))
    assert {c.cell_id for c in a} == {c.cell_id for c in b}
    assert len({c.cell_id for c in a}) == 4
    # the same cell in a bigger campaign keeps its id; any run setting changes it
    big = cp.cells(cp.read_campaign(_write(tmp_path, "big.toml", headings="[0, 60, 90]", seeds=3)))
    assert {c.cell_id for c in a} < {c.cell_id for c in big}
    import dataclasses

    other = dataclasses.replace(cp.read_campaign(_write(tmp_path, "d.toml")), duration_s=40.0)
    assert not {c.cell_id for c in a} & {c.cell_id for c in cp.cells(other)}
    # a ship file is identified by its content, not its path
    from ship_gym.ship import bundled_ship_path

    copy = tmp_path / "sub" / "my_s175.toml"
    copy.parent.mkdir()
    copy.write_bytes(bundled_ship_path("s175").read_bytes())
    text = _write(tmp_path, "f.toml").read_text().replace('["s175"]', '["sub/my_s175.toml"]')
    (tmp_path / "f.toml").write_text(text)
    by_file = cp.cells(cp.read_campaign(tmp_path / "f.toml"))
    assert {c.cell_id for c in by_file} == {c.cell_id for c in a}
    # pinned: a change of the hash contents must be deliberate (bump CELL_SCHEMA)
    assert len(a[0].cell_id) == 20 and all(ch in "0123456789abcdef" for ch in a[0].cell_id)


@pytest.mark.parametrize(
    ("extra_or_replace", "message"),
    [
        (("seeds = 2", "seeds = 0"), "seeds = 0; expected an integer >= 1"),
        (("height_m = 2.0", "height_m = -2.0"), "[[seas]] #1 height_m = -2.0"),
        (("height_m = 2.0", "hs_m = 2.0"), "[[seas]] #1 hs_m: unknown key"),
        (('kind = "regular"', 'kind = "stokes"'), "[[seas]] #1 kind = 'stokes'"),
        (("froude_numbers = [0.2]", "froude_numbers = [1.5]"), "froude_numbers = [1.5]"),
        (("froude_numbers = [0.2]", "speeds_mps = [8.0]\nfroude_numbers = [0.2]"), "exactly one"),
        (("headings_deg = [90, 60]", "headings_deg = [90, 450]"), "headings_deg"),
        (("headings_deg = [90, 60]", "headings_deg = [0, 360]"), "appears twice"),
        (("duration_s = 20.0", "duration_s = 20.1"), "duration_s = 20.1"),
        (("capsize_angle_deg = 1.0", 'capsize_angle_deg = "big"'), "capsize_angle_deg = 'big'"),
        (('name = "tiny"', 'controller = "policy.zip"'), "expected 'autopilot', 'none' or"),
        (('name = "tiny"', "bogus = 1"), "bogus: unknown key"),
        (('["s175"]', '["nosuchship"]'), "ships: 'nosuchship'"),
        (('name = "tiny"', "loadings = [{bogus_key = 1}]"), "loadings[0]"),
    ],
)
def test_bad_fields_are_named(tmp_path, extra_or_replace, message):
    old, new = extra_or_replace
    path = _write(tmp_path)
    path.write_text(path.read_text().replace(old, new, 1))
    with pytest.raises(cp.CampaignError) as err:
        cp.read_campaign(path)
    assert message in str(err.value) and str(path) in str(err.value)


def test_short_crested_sea_rolls_the_ship_in_head_seas_and_keeps_long_crested_ids(tmp_path):
    """A cos-2s sea reaches the engine: in head seas (β = 180°) a long-crested sea leaves the
    symmetric ship upright (|φ| < 1e-6°), a short-crested one (s = 2) rolls it; adding
    ``spreading_s`` leaves the long-crested cells' ids as they were."""
    long_sea = '\n[[seas]]\nkind = "jonswap"\nhs_m = 3.0\ntp_s = 10.0\nramp_s = 5.0\n'
    short_sea = long_sea + "spreading_s = 2\n"
    text = TINY.format(headings="[180]", seeds=1).replace("capsize_angle_deg = 1.0", "")
    base = tmp_path / "base.toml"
    base.write_text(text + long_sea)
    both = tmp_path / "both.toml"
    both.write_text(text + long_sea + short_sea)
    ids_before = {c.cell_id for c in cp.cells(cp.read_campaign(base))}
    spec = cp.read_campaign(both)
    assert spec.seas[2].spreading_s == 2.0 and spec.seas[1].spreading_s is None
    assert "s=2" in spec.seas[2].label
    cells = cp.cells(spec)
    assert ids_before < {c.cell_id for c in cells} and len(cells) == 3
    res = cp.run_campaign(spec, tmp_path / "s", progress=False)
    by_sea = {r["sea"]: r for r in res.records}
    long_roll = by_sea[spec.seas[1].label]["max_abs_roll_deg"]
    short = by_sea[spec.seas[2].label]
    assert long_roll < 1e-6 and short["max_abs_roll_deg"] > 0.05
    assert short["sea_spreading_s"] == 2.0 and by_sea[spec.seas[1].label]["sea_spreading_s"] is None


def test_bad_spreading_is_refused_and_speeds_in_mps_run(tmp_path):
    sea = '\n[[seas]]\nkind = "jonswap"\nhs_m = 3.0\ntp_s = 10.0\nspreading_s = -1\n'
    path = _write(tmp_path, extra=sea)
    with pytest.raises(cp.CampaignError, match=r"#2 spreading_s = -1; expected a cos-2s"):
        cp.read_campaign(path)
    path.write_text(path.read_text().replace("spreading_s = -1\n", ""))
    spec = cp.read_campaign(path)
    assert spec.seas[1].kind == "irregular" and spec.seas[1].gamma == 3.3
    text = path.read_text().replace("froude_numbers = [0.2]", "speeds_mps = [8.0]")
    text = text.replace("headings_deg = [90, 60]", "headings_deg = [90]").replace(
        "seeds = 2", "seeds = 1"
    )
    path.write_text(text)
    res = cp.run_campaign(cp.read_campaign(path), tmp_path / "s", progress=False)
    assert res.n_run == 2
    assert all(abs(r["speed_mps"] - 8.0) < 1e-9 for r in res.records)
    assert {r["speed_kind"] for r in res.records} == {"mps"}


def test_store_without_pyarrow_names_the_extra(monkeypatch):
    import builtins

    real = builtins.__import__

    def fake(name, *a, **k):
        if name.startswith("pyarrow"):
            raise ImportError("no pyarrow")
        return real(name, *a, **k)

    monkeypatch.setattr(builtins, "__import__", fake)
    with pytest.raises(ImportError, match=r"ship_gym\[distributed\]"):
        st.read_store(".")


# ----------------------------------------------------------------------------- statistics
def test_wilson_interval_against_the_textbook_formula():
    # Wilson (1927): (p + z²/2n ± z√(p(1-p)/n + z²/4n²)) / (1 + z²/n), z = 1.959964
    z = 1.959963984540054
    lo, hi = cs.wilson_interval(0, 10)
    assert lo == 0.0
    assert hi == pytest.approx(z * z / (10 + z * z), rel=1e-12)  # = 0.27753…
    assert hi == pytest.approx(0.2775327, abs=1e-7)
    lo, hi = cs.wilson_interval(5, 10)
    half = z * math.sqrt(0.25 / 10 + z * z / 400) / (1 + z * z / 10)
    assert (lo, hi) == pytest.approx((0.5 - half, 0.5 + half), rel=1e-12)
    assert (lo, hi) == pytest.approx((0.2365931, 0.7634069), abs=1e-7)
    with pytest.raises(ValueError, match="k must be"):
        cs.wilson_interval(11, 10)


@pytest.mark.parametrize(("k", "n"), [(0, 10), (1, 10), (5, 10), (10, 10), (3, 37)])
def test_clopper_pearson_matches_scipy_binomtest(k, n):
    from scipy.stats import binomtest

    ref = binomtest(k, n).proportion_ci(confidence_level=0.9, method="exact")
    assert cs.clopper_pearson_interval(k, n, 0.9) == pytest.approx(
        (ref.low, ref.high), abs=1e-12
    )  # tolerance: both are beta quantiles; 1e-12 allows for the ppf's rounding


def test_seeds_for_half_width():
    n = cs.seeds_for_half_width(0.5, 0.1)
    assert cs.wilson_half_width(0.5, n) <= 0.1 < cs.wilson_half_width(0.5, n - 1)
    assert 90 <= n <= 100  # the Wald approximation z²/4h² = 96
    assert cs.seeds_for_half_width(0.0, 0.1) < n  # fewer seeds at the edges


def test_kaplan_meier_with_censoring():
    # capsizes at 10, 20; censored at 15 and 30: S = 3/4 after 10, 3/4 · 1/2 after 20
    curve = cs.kaplan_meier([10.0, 15.0, 20.0, 30.0], [True, False, True, False])
    assert np.allclose(curve.time, [0.0, 10.0, 20.0])
    assert np.allclose(curve.survival, [1.0, 0.75, 0.375])
    assert list(curve.at_risk) == [4, 4, 2]
    assert curve.median() == 20.0
    assert math.isnan(cs.kaplan_meier([5.0, 5.0], [False, False]).median())


def test_survival_figure_draws_the_cells_that_capsized(serial, tmp_path):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    _, res = serial
    summary = cs.summarise_cells(res.records)
    assert all(s.survival is not None and s.survival.n == s.n for s in summary)
    closed = []
    real_close = plt.close
    try:
        plt.close = lambda fig=None: closed.append(fig)  # keep the figure to look into it
        cs.plot_survival(summary, tmp_path / "km.png", title="tiny")
    finally:
        plt.close = real_close
    ax = closed[0].axes[0]
    steps = [line for line in ax.lines if line.get_drawstyle() == "steps-post"]
    assert len(steps) == sum(s.k > 0 for s in summary) >= 1
    capsizing = sorted((s for s in summary if s.k), key=lambda s: -s.p_hat)
    for line, s in zip(steps, capsizing, strict=True):
        # the curve ends at the Kaplan–Meier survival, 1 - k/n without censoring before the end
        assert line.get_ydata()[-1] == pytest.approx(1.0 - s.k / s.n)
    assert ax.get_xlabel() == "time t [s]" and "Kaplan" in ax.get_ylabel()
    real_close(closed[0])


def test_summary_plot_and_cli_report(serial, tmp_path, capsys):
    from ship_gym.cli import main

    _, res = serial
    summary = cs.summarise_cells(res.records, half_width=0.2)
    assert len(summary) == 2 and all(s.n == 2 for s in summary)
    for s in summary:
        assert s.lower <= s.p_hat <= s.upper and s.seeds_needed >= 1
    png = cs.plot_polar_capsize(summary, tmp_path / "map.png", title="tiny")
    assert png.stat().st_size > 1000
    out_json = tmp_path / "r.json"
    status = main(
        ["campaign", "report", str(res.store), "--plot", str(tmp_path / "p.png"), "--json",
         str(out_json), "--survival", str(tmp_path / "km.png")]
    )  # fmt: skip
    out = capsys.readouterr().out
    assert status == 0, out
    assert "4 runs in 2 cells" in out and "95% CI" in out
    assert (tmp_path / "km.png").stat().st_size > 1000
    cells = json.loads(out_json.read_text())["cells"]
    assert {c["k"] for c in cells} <= {0, 1, 2}


def test_cli_run_then_report_from_the_toml(tmp_path, capsys):
    from ship_gym.cli import main

    path = _write(tmp_path, headings="[90]", seeds=1)
    assert main(["campaign", "run", str(path), "--no-progress"]) == 0
    assert (tmp_path / "c.campaign").is_dir()
    assert main(["campaign", "run", str(path), "--no-progress"]) == 0
    out = capsys.readouterr().out
    assert "ran 1 cells" in out and "ran 0 cells" in out and "1 already in the store" in out
    assert main(["campaign", "report", str(path)]) == 0
    assert "1 runs in 1 cells" in capsys.readouterr().out


def run_task_killed_once(marker: str, task):
    """campaign.run_task, but the first call SIGKILLs its own worker (a marker remembers)."""
    import os
    import signal

    if not os.path.exists(marker):
        Path(marker).write_text("killed")
        os.kill(os.getpid(), signal.SIGKILL)
    return cp.run_task(task)


def test_a_killed_local_worker_is_retried_and_the_run_finishes(serial, tmp_path):
    import functools

    from ship_gym.analysis import executors as ex

    marker = str(tmp_path / "killed")

    class KillOnce(ex.ProcessExecutor):
        def map_unordered(self, fn, items):
            return super().map_unordered(functools.partial(run_task_killed_once, marker), items)

    _, ref = serial
    spec = cp.read_campaign(_write(tmp_path))
    said: list[str] = []
    with KillOnce(workers=2) as executor:
        res = cp.run_campaign(
            spec, tmp_path / "store", executor=executor, progress=False, report=said.append
        )
    assert res.n_run == 4 and _outputs(res.records) == _outputs(ref.records)
    assert any("a worker process died running task" in m and "ship s175" in m for m in said)
    assert "were run again" in said[-1] and "every cell finished" in said[-1]


def run_task_always_killed(task):
    import os
    import signal

    os.kill(os.getpid(), signal.SIGKILL)


def test_a_task_whose_worker_always_dies_is_a_clear_error_naming_its_cells(tmp_path):
    from ship_gym.analysis import executors as ex

    class KillAlways(ex.ProcessExecutor):
        def map_unordered(self, fn, items):
            return super().map_unordered(run_task_always_killed, items)

    spec = cp.read_campaign(_write(tmp_path, headings="[90]"))
    with (
        KillAlways(workers=1, max_retries=1) as executor,
        pytest.raises(cp.CampaignError, match=r"task \w+ \(ship s175, .*heading 90 deg.*seeds "
                      r"\[0, 1\]\): its worker process died 2 times .*rerun to resume"),
    ):  # fmt: skip
        cp.run_campaign(
            spec, tmp_path / "store", executor=executor, progress=False, report=lambda m: None
        )


def test_the_store_ignores_foreign_and_changed_shards_naming_them(serial, tmp_path, capsys):
    import shutil

    from ship_gym.cli import main

    spec, res = serial
    store = tmp_path / "store"
    shutil.copytree(res.store, store)
    lines = (store / st.MANIFEST).read_text().splitlines()
    assert json.loads(lines[0])["campaign"] == st.campaign_digest(c.cell_id for c in cp.cells(spec))
    # a shard of another campaign (other headings) copied in: ignored, named
    other = cp.read_campaign(_write(tmp_path, "other.toml", headings="[30]", seeds=1))
    other_store = tmp_path / "other_store"
    cp.run_campaign(other, other_store, progress=False)
    foreign = next(other_store.glob("part-*.parquet"))
    shutil.copy(foreign, store / foreign.name)
    said: list[str] = []
    records = st.read_store(store, report=said.append)
    assert len(records) == 4 and all(r["heading_deg"] != 30.0 for r in records)
    assert len(said) == 1 and foreign.name in said[0] and "not in the store's manifest" in said[0]
    assert main(["campaign", "report", str(store)]) == 0
    captured = capsys.readouterr()
    assert f"{foreign.name}: not in the store's manifest" in captured.err
    assert "4 runs" in captured.out
    # a shard of the store changed since it was written: ignored, named; its cells re-run
    own = sorted(p for p in store.glob("part-*.parquet") if p.name != foreign.name)[0]
    own.write_bytes(foreign.read_bytes())
    said.clear()
    assert len(st.read_store(store, report=said.append)) == 2
    assert any(own.name in m and "changed since" in m for m in said)
    again = cp.run_campaign(spec, store, progress=False, report=said.append)
    assert again.n_run == 2 and len(again.records) == 4
    assert _outputs(again.records) == _outputs(res.records)


def test_a_store_of_an_earlier_version_is_adopted_and_a_damaged_shard_is_named(
    serial, tmp_path, capsys
):
    import shutil

    import pyarrow as pa
    import pyarrow.parquet as pq

    from ship_gym.cli import main

    spec, res = serial
    store = tmp_path / "legacy"
    shutil.copytree(res.store, store)
    (store / st.MANIFEST).unlink()  # as written before the manifest existed
    assert len(st.read_store(store)) == 4
    again = cp.run_campaign(spec, store, progress=False)  # adopts its shards, runs nothing
    assert again.n_run == 0 and len(again.records) == 4
    assert sum('"adopted": true' in line for line in (store / st.MANIFEST).open()) == 2
    # an earlier version's store with a shard holding only cell ids: the file is named
    (store / st.MANIFEST).unlink()
    shard = sorted(store.glob("part-*.parquet"))[0]
    pq.write_table(pa.table({"cell_id": ["abc"]}), shard)
    with pytest.raises(ValueError, match=rf"{shard.name}: a record \(cell 'abc'\) has no ship"):
        st.read_store(store)
    assert main(["campaign", "report", str(store)]) == 1
    err = capsys.readouterr().err
    assert shard.name in err and "internal error" not in err


def test_an_initial_heel_starts_each_seed_disturbed_and_keeps_upright_ids(tmp_path):
    """``initial_heel_deg``: in head seas (β = 180°, long-crested) an upright symmetric ship
    stays upright (|φ| < 1e-6°); heeled by a per-seed draw within ±3° it rolls. Upright
    campaigns keep their cell ids; the heel is part of the ids when set; bad values and a
    policy controller are refused by name."""
    text = TINY.format(headings="[180]", seeds=2).replace("capsize_angle_deg = 1.0", "")
    upright = tmp_path / "upright.toml"
    upright.write_text(text)
    heeled = tmp_path / "heeled.toml"
    heeled.write_text("initial_heel_deg = 3.0\n" + text)
    spec_up, spec_heel = cp.read_campaign(upright), cp.read_campaign(heeled)
    assert spec_heel.initial_heel_deg == 3.0
    ids_up = {c.cell_id for c in cp.cells(spec_up)}
    ids_heel = {c.cell_id for c in cp.cells(spec_heel)}
    assert not ids_up & ids_heel
    zero = tmp_path / "zero.toml"
    zero.write_text("initial_heel_deg = 0\n" + text)
    assert {c.cell_id for c in cp.cells(cp.read_campaign(zero))} == ids_up
    rolls_up = [r["max_abs_roll_deg"] for r in cp.run_campaign(spec_up, tmp_path / "u").records]
    res = cp.run_campaign(spec_heel, tmp_path / "h", progress=False)
    rolls = sorted(r["max_abs_roll_deg"] for r in res.records)
    assert max(rolls_up) < 1e-6 and min(rolls) > 0.01 and rolls[0] != rolls[1]
    bad = tmp_path / "bad.toml"
    bad.write_text("initial_heel_deg = 40\n" + text)
    with pytest.raises(cp.CampaignError, match="initial_heel_deg = 40"):
        cp.read_campaign(bad)
