"""Every page that installs bras-kit installs it as the README does: with the lock (issue 52, item 7).

The oracle is the README's own install line, ``pip install -c constraints.txt -e ".[dev]"``: any
``pip install`` of this repository (``-e .`` with or without an extra) in the README, the docs
site or the lessons' README carries ``-c constraints.txt``, so the versions a learner gets are the
ones the project is tested with. ``.gitignore`` keeps the virtual environment the pages create
(``python3 -m venv .venv``) out of git.
"""

from __future__ import annotations

import re
import subprocess
from pathlib import Path

import pytest
from paths import REPO

ROOT = REPO
PAGES = sorted({ROOT / "README.md", ROOT / "lessons" / "README.md", *(ROOT / "docs").rglob("*.md")})
# an install of the repository itself: pip install [options] -e . or -e ".[extra]"
_OWN_INSTALL = re.compile(r"pip install\b[^\n`|]*?-e\s+[\"']?\.(\[[\w,]+\])?[\"']?(?=[\s`|]|$)")


def own_installs(text: str) -> list[str]:
    return [m.group() for m in _OWN_INSTALL.finditer(text)]


def test_the_readme_line_is_what_the_pages_are_held_to():
    readme = own_installs((ROOT / "README.md").read_text(encoding="utf-8"))
    assert 'pip install -c constraints.txt -e ".[dev]"' in readme
    assert own_installs('run `pip install -e ".[lessons]"` then') == ['pip install -e ".[lessons]"']
    assert own_installs("pip install mujoco") == own_installs("pip install 'bras-kit[cluster]'") == []


@pytest.mark.parametrize("page", PAGES, ids=lambda p: str(p.relative_to(ROOT)))
def test_a_page_installs_bras_kit_with_the_constraints(page: Path):
    lines = [line for line in own_installs(page.read_text(encoding="utf-8")) if "-c constraints.txt" not in line]
    assert lines == [], f"{page.relative_to(ROOT)}: install with -c constraints.txt, as the README does"


def test_the_virtual_environment_of_the_pages_is_ignored(tmp_path: Path):
    done = subprocess.run(["git", "check-ignore", "-q", "--no-index", ".venv/bin/python"], cwd=ROOT)
    assert done.returncode == 0, ".venv/ is not in .gitignore"
