"""Build-time page generator (mkdocs-gen-files): the API reference and the environment pages.

Run by ``mkdocs build`` (``plugins: gen-files: scripts: [docs/gen_pages.py]``); writes nothing to
disk itself, the pages exist only inside the build.

* ``reference/<name>.md``: one page per public top-level subpackage or module of ``ship_gym``,
  found by walking the *installed* package with :func:`pkgutil.walk_packages`, with a
  ``::: module`` directive for the package and one for each of its public modules, so that a
  module moved or added in the tree appears without editing any page. Private modules (a leading
  underscore anywhere in the dotted name), ``__main__`` and the names in ``SKIP`` are left out.
  ``reference/SUMMARY.md`` is the section's navigation (mkdocs-literate-nav).
* ``envs/<Name>.md``: one page per registered id (:data:`ship_gym.envs.registration.ENTRIES`),
  with the id, entry points, time limit, the action/observation/reward/end summary taken from
  the README's "Environment ids" table, and the env class docstring rendered by mkdocstrings
  (``force_inspection``: the ship envs complete their docstrings at import time).
"""

from __future__ import annotations

import importlib
import pkgutil
import re
from pathlib import Path

import mkdocs_gen_files

import ship_gym
from ship_gym.envs.registration import ENTRIES

ROOT = Path(__file__).resolve().parent.parent

#: Top-level names not given an API page: the command line (documented by ``ship-gym --help``
#: and the quick-start) and the bundled data files.
SKIP = {"cli", "data"}

#: Order of the API pages: the pipeline, then the shared modules; anything else (a package added
#: later) follows alphabetically.
ORDER = [
    "hull",
    "ship",
    "hydro",
    "waves",
    "forces",
    "control",
    "numerics",
    "engine",
    "roll",
    "comfort",
    "envs",
    "agents",
    "analysis",
    "conventions",
    "kinematics",
    "typing",
]


def _public(name: str) -> bool:
    return not any(part.startswith("_") for part in name.split("."))


def _modules() -> dict[str, list[tuple[str, bool]]]:
    """Top-level name -> [(dotted module name, is_package), ...] in walk order."""
    groups: dict[str, list[tuple[str, bool]]] = {}

    def onerror(name: str) -> None:
        raise ImportError(f"gen_pages: importing {name} failed while walking ship_gym")

    for info in pkgutil.walk_packages(ship_gym.__path__, "ship_gym.", onerror=onerror):
        if not _public(info.name):
            continue
        top = info.name.split(".")[1]
        if top in SKIP:
            continue
        groups.setdefault(top, []).append((info.name, info.ispkg))
    return groups


def _sort_key(top: str) -> tuple[int, str]:
    return (ORDER.index(top) if top in ORDER else len(ORDER), top)


def _first_line(module_name: str) -> str:
    doc = importlib.import_module(module_name).__doc__ or ""
    line = doc.strip().split("\n\n")[0].replace("\n", " ").strip()
    return line.replace("|", "\\|")


def write_reference() -> None:
    groups = _modules()
    nav = ["* [Overview](index.md)"]
    rows = []
    for top in sorted(groups, key=_sort_key):
        modules = sorted(groups[top], key=lambda m: (not m[1], m[0]))  # package first
        package = f"ship_gym.{top}"
        path = f"reference/{top}.md"
        with mkdocs_gen_files.open(path, "w") as fd:
            # the package (or top-level module) is the page's level-1 heading, so that its
            # anchor exists for cross-references; its modules are level-2 sections
            is_package = modules[0] == (package, True)
            fd.write(f"::: {package}\n    options:\n      heading_level: 1\n")
            if is_package:
                fd.write("      members: false\n\n")
                for name, _ in modules[1:]:
                    fd.write(f"::: {name}\n\n")
            else:
                fd.write("\n")
        mkdocs_gen_files.set_edit_path(path, Path("..") / _source(package))
        nav.append(f"* [{package}]({top}.md)")
        rows.append(f"| [`{package}`]({top}.md) | {_first_line(package)} |")
    with mkdocs_gen_files.open("reference/SUMMARY.md", "w") as fd:
        fd.write("\n".join(nav) + "\n")
    with mkdocs_gen_files.open("reference/index.md", "w") as fd:
        fd.write(
            "# API reference\n\n"
            "Generated from the docstrings of the installed package (NumPy style, units in "
            "brackets): one page per top-level subpackage, one section per public module.\n\n"
            "| module | summary |\n|---|---|\n" + "\n".join(rows) + "\n"
        )


def _source(module_name: str) -> str:
    parts = module_name.split(".")
    pkg = Path(*parts)
    return str(pkg / "__init__.py") if (ROOT / pkg).is_dir() else str(pkg) + ".py"


def _readme_env_rows() -> dict[str, list[str]]:
    """The README's environment table: id -> [actions, observations, reward terms, end]."""
    text = (ROOT / "README.md").read_text(encoding="utf-8")
    rows: dict[str, list[str]] = {}
    for line in text.splitlines():
        m = re.match(r"^\| `(ship_gym/[A-Za-z]+-v\d+)` \|(.*)\|\s*$", line)
        if m:
            cells = [c.strip() for c in re.split(r"(?<!\\)\|", m.group(2))]
            rows[m.group(1)] = cells
    return rows


def write_envs() -> None:
    table = _readme_env_rows()
    missing = [e.id for e in ENTRIES if e.id not in table or len(table[e.id]) != 4]
    if missing:
        raise RuntimeError(
            f"gen_pages: README.md's environment table has no 4-column row for {missing}"
        )
    nav = ["* [Overview](index.md)"]
    overview = [
        "# Environments\n",
        "`import ship_gym` registers the ids; "
        '`gymnasium.make("ship_gym:ship_gym/<Name>-vN")` works in a fresh interpreter, '
        '`gymnasium.make_vec(id, num_envs=N, vectorization_mode="vector_entry_point")` steps '
        "N episodes in one engine call. Actions are `Box(-1, 1, float32)` scaled inside to "
        "physical commands; observations are float32 with names and units in "
        "`env.unwrapped.observation_names`; reward = Σ weighted terms, each in "
        '`info["reward_<term>"]`, the Safe-RL cost in `info["cost"]`.\n',
        "| id | actions | observations | reward terms | end (terminated / truncated) |",
        "|---|---|---|---|---|",
    ]
    for entry in ENTRIES:
        actions, observations, rewards, end = table[entry.id]
        module, cls = entry.entry_point.split(":")
        vec_module, vec_cls = entry.vector_entry_point.split(":")
        page = f"envs/{entry.name}.md"
        with mkdocs_gen_files.open(page, "w") as fd:
            fd.write(
                f"# {entry.name}-v{entry.version}\n\n"
                f"| | |\n|---|---|\n"
                f"| id | `{entry.id}` |\n"
                f'| make | `gymnasium.make("ship_gym:{entry.id}")` |\n'
                f"| single env | `{module}.{cls}` |\n"
                f"| vector env | `{vec_module}.{vec_cls}` |\n"
                f"| time limit | {entry.max_episode_steps} control steps |\n"
                f"| actions | {actions} |\n"
                f"| observations | {observations} |\n"
                f"| reward terms | {rewards} |\n"
                f"| end (terminated / truncated) | {end} |\n\n"
                f"::: {module}.{cls}\n"
                "    options:\n"
                "      show_root_heading: false\n"
                "      show_root_toc_entry: false\n"
                "      members: false\n"
                "      heading_level: 2\n"
            )
        mkdocs_gen_files.set_edit_path(page, Path("..") / _source(module))
        nav.append(f"* [{entry.name}-v{entry.version}]({entry.name}.md)")
        overview.append(
            f"| [`{entry.id}`]({entry.name}.md) | {actions} | {observations} | {rewards} | {end} |"
        )
    with mkdocs_gen_files.open("envs/SUMMARY.md", "w") as fd:
        fd.write("\n".join(nav) + "\n")
    with mkdocs_gen_files.open("envs/index.md", "w") as fd:
        fd.write("\n".join(overview) + "\n")


write_reference()
write_envs()
