"""bras_kit's modules import each other in one direction: no import circle at module level.

The graph is read from the source (``import`` and ``from ... import`` statements at a module's
top level, not those inside functions, which run later), so the test needs nothing imported.
"""

from __future__ import annotations

import ast
from pathlib import Path

import bras_kit

ROOT = Path(bras_kit.__file__).resolve().parent


def _module_name(path: Path) -> str:
    parts = list(path.relative_to(ROOT.parent).with_suffix("").parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


def _resolve(module: str, is_package: bool, node: ast.ImportFrom) -> list[str]:
    if node.level:
        base = module.split(".") if is_package else module.split(".")[:-1]
        base = base[: len(base) - (node.level - 1)]
        target = ".".join(base + ([node.module] if node.module else []))
    else:
        target = node.module or ""
    names = [f"{target}.{alias.name}" for alias in node.names]
    return [target, *names]


def module_graph() -> dict[str, set[str]]:
    """module -> the bras_kit modules it imports at its top level (``if TYPE_CHECKING`` left out)."""
    paths = {_module_name(p): p for p in ROOT.rglob("*.py")}
    graph: dict[str, set[str]] = {}
    for module, path in paths.items():
        tree = ast.parse(path.read_text(encoding="utf-8"))
        found: set[str] = set()
        for node in tree.body:
            if isinstance(node, ast.If) and "TYPE_CHECKING" in ast.unparse(node.test):
                continue
            statements = [node] if isinstance(node, (ast.Import, ast.ImportFrom)) else \
                [n for n in ast.walk(node) if isinstance(n, (ast.Import, ast.ImportFrom))] \
                if isinstance(node, (ast.If, ast.Try)) else []
            for statement in statements:
                if isinstance(statement, ast.Import):
                    targets = [alias.name for alias in statement.names]
                else:
                    targets = _resolve(module, path.name == "__init__.py", statement)
                found |= {t for t in targets if t in paths and t != module}
        graph[module] = found
    return graph


def find_cycle(graph: dict[str, set[str]]) -> list[str] | None:
    """One import circle as a list of modules (first == last), or None."""
    state: dict[str, int] = {}
    stack: list[str] = []

    def visit(node: str) -> list[str] | None:
        state[node] = 1
        stack.append(node)
        for nxt in sorted(graph.get(node, ())):
            if state.get(nxt) == 1:
                return stack[stack.index(nxt):] + [nxt]
            if nxt not in state:
                found = visit(nxt)
                if found:
                    return found
        stack.pop()
        state[node] = 2
        return None

    for node in sorted(graph):
        if node not in state:
            found = visit(node)
            if found:
                return found
    return None


def _is_package_parent(a: str, b: str) -> bool:
    """A package's __init__ importing its own submodule (and the submodule importing a sibling
    through the package) is how Python packages work, not a circle between features."""
    return b.startswith(a + ".") or a.startswith(b + ".")


def test_bras_kit_has_no_import_circle():
    graph = module_graph()
    # a package importing its submodules is not an edge of the feature graph
    pruned = {m: {t for t in targets if not _is_package_parent(m, t)} for m, targets in graph.items()}
    assert find_cycle(pruned) is None, " -> ".join(find_cycle(pruned) or [])


def test_the_detector_finds_a_circle():
    assert find_cycle({"a": {"b"}, "b": {"c"}, "c": {"a"}}) == ["a", "b", "c", "a"]
    assert find_cycle({"a": {"b"}, "b": set()}) is None


def test_errors_and_message_import_nothing_above_them():
    graph = module_graph()
    assert graph["bras_kit.core.message"] == set()
    assert graph["bras_kit.core.errors"] <= {"bras_kit.core.message"}


def test_contributor_tools_sit_above_the_runtime():
    """No module imports bras_kit.cli.catalogs (the catalogs' extraction and compilation), not even
    inside a function: it imports the runtime's i18n, never the other way round."""
    importers = []
    for path in ROOT.rglob("*.py"):
        module = _module_name(path)
        if module == "bras_kit.cli.catalogs":
            continue
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.ImportFrom):
                targets = _resolve(module, path.name == "__init__.py", node)
            elif isinstance(node, ast.Import):
                targets = [alias.name for alias in node.names]
            else:
                continue
            if "bras_kit.cli.catalogs" in targets:
                importers.append(f"{module}:{node.lineno}")
    assert importers == []
