"""What a test costs, as its markers say (browser, real_ros, notebook, subprocess): read from the
fixtures it uses and the names its code reaches. tests/conftest.py's collection hook applies it."""

from __future__ import annotations

import inspect
import types
from pathlib import Path

# a test that uses one of these fixtures (directly or through another fixture) gets the marker; the
# tests that run a lesson notebook carry `notebook` by hand (tests/lessons/test_lessons.py, tests/project/test_docs.py)
COST_OF_FIXTURES = {
    "chromium": "browser",  # the browser fixture asks for it; so do the tests that start chromium themselves
    "real_rclpy": "real_ros",
}
# a test whose code, or the code of a fixture it uses, reaches one of these names has that cost (the
# helpers of the test module and of tests/*.py it calls are followed, a few calls deep)
COST_OF_NAMES = {
    "subprocess": frozenset({"subprocess", "Popen", "multiprocessing", "fork"}),  # a child process
    "real_ros": frozenset({"oracle_python", "in_loopback_namespace", "shell_in_loopback_namespace", "run_isolated"}),
}
COSTS = ("browser", "real_ros", "notebook", "subprocess")


def names_reached(function, depth: int = 4, seen: set | None = None) -> set[str]:
    """The global and attribute names the code of ``function`` reads, with those of the tests'
    own helpers it calls (functions defined under tests/), ``depth`` calls deep."""
    seen = set() if seen is None else seen
    function = inspect.unwrap(function)
    code = getattr(function, "__code__", None)
    if code is None or code in seen:
        return set()
    seen.add(code)
    names: set[str] = set()
    stack = [code]
    while stack:
        current = stack.pop()
        names.update(current.co_names)
        stack.extend(const for const in current.co_consts if isinstance(const, types.CodeType))
    if depth > 0:
        here = Path(__file__).resolve().parent
        scope = getattr(function, "__globals__", {})
        for name in list(names):
            helper = scope.get(name)
            if isinstance(helper, types.FunctionType) and Path(helper.__code__.co_filename).resolve().is_relative_to(here):
                names |= names_reached(helper, depth - 1, seen)
    return names
