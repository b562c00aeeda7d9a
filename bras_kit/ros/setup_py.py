"""setup.py read statically, as the package rules need it: the ``setup(...)`` call's data_files
and console_scripts as far as they can be read without running the file, and the names the call
uses that Python would not find (colcon build stops there with NameError)."""

from __future__ import annotations

import ast
from dataclasses import dataclass, field
from typing import Any

from .staticpy import Evaluator, known


@dataclass(frozen=True)
class DataEntry:
    """One (destination, [sources]) entry of setup.py's data_files, and its line."""

    destination: str  # "share/PKG/urdf"
    sources: list[str]  # relative to the package folder
    line: int


@dataclass(frozen=True)
class EntryPoint:
    """One console_scripts entry: ``name = module:function``, and its line."""

    name: str
    module: str
    function: str
    line: int


@dataclass
class Setup:
    """What the rules read of setup.py, statically: the name, data_files and console scripts."""

    name: Any  # str, or UNKNOWN
    name_line: int
    line: int  # the setup( call
    data_files: list[DataEntry] | None  # None when not all of it could be read
    data_files_line: int
    scripts: list[EntryPoint] | None  # None when console_scripts could not be read
    scripts_line: int  # entry_points=, else the setup( call
    undefined: list[tuple[str, int]] = field(default_factory=list)  # names setup( uses that Python will not find
    defined: dict[str, str] = field(default_factory=dict)  # module-level names: "module" (import x) or "value"


def module_names(tree: ast.Module) -> dict[str, str]:
    """Names a module defines at its top level: ``import os`` -> os: module; assignments, defs -> value."""
    out: dict[str, str] = {}
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            for alias in node.names:
                out[alias.asname or alias.name.split(".")[0]] = "module"
        elif isinstance(node, ast.ImportFrom):
            for alias in node.names:
                out[alias.asname or alias.name] = "value"
        elif isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
            out[node.name] = "value"
            out.update((a.arg, "value") for a in ast.walk(node.args) if isinstance(a, ast.arg))
        elif isinstance(node, ast.ClassDef):
            out[node.name] = "value"
        elif isinstance(node, ast.Name) and isinstance(node.ctx, ast.Store):
            out.setdefault(node.id, "value")
    return out


def undefined_names(tree: ast.Module, call: ast.Call) -> list[tuple[str, int]]:
    """Names read by the ``setup(...)`` call that neither the module nor Python's builtins define:
    running setup.py (colcon build) stops there with NameError."""
    import builtins

    defined = module_names(tree)
    seen: dict[str, int] = {}
    for node in ast.walk(call):
        if isinstance(node, ast.Name) and isinstance(node.ctx, ast.Load) and node.id not in defined \
                and not hasattr(builtins, node.id):
            seen.setdefault(node.id, node.lineno)
    return sorted(seen.items(), key=lambda item: item[1])


def read_data_files(evaluator: Evaluator, node: ast.expr | None) -> list[DataEntry] | None:
    if node is None:
        return []
    if not isinstance(node, (ast.List, ast.Tuple)):
        value = evaluator.value(node)
        return _entries(value, node.lineno) if known(value) else None
    out = []
    for element in node.elts:
        value = evaluator.value(element)
        entries = _entries([value], element.lineno) if known(value) else None
        if entries is None:
            return None
        out += entries
    return out


def _entries(value: Any, line: int) -> list[DataEntry] | None:
    if not isinstance(value, (list, tuple)):
        return None
    out = []
    for item in value:
        if not (isinstance(item, (list, tuple)) and len(item) == 2 and isinstance(item[0], str)
                and isinstance(item[1], (list, tuple)) and all(isinstance(s, str) for s in item[1])):
            return None
        out.append(DataEntry(item[0], list(item[1]), line))
    return out


def read_console_scripts(evaluator: Evaluator, node: ast.expr | None) -> list[EntryPoint] | None:
    if node is None:
        return []
    if isinstance(node, ast.Dict):
        for key, value in zip(node.keys, node.values):
            if key is not None and evaluator.value(key) == "console_scripts":
                return _scripts(evaluator, value)
        return [] if all(k is not None and known(evaluator.value(k)) for k in node.keys) else None
    return None


def _scripts(evaluator: Evaluator, node: ast.expr) -> list[EntryPoint] | None:
    elements = node.elts if isinstance(node, (ast.List, ast.Tuple)) else None
    if elements is None:
        return None
    out = []
    for element in elements:
        text = evaluator.value(element)
        if not isinstance(text, str):
            return None
        name, _, target = text.partition("=")
        module, _, function = target.strip().partition(":")
        out.append(EntryPoint(name.strip(), module.strip(), function.strip(), element.lineno))
    return out
