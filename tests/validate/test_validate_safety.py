"""Hostile XML: external entities and entity bombs are refused before anything is read or expanded."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

from paths import TESTS

from bras_kit.validate import validate_path

DATA = TESTS / "data" / "urdf" / "broken"
MARKER = "SECRET-MARKER-7f3a9"  # the content of broken/secret.txt, which xxe.urdf points at


def _texts(findings) -> str:
    return " ".join(f"{f.text('en')} {f.hint_text('en')}" for f in findings)


def test_external_entity_is_refused_and_its_file_not_shown():
    findings = validate_path(str(DATA / "xxe.urdf"))
    assert [(f.code, f.line) for f in findings] == [("BK101", 3)]  # the <!ENTITY> line (a bare DOCTYPE is harmless)
    assert MARKER not in _texts(findings)


def test_billion_laughs_is_refused():
    findings = validate_path(str(DATA / "billion_laughs.urdf"))
    assert [(f.code, f.line, f.text("en")) for f in findings] == [
        ("BK101", 3, "refused: the file declares an entity (<!ENTITY ...>)")]


def _validate_in_subprocess(path: Path) -> subprocess.CompletedProcess:
    # A separate process with a timeout: if the file were opened or the entities expanded,
    # the call would block (FIFO) or exhaust memory instead of returning.
    return subprocess.run([sys.executable, "-m", "bras_kit", "validate", str(path)],
                          capture_output=True, text=True, timeout=120)


def test_external_entity_target_is_never_opened(tmp_path):
    """The entity points at a named pipe: opening it for reading would block until a writer came."""
    fifo = tmp_path / "pipe"
    os.mkfifo(fifo)
    robot = tmp_path / "xxe_pipe.urdf"
    robot.write_text(f'<?xml version="1.0"?>\n<!DOCTYPE robot [<!ENTITY x SYSTEM "file://{fifo}">]>\n'
                     '<robot name="&x;"><link name="base"/></robot>\n', encoding="utf-8")
    done = _validate_in_subprocess(robot)
    assert done.returncode == 2
    assert f"{robot}:2: BK101 error refused: the file declares an entity" in done.stdout


def test_billion_laughs_returns_in_a_subprocess():
    done = _validate_in_subprocess(DATA / "billion_laughs.urdf")
    assert done.returncode == 2
    assert "BK101" in done.stdout and "Traceback" not in done.stderr


def test_entity_in_a_xacro_include_is_refused(tmp_path):
    (tmp_path / "piece.xacro").write_text(
        '<?xml version="1.0"?>\n<!DOCTYPE robot [<!ENTITY x SYSTEM "secret.txt">]>\n'
        '<robot xmlns:xacro="http://www.ros.org/wiki/xacro"><link name="&x;"/></robot>\n', encoding="utf-8")
    (tmp_path / "secret.txt").write_text(MARKER)
    main = tmp_path / "bras.urdf.xacro"
    main.write_text('<robot name="bras" xmlns:xacro="http://www.ros.org/wiki/xacro">'
                    '<xacro:include filename="piece.xacro"/></robot>', encoding="utf-8")
    findings = validate_path(str(main))
    assert [f.code for f in findings] == ["BK101"]
    assert findings[0].text("en") == f"refused: the file declares an entity (<!ENTITY ...>) ({tmp_path / 'piece.xacro'}:2)"
    assert MARKER not in _texts(findings)


def test_xacro_expression_running_code_is_refused(tmp_path):
    main = tmp_path / "bras.urdf.xacro"
    main.write_text('<robot name="bras" xmlns:xacro="http://www.ros.org/wiki/xacro">'
                    '<link name="${().__class__.__base__.__subclasses__()}"/></robot>', encoding="utf-8")
    findings = validate_path(str(main))
    assert [(f.code, f.hint_text("en")) for f in findings] == [
        ("BK102", "xacro expressions may only compute numbers and strings from properties")]
