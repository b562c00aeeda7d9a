"""Shared fixtures. Feature test modules keep their own fixtures; add here only what several share."""

from __future__ import annotations

import os
import shutil
import tempfile

import pytest

os.environ.setdefault("PYOPENGL_PLATFORM", "egl")
for _variable in ("BRAS_KIT_LANG", "LC_ALL", "LC_MESSAGES", "LANGUAGE"):
    os.environ.pop(_variable, None)  # English unless a test asks for French
os.environ["LANG"] = "C.UTF-8"  # English, and UTF-8 text in the commands the tests run
# the bus between bras-kit processes lives in $XDG_RUNTIME_DIR/bras-kit: each test session gets its
# own, so two sessions on one machine (CI runs two Pythons at once) never meet on it
_RUNTIME = tempfile.mkdtemp(prefix="bras-kit-tests-runtime-")
os.environ["XDG_RUNTIME_DIR"] = _RUNTIME
# each lesson notebook runs once per session: the site's build (tests/project/test_docs.py, through
# docs/hooks/lessons.py) and tests/lessons/test_lessons.py share the runs, kept here by the notebook's digest
_LESSONS_RUN = tempfile.mkdtemp(prefix="bras-kit-tests-lessons-")
os.environ["BRAS_KIT_LESSONS_EXECUTED"] = _LESSONS_RUN


def pytest_sessionfinish(session, exitstatus):  # noqa: ARG001 - pytest's hook signature
    shutil.rmtree(_RUNTIME, ignore_errors=True)
    shutil.rmtree(_LESSONS_RUN, ignore_errors=True)


@pytest.fixture(autouse=True)
def _english_by_default():
    """A command run with --lang fr sets the process's language: each test starts from the default."""
    from bras_kit.core import i18n

    i18n._language.clear()
    yield
    i18n._language.clear()


@pytest.fixture(scope="session")
def tutorial_robot():
    from bras_kit.model.authoring import arm

    return arm()


@pytest.fixture(scope="session")
def wrist_robot():
    from bras_kit.model.authoring import arm

    return arm(wrist=True)


@pytest.fixture(scope="session")
def tutorial_tree(tutorial_robot):
    from bras_kit.kinematics.frames import tf_tree

    return tf_tree(tutorial_robot)


@pytest.fixture
def run_cli(capsys):
    """Run the CLI in-process: returns (exit code, stdout, stderr)."""
    from bras_kit.cli import main

    def runner(*argv: str):
        try:
            code = main(list(argv))
        except SystemExit as exc:  # argparse usage errors
            code = exc.code if isinstance(exc.code, int) else 2
        out, err = capsys.readouterr()
        return code, out, err

    return runner


# ---------------------------------------------------------------- what several test files share

@pytest.fixture(scope="session")
def chromium() -> str:
    """Debian's chromium, which the page tests drive (skipped without it, failed in CI: tests/system.py)."""
    import system
    from pages import CHROMIUM

    return system.file(CHROMIUM, "chromium")


@pytest.fixture(scope="module")
def browser(chromium):
    """One headless chromium per test module, WebGL on the CPU (SwiftShader), driven by Playwright."""
    from pages import ARGS
    from playwright.sync_api import sync_playwright

    with sync_playwright() as playwright:
        launched = playwright.chromium.launch(executable_path=chromium, headless=True, args=ARGS)
        yield launched
        launched.close()


@pytest.fixture()
def arm_file(tmp_path):
    """The tutorial arm's URDF as `bras-kit urdf -o` writes it, in a child process."""
    import subprocess
    import sys

    path = tmp_path / "bras.urdf"
    done = subprocess.run([sys.executable, "-m", "bras_kit", "urdf", "-o", str(path)], capture_output=True)
    assert done.returncode == 0, done.stderr
    return path


@pytest.fixture()
def viewer(arm_file):
    """`bras-kit view` of arm_file, serving on a free port of 127.0.0.1, with the tutorial motion."""
    from pages import free_port

    from bras_kit.view import Source, Viewer

    with Viewer(Source(path=str(arm_file)), port=free_port(), motion_specs=["tutorial"]) as running:
        yield running


@pytest.fixture()
def private_runtime(monkeypatch):
    """A runtime folder of this test's own, short (a Unix socket's path holds at most 107 bytes)."""
    from pathlib import Path

    runtime = Path(tempfile.mkdtemp(prefix="bk-", dir="/tmp"))
    runtime.chmod(0o700)
    monkeypatch.setenv("XDG_RUNTIME_DIR", str(runtime))
    monkeypatch.delenv("ROS_DOMAIN_ID", raising=False)
    yield runtime
    shutil.rmtree(runtime, ignore_errors=True)


@pytest.fixture(scope="session")
def real_rclpy() -> str:
    """An interpreter with the real rclpy of Jazzy (tests/realros.py): made once, then reused. Its
    processes run in a loopback-only network namespace (realros.in_loopback_namespace)."""
    import realros

    return realros.oracle_python()


# ---------------------------------------------------------------- markers by cost

def pytest_collection_modifyitems(config, items):  # noqa: ARG001 - pytest's hook signature
    """Each test gets the markers of its cost from the fixtures it uses and the code it runs (tests/costs.py)."""
    from costs import COST_OF_FIXTURES, COST_OF_NAMES, names_reached

    for item in items:
        fixtures = set(getattr(item, "fixturenames", ()))
        marks = {COST_OF_FIXTURES[name] for name in fixtures if name in COST_OF_FIXTURES}
        functions = [getattr(item, "function", None)]
        info = getattr(item, "_fixtureinfo", None)
        if info is not None:
            functions += [definition.func for definitions in info.name2fixturedefs.values()
                          for definition in definitions]
        seen: set = set()
        reached = set().union(*(names_reached(function, seen=seen) for function in functions if function))
        marks |= {cost for cost, names in COST_OF_NAMES.items() if names & reached}
        for mark in sorted(marks - {mark.name for mark in item.iter_markers()}):
            item.add_marker(mark)
