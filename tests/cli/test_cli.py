"""ship_gym.cli: the command list, one module per command group, one ``--set`` helper, errors."""

import argparse
import json
import subprocess
import sys
from pathlib import Path

import pytest

import ship_gym.cli
from ship_gym.cli import build_parser, main

# command group module -> the commands the user types
GROUPS = {
    "ship": ("ship",),
    "hull": ("hull",),
    "hydro": ("hydro", "kernels"),
    "simulate": ("simulate",),
    "manoeuvre": ("manoeuvre",),
    "capsize": ("capsize-map", "parametric-roll", "dead-ship"),
    "campaign": ("campaign",),
    "safe_basin": ("safe-basin",),
    "identify": ("identify",),
    "agents": ("train", "evaluate", "benchmark"),
}
COMMANDS = [c for commands in GROUPS.values() for c in commands]
CLI_DIR = Path(ship_gym.cli.__file__).parent


def _ship_gym_command() -> list[str]:
    script = Path(sys.executable).with_name("ship-gym")
    return [str(script)] if script.exists() else [sys.executable, "-m", "ship_gym.cli"]


def _commands_of(parser: argparse.ArgumentParser) -> list[str]:
    (sub,) = (a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    return list(sub.choices)


def test_help_lists_every_command():
    out = subprocess.run(
        [*_ship_gym_command(), "--help"], capture_output=True, text=True, timeout=120, check=True
    ).stdout
    for command in COMMANDS:
        assert f"    {command} " in out, f"ship-gym --help does not list {command!r}:\n{out}"
    assert _commands_of(build_parser()) == COMMANDS


def test_python_dash_m_runs_the_cli():
    out = subprocess.run(
        [sys.executable, "-m", "ship_gym.cli", "--help"],
        capture_output=True,
        text=True,
        timeout=120,
        check=True,
    ).stdout
    assert out.startswith("usage: ship-gym")


@pytest.mark.parametrize("module", sorted(GROUPS))
def test_each_command_module_registers_the_commands_it_is_named_after(module):
    import importlib

    parser = argparse.ArgumentParser()
    importlib.import_module(f"ship_gym.cli.{module}").add_commands(parser.add_subparsers())
    assert tuple(_commands_of(parser)) == GROUPS[module]


def test_the_command_modules_are_the_groups():
    modules = {p.stem for p in CLI_DIR.glob("*.py")} - {"__init__", "__main__", "common"}
    assert modules == set(GROUPS)


def test_one_overrides_helper():
    """``--set`` is declared once (cli/common.py); every command that takes it parses it alike."""
    declaring = sorted(p.name for p in CLI_DIR.glob("*.py") if '"--set"' in p.read_text())
    assert declaring == ["common.py"]
    parser = build_parser()
    (sub,) = (a for a in parser._actions if isinstance(a, argparse._SubParsersAction))
    with_set = [name for name, p in sub.choices.items() if "--set" in p._option_string_actions]
    assert set(with_set) == {
        "hull", "hydro", "capsize-map", "parametric-roll", "dead-ship", "evaluate",
    }  # fmt: skip
    for name in with_set:
        args = sub.choices[name]._option_string_actions["--set"]
        assert (args.nargs, args.metavar, args.default) == ("*", "KEY=VALUE", [])


def test_parser_imports_no_heavy_module():
    code = (
        "import json, sys; from ship_gym.cli import build_parser; build_parser(); "
        "print(json.dumps(sorted(sys.modules)))"
    )
    out = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, timeout=120, check=True
    )
    loaded = json.loads(out.stdout.strip().splitlines()[-1])
    heavy = ("torch", "stable_baselines3", "capytaine", "matplotlib")
    assert not [m for m in loaded if m.split(".")[0] in heavy]


def test_user_errors_are_messages_not_tracebacks(tmp_path, monkeypatch, capsys):
    monkeypatch.chdir(tmp_path)
    assert main(["train", "no_such_config"]) == 1
    err = capsys.readouterr().err
    assert err.startswith("ship-gym train: error: no config file no_such_config")
    assert "ppo_roll_one_dof" in err  # the shipped names are offered
    assert "Traceback" not in err
    assert main(["hull", "s175", "--set", "kg"]) == 2  # a usage error, found by argparse
    assert "argument --set: override 'kg' must look like key=value" in capsys.readouterr().err
