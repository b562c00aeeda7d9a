"""The terminal's gate (bras_kit.trust.inert, docs/security.md "Text for a terminal"): every byte bras-kit
writes to stdout and stderr, by whatever path, shows a control character instead of obeying it;
bras-kit's own colours pass only as Styled.

Oracles: the Unicode character database (Python's unicodedata: the general categories of the
characters a terminal acts on or that hide or reorder text), over every code point and over
generated text; the bytes the ``bras-kit`` process (and the node it runs) write to their pipes;
Python's own ``ast`` over bras-kit's source for the ways around the gate."""

from __future__ import annotations

import ast
import io
import json
import logging
import os
import subprocess
import sys
import unicodedata
from contextlib import redirect_stderr, redirect_stdout
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from paths import REPO

from bras_kit.trust.inert import (
    CLEAR_SCREEN,
    Styled,
    TerminalWriter,
    emit,
    for_terminal,
    gated_streams,
    join,
    styled,
    write_document,
)

ROOT = REPO
# the characters a terminal must never receive raw: controls (Cc), format characters (Cf: bidi
# controls, zero-width and invisible ones), lone surrogates (Cs), line and paragraph separators;
# kept: line feed, tab, and the zero-width (non-)joiner that Persian, Indic scripts and emoji need
OBEYED_CATEGORIES = {"Cc", "Cf", "Cs", "Zl", "Zp"}
KEPT = {"\n", "\t", "\u200c", "\u200d"}


def _raw(text: str) -> list[str]:
    return [c for c in text if unicodedata.category(c) in OBEYED_CATEGORIES and c not in KEPT]


# what a stranger would write: escape sequences whole (CSI, OSC title, DCS, APC, PM, SOS, their
# 8-bit forms), every bidi control, invisible format characters, C0 and C1, and ordinary text
SEQUENCES = ["\x1b]0;pwned-title\x07", "\x1b]8;;http://evil/\x1b\\", "\x1b[2J", "\x1b[31m", "\x1bP1$r\x1b\\",
             "\x1b_apc\x1b\\", "\x1b^pm\x1b\\", "\x1bXsos\x1b\\", "\x9b2J", "\x9d0;t\x9c", "\x90q\x9c", "\r", "\b"]
CONTROLS = [chr(c) for c in (*range(0x20), 0x7f, *range(0x80, 0xa0), 0x061c, 0x200b, 0x200e, 0x200f,
                             *range(0x202a, 0x202f), 0x2060, *range(0x2066, 0x206a), 0xfeff, 0x00ad,
                             0x2028, 0x2029, 0xe0041, 0xe0001)]
hostile = st.lists(st.one_of(st.sampled_from(SEQUENCES), st.sampled_from(CONTROLS),
                             st.text(st.characters(blacklist_categories=("Cs",)), max_size=4)),
                   min_size=1, max_size=12).map("".join)


def test_the_gate_covers_exactly_the_characters_the_oracle_names():
    """Over every code point: each one of the obeyed categories comes out escaped; each other
    one (but those this Python's Unicode has not assigned yet) comes out as itself."""
    for code in range(0x110000):
        c = chr(code)
        shown = for_terminal(c)
        if unicodedata.category(c) in OBEYED_CATEGORIES and c not in KEPT:
            assert shown != c and _raw(shown) == [], hex(code)
        elif unicodedata.category(c) != "Cn":
            assert shown == c, hex(code)


@pytest.mark.parametrize(("text", "shown"), [
    ("\x7f", "\\u007f"), ("\x85", "\\u0085"), ("\u200b", "\\u200b"), ("\U000e0041", "\\udb40\\udc41"),
    ("\udc9b", "\\udc9b"), ("\u2028", "\\u2028"), ("a\u200db", "a\u200db")])
def test_an_escape_beyond_ascii_is_also_a_json_escape(text, shown):
    """A JSON report (json.dumps, ensure_ascii=False) passes the gate too: what it escapes must
    read back as the same string."""
    assert for_terminal(text) == shown
    assert json.loads(f'"{shown}"') == text


@settings(max_examples=200, deadline=None)
@given(hostile)
def test_a_json_report_through_the_gate_reads_back_the_same(text):
    dumped = json.dumps({"name": text}, ensure_ascii=False)
    shown = for_terminal(dumped)
    assert _raw(shown) == []
    assert json.loads(shown) == {"name": text}


@settings(max_examples=150, deadline=None)
@given(hostile)
def test_every_way_a_process_writes_text_passes_the_gate(text):
    """print, write, writelines, a logging handler made inside, argparse's error (which quotes the
    arguments), a warning as the CLI shows it: to stdout and stderr."""
    import argparse
    import warnings

    from bras_kit.cli import _show_warning

    out, err = io.StringIO(), io.StringIO()
    with redirect_stdout(out), redirect_stderr(err), gated_streams():
        print(text)
        sys.stdout.write(text)
        sys.stdout.writelines([text, "\n"])
        print(text, file=sys.stderr)
        handler = logging.StreamHandler()  # its stream: sys.stderr, the gate
        handler.emit(logging.LogRecord("learner", logging.WARNING, "node.py", 1, text, None, None))
        with pytest.raises(SystemExit):
            argparse.ArgumentParser(prog="bras-kit").error(text)
        with warnings.catch_warnings():
            warnings.simplefilter("always")
            warnings.showwarning = _show_warning
            # a warning of bras-kit's own category (defined in bras_kit) is shown, quoting its text
            own = type("OwnWarning", (UserWarning,), {"__module__": "bras_kit.example"})
            warnings.warn(text, own, stacklevel=1)
    shown = out.getvalue() + err.getvalue()
    assert _raw(shown) == [], shown
    assert for_terminal(text) in out.getvalue() and for_terminal(text) in err.getvalue()


def test_the_streams_are_given_back_and_gated_once():
    saved = sys.stdout, sys.stderr
    with gated_streams():
        first = sys.stdout
        assert isinstance(first, TerminalWriter)
        with gated_streams():
            assert sys.stdout is first  # no second gate: escapes are not escaped again
    assert (sys.stdout, sys.stderr) == saved


def test_bras_kits_own_styles_pass_only_as_styled():
    sink = io.StringIO()
    gate = TerminalWriter(sink)
    line = styled("BK101", "bold") + " \x1b]0;joint\x07 " + styled("error", "red")
    emit(gate, CLEAR_SCREEN, line)
    assert sink.getvalue() == "\x1b[H\x1b[2J\x1b[3J\x1b[1mBK101\x1b[0m \\x1b]0;joint\\x07 \x1b[31merror\x1b[0m\n"
    # a style never travels inside a string: an f-string or print of a Styled is its plain text
    assert f"{line}" == str(line) == "BK101 \x1b]0;joint\x07 error"
    sink.seek(0), sink.truncate()
    print(line, file=gate)
    assert sink.getvalue() == "BK101 \\x1b]0;joint\\x07 error\n"
    # a learner's text styled by bras-kit is still inert inside the style
    sink.seek(0), sink.truncate()
    emit(gate, styled("\x1b[2J", "green"), end="")
    assert sink.getvalue() == "\x1b[32m\\x1b[2J\x1b[0m"
    with pytest.raises(TypeError):
        "\n".join([line])  # type: ignore[list-item]  # str.join refuses it: the wrong path fails loudly
    assert join("\n", ["a", line]) == Styled((("a", None), ("\n", None))) + line
    with pytest.raises(ValueError):
        styled("x", "\x1b[5m")  # only bras-kit's named styles


def test_a_document_goes_to_a_pipe_byte_for_byte_and_to_a_terminal_through_the_gate():
    class Tty(io.StringIO):
        def isatty(self) -> bool:
            return True

    text = "<robot name='\u202earm'/>\n"
    pipe, tty = io.StringIO(), Tty()
    write_document(TerminalWriter(pipe), text)  # type: ignore[arg-type]
    write_document(TerminalWriter(tty), text)  # type: ignore[arg-type]
    assert pipe.getvalue() == text
    assert tty.getvalue() == "<robot name='\\u202earm'/>\n"


# --- through the command line, in this process ------------------------------------------------

def _urdf(name: str) -> str:
    from xml.sax.saxutils import quoteattr

    return (f"<robot name={quoteattr(name)}><link name='base'/><link name={quoteattr(name)}/>"
            f"<joint name={quoteattr(name + 'j')} type='revolute'><parent link='base'/>"
            f"<child link={quoteattr(name + 'missing')}/><limit lower='0' upper='1' effort='1' velocity='1'/>"
            "</joint></robot>\n")


def _xml_safe(text: str) -> str:
    """What XML 1.0 can hold (no C0 but tab and line feed, no surrogates, no U+FFFE/U+FFFF)."""
    return "".join(c for c in text if (c in "\t\n" or ord(c) >= 0x20) and not 0xd800 <= ord(c) <= 0xdfff
                   and c not in "\ufffe\uffff") or "x"


@settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(text=hostile)
def test_validate_quoting_a_strangers_names_and_file_name_shows_them_inert(text, tmp_path_factory, run_cli):
    folder = tmp_path_factory.mktemp("names")
    file_name = "".join(c for c in text if c not in "/\x00")[:40] or "x"
    path = folder / (file_name + ".urdf")
    name = _xml_safe(text)
    path.write_text(_urdf(name), encoding="utf-8", errors="surrogateescape")
    code, out, err = run_cli("validate", str(path))
    assert code != 0
    assert _raw(out + err) == [], out + err
    assert for_terminal(name + "missing") in out  # quoted, visibly


@settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(text=hostile)
def test_argparse_quoting_a_strangers_arguments_shows_them_inert(text, run_cli):
    argument = text.replace("\x00", "") or "x"
    code, out, err = run_cli("validate", "--" + argument)
    assert code == 2 and _raw(out + err) == [], err
    code, out, err = run_cli(argument)
    assert code == 2 and _raw(out + err) == [], err


def _yaml_quoted(text: str) -> str:
    return '"' + "".join(f"\\U{ord(c):08x}" for c in text) + '"'


@settings(max_examples=10, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(text=hostile)
def test_exercises_list_of_a_strangers_set_shows_its_titles_inert(text, tmp_path_factory, run_cli):
    import shutil

    root = tmp_path_factory.mktemp("set")
    source = ROOT / "bras_kit" / "exercises" / "track"
    exercise_set = root / "set"
    shutil.copytree(source, exercise_set)
    track = exercise_set / "track.yaml"
    track.write_text(track.read_text(encoding="utf-8").replace('"The tutorial arm, exercise by exercise"',
                                                                _yaml_quoted(text)), encoding="utf-8")
    first = exercise_set / "01-links" / "exercise.yaml"
    first.write_text(first.read_text(encoding="utf-8").replace('"Describe the arm: the links"',
                                                                _yaml_quoted(text)), encoding="utf-8")
    code, out, err = run_cli("exercises", "init", str(root / "work"), "--track", str(exercise_set))
    assert code == 0, err
    for action in ("list", "check", "hint"):
        code, out, err = run_cli("exercises", action, "--dir", str(root / "work"))
        assert _raw(out + err) == [], (action, out + err)
    code, out, _ = run_cli("exercises", "list", "--dir", str(root / "work"))
    assert for_terminal(text).strip()[:10] in out


# --- through the command line, as a terminal receives it --------------------------------------

NODE = '''
import os
import sys

import rclpy
from sensor_msgs.msg import JointState

TRICK = {trick!r}


def main():
    rclpy.init()
    node = rclpy.create_node("writer")
    publisher = node.create_publisher(JointState, "joint_states", 10)
    os.write(1, ("fd1:" + TRICK + "\\n").encode("utf-8", "surrogateescape"))
    os.write(2, ("fd2:" + TRICK + "\\n").encode("utf-8", "surrogateescape"))
    sys.__stdout__.write("dunder:" + TRICK + "\\n")
    sys.__stdout__.flush()
    sys.__stderr__.write("dunder2:" + TRICK + "\\n")
    print("print:" + TRICK)
    node.get_logger().warning("log:" + TRICK)
    message = JointState()
    message.name = [TRICK]
    message.position = [0.0]
    publisher.publish(message)
    node.destroy_node()
    rclpy.shutdown()
'''


@pytest.mark.parametrize("trick", ["\x1b]0;pwned-title\x07\x1b[2J\x9b31m\u202eevil\u2066\x90q\x9c",
                                   "\x1b_apc\x1b\\\x1bP$q\x1b\\\r\x08\ufeff\U000e0041\u200b"])
def test_a_node_writing_to_its_descriptors_reaches_the_terminal_inert(tmp_path, trick):
    """The node writes through file descriptors 1 and 2, sys.__stdout__ and sys.__stderr__ (the
    streams under any Python-level wrapper), print, its logger, and publishes a joint named with
    the trick: bras-kit relays all of it through the gate."""
    node = tmp_path / "writer.py"
    node.write_text(NODE.format(trick=trick) + "\nif __name__ == '__main__':\n    main()\n")
    env = {**os.environ, "LANGUAGE": "en", "LANG": "C.UTF-8",
           "PATH": f"{Path(sys.executable).parent}{os.pathsep}{os.environ.get('PATH', '')}"}
    done = subprocess.run(["bras-kit", "run", str(node), "--duration", "1", "-o", str(tmp_path / "js.csv")],
                          capture_output=True, timeout=180, cwd=tmp_path, env=env)
    shown = (done.stdout + done.stderr).decode("utf-8", "surrogateescape")
    assert _raw(shown) == [], shown
    for where in ("fd1:", "fd2:", "dunder:", "dunder2:", "print:", "log:"):
        assert where + for_terminal(trick) in shown, (where, shown)


# --- no way around the gate -------------------------------------------------------------------

# the raw streams, a descriptor written directly, escape sequences spelled in the source: each
# allowed only where the gate itself or a binary output lives
ALLOWED = {
    "bras_kit/trust/inert.py": {"escape"},
    "bras_kit/trust/outputs.py": {"buffer"},  # write_bytes: a binary document to stdout (PNG, GIF)
    "bras_kit/cli/render.py": {"buffer"},  # a PNG to stdout
    "bras_kit/trust/sandbox.py": {"os.write"},  # the child's answer to its own pipe
    # pipes between the contained processes, and the maps written in /proc
    "bras_kit/trust/contain/kernel.py": {"os.write"},
    "bras_kit/trust/contain/namespaces.py": {"os.write"},
    "bras_kit/trust/contain/probe.py": {"os.write"},
    "bras_kit/run/node.py": {"os.write"},  # the child's joint states to their pipe
}


def _ways_around(tree: ast.AST) -> set[str]:
    found = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Attribute) and node.attr in ("__stdout__", "__stderr__"):
            found.add("dunder")
        if isinstance(node, ast.Attribute) and node.attr == "buffer" and isinstance(node.value, ast.Attribute) \
                and node.value.attr in ("stdout", "stderr"):
            found.add("buffer")
        if isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute) and node.func.attr == "write" \
                and isinstance(node.func.value, ast.Name) and node.func.value.id == "os":
            found.add("os.write")
        if isinstance(node, ast.Constant) and isinstance(node.value, str) and ("\x1b" in node.value
                                                                               or "\x9b" in node.value):
            found.add("escape")
    return found


def test_no_module_writes_to_the_terminal_around_the_gate():
    offenders = {}
    for path in sorted((ROOT / "bras_kit").rglob("*.py")):
        rel = path.relative_to(ROOT).as_posix()
        if "/standin/" in rel or "/templates/" in rel:  # the learner's side of the wall: runs in the child
            continue
        ways = _ways_around(ast.parse(path.read_text(encoding="utf-8"))) - ALLOWED.get(rel, set())
        if ways:
            offenders[rel] = sorted(ways)
    assert offenders == {}, "write through bras_kit.trust.inert (emit, Styled, the gated streams) instead"


def test_the_check_finds_each_way_around():
    source = ("import os, sys\nsys.__stdout__.write('x')\nsys.stdout.buffer.write(b'x')\n"
              "os.write(1, b'x')\nprint('\\x1b[31m')\n")
    assert _ways_around(ast.parse(source)) == {"dunder", "buffer", "os.write", "escape"}


OWN_SEQUENCES = {"\x1b[0m", "\x1b[1m", "\x1b[2m", "\x1b[31m", "\x1b[32m", "\x1b[33m", "\x1b[36m", "\x1b[H\x1b[2J\x1b[3J"}


def _without_own_sequences(text: str) -> str:
    for sequence in sorted(OWN_SEQUENCES, key=len, reverse=True):
        text = text.replace(sequence, "")
    return text


def test_validate_in_colour_writes_its_own_styles_and_the_names_inert(tmp_path, monkeypatch, run_cli):
    """A terminal that takes colours: the codes in bold and the severities in colour are the
    only sequences; the learner's names inside the findings are shown, not obeyed."""
    import bras_kit.cli.validate as command

    monkeypatch.setattr(command, "_use_colour", lambda: True)
    path = tmp_path / "arm.urdf"
    path.write_text(_urdf("]0;t\u202ex\x9b31m\x85"), encoding="utf-8")  # what XML can hold
    code, out, err = run_cli("validate", str(path))
    assert code != 0
    assert "\x1b[1mBK112\x1b[0m" in out and "\x1b[31merror\x1b[0m" in out
    assert _raw(_without_own_sequences(out)) == []
    assert "]0;t\\u202ex\\u009b31m\\u0085" in out


def test_exercises_in_colour_write_their_own_styles_and_the_titles_inert(tmp_path, monkeypatch, run_cli):
    import shutil

    import bras_kit.exercises.screen as screen

    monkeypatch.setattr(screen, "wants_colour", lambda stream: True)
    exercise_set = tmp_path / "set"
    shutil.copytree(ROOT / "bras_kit" / "exercises" / "track", exercise_set)
    track = exercise_set / "track.yaml"
    track.write_text(track.read_text(encoding="utf-8").replace('"The tutorial arm, exercise by exercise"',
                                                                '"\\e]0;t\\a\\u202etitle"'), encoding="utf-8")
    assert run_cli("exercises", "init", str(tmp_path / "work"), "--track", str(exercise_set))[0] == 0
    code, out, _ = run_cli("exercises", "list", "--dir", str(tmp_path / "work"))
    assert code == 0
    assert "\x1b[1m\\x1b]0;t\\x07\\u202etitle\x1b[0m" in out  # bold, its text inert
    assert _raw(_without_own_sequences(out)) == []
