"""Data flows one way (DESIGN.md §2): no module imports a stage to its right.

Each module is imported in a fresh interpreter and the ship_gym modules it pulled in are checked
against the stage order; ``import ship_gym`` must load neither torch nor capytaine, and capytaine
may only be imported by the BEM adapter.
"""

import json
import pkgutil
import subprocess
import sys

import pytest

import ship_gym

# stage rank of each top-level sub-package / module; a module may import ranks <= its own
STAGES = {
    "conventions": 0,
    "kinematics": 0,
    "io_utils": 0,
    "data": 0,
    "hull": 1,
    "hydro": 2,
    "waves": 3,
    "forces": 4,
    "control": 5,
    "engine": 6,
    "typing": 0,
    "envs": 7,
    "analysis": 8,
    "cli": 9,
    "cli_hydro": 9,
    "cli_simulate": 9,
    "cli_manoeuvre": 9,
    "cli_capsize": 9,
    "cli_roll": 9,
    "cli_agents": 9,
    "cli_identify": 9,
    "cli_common": 9,
}


def _modules() -> list[str]:
    names = [
        m.name
        for m in pkgutil.walk_packages(ship_gym.__path__, prefix="ship_gym.")
        if not m.name.endswith("__main__")
    ]
    return sorted(names)


def _stage(module: str) -> int:
    part = module.split(".")[1]
    if part not in STAGES:
        raise AssertionError(f"module {module} belongs to no stage; add it to STAGES")
    return STAGES[part]


def _loaded_after_import(module: str) -> list[str]:
    code = (
        f"import importlib, json, sys; importlib.import_module({module!r}); "
        "print(json.dumps(sorted(sys.modules)))"
    )
    out = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, check=True, timeout=120
    )
    return json.loads(out.stdout.strip().splitlines()[-1])


def test_import_ship_gym_is_light():
    loaded = _loaded_after_import("ship_gym")
    assert not any(m == "torch" or m.startswith("torch.") for m in loaded)
    assert not any(m.startswith("capytaine") for m in loaded)


# ``import ship_gym`` registers the Gymnasium ids: these (string entry points, no env module)
# are loaded by every ship_gym import and are exempt from the stage rule.
REGISTRATION = {"ship_gym.envs", "ship_gym.envs.registration"}


def test_import_ship_gym_loads_only_the_registration():
    loaded = {m for m in _loaded_after_import("ship_gym") if m.startswith("ship_gym.")}
    assert loaded <= REGISTRATION, f"import ship_gym loads {sorted(loaded - REGISTRATION)}"


@pytest.mark.parametrize("module", _modules())
def test_no_import_to_the_right(module):
    loaded = _loaded_after_import(module)
    own = _stage(module)
    offenders = [
        m for m in loaded if m.startswith("ship_gym.") and m not in REGISTRATION and _stage(m) > own
    ]
    assert not offenders, f"{module} (stage {own}) imports modules to its right: {offenders}"
    if module != "ship_gym.hydro.bem":
        assert not any(m.startswith("capytaine") for m in loaded), (
            f"{module} imports capytaine; only ship_gym.hydro.bem may"
        )
    assert not any(m == "torch" or m.startswith("stable_baselines3") for m in loaded), (
        f"{module} imports torch/stable-baselines3 at import time; only agents/ may"
    )
