"""Griffe extension for the docs build: Sphinx roles to cross-references, runtime docstrings.

Loaded by mkdocstrings (``mkdocs.yml``: ``handlers.python.options.extensions``); it changes only
what the site shows, never the package.

* **Roles.** The docstrings use Sphinx roles (``:func:`x```, ``:class:`~a.b.C```, ``:mod:``,
  ``:meth:``, ``:attr:``, ``:data:``, ``:obj:``, ``:exc:``, ``:const:``), which Markdown would
  print literally. Each becomes an *optional* mkdocs-autorefs cross-reference: a link when the
  target is rendered somewhere in the site, plain code otherwise (no warning: private helpers
  and third-party names are not documented here). Relative names (``:meth:`Simulator.run```)
  are resolved in the scope of the object whose docstring holds them; a leading ``~`` shows
  only the last component, as in Sphinx.
* **Runtime docstrings.** A class whose docstring is completed at import time (the ship envs:
  ``@env_docstring`` fills ``{ship_observations}``/``{time_limit}`` and appends the Arguments
  and Version History sections; the vector envs assign ``__doc__``) is documented with the
  docstring Python actually sees, read from the imported class.
* **Units in brackets.** ``L [1 − C_P] [m]`` is Markdown's reference-link syntax ``[text] [id]``
  (autorefs would warn about the missing target ``m``): outside code spans the ``[`` that follows
  ``] `` is escaped.
* **reST leftovers.** reST *simple tables* (``====  ====`` borders) become Markdown tables, and a
  NumPy-style ``Arguments`` section (RollOneDOFEnv: the keyword arguments passed on to the task)
  is read as ``Other Parameters``, the NumPy section for keyword arguments, so that it renders as
  a parameter table; a paragraph ending in reST's literal-block marker ``::`` ends in ``:``
  (the indented block after it is a Markdown code block already).
"""

from __future__ import annotations

import html
import importlib
import inspect
import re
from typing import Any

import griffe

_ROLE = re.compile(
    r":(?:py:)?(?P<role>func|class|meth|mod|attr|data|obj|exc|const):`(?P<target>[^`]+)`"
)
_MARKER = re.compile(r"\{(ship_observations|time_limit)\}")
_ARGUMENTS_SECTION = re.compile(r"^(?P<indent>[ \t]*)Arguments\n(?P=indent)-{9,}[ \t]*$", re.M)
_LITERAL_MARKER = re.compile(r"(?<=[^\s:])::[ \t]*$", re.M)
_BORDER = re.compile(r"^(?P<indent>[ \t]*)=+(?: +=+)+[ \t]*$")
_CODE_SPAN = re.compile(r"(`+)(?:(?!\1).)+?\1", flags=re.DOTALL)


def _walk(obj: griffe.Object) -> Any:
    yield obj
    for member in obj.members.values():
        if member.is_alias:
            continue
        yield from _walk(member)


class SphinxRolesAndRuntimeDocstrings(griffe.Extension):
    """See the module docstring."""

    def on_package(self, *, pkg: griffe.Module, loader: griffe.GriffeLoader, **kwargs: Any) -> None:
        if pkg.name != "ship_gym":
            return
        self._collection = loader.modules_collection
        for obj in _walk(pkg):
            if obj.is_class:
                self._runtime_docstring(obj, loader)
            if obj.docstring is not None:
                obj.docstring.value = self._convert(obj.docstring.value, obj)

    # --- runtime docstrings -------------------------------------------------------------------
    def _runtime_docstring(self, cls: griffe.Object, loader: griffe.GriffeLoader) -> None:
        assigned = "__doc__" in cls.members
        static = cls.docstring.value if cls.docstring is not None else ""
        if not assigned and not _MARKER.search(static):
            return
        try:
            runtime = getattr(importlib.import_module(cls.module.path), cls.name).__doc__
        except Exception:  # keep the static docstring if the import fails
            return
        if not runtime:
            return
        text = inspect.cleandoc(runtime)
        if assigned:
            del cls.members["__doc__"]
        if cls.docstring is not None:
            cls.docstring.value = text
        else:
            cls.docstring = griffe.Docstring(
                text,
                lineno=cls.lineno,
                endlineno=cls.lineno,
                parent=cls,
                parser=loader.docstring_parser,
                parser_options=loader.docstring_options,
            )

    # --- roles --------------------------------------------------------------------------------
    def _identifier(self, target: str, scope: griffe.Object) -> str:
        target = target.strip("()").lstrip(".")
        first, _, rest = target.partition(".")
        if not target.startswith("ship_gym"):
            try:
                resolved = scope.resolve(first)
            except Exception:  # unresolvable names stay as written
                resolved = None
            if resolved:
                target = f"{resolved}.{rest}" if rest else resolved
        # follow re-exports (``ship_gym.hull.load_hull``) to the documented object
        for _ in range(5):
            try:
                found = self._collection[target]
            except Exception:  # not a loaded object
                break
            if not found.is_alias:
                break
            target = found.target_path
        return target

    def _convert(self, text: str, scope: griffe.Object) -> str:
        text = _ARGUMENTS_SECTION.sub(_other_parameters, text)
        text = _rst_simple_tables(text)
        text = _LITERAL_MARKER.sub(":", text)
        text = _escape_bracket_pairs(text)
        if ":`" not in text:
            return text

        def replace(m: re.Match[str]) -> str:
            raw = m["target"].strip()
            if "<" in raw and raw.endswith(">"):  # :func:`title <target>`
                title, _, raw = raw[:-1].partition("<")
                title = title.strip()
            else:
                title = raw.split(".")[-1] if raw.startswith("~") else raw
            raw = raw.lstrip("~")
            identifier = self._identifier(raw, scope)
            return (
                f'<autoref identifier="{html.escape(identifier)}" optional>'
                f"<code>{html.escape(title.lstrip('~'))}</code></autoref>"
            )

        return _ROLE.sub(replace, text)


def _escape_bracket_pairs(text: str) -> str:
    """Escape the ``[`` of ``] [`` outside inline code (not a reference link: two brackets)."""
    if "] [" not in text:
        return text
    out, last = [], 0
    for m in _CODE_SPAN.finditer(text):
        out.append(text[last : m.start()].replace("] [", "] \\["))
        out.append(m.group(0))
        last = m.end()
    out.append(text[last:].replace("] [", "] \\["))
    return "".join(out)


def _other_parameters(m: re.Match[str]) -> str:
    indent = m["indent"]
    return f"{indent}Other Parameters\n{indent}----------------"


def _rst_simple_tables(text: str) -> str:
    """reST simple tables (header between the first two borders) to Markdown tables."""
    if "==" not in text:
        return text
    lines = text.split("\n")
    out: list[str] = []
    i = 0
    while i < len(lines):
        m = _BORDER.match(lines[i])
        if not m:
            out.append(lines[i])
            i += 1
            continue
        # find the borders of this table: top, under the header, bottom
        borders = [i]
        j = i + 1
        while j < len(lines) and len(borders) < 3:
            if lines[j].strip() == "":
                break
            if _BORDER.match(lines[j]):
                borders.append(j)
            j += 1
        if len(borders) < 3:
            out.append(lines[i])
            i += 1
            continue
        top, mid, bottom = borders
        indent = m["indent"]
        border = lines[top][len(indent) :]
        spans = [(s.start(), s.end()) for s in re.finditer(r"=+", border)]

        header = _rows(lines[top + 1 : mid], indent, spans)
        body = _rows(lines[mid + 1 : bottom], indent, spans)
        md = [" | ".join(h.replace("|", "\\|") for h in header[0])]
        md.append(" | ".join("---" for _ in spans))
        md += [" | ".join(c.replace("|", "\\|") for c in row) for row in body]
        if out and out[-1].strip():
            out.append("")
        out += [f"{indent}| {line} |" for line in md]
        i = bottom + 1
    return "\n".join(out)


def _cells(line: str, indent: str, spans: list[tuple[int, int]]) -> list[str]:
    body = line[len(indent) :]
    starts = [a for a, _ in spans] + [len(body) + 1]
    return [body[starts[k] : starts[k + 1]].strip() for k in range(len(spans))]


def _rows(block: list[str], indent: str, spans: list[tuple[int, int]]) -> list[list[str]]:
    """Table rows; a line with an empty first column continues the row above (reST rule)."""
    result: list[list[str]] = []
    for line in block:
        c = _cells(line, indent, spans)
        if result and c[0] == "":
            result[-1] = [f"{a} {b}".strip() for a, b in zip(result[-1], c, strict=True)]
        else:
            result.append(c)
    return result
