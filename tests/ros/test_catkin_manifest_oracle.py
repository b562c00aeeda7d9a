"""bras_kit.ros.catkin against catkin_pkg 1.1.1 itself (the one colcon-ros reads package.xml with, in
the real colcon's venv: tests/realcolcon.py): which manifests it refuses, what their run dependencies
and build type are, and how format 3's conditions evaluate. One child process answers every case."""

from __future__ import annotations

import json
import subprocess
from pathlib import Path

import colcon_corpus
import pytest
import realcolcon

from bras_kit.model.xmlio import parse_xml
from bras_kit.ros.catkin import evaluate_condition, read_manifest

CONDITIONS = [
    "$ROS_VERSION == 2", "$ROS_VERSION != 2", "$ROS_VERSION == ''", '$ROS_DISTRO == "jazzy"',
    "$ROS_VERSION == 2 and $ROS_DISTRO == jazzy", "$ROS_VERSION == 1 or $ROS_DISTRO == jazzy",
    "$ROS_VERSION == 1 or $ROS_VERSION == 2 and $ROS_DISTRO == humble",
    "($ROS_VERSION == 1 or $ROS_VERSION == 2) and $ROS_DISTRO == humble",
    "$ROS_DISTRO >= humble", "$ROS_DISTRO < iron", "$X <= 10", "2 == $ROS_VERSION", "$PLATFORM != windows",
    "$A_B-c == x",  # a dash ends the variable's name
]
CONTEXTS = [{}, {"ROS_VERSION": "2", "ROS_DISTRO": "jazzy"}, {"ROS_VERSION": "1", "ROS_DISTRO": "humble"},
            {"ROS_DISTRO": "iron", "X": "9", "PLATFORM": "windows"}]
BAD_CONDITIONS = ["$ROS_VERSION", "$ROS_VERSION = 2", "($ROS_VERSION == 2", "$ROS_VERSION == 2 and", "== 2"]


def manifests() -> dict[str, str]:
    """The corpus's package.xml texts, and more shapes of what catkin_pkg refuses or accepts."""
    out = {name: files[path] for name, files in colcon_corpus.VARIANTS.items()
           for path in files if path.endswith("package.xml")}
    base = colcon_corpus.package_xml()
    out.update({
        "version_leading_zero": base.replace("0.0.1", "0.01.1"),  # a warning only
        "version_empty": base.replace("<version>0.0.1</version>", "<version></version>"),
        "two_names": base.replace("</name>", "</name>\n  <name>autre</name>"),
        "no_description": base.replace("  <description>Le bras</description>\n", ""),
        "empty_description": base.replace("<description>Le bras</description>", "<description></description>"),
        "no_maintainer": base.replace(f"  {colcon_corpus.MAINTAINER}\n", ""),
        "empty_license": base.replace("<license>Apache-2.0</license>", "<license> </license>"),
        "format_4": base.replace('format="3"', 'format="4"'),
        "root_not_package": base.replace("<package", "<paquet").replace("</package>", "</paquet>"),
        "unknown_attribute": base.replace("<license>", '<license lang="fr">'),
        "child_in_name": base.replace("<name>bras_description</name>", "<name>bras_description<b/></name>"),
        "depend_redundant": base.replace("  <export>", "  <depend>rclpy</depend>\n  <exec_depend>rclpy</exec_depend>\n"
                                                        "  <export>"),
        "group_depend": base.replace("  <export>", "  <group_depend>rosidl_interface_packages</group_depend>\n"
                                                   "  <export>"),
        "conditional_build_type": base.replace("<build_type>ament_python</build_type>",
                                               '<build_type condition="$ROS_VERSION == 1">catkin</build_type>\n'
                                               '    <build_type condition="$ROS_VERSION != 1">ament_python</build_type>'),
        "uppercase_name": base.replace("<name>bras_description</name>", "<name>Bras_Description</name>"),
        "url_and_author": base.replace("  <license>", '  <url type="website">https://example.com</url>\n'
                                                      '  <author email="a@b.fr">Auteur</author>\n  <license>'),
    })
    return out


CATKIN = """
import json, sys
from catkin_pkg.condition import evaluate_condition
from catkin_pkg.package import InvalidPackage, parse_package_string
asked = json.load(sys.stdin)
conditions = []
for text, context in asked["conditions"]:
    try:
        conditions.append(bool(evaluate_condition(text, context)))
    except ValueError:
        conditions.append(None)
packages = {}
for name, text in asked["manifests"].items():
    try:
        pkg = parse_package_string(text, warnings=[])
    except (InvalidPackage, AssertionError) as exc:
        packages[name] = {"refused": str(exc)}
        continue
    pkg.evaluate_conditions({"DISABLE_GROUPS_WORKAROUND": "1"})
    run = sorted({d.name for d in pkg.build_export_depends + pkg.buildtool_export_depends + pkg.exec_depends
                  if d.evaluated_condition})
    try:
        build_type = pkg.get_build_type()
    except InvalidPackage:
        build_type = ""
    packages[name] = {"name": pkg.name, "run": run, "build_type": build_type}
json.dump({"conditions": conditions, "packages": packages}, sys.stdout)
"""


@pytest.fixture(scope="module")
def catkin() -> dict:
    python = Path(realcolcon.colcon_executable()).with_name("python")
    asked = {"conditions": [[c, ctx] for c in CONDITIONS + BAD_CONDITIONS for ctx in CONTEXTS],
             "manifests": manifests()}
    done = subprocess.run([str(python), "-c", CATKIN], input=json.dumps(asked), capture_output=True, text=True,
                          check=True, timeout=120)
    return json.loads(done.stdout)


def test_conditions_evaluate_as_catkin_pkg_evaluates_them(catkin):
    ours = []
    for condition in CONDITIONS + BAD_CONDITIONS:
        for context in CONTEXTS:
            try:
                ours.append(evaluate_condition(condition, context))
            except ValueError:
                ours.append(None)
    pairs = [(c, ctx) for c in CONDITIONS + BAD_CONDITIONS for ctx in CONTEXTS]
    differ = [(pair, theirs, mine) for pair, theirs, mine in zip(pairs, catkin["conditions"], ours) if theirs != mine]
    assert differ == []


@pytest.mark.parametrize("name", sorted(manifests()))
def test_manifest_is_read_as_catkin_pkg_reads_it(name, catkin):
    theirs = catkin["packages"][name]
    try:
        xml = parse_xml(manifests()[name].encode())
    except Exception:  # noqa: BLE001 - not XML: catkin_pkg refuses it too
        assert "refused" in theirs
        return
    mine = read_manifest(xml, {})
    if "refused" in theirs:
        assert mine.problem, (name, theirs)
        first = theirs["refused"].splitlines()[-1].lstrip("- ")
        assert first.split(" ")[0] in mine.problem, (theirs["refused"], mine.problem)
        return
    assert mine.problem == "", (name, mine.problem)
    assert (mine.name, list(mine.run_depends)) == (theirs["name"], theirs["run"])
    assert (mine.build_type if mine.build_types <= 1 else "") == theirs["build_type"], (name, mine)
