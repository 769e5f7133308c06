"""Data flows one way (DESIGN.md §2): no module imports a stage to its right, and no cycle.

Stages: foundations → hull → hydro → waves → forces → control and ship (a ship's hull, appendages
and database) → engine (with the 1-DOF roll model
and the comfort metrics beside it) → envs → analysis → agents → cli.

* Statically (the source's ``import`` statements, also those inside functions and under
  ``TYPE_CHECKING``): every import of a ship_gym module goes to the same or an earlier stage,
  and the imports executed when a module is imported form no cycle.
* At run time: each module is imported in a fresh interpreter and the ship_gym modules it pulled
  in are checked against the stage order; ``import ship_gym`` must load neither torch nor
  capytaine, and capytaine may only be imported by the BEM adapter.
"""

import ast
import json
import pkgutil
import subprocess
import sys
from pathlib import Path

import pytest

import ship_gym

# stage rank of each top-level sub-package / module; a module may import ranks <= its own
STAGES = {
    "conventions": 0,
    "typing": 0,
    "io_utils": 0,
    "data": 0,
    "kinematics": 1,
    "numerics": 1,
    "hull": 2,
    "hydro": 3,
    "waves": 4,
    "forces": 5,
    "control": 6,
    "ship": 6,
    "engine": 7,
    "roll": 7,
    "comfort": 7,
    "envs": 8,
    "analysis": 9,
    "agents": 10,
    "cli": 11,
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
        f"{module} imports torch/stable-baselines3 at import time (import them inside functions)"
    )


# ---------------------------------------------------------------------------------- static
PACKAGE = Path(__file__).resolve().parents[2] / "ship_gym"


def _module_name(path: Path) -> str:
    parts = path.relative_to(PACKAGE.parent).with_suffix("").parts
    return ".".join(parts[:-1] if parts[-1] == "__init__" else parts)


def _unit(module: str) -> str:
    parts = module.split(".")
    return parts[1] if len(parts) > 1 else "__init__"


def _is_type_checking(node: ast.If) -> bool:
    test = node.test
    return (isinstance(test, ast.Name) and test.id == "TYPE_CHECKING") or (
        isinstance(test, ast.Attribute) and test.attr == "TYPE_CHECKING"
    )


def _imports(
    tree: ast.Module, package: str
) -> tuple[list[tuple[str, int]], set[tuple[str, tuple[str, ...]]]]:
    """(every ship_gym import with its line, the imports executed when the module is imported:
    (module, the names ``from module import …`` takes, as dotted paths))."""
    every: list[tuple[str, int]] = []
    eager: set[tuple[str, tuple[str, ...]]] = set()

    def targets(node: ast.stmt) -> list[str]:
        if isinstance(node, ast.ImportFrom):
            if node.level:  # relative import
                base = package.rsplit(".", node.level - 1)[0] if node.level > 1 else package
                mod = f"{base}.{node.module}" if node.module else base
            else:
                mod = node.module or ""
            if not mod.startswith("ship_gym"):
                return []
            # ``from ship_gym.x import y`` may import the submodule ship_gym.x.y
            return [mod] + [f"{mod}.{a.name}" for a in node.names]
        if isinstance(node, ast.Import):
            return [a.name for a in node.names if a.name.startswith("ship_gym")]
        return []

    def visit(body: list[ast.stmt], at_import: bool) -> None:
        for node in body:
            found = targets(node)
            if found:
                every.append((found[0], node.lineno))
                if at_import:
                    eager.add((found[0], tuple(found[1:])))
            if isinstance(node, ast.If):
                visit(node.body, at_import and not _is_type_checking(node))
                visit(node.orelse, at_import)
            elif isinstance(node, ast.Try):
                for block in (node.body, node.orelse, node.finalbody):
                    visit(block, at_import)
                for handler in node.handlers:
                    visit(handler.body, at_import)
            elif isinstance(node, ast.With):
                visit(node.body, at_import)
            elif isinstance(node, ast.FunctionDef | ast.AsyncFunctionDef | ast.ClassDef):
                visit(node.body, at_import and isinstance(node, ast.ClassDef))

    visit(tree.body, True)
    return every, eager


def _graph() -> tuple[dict[str, list[tuple[str, int]]], dict[str, set]]:
    every: dict[str, list[tuple[str, int]]] = {}
    eager: dict[str, set] = {}
    for path in sorted(PACKAGE.rglob("*.py")):
        name = _module_name(path)
        package = name if path.name == "__init__.py" else name.rsplit(".", 1)[0]
        every[name], eager[name] = _imports(ast.parse(path.read_text()), package)
    return every, eager


EVERY, EAGER = _graph()


def test_every_subpackage_has_a_stage():
    units = {_unit(m) for m in EVERY} - {"__init__"}  # ship_gym/__init__: the registration
    assert units <= STAGES.keys(), f"subpackages without a stage: {sorted(units - STAGES.keys())}"


@pytest.mark.parametrize("module", sorted(EVERY))
def test_no_import_from_a_later_stage_in_the_source(module):
    stage = STAGES.get(_unit(module), 12)
    later = [
        f"line {line}: {target}"
        for target, line in EVERY[module]
        if STAGES.get(_unit(target), 12) > stage
    ]
    assert not later, f"{module} (stage {stage}) imports a later stage: {later}"


def test_module_level_imports_have_no_cycle():
    modules = set(EAGER)

    def edges(m: str) -> list[str]:
        out: set[str] = set()
        for target, names in EAGER[m]:
            subs = [n for n in names if n in modules]
            # ``from package import submodule`` loads the submodule (the package is already
            # being initialised): an edge to the package only when a name is not a submodule
            if not (names and len(subs) == len(names)):
                out.add(target)
            out.update(subs)
        return sorted(t for t in out if t in modules and t != m)

    graph = {m: edges(m) for m in modules}
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    cycles: list[list[str]] = []
    counter = [0]

    def strongconnect(v: str) -> None:  # Tarjan's strongly connected components
        index[v] = low[v] = counter[0]
        counter[0] += 1
        stack.append(v)
        on_stack.add(v)
        for w in graph[v]:
            if w not in index:
                strongconnect(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                component.append(w)
                if w == v:
                    break
            if len(component) > 1:
                cycles.append(sorted(component))

    for v in sorted(graph):
        if v not in index:
            strongconnect(v)
    assert not cycles, f"import cycles among module-level imports: {cycles}"


def test_the_graph_is_not_empty():
    # the parser found the imports (a test that cannot fail otherwise)
    assert len(EVERY) > 50
    assert "ship_gym.engine.batch" in {t for t, _ in EAGER["ship_gym.engine.simulator"]}
