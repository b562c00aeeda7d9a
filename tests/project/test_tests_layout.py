"""The tests mirror bras_kit's layers (docs/design/architecture.md, "Tests"): each test file sits
in a folder named after a package of bras_kit (or project/, for the whole project's checks, or
lessons/, for the repository's lessons and the first hour they walk through), and
a test module imports helpers, never another test module."""

from __future__ import annotations

import ast

from paths import REPO, TESTS

PACKAGES = {p.name for p in (REPO / "bras_kit").iterdir() if (p / "__init__.py").is_file()}


def test_every_test_file_sits_in_the_folder_of_a_layer():
    misplaced = [p.relative_to(TESTS).as_posix() for p in TESTS.rglob("test_*.py")
                 if "data" not in p.relative_to(TESTS).parts
                 and (len(p.relative_to(TESTS).parts) != 2 or p.parent.name not in PACKAGES | {"project", "lessons"})]
    assert misplaced == []


def test_no_test_module_imports_another():
    tests = {p.stem for p in TESTS.rglob("test_*.py") if "data" not in p.relative_to(TESTS).parts}
    found = []
    for path in TESTS.rglob("*.py"):
        if "data" in path.relative_to(TESTS).parts:
            continue
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            names = [a.name for a in node.names] if isinstance(node, ast.Import) else \
                [node.module or ""] if isinstance(node, ast.ImportFrom) else []
            found += [f"{path.relative_to(TESTS)}:{node.lineno} {name}" for name in names
                      if name.split(".")[-1] in tests or name.startswith("tests.")]
    assert found == []


def test_the_helpers_of_the_tests_are_found_from_every_folder():
    """pytest puts tests/ on sys.path (pyproject's pythonpath): a helper module imports by name."""
    import pages

    assert TESTS / "pages.py" == type(TESTS)(pages.__file__).resolve()
