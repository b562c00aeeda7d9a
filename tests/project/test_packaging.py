"""What `pip install .` ships: every subpackage of bras_kit and every template."""

from __future__ import annotations

import re
import subprocess
import sys
import zipfile

import pytest
from paths import REPO

ROOT = REPO


def subpackages() -> set[str]:
    """Folders Python can import as bras_kit.X.Y: the learner's packages shipped as data inside
    the exercise track (``track/06-data-files/start/...``) are not: their path is no dotted name."""
    found = {p.parent.relative_to(ROOT).parts for p in (ROOT / "bras_kit").rglob("__init__.py")}
    return {".".join(parts) for parts in found if all(part.isidentifier() for part in parts)}


def test_every_subpackage_is_declared_in_pyproject():
    # the [tool.setuptools] packages list (read by hand: tomllib is Python 3.11+, we support 3.10)
    block = re.search(r"^packages = \[(.*?)\]", (ROOT / "pyproject.toml").read_text(), re.S | re.M)
    assert block is not None
    declared = set(re.findall(r'"([\w.]+)"', block.group(1)))
    assert subpackages() <= declared
    assert "bras_kit.templates" in declared


@pytest.mark.slow
def test_the_wheel_holds_every_module_and_template(tmp_path):
    subprocess.run([sys.executable, "-m", "pip", "wheel", "--no-deps", "--no-build-isolation", "-q",
                    "-w", str(tmp_path), str(ROOT)], check=True, capture_output=True)
    wheel = next(tmp_path.glob("bras_kit-*.whl"))
    names = set(zipfile.ZipFile(wheel).namelist())
    modules = {p.relative_to(ROOT).as_posix() for p in (ROOT / "bras_kit").rglob("*.py")}
    assert modules - names == set()
    templates = {p.relative_to(ROOT).as_posix() for p in (ROOT / "bras_kit" / "templates").rglob("*")
                 if p.is_file() and "__pycache__" not in p.parts}
    assert templates - names == set()
    assert "bras_kit/templates/robot/bras.urdf.xacro" in names
