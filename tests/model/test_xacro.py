"""xacro without ROS: the real xacro package, $(find) from package folders, clean errors, and
expressions that can never run code."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest
from paths import TESTS

from bras_kit.core.errors import XacroError, XMLSafetyError, XMLSyntaxError
from bras_kit.model.package_paths import PACKAGE_PATH_ENV
from bras_kit.model.robot import robot_from_xml
from bras_kit.model.xacro import expand_xacro
from bras_kit.model.xmlio import parse_xml

DATA = TESTS / "data" / "xacro"
PACKAGES = DATA / "packages"
MARKER = "bras_kit_marker"


@pytest.fixture(autouse=True)
def no_ros_environment(monkeypatch):
    """Package lookups see only what each test gives them."""
    for var in (PACKAGE_PATH_ENV, "AMENT_PREFIX_PATH", "ROS_PACKAGE_PATH"):
        monkeypatch.delenv(var, raising=False)


def robot_of(text: str):
    return robot_from_xml(parse_xml(text, "expanded.urdf"), "expanded.urdf", text)


def box_of(robot, link: str):
    visual = robot.link(link).visuals[0]
    return visual.geometry.size, visual.origin.xyz


# --- the language: properties, macros, conditionals, arguments ----------------------------------

def test_properties_and_macro_defaults_are_expanded():
    robot = robot_of(expand_xacro(DATA / "features.xacro"))
    assert robot.name == "features"
    assert box_of(robot, "arm") == ((0.05, 0.05, 0.4), (0.0, 0.0, 0.2))
    assert box_of(robot, "thin") == ((0.02, 0.02, 0.8), (0.0, 0.0, 0.4))
    assert robot.joint("elbow").origin.xyz == (0.0, 0.0, 0.4)
    assert robot.joint("shoulder").limit.lower == pytest.approx(-1.5707963267948966, abs=1e-12)
    assert robot.issues == []


def test_unless_branch_is_kept_and_if_branch_dropped_by_default():
    robot = robot_of(expand_xacro(DATA / "features.xacro"))
    assert robot.link_names == ["base", "arm", "thin", "cap"]
    assert robot.joint("tool_joint") is None


def test_arguments_switch_branches_and_change_numbers():
    robot = robot_of(expand_xacro(DATA / "features.xacro", {"with_tool": "true", "length": "0.5"}))
    assert robot.link_names == ["base", "arm", "thin", "tool"]
    assert robot.joint("cap_joint") is None
    assert box_of(robot, "arm") == ((0.05, 0.05, 0.5), (0.0, 0.0, 0.25))
    assert robot.joint("tool_joint").origin.xyz == (0.0, 0.0, 1.0)


def test_cli_takes_name_value_arguments_and_writes_a_file(run_cli, tmp_path):
    out = tmp_path / "features.urdf"
    code, _, err = run_cli("xacro", str(DATA / "features.xacro"), "with_tool:=true", "length:=0.3",
                           "-o", str(out))
    assert code == 0, err
    robot = robot_of(out.read_text())
    assert robot.link("tool") is not None
    assert robot.joint("tool_joint").origin.xyz == (0.0, 0.0, 0.6)


def test_cli_refuses_an_argument_without_colon_equals(run_cli):
    code, out, err = run_cli("xacro", str(DATA / "features.xacro"), "length=0.3")
    assert code == 2
    assert "NAME:=VALUE" in err and "Traceback" not in err


def test_cli_output_is_not_overwritten_without_force(run_cli, tmp_path):
    out = tmp_path / "mine.urdf"
    out.write_text("my own work")
    code, _, err = run_cli("xacro", str(DATA / "features.xacro"), "-o", str(out))
    assert code == 2 and "--force" in err
    assert out.read_text() == "my own work"
    code, _, _ = run_cli("xacro", str(DATA / "features.xacro"), "-o", str(out), "--force")
    assert code == 0 and "<robot" in out.read_text()


# --- $(find pkg) ----------------------------------------------------------------------------------

def gripper_mesh(text: str) -> str:
    return robot_of(text).link("pince").visuals[0].geometry.filename


@pytest.mark.parametrize("root,found", [
    (PACKAGES, PACKAGES / "bk_parts"),                         # a folder holding packages
    (PACKAGES / "bk_parts", PACKAGES / "bk_parts"),            # the package folder itself
    (DATA / "install", DATA / "install" / "share" / "bk_parts"),  # an install prefix
    (DATA / "install" / "share", DATA / "install" / "share" / "bk_parts"),  # its share/ tree
], ids=["workspace-src", "package-itself", "install-prefix", "install-share"])
def test_find_resolves_from_package_path(run_cli, root, found):
    code, out, err = run_cli("xacro", str(DATA / "uses_find.xacro"), "--package-path", str(root))
    assert code == 0, err
    assert gripper_mesh(out) == f"file://{found.resolve()}/meshes/pince.stl"
    joint = robot_of(out).joint("pince_joint")
    assert (joint.parent, joint.child, joint.origin.xyz) == ("base", "pince", (0.0, 0.0, 0.1))


def test_find_resolves_from_environment_variable(monkeypatch):
    monkeypatch.setenv(PACKAGE_PATH_ENV, os.pathsep.join([str(DATA / "nowhere"), str(PACKAGES)]))
    text = expand_xacro(DATA / "uses_find.xacro")
    assert gripper_mesh(text) == f"file://{(PACKAGES / 'bk_parts').resolve()}/meshes/pince.stl"


def test_package_path_comes_before_environment(monkeypatch):
    monkeypatch.setenv(PACKAGE_PATH_ENV, str(PACKAGES))
    text = expand_xacro(DATA / "uses_find.xacro", package_paths=[str(DATA / "install")])
    assert "/install/share/bk_parts/meshes/pince.stl" in gripper_mesh(text)


def test_unknown_package_says_where_it_looked(run_cli, tmp_path):
    code, _, err = run_cli("xacro", str(DATA / "uses_find.xacro"), "--package-path", str(tmp_path))
    assert code == 2
    assert "package 'bk_parts' not found" in err
    assert "--package-path" in err and str(tmp_path) in err
    assert "Traceback" not in err


# --- broken files: one clean error naming the file, exit code 2 -------------------------------------

@pytest.mark.parametrize("name,error,line,words", [
    ("malformed.xacro", XMLSyntaxError, 4, "<visual> opened on line 4 is never closed"),
    ("undefined_property.xacro", XacroError, 6, "'height' is not defined"),
    ("missing_include.xacro", XacroError, 4, "cannot include"),
    ("undefined_arg.xacro", XacroError, 4, "Undefined substitution argument tool_name"),
], ids=["malformed-xml", "undefined-property", "missing-include", "undefined-arg"])
def test_broken_xacro_gives_located_error(run_cli, name, error, line, words):
    path = DATA / "broken" / name
    with pytest.raises(error) as info:
        expand_xacro(path)
    assert Path(info.value.path).resolve() == path.resolve()
    assert info.value.line == line
    assert words in str(info.value.message)
    assert info.value.hint

    code, out, err = run_cli("xacro", str(path))
    assert code == 2 and out == ""
    assert err.startswith(f"bras-kit xacro: error: {path}:{line}: ")
    assert "Traceback" not in err


def test_missing_include_names_the_missing_file():
    with pytest.raises(XacroError) as info:
        expand_xacro(DATA / "broken" / "missing_include.xacro")
    assert str(DATA / "broken" / "parts" / "not_there.xacro") in str(info.value.message)


def test_broken_xacro_in_a_real_process_prints_no_traceback():
    result = subprocess.run([sys.executable, "-m", "bras_kit", "xacro",
                             str(DATA / "broken" / "undefined_property.xacro")],
                            capture_output=True, text=True, timeout=120)
    assert result.returncode == 2
    assert "undefined_property.xacro:6" in result.stderr
    assert "Traceback" not in result.stderr


def test_missing_file_is_a_clean_error(run_cli, tmp_path):
    code, _, err = run_cli("xacro", str(tmp_path / "absent.xacro"))
    assert code == 2 and "no such file" in err


# --- DTDs and entities: refused before xacro sees them --------------------------------------------

def test_dtd_with_entity_is_refused_on_the_entity_line():
    with pytest.raises(XMLSafetyError) as info:
        expand_xacro(DATA / "broken" / "dtd_entity.xacro")
    assert info.value.line == 3
    assert "entity" in str(info.value.message)


def test_plain_doctype_without_entities_is_accepted_like_xacro():
    text = expand_xacro(DATA / "doctype_plain.xacro")
    assert "<!DOCTYPE robot>" in text
    assert robot_of(text).link_names == ["base"]


def test_dtd_in_an_included_file_is_refused_and_names_that_file(run_cli):
    code, out, err = run_cli("xacro", str(DATA / "broken" / "includes_entity.xacro"))
    assert code == 2 and out == ""
    assert f"{DATA / 'broken' / 'parts' / 'entity_part.xacro'}:3: refused" in err
    assert "hidden" not in err


# --- expressions that would run code ---------------------------------------------------------------

@pytest.mark.parametrize("name,reason", [
    ("import.xacro", "the name '__import__'"),
    ("subclasses.xacro", "the function 'vars', which is not allowed"),
    ("subclasses_split.xacro", "the function 'vars', which is not allowed"),
], ids=["dunder-import", "vars-subclasses", "vars-subclasses-split"])
def test_unsafe_expression_is_refused_and_does_not_run(run_cli, monkeypatch, tmp_path, name, reason):
    monkeypatch.chdir(tmp_path)
    path = DATA / "unsafe" / name
    with pytest.raises(XacroError) as info:
        expand_xacro(path)
    assert f"it uses {reason}" in str(info.value.message)
    assert Path(info.value.path).resolve() == path.resolve()
    code, _, err = run_cli("xacro", str(path))
    assert code == 2 and "refused the expression" in err
    assert not (tmp_path / MARKER).exists()


def test_eval_form_of_the_import_is_refused_and_does_not_run(run_cli, monkeypatch, tmp_path):
    monkeypatch.chdir(tmp_path)
    code, _, err = run_cli("xacro", str(DATA / "unsafe" / "eval_import.xacro"))
    assert code == 2 and "Traceback" not in err
    assert not (tmp_path / MARKER).exists()


def test_the_subclasses_payload_is_a_real_escape_in_plain_xacro(tmp_path):
    """Shows the fixture is not a straw man: unguarded xacro runs it and makes the marker file."""
    code = "import subprocess, sys, xacro; xacro.process_file(sys.argv[1])"
    subprocess.run([sys.executable, "-c", code, str(DATA / "unsafe" / "subclasses.xacro")],
                   cwd=tmp_path, capture_output=True, timeout=120)
    assert (tmp_path / MARKER).exists(), "plain xacro now refuses this payload: pick a new one"


def test_huge_power_is_refused_without_being_computed():
    # In a child process with a time-out, so a broken guard fails the test instead of hanging it.
    result = subprocess.run([sys.executable, "-m", "bras_kit", "xacro",
                             str(DATA / "unsafe" / "huge_power.xacro")],
                            capture_output=True, text=True, timeout=120)
    assert result.returncode == 2
    assert "huge_power.xacro:5: refused the expression '10**10**10': 10 ** 10000000000 is too large" \
        in result.stderr


@pytest.mark.parametrize("expression,allowed", [
    ("2 ** 8", True),
    ("pi / 2 * radius", True),
    ("[x * 2 for x in python.range(3)]", True),
    ("10 ** 100", True),
    ("10 ** 10000", False),
    ("().__class__", False),
    ("python.getattr(1, 'real')", False),
    ("(lambda: 1)()", True),  # xacro accepts lambdas; their bodies are interpreted like the rest
    ("(lambda: ().__class__)()", False),
    ("f'{width.__class__}'", False),
])
def test_expression_guard(expression, allowed):
    from bras_kit.model.xacro_walls import check_expression

    if allowed:
        check_expression(expression)
    else:
        with pytest.raises(XacroError, match="refused the expression"):
            check_expression(expression)


@pytest.mark.parametrize("expression", ["'a' * 10**10", "[0] * 10**9", "10**9 * 'ab'"])
def test_repeating_text_or_lists_is_refused_before_it_fills_memory(tmp_path, run_cli, expression):
    path = tmp_path / "repeat.xacro"
    path.write_text('<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
                    f'  <link name="${{{expression}}}"/>\n</robot>\n')
    code, _, err = run_cli("xacro", str(path))
    assert code == 2
    assert "repeating this text or list makes it too large" in err
    assert f"{path}:2:" in err


# --- where an error is: the file and line the expression is written on, root cause first ----------

@pytest.mark.parametrize("name,line,words", [
    ("chain.xacro", 5, "ZeroDivisionError: division by zero in the expression '1 / zero'"),
    ("keyword_error.xacro", 6, "'reversed' is an invalid keyword argument"),
    ("less_than.xacro", 5, "name 'missing_name' is not defined"),
], ids=["chain-of-properties", "keyword-argument", "escaped-less-than"])
def test_expression_error_names_the_line_it_is_written_on(name, line, words):
    path = DATA / "broken" / name
    with pytest.raises(XacroError) as info:
        expand_xacro(path)
    assert (Path(info.value.path).resolve(), info.value.line) == (path.resolve(), line)
    assert str(info.value.message).startswith(words) or words in str(info.value.message)


def test_chain_of_failing_properties_puts_the_root_cause_first_then_who_used_it():
    with pytest.raises(XacroError) as info:
        expand_xacro(DATA / "broken" / "chain.xacro")
    text = str(info.value.message)
    assert text.startswith("ZeroDivisionError: division by zero")
    assert text.endswith("(used by 'p3 + 1', 'p2 * 2', 'p1')")
    assert "when evaluating" not in text


def test_refusal_inside_a_macro_of_an_included_file_names_that_file_and_line():
    with pytest.raises(XacroError) as info:
        expand_xacro(DATA / "broken" / "includes_refused.xacro")
    part = DATA / "broken" / "parts" / "refused_part.xacro"
    assert (Path(info.value.path).resolve(), info.value.line) == (part.resolve(), 5)
    assert "__class__" in str(info.value.message)
