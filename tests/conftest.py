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
# each lesson notebook runs once per session: the site's build (tests/test_docs.py, through
# docs/hooks/lessons.py) and tests/test_lessons.py share the runs, kept here by the notebook's digest
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
