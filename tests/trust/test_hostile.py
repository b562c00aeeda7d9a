"""Hostile xacro files (tests/data/hostile/, each with its expected verdict in MANIFEST.tsv).

Each file is run through ``bras-kit xacro`` and ``bras-kit validate`` in a real process, from
a folder holding a canary path the code-running payloads try to create. Every one must end
quickly with a clean message and exit code 2, print no traceback, and leave no canary.
"""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
import time

import pytest
from paths import TESTS

HOSTILE = TESTS / "data" / "hostile"
CANARY = "bras_kit_canary"


def _manifest() -> list[tuple[str, int, str]]:
    rows = []
    for line in (HOSTILE / "MANIFEST.tsv").read_text().splitlines():
        if line.strip() and not line.startswith("#"):
            name, code, words = line.split("\t")
            rows.append((name, int(code), words))
    return rows


ROWS = _manifest()


def test_every_hostile_file_is_in_the_manifest():
    listed = {name for name, _, _ in ROWS}
    assert listed == {p.name for p in HOSTILE.glob("*.xacro")}


@pytest.fixture()
def workdir(tmp_path):
    for item in HOSTILE.iterdir():
        shutil.copy(item, tmp_path / item.name)
    os.mkfifo(tmp_path / "fifo.xacro")
    return tmp_path


@pytest.mark.slow
@pytest.mark.parametrize("command", ["xacro", "validate"])
@pytest.mark.parametrize("name,code,words", ROWS, ids=[r[0] for r in ROWS])
def test_hostile_file_is_refused_cleanly(workdir, command, name, code, words):
    start = time.monotonic()
    result = subprocess.run([sys.executable, "-m", "bras_kit", command, name], cwd=workdir,
                            capture_output=True, text=True, timeout=120, stdin=subprocess.DEVNULL)
    elapsed = time.monotonic() - start
    output = result.stdout + result.stderr
    assert "Traceback" not in output, output
    assert not (workdir / CANARY).exists(), "a payload ran code"
    assert re.search(words, output), output
    # validate reports an unreadable file as a finding (exit 1) or an error (exit 2)
    assert result.returncode == (code if command == "xacro" else result.returncode) and result.returncode in (1, 2)
    assert elapsed < 60, f"{name} took {elapsed:.1f} s"


def test_the_escape_payload_really_runs_code_in_plain_xacro(workdir):
    """The fixture is not a straw man: the real xacro, unguarded, runs it and makes the canary."""
    code = "import sys, xacro\ntry:\n    xacro.process_file(sys.argv[1])\nexcept Exception:\n    pass\n"
    subprocess.run([sys.executable, "-c", code, "getattribute_escape.xacro"], cwd=workdir,
                   capture_output=True, timeout=120)
    assert (workdir / CANARY).exists(), "plain xacro now refuses this payload: pick a new one"
