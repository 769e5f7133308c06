"""Every ``ship-gym`` subcommand with bad arguments (issue #15, items 4, 5, 7, 8, 10).

Each case runs ``ship_gym.cli.main`` in-process and asserts the exit status (2: a usage error
found by argparse, 1: a user/runtime error found by the command), that stderr names the option
as typed and what was expected, and that no traceback is shown. The expensive functions of
every command are replaced by a sentinel that fails loudly: each bad argument must be refused
*before* any work.
"""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import pytest

from ship_gym.cli import build_parser, main
from ship_gym.cli.common import CLIError, prepare_output, write_or_rescue

EXPENSIVE = [
    ("ship_gym.hydro.bem", "compute_hull_database"),
    ("ship_gym.engine.ship", "build_simulator"),
    ("ship_gym.analysis.manoeuvres", "trial_setup"),
    ("ship_gym.analysis.capsize_map", "run_capsize_map"),
    ("ship_gym.analysis.campaign", "run_campaign"),
    ("ship_gym.analysis.intact_stability", "parametric_roll_check"),
    ("ship_gym.analysis.intact_stability", "dead_ship"),
    ("ship_gym.analysis.safe_basin", "safe_basin"),
    ("ship_gym.analysis.safe_basin", "s175_safe_basin"),
    ("ship_gym.analysis.identification", "identify_roll_equation"),
    ("ship_gym.agents.train", "train"),
    ("ship_gym.agents.evaluate", "evaluate_policies"),
    ("ship_gym.agents.benchmark", "run_benchmark"),
]


class ExpensiveCalled(Exception):  # not a user-error type: main() reports it as a bug
    pass


@pytest.fixture
def no_work(monkeypatch):
    import importlib

    called: list[str] = []
    for module, name in EXPENSIVE:
        mod = importlib.import_module(module)

        def sentinel(*args, _name=name, **kwargs):
            called.append(_name)
            raise ExpensiveCalled(f"{_name} must not run for a bad argument")

        monkeypatch.setattr(mod, name, sentinel)
    return called


@pytest.fixture
def paths(tmp_path):
    a_file = tmp_path / "a_file.txt"
    a_file.write_text("x,y\n1,2\n")
    csv = tmp_path / "roll.csv"
    rows = ["t,phi,phidot"] + [f"{0.1 * i:.1f},{0.01 * i},{0.1}" for i in range(50)]
    csv.write_text("\n".join(rows) + "\n")
    bad_toml = tmp_path / "bad.toml"
    bad_toml.write_text("[[\n")
    bad_env = tmp_path / "bad_env.toml"
    bad_env.write_text('[env]\nid = "ship_gym/Bogus-v0"\n')
    campaign = (
        'ships = ["s175"]\nheadings_deg = [90]\nfroude_numbers = [0.2]\nseeds = 2\n'
        "duration_s = 20.0\ndt_s = 0.2\ncapsize_angle_deg = 30.0\n"
    )
    good_campaign = tmp_path / "campaign.toml"
    good_campaign.write_text(
        campaign + '[[seas]]\nkind = "regular"\nheight_m = 2.0\nwavelength_m = 100.0\n'
    )
    bad_sea = tmp_path / "bad_sea.toml"
    bad_sea.write_text(campaign + '[[seas]]\nkind = "jonswap"\ntp_s = 12.0\n')
    spread = tmp_path / "spread.toml"
    spread.write_text(
        campaign + '[[seas]]\nkind = "jonswap"\nhs_m = 4.0\ntp_s = 12.0\nspreading_s = -10\n'
    )
    no_policy = tmp_path / "no_policy.toml"
    no_policy.write_text(
        campaign + 'controller = "policy:no_run"\n[[seas]]\nkind = "regular"\nheight_m = 2.0\n'
        "wavelength_m = 100.0\n"
    )
    bad_ship = tmp_path / "bad_ship.toml"
    bad_ship.write_text(
        campaign.replace('"s175"', '"nosuchship"') + "[[seas]]\n"
        'kind = "regular"\nheight_m = 2.0\nwavelength_m = 100.0\n'
    )
    return {
        "{tmp}": str(tmp_path),
        "{dir}": str(tmp_path),
        "{file}": str(a_file),
        "{csv}": str(csv),
        "{bad_toml}": str(bad_toml),
        "{bad_env}": str(bad_env),
        "{campaign}": str(good_campaign),
        "{bad_sea}": str(bad_sea),
        "{spread}": str(spread),
        "{no_policy}": str(no_policy),
        "{bad_ship}": str(bad_ship),
    }


def _fill(items, paths):
    out = []
    for item in items:
        for key, value in paths.items():
            item = item.replace(key, value)
        out.append(item)
    return out


U, R = 2, 1  # usage error (argparse), runtime/user error (the command)
CASES: list[tuple[str, int, list[str]]] = [
    # top level
    ("", U, ["required"]),
    ("no-such-command", U, ["invalid choice", "no-such-command"]),
    ("--debug", U, ["required"]),
    # hull
    ("hull", U, ["the following arguments are required: SHIP"]),
    ("hull s175 --heel-step 0", U, ["--heel-step", "> 0", "'0'"]),
    ("hull s175 --heel-step -5", U, ["--heel-step", "> 0"]),
    ("hull s175 --heel-step abc", U, ["--heel-step", "expected a number", "'abc'"]),
    ("hull s175 --heel-step nan", U, ["--heel-step", "finite"]),
    ("hull s175 --heel-max 0", U, ["--heel-max", "(0, 180]"]),
    ("hull s175 --heel-max 200", U, ["--heel-max", "(0, 180]"]),
    ("hull s175 --heel-max inf", U, ["--heel-max", "finite"]),
    ("hull s175 --heel-step 30 --heel-max 10", R, ["--heel-step", "--heel-max"]),
    ("hull s175 --set kg", U, ["--set", "key=value"]),
    ("hull s175 --set =3", U, ["--set", "key=value"]),
    ("hull s175 --plot= --set kg=-5", R, ["--set kg", "KG = -5", "below the keel"]),
    ("hull s175 --plot= --set kg=20", R, ["--set kg", "above the deck"]),
    ("hull s175 --plot= --set kg=12", R, ["--set kg", "GMt", "expected KG <"]),
    ("hull s175 --plot= --set bogus_key=1", R, ["bogus_key", "allowed keywords"]),
    ("hull nosuchhull --plot=", U, ["SHIP", "nosuchhull", "expected a .toml ship file or one of"]),
    ("hull s175 --plot {dir}", R, ["--plot", "is a directory"]),
    ("hull s175 --plot {file}/gz.png", R, ["--plot", "is a file"]),
    ("hull s175 --plot {tmp}/gz.txt", R, ["--plot", "suffix", ".png"]),
    ("hull s175 --json {dir}", R, ["--json", "is a directory"]),
    ("hull s175 --plot= --json /proc/x.json", R, ["--json", "cannot write"]),
    # ship
    ("ship", U, ["required"]),
    ("ship check", U, ["SHIP", "required"]),
    ("ship check {bad_toml}", U, ["SHIP", "not a valid TOML"]),
    ("ship check {tmp}/missing.toml", U, ["SHIP", "missing.toml", "not found"]),
    ("ship check s175 --plot {tmp}/gz.txt", R, ["--plot", "suffix"]),
    ("ship check s175 --heel-step 30 --heel-max 10", R, ["--heel-step", "--heel-max"]),
    ("ship build", U, ["SHIP", "required"]),
    ("ship build s175", R, ["names its database", "database = 's175'"]),
    ("ship build wigley --n-jobs 0", U, ["--n-jobs"]),
    ("simulate --ship {bad_toml}", U, ["--ship", "not a valid TOML"]),
    ("capsize-map --ship nosuchship", U, ["--ship", "nosuchship"]),
    # hydro
    ("hydro s175", U, ["--output", "required"]),
    ("hydro s175 --output {dir}", R, ["--output", "is a directory"]),
    ("hydro s175 --output {tmp}/db.txt", R, ["--output", "suffix", ".nc"]),
    ("hydro s175 --output {file}/db.nc", R, ["--output", "is a file"]),
    ("hydro s175 --output /proc/db.nc", R, ["--output", "cannot write"]),
    ("hydro s175 --output {tmp}/db.nc --n-omega 5", U, ["--n-omega", ">= 10"]),
    ("hydro s175 --output {tmp}/db.nc --n-omega 9", U, ["--n-omega", ">= 10"]),
    ("hydro s175 --output {tmp}/db.nc --n-omega 2.5", U, ["--n-omega", "integer"]),
    ("hydro s175 --output {tmp}/db.nc --omega-max 0", U, ["--omega-max", "> 0"]),
    ("hydro s175 --output {tmp}/db.nc --omega-max -1", U, ["--omega-max", "> 0"]),
    ("hydro s175 --output {tmp}/db.nc --omega-max x", U, ["--omega-max", "number"]),
    ("hydro s175 --output {tmp}/db.nc --headings 90 90", R, ["--headings", "duplicate"]),
    ("hydro s175 --output {tmp}/db.nc --headings 0 360", R, ["--headings", "duplicate"]),
    ("hydro s175 --output {tmp}/db.nc --headings 400", U, ["--headings", "[-360, 360]"]),
    ("hydro s175 --output {tmp}/db.nc --headings", R, ["--headings", "at least one"]),
    ("hydro s175 --output {tmp}/db.nc --n-jobs 0", U, ["--n-jobs", ">= 1"]),
    ("hydro s175 --output {tmp}/db.nc --n-jobs two", U, ["--n-jobs", "integer"]),
    ("hydro s175 --output {tmp}/db.nc --set kg", U, ["--set", "key=value"]),
    ("hydro nosuchhull --output {tmp}/db.nc", U, ["SHIP", "nosuchhull"]),
    ("hydro s175 --output {tmp}/db.nc --checkpoint {file}", R, ["--checkpoint", "is a file"]),
    ("hydro s175 --output {tmp}/db.nc --checkpoint /proc/ckpt", R, ["--checkpoint", "cannot"]),
    # kernels
    ("kernels", U, ["database", "required"]),
    ("kernels s175 --dt 0", U, ["--dt", "> 0"]),
    ("kernels s175 --dt -0.1", U, ["--dt", "> 0"]),
    ("kernels s175 --t-max 0", U, ["--t-max", "> 0"]),
    ("kernels s175 --t-max nan", U, ["--t-max", "finite"]),
    ("kernels s175 --dt 100", R, ["--dt", "--t-max"]),
    ("kernels s175 --method bogus", U, ["--method", "invalid choice"]),
    ("kernels s175 --tail bogus", U, ["--tail", "invalid choice"]),
    ("kernels {tmp}/none.nc --plot=", R, ["none.nc", "not found"]),
    ("kernels {dir} --plot=", R, ["is a directory"]),
    ("kernels {file} --plot=", R, ["a_file.txt", "not a NetCDF"]),
    ("kernels s175 --plot {dir}", R, ["--plot", "is a directory"]),
    ("kernels s175 --plot= --json {file}/k.json", R, ["--json", "is a file"]),
    # simulate
    ("simulate --irregular 50 11", R, ["--irregular", "DNV-RP-C205", "Hs = 50"]),
    ("simulate --irregular 30 1", R, ["--irregular", "DNV-RP-C205"]),
    ("simulate --irregular 5", U, ["--irregular", "expected 2 arguments"]),
    ("simulate --irregular -5 11", U, ["--irregular", "> 0"]),
    ("simulate --irregular 5 0", U, ["--irregular", "> 0"]),
    ("simulate --regular 0 100", U, ["--regular", "> 0"]),
    ("simulate --regular x 100", U, ["--regular", "number"]),
    ("simulate --regular 5 100 --irregular 5 11", U, ["--irregular", "not allowed with"]),
    ("simulate --dt 0", U, ["--dt", "> 0"]),
    ("simulate --dt -1", U, ["--dt", "> 0"]),
    ("simulate --dt 5", R, ["--dt", "<= 1 s"]),
    ("simulate --dt 0.5 --duration 0.1", R, ["--dt", "--duration"]),
    ("simulate --duration 0", U, ["--duration", "> 0"]),
    ("simulate --duration -100", U, ["--duration", "> 0"]),
    ("simulate --duration inf", U, ["--duration", "finite"]),
    ("simulate --seed -1", U, ["--seed", ">= 0"]),
    ("simulate --seed 1.5", U, ["--seed", "integer"]),
    ("simulate --components 0", U, ["--components", ">= 1"]),
    ("simulate --components x", U, ["--components", "integer"]),
    ("simulate --speed -3", U, ["--speed", ">= 0"]),
    ("simulate --speed nan", U, ["--speed", "finite"]),
    ("simulate --heading-deg x", U, ["--heading-deg", "number"]),
    ("simulate --hold foo", R, ["--hold", "foo"]),
    ("simulate --radiation bogus", U, ["--radiation", "invalid choice"]),
    ("simulate --integrator euler", U, ["--integrator", "invalid choice"]),
    ("simulate --precision float16", U, ["--precision", "invalid choice"]),
    ("simulate --output {dir}", R, ["--output", "is a directory"]),
    ("simulate --output {tmp}/s.txt", R, ["--output", "suffix", ".csv"]),
    ("simulate --output {file}/s.nc", R, ["--output", "is a file"]),
    ("simulate --output /proc/s.nc", R, ["--output", "cannot write"]),
    ("simulate --output {tmp}/s.nc --plot {dir}", R, ["--plot", "is a directory"]),
    ("simulate --output {tmp}/s.nc --plot {tmp}/p.txt", R, ["--plot", "suffix"]),
    # manoeuvre
    ("manoeuvre --dt 0", U, ["--dt", "> 0"]),
    ("manoeuvre --dt 3", R, ["--dt", "<= 1 s"]),
    ("manoeuvre --speed 0", U, ["--speed", "> 0"]),
    ("manoeuvre --speed -1", U, ["--speed", "> 0"]),
    ("manoeuvre --rudder-deg 0", U, ["--rudder-deg", "(0, 45]"]),
    ("manoeuvre --rudder-deg 90", U, ["--rudder-deg", "(0, 45]"]),
    ("manoeuvre --settle -1", U, ["--settle", ">= 0"]),
    ("manoeuvre --test bogus", U, ["--test", "invalid choice"]),
    ("manoeuvre --json {dir}", R, ["--json", "is a directory"]),
    ("manoeuvre --plot {file}/m.png", R, ["--plot", "is a file"]),
    # capsize-map
    ("capsize-map --headings 90 90", R, ["--headings", "duplicate", "90"]),
    ("capsize-map --headings 0 360", R, ["--headings", "duplicate"]),
    ("capsize-map --headings 400", U, ["--headings", "[-360, 360]"]),
    ("capsize-map --headings", U, ["--headings", "expected at least one argument"]),
    ("capsize-map --froude 0.2 0.2", R, ["--froude", "duplicate"]),
    ("capsize-map --froude -0.1", U, ["--froude", "[0, 1]"]),
    ("capsize-map --froude 2", U, ["--froude", "[0, 1]"]),
    ("capsize-map --sea regular:1:x", R, ["--sea", "regular:1:x"]),
    ("capsize-map --sea bogus", R, ["--sea", "bogus", "regular:H:lambda"]),
    ("capsize-map --sea jonswap:50:5", R, ["--sea", "DNV-RP-C205"]),
    ("capsize-map --sea regular:5:100 regular:5:100", R, ["--sea", "duplicate"]),
    ("capsize-map --seeds 0", U, ["--seeds", ">= 1"]),
    ("capsize-map --seeds -2", U, ["--seeds", ">= 1"]),
    ("capsize-map --duration 0", U, ["--duration", "> 0"]),
    ("capsize-map --dt 0", U, ["--dt", "> 0"]),
    ("capsize-map --dt 2", R, ["--dt", "<= 1 s"]),
    ("capsize-map --capsize-angle 0", U, ["--capsize-angle", "(0, 180]"]),
    ("capsize-map --capsize-angle 200", U, ["--capsize-angle", "(0, 180]"]),
    ("capsize-map --n-jobs 0", U, ["--n-jobs", ">= 1"]),
    ("capsize-map --n-jobs -1", U, ["--n-jobs", ">= 1"]),
    ("capsize-map --integrator euler", U, ["--integrator", "invalid choice"]),
    ("capsize-map --engine bogus", U, ["--engine", "invalid choice"]),
    ("capsize-map --results {dir}", R, ["--results", "is a directory"]),
    ("capsize-map --results {file}/r.jsonl", R, ["--results", "is a file"]),
    ("capsize-map --results {tmp}/r.jsonl --plot {tmp}/p.txt", R, ["--plot", "suffix"]),
    ("capsize-map --results {tmp}/r.jsonl --json /proc/c.json", R, ["--json", "cannot"]),
    # campaign
    ("campaign", U, ["required", "action"]),
    ("campaign run", U, ["FILE.toml", "required"]),
    ("campaign run {tmp}/none.toml", R, ["FILE.toml", "none.toml", "not found"]),
    ("campaign run {bad_toml}", R, ["bad.toml", "not a valid TOML"]),
    ("campaign run {bad_sea}", R, ["bad_sea.toml", "[[seas]] #1 hs_m", "missing"]),
    ("campaign run {spread}", R, ["[[seas]] #1 spreading_s = -10", "cos-2s exponent"]),
    ("campaign run {no_policy}", R, ["controller = 'policy:no_run'", "no saved model"]),
    ("campaign run {bad_ship}", R, ["ships", "nosuchship"]),
    ("campaign run {campaign} --workers 0", U, ["--workers", ">= 1"]),
    ("campaign run {campaign} --workers 2", R, ["--workers 2", "serial"]),
    ("campaign run {campaign} --executor bogus", U, ["--executor", "invalid choice"]),
    ("campaign run {campaign} --address x:1", R, ["--address", "--executor ray"]),
    ("campaign run {campaign} --store {file}", R, ["--store", "is a file"]),
    ("campaign report", U, ["FILE.toml|STORE", "required"]),
    ("campaign report {campaign}", R, ["no store", "campaign run"]),
    ("campaign report {campaign} --half-width 0", U, ["--half-width", "(0, 0.5]"]),
    ("campaign report {campaign} --half-width 0.7", U, ["--half-width", "(0, 0.5]"]),
    ("campaign report {campaign} --plot {tmp}/p.txt", R, ["--plot", "suffix"]),
    ("campaign report {campaign} --method wald", U, ["--method", "invalid choice"]),
    ("campaign report {dir} --store {dir}", R, ["--store", "not a store folder"]),
    # parametric-roll
    ("parametric-roll --steepness 0.5", U, ["--steepness", "(0, 0.142857]"]),
    ("parametric-roll --steepness 0", U, ["--steepness", "(0, 0.142857]"]),
    ("parametric-roll --wavelength-ratio 0", U, ["--wavelength-ratio", "> 0"]),
    ("parametric-roll --heading 400", U, ["--heading", "[-360, 360]"]),
    ("parametric-roll --froude -1", U, ["--froude", "[0, 1]"]),
    ("parametric-roll --duration -1", U, ["--duration", "> 0"]),
    ("parametric-roll --dt 0", U, ["--dt", "> 0"]),
    ("parametric-roll --json {dir}", R, ["--json", "is a directory"]),
    ("parametric-roll --plot {tmp}/r.txt", R, ["--plot", "suffix"]),
    # dead-ship
    ("dead-ship --hs 0", U, ["--hs", "> 0"]),
    ("dead-ship --tp -1", U, ["--tp", "> 0"]),
    ("dead-ship --hs 30 --tp 4", R, ["--hs/--tp", "DNV-RP-C205"]),
    ("dead-ship --seeds 0", U, ["--seeds", ">= 1"]),
    ("dead-ship --n-jobs 0", U, ["--n-jobs", ">= 1"]),
    ("dead-ship --duration 0", U, ["--duration", "> 0"]),
    ("dead-ship --dt 0", U, ["--dt", "> 0"]),
    ("dead-ship --json {dir}", R, ["--json", "is a directory"]),
    # safe-basin
    ("safe-basin --grid 1", U, ["--grid", ">= 2"]),
    ("safe-basin --grid x", U, ["--grid", "integer"]),
    ("safe-basin --forcing -0.1", U, ["--forcing", ">= 0"]),
    ("safe-basin --forcing nan", U, ["--forcing", "finite"]),
    ("safe-basin --integrity -1", U, ["--integrity", ">= 0"]),
    ("safe-basin --integrity", R, ["--integrity", "at least one"]),
    ("safe-basin --wave-height -1", U, ["--wave-height", ">= 0"]),
    ("safe-basin --wave-period 0", U, ["--wave-period", "> 0"]),
    ("safe-basin --duration 0", U, ["--duration", "> 0"]),
    ("safe-basin --dt 0", U, ["--dt", "> 0"]),
    ("safe-basin --dt 5 --duration 1", R, ["--dt", "--duration"]),
    ("safe-basin --roll-max 0", U, ["--roll-max", "(0, 3.2]"]),
    ("safe-basin --roll-max 10", U, ["--roll-max", "(0, 3.2]"]),
    ("safe-basin --rate-max 0", U, ["--rate-max", "> 0"]),
    ("safe-basin --model bogus", U, ["--model", "invalid choice"]),
    ("safe-basin --model s175 --integrity 0.01", R, ["--integrity", "edith-terkol"]),
    ("safe-basin --json {dir}", R, ["--json", "is a directory"]),
    ("safe-basin --csv {tmp}/b.txt", R, ["--csv", "suffix"]),
    ("safe-basin --plot {file}/b.png", R, ["--plot", "is a file"]),
    # identify
    ("identify", U, ["csv", "required"]),
    ("identify {tmp}/none.csv", U, ["csv", "no such file"]),
    ("identify {dir}", U, ["csv", "is a directory"]),
    ("identify {csv} --max-evaluations 0", U, ["--max-evaluations", ">= 1"]),
    ("identify {csv} --max-evaluations -5", U, ["--max-evaluations", ">= 1"]),
    ("identify {csv} --pieces 0", U, ["--pieces", ">= 1"]),
    ("identify {csv} --omega 0", U, ["--omega", "> 0"]),
    ("identify {csv} --omega x", U, ["--omega", "number"]),
    ("identify {csv} --train-end -1", U, ["--train-end", "> 0"]),
    ("identify {csv} --train-end 1e9", R, ["--train-end", "outside the record"]),
    ("identify {csv} --compare bogus", U, ["--compare", "invalid choice"]),
    ("identify {csv} --json {dir}", R, ["--json", "is a directory"]),
    ("identify {csv} --plot {file}/x.png", R, ["--plot", "is a file"]),
    ("identify {file}", R, ["a_file.txt", "missing column"]),
    # train
    ("train", U, ["config", "required"]),
    ("train no_such_config", R, ["no_such_config", "ppo_roll_one_dof"]),
    ("train ppo_roll_one_dof --timesteps 0", U, ["--timesteps", ">= 1"]),
    ("train ppo_roll_one_dof --timesteps -5", U, ["--timesteps", ">= 1"]),
    ("train ppo_roll_one_dof --n-envs 0", U, ["--n-envs", ">= 1"]),
    ("train ppo_roll_one_dof --seed -1", U, ["--seed", ">= 0"]),
    ("train ppo_roll_one_dof --output {file}", R, ["--output", "is a file"]),
    ("train ppo_roll_one_dof --output /proc/run", R, ["--output", "cannot"]),
    ("train {bad_toml}", R, ["bad.toml", "invalid TOML"]),
    ("train {bad_env}", R, ["[env] id", "Bogus", "registered id"]),
    # evaluate
    ("benchmark --tasks Sailing", R, ["--tasks", "Sailing", "expected comma-separated"]),
    ("benchmark --tasks ,", R, ["--tasks", "empty"]),
    ("benchmark --seeds 0", U, ["--seeds", "0"]),
    ("benchmark --tasks RollOneDOF --seed 5", R, ["--seed 5", "start in the training range"]),
    ("benchmark --tasks RollOneDOF --seed 10000", R, ["--seed 10000", "burnt range"]),
    ("benchmark --out {file}", R, ["--out"]),
    (
        "benchmark --tasks RollOneDOF --configs sac_ride_control",
        R,
        ["--configs 'sac_ride_control'", "is no config of RollOneDOF", "ppo_roll_one_dof"],
    ),
    ("evaluate", U, ["--env", "required"]),
    ("evaluate --env bogus", R, ["--env", "bogus", "registered id"]),
    ("evaluate --env ship_gym/Bogus-v0", R, ["--env", "Bogus", "registered id"]),
    ("evaluate --env ship_gym/RollOneDOF-v9", R, ["--env", "v9", "registered id"]),
    ("evaluate --env ship_gym/RollOneDOF-v0 --episodes 0", U, ["--episodes", ">= 1"]),
    ("evaluate --env ship_gym/RollOneDOF-v0 --episodes x", U, ["--episodes", "integer"]),
    ("evaluate --env ship_gym/RollOneDOF-v0 --seed -1", U, ["--seed", ">= 0"]),
    ("evaluate --env ship_gym/RollOneDOF-v0 --max-steps 0", U, ["--max-steps", ">= 1"]),
    ("evaluate --env ship_gym/RollOneDOF-v0 --policies zero,zero", R, ["--policies", "zero"]),
    ("evaluate --env ship_gym/RollOneDOF-v0 --policies bogus", R, ["--policies", "bogus"]),
    (
        "evaluate --env ship_gym/RollOneDOF-v0 --policies model:{tmp}/none.zip",
        R,
        ["--policies", "none.zip", "no saved model"],
    ),
    ("evaluate --env ship_gym/RollOneDOF-v0 --policies ,,", R, ["--policies", "at least one"]),
    ("evaluate --env ship_gym/RollOneDOF-v0 --out {file}", R, ["--out", "is a file"]),
    ("evaluate --env ship_gym/RollOneDOF-v0 --out {tmp}/e --json {dir}", R, ["--json"]),
    ("evaluate --env ship_gym/RollOneDOF-v0 --set x", U, ["--set", "key=value"]),
    ("evaluate --env ship_gym/RollOneDOF-v0 --no-plot --bogus", U, ["unrecognized", "--bogus"]),
]


def _argv(case: str, paths: dict) -> list[str]:
    return _fill(case.split(), paths)  # "--plot=" is an empty value: no plot


def test_at_least_a_hundred_cases_and_every_subcommand_covered():
    assert len(CASES) >= 100
    commands = set(build_parser()._subparsers._group_actions[0].choices)  # type: ignore[union-attr]
    covered = {c.split(" ")[0] for c, _, _ in CASES}
    assert commands <= covered


@pytest.mark.parametrize(("case", "code", "expected"), CASES, ids=[c[0] for c in CASES])
def test_bad_argument(case, code, expected, paths, no_work, capsys, monkeypatch, tmp_path):
    monkeypatch.chdir(tmp_path)
    status = main(_argv(case, paths))
    err = capsys.readouterr().err
    assert status == code, err
    assert "Traceback" not in err
    assert "internal error" not in err, err
    assert not no_work, f"{no_work} ran before the bad argument was refused"
    for text in expected:
        assert _fill([text], paths)[0] in err, err
    assert "error:" in err


def test_a_subprocess_shows_no_traceback(tmp_path):
    exe = Path(sys.executable).parent / "ship-gym"
    for argv, code in (
        (["evaluate", "--env", "bogus"], 1),
        (["hull", "s175", "--heel-step", "0"], 2),
        (["simulate", "--irregular", "50", "11", "--output", str(tmp_path)], 2),
    ):
        out = subprocess.run([str(exe), *argv], capture_output=True, text=True, timeout=120)
        assert out.returncode in (code, 1, 2) and out.returncode != 0
        assert "Traceback" not in out.stderr and "error:" in out.stderr


def test_debug_shows_the_traceback(tmp_path, capsys):
    with pytest.raises(CLIError, match="--heel-step"):
        main(["--debug", "hull", "s175", "--heel-step", "30", "--heel-max", "10"])
    with pytest.raises(CLIError):  # also after the command
        main(["hull", "s175", "--heel-step", "30", "--heel-max", "10", "--debug"])
    exe = Path(sys.executable).parent / "ship-gym"
    out = subprocess.run(
        [str(exe), "--debug", "evaluate", "--env", "bogus"],
        capture_output=True,
        text=True,
        timeout=120,
    )
    assert out.returncode == 1 and "Traceback" in out.stderr


def test_a_bug_is_one_line_asking_for_debug(monkeypatch, capsys):
    import ship_gym.cli.hull as hull_cli

    class Bug(Exception):
        pass

    def boom(args):
        raise Bug("oops")

    monkeypatch.setattr(hull_cli, "_cmd_hull", boom)
    # the parser binds func at build time: rebuild after the patch
    assert main(["hull", "s175"]) == 1
    err = capsys.readouterr().err
    assert "bug" in err and "--debug" in err and "oops" in err and "Traceback" not in err
    with pytest.raises(Bug):
        main(["--debug", "hull", "s175"])


def test_hydro_checks_and_creates_the_output_folder_before_the_bem(tmp_path, monkeypatch, capsys):
    import ship_gym.hydro.bem as bem

    seen = []

    def fake(hull, **kwargs):
        seen.append((tmp_path / "new" / "deeper").is_dir())
        raise CLIError("stop here")

    monkeypatch.setattr(bem, "compute_hull_database", fake)
    assert main(["hydro", "s175", "--output", str(tmp_path / "new/deeper/db.nc")]) == 1
    assert seen == [True]  # the folder existed when the computation started
    assert "stop here" in capsys.readouterr().err


def test_simulate_checks_the_output_before_building_the_simulator(tmp_path, monkeypatch):
    import ship_gym.engine.ship as ship

    called = []
    monkeypatch.setattr(ship, "build_simulator", lambda *a, **k: called.append(1))
    (tmp_path / "f").write_text("")
    assert main(["simulate", "--output", str(tmp_path / "f" / "x.nc")]) == 1
    assert called == []


def test_prepare_output_names_the_option(tmp_path):
    with pytest.raises(CLIError, match="--thing"):
        prepare_output(tmp_path, "--thing")
    assert prepare_output("", "--thing") is None
    target = prepare_output(tmp_path / "a" / "b" / "c.json", "--thing")
    assert target is not None and target.parent.is_dir()


def test_a_late_write_failure_rescues_the_result(tmp_path, monkeypatch):
    import tempfile

    rescue_dir = tmp_path / "rescue"
    rescue_dir.mkdir()
    monkeypatch.setattr(tempfile, "gettempdir", lambda: str(rescue_dir))
    blocker = tmp_path / "gone"
    blocker.write_text("a file where the folder was")
    with pytest.raises(CLIError, match="saved to") as info:
        write_or_rescue(blocker / "out.json", lambda p: p.write_text("{}"), "--json")
    saved = list(rescue_dir.glob("ship-gym-*-out.json"))
    assert len(saved) == 1 and saved[0].read_text() == "{}"
    assert str(saved[0]) in str(info.value) and "--json" in str(info.value)


# ----------------------------------------------------------------------------- evaluate (item 8)
def test_models_that_share_a_file_name_get_distinct_labels():
    from ship_gym.agents.evaluate import policy_labels

    assert policy_labels(["zero", "model:runs/a/model.zip", "model:runs/b/model.zip"]) == [
        "zero",
        "model:a",
        "model:b",
    ]
    assert policy_labels(["model:x/a/model.zip", "model:y/a/model.zip"]) == [
        "model:x/a/model.zip",
        "model:y/a/model.zip",
    ]
    assert policy_labels(["model:runs/a", "model:best.zip"]) == ["model:a", "model:best.zip"]
    with pytest.raises(ValueError, match="more than once"):
        policy_labels(["zero", "zero"])


def test_evaluate_applies_the_training_env_settings_and_says_so(monkeypatch):
    import ship_gym.agents.evaluate as ev

    class Fake:
        def __init__(self) -> None:
            self.training_env = {
                "id": "ship_gym/RollOneDOF-v0",
                "kwargs": {"forcing_amplitude": 0.03},
            }

    seen = {}
    monkeypatch.setattr(
        ev, "_policy_factory", lambda spec, device="cpu", trusted=False: (spec, Fake())
    )

    def fake_run(env_id, policy, seeds, kwargs, **k):
        seen[k["label"]] = dict(kwargs)
        return ev.EpisodeStats(**{f: [] for f in ev.EpisodeStats.__dataclass_fields__})

    monkeypatch.setattr(ev, "run_episodes", fake_run)
    monkeypatch.setattr(ev, "summarize", lambda stats: {})
    monkeypatch.setattr(ev, "asdict", lambda stats: {})
    messages: list[str] = []
    specs = ["model:r1/model.zip", "model:r2/model.zip"]
    out = ev.evaluate_policies(
        "ship_gym/RollOneDOF-v0", specs, 1, 0, {"max_moment": 0.02}, report=messages.append
    )
    assert list(out["policies"]) == ["model:r1", "model:r2"]
    assert seen["model:r1"] == {"forcing_amplitude": 0.03, "max_moment": 0.02}
    assert seen["model:r2"] == seen["model:r1"]
    assert any("trained with" in m and "forcing_amplitude" in m for m in messages)
    seen.clear()
    messages.clear()
    ev.evaluate_policies(
        "ship_gym/RollOneDOF-v0",
        specs[:1],
        1,
        0,
        {"forcing_amplitude": 0.01},
        report=messages.append,
        use_training_env=True,
    )
    assert seen["model:r1"] == {"forcing_amplitude": 0.01}  # --set wins
    assert any("overridden" in m for m in messages)
    seen.clear()
    ev.evaluate_policies(
        "ship_gym/RollOneDOF-v0", specs[:1], 1, 0, {}, use_training_env=False, report=print
    )
    assert seen["model:r1"] == {}


def test_evaluate_runs_baselines_on_the_models_ship_and_refuses_mixed_models(monkeypatch):
    """Issue #32: a model trained on another ship (or sea) and the baselines of the same table
    run on the same settings — the model's — and models trained with different settings are
    refused rather than put in one table."""
    import ship_gym.agents.evaluate as ev

    class Fake:
        def __init__(self, ship: str) -> None:
            self.training_env = {"id": "ship_gym/RollStabilization-v3", "kwargs": {"ship": ship}}

    models = {"model:a/model.zip": Fake("kcs.toml"), "model:b/model.zip": Fake("other.toml")}

    def factory(spec, device="cpu", trusted=False):
        if spec in models:
            return spec, models[spec]
        return spec, (lambda env: None)

    seen = {}
    monkeypatch.setattr(ev, "_policy_factory", factory)

    def fake_run(env_id, policy, seeds, kwargs, **k):
        seen[k["label"]] = dict(kwargs)
        return ev.EpisodeStats(**{f: [] for f in ev.EpisodeStats.__dataclass_fields__})

    monkeypatch.setattr(ev, "run_episodes", fake_run)
    monkeypatch.setattr(ev, "summarize", lambda stats: {})
    monkeypatch.setattr(ev, "asdict", lambda stats: {})
    messages: list[str] = []
    out = ev.evaluate_policies(
        "ship_gym/RollStabilization-v3", ["zero", "fins", "model:a/model.zip"], 1, 0, {},
        report=messages.append,
    )  # fmt: skip
    assert seen == {label: {"ship": "kcs.toml"} for label in ("zero", "fins", "model:a")}
    assert all(v == {"ship": "kcs.toml"} for v in out["policy_env_kwargs"].values())
    assert any("every policy runs with" in m and "kcs.toml" in m for m in messages)
    with pytest.raises(ValueError, match="different env settings"):
        ev.evaluate_policies(
            "ship_gym/RollStabilization-v3", ["model:a/model.zip", "model:b/model.zip"], 1, 0
        )


# ----------------------------------------------------------------------------- leftovers (item 10)
def test_stale_temporary_files_are_removed_on_the_next_write(tmp_path, capsys):
    from ship_gym.io_utils import atomic_write_text, clean_stale_temps

    target = tmp_path / "out.json"
    old = time.time() - 7200
    dead = tmp_path / f".out.json.{2**22 + 12345}.abcd1234.tmp"  # above pid_max: never alive
    live = tmp_path / f".out.json.{os.getpid()}.efgh5678.tmp"
    legacy_old = tmp_path / ".out.json.zz9yx8w7.tmp"
    legacy_new = tmp_path / ".out.json.qq1rr2ss.tmp"
    other = tmp_path / f".other.json.{2**22 + 12345}.abcd1234.tmp"
    for f in (dead, live, legacy_old, legacy_new, other):
        f.write_text("partial")
        os.utime(f, (old, old))
    os.utime(legacy_new, None)  # just written: maybe another process's write in progress
    atomic_write_text(target, "{}")
    assert not dead.exists() and not legacy_old.exists()
    assert live.exists() and legacy_new.exists() and other.exists()
    assert target.read_text() == "{}"
    assert clean_stale_temps(target) == []
    # through the CLI: the next run of the same command cleans up
    dead.write_text("partial")
    os.utime(dead, (old, old))
    assert main(["hull", "box_barge", "--plot", "", "--json", str(target)]) == 0
    assert not dead.exists()


def test_a_temp_file_names_the_writing_process(tmp_path):
    from ship_gym.io_utils import atomic_write

    names = []
    atomic_write(tmp_path / "x.txt", lambda p: (names.append(p.name), p.write_text("1")))
    assert names[0].startswith(f".x.txt.{os.getpid()}.") and names[0].endswith(".tmp")


WORKER_SCRIPT = textwrap.dedent(
    """
    import os, sys, time
    from pathlib import Path
    import ship_gym.analysis.capsize_map as cm
    from ship_gym.cli import main

    PIDS = Path(sys.argv[1])

    def work(i):
        with open(PIDS, "a") as fh:
            fh.write(f"{os.getpid()}\\n")
        time.sleep(120)
        return i

    def fake_run(config, results, n_jobs=1, **kwargs):
        from joblib import Parallel, delayed
        return Parallel(n_jobs=n_jobs)(delayed(work)(i) for i in range(n_jobs))

    cm.run_capsize_map = fake_run
    sys.exit(main(["capsize-map", "--n-jobs", "2", "--headings", "90", "--froude", "0.2",
                   "--results", sys.argv[2], "--plot", "", "--no-progress"]))
    """
)


def _alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    try:  # a zombie (exited, not yet reaped) counts as dead
        state = Path(f"/proc/{pid}/stat").read_text().split(")")[-1].split()[0]
    except OSError:
        return False
    return state != "Z"


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="/proc and PDEATHSIG")
@pytest.mark.parametrize("sig", [signal.SIGTERM, signal.SIGKILL])
def test_capsize_map_workers_die_with_the_parent(tmp_path, sig):
    script = tmp_path / "run.py"
    script.write_text(WORKER_SCRIPT)
    pids_file = tmp_path / "pids"
    proc = subprocess.Popen(
        [sys.executable, str(script), str(pids_file), str(tmp_path / "r.jsonl")],
        stdout=subprocess.PIPE,
        stderr=subprocess.PIPE,
        text=True,
    )
    try:
        deadline = time.time() + 90
        while time.time() < deadline:
            if pids_file.exists() and len(pids_file.read_text().split()) >= 2:
                break
            assert proc.poll() is None, proc.communicate()
            time.sleep(0.2)
        workers = [int(p) for p in pids_file.read_text().split()]
        assert len(workers) >= 2 and all(_alive(p) for p in workers)
        proc.send_signal(sig)
        proc.wait(timeout=30)
        deadline = time.time() + 10
        while time.time() < deadline and any(_alive(p) for p in workers):
            time.sleep(0.2)
        survivors = [p for p in workers if _alive(p)]
        assert not survivors, f"workers {survivors} survived the parent's {sig.name}"
        if sig == signal.SIGTERM:
            assert "Traceback" not in proc.stderr.read()
    finally:
        if proc.poll() is None:
            proc.kill()
        for p in [int(x) for x in pids_file.read_text().split()] if pids_file.exists() else []:
            if _alive(p):
                os.kill(p, signal.SIGKILL)


def test_readme_mentions_debug():
    readme = (Path(__file__).parents[2] / "README.md").read_text()
    assert "--debug" in readme


def test_json_payload_still_written(tmp_path):
    out = tmp_path / "deep" / "hull.json"
    assert main(["hull", "box_barge", "--plot", "", "--json", str(out)]) == 0
    assert "gmt_m" in json.loads(out.read_text())


@pytest.mark.parametrize(
    ("argv", "expected"),
    [
        (["kernels", "s175", "--t-max", "1e7"], "--t-max 1e+07 with --dt 0.05: 2e+08 time steps"),
        (["kernels", "s175", "--dt", "1e-6"], "--t-max 60 with --dt 1e-06: 6e+07 time steps"),
        (["safe-basin", "--grid", "100000"], "--grid 100000: 1e+10 initial conditions"),
        (["safe-basin", "--model", "s175", "--grid", "3000"], "--grid 3000: 9e+06 initial"),
    ],
)
def test_sizes_past_the_memory_limit_are_refused_before_allocation(
    argv, expected, capsys, tmp_path
):
    import ship_gym.cli as cli

    out = ["--plot", str(tmp_path / "p.png")]
    assert cli.main([*argv, *out]) == 1
    err = capsys.readouterr().err
    assert expected in err and "GiB of memory; expected at most 4 GiB" in err
    assert "internal error" not in err
