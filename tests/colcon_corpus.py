"""Package variants a learner makes, by category, for comparing ``bras-kit build`` with the real colcon.

Each variant is a workspace as files: ``{path under src/: text}``. The categories come from what
colcon-core 0.21.3 and colcon-ros 0.5.0 read (colcon_ros/package_identification/ros.py: package.xml
and its build type; colcon_ros/task/ament_python/build.py: the index marker and package.xml, installed
implicitly when data_files does not; colcon_core/task/python/build.py: setup.cfg's [install]
install-scripts or install_scripts; colcon_core/environment/__init__.py: the run dependencies in
share/colcon-core/packages/PKG) and from what setuptools' install_data does with data_files.
``ASIDE`` names the variants kept out of sight while build.py was fixed; the test runs them last.
``GENERATED`` (round 2, issue 57) adds 26 more, one or more per category of colcon's and catkin_pkg's
source, ``ASIDE_GENERATED`` the 5 of them written with the others and run only once the rest agreed.
"""

from __future__ import annotations

PKG = "bras_description"
MAINTAINER = '<maintainer email="eleve@example.com">Élève</maintainer>'
SETUP_CFG = f"[develop]\nscript_dir=$base/lib/{PKG}\n[install]\ninstall_scripts=$base/lib/{PKG}\n"
URDF = '<?xml version="1.0"?>\n<robot name="bras">\n  <link name="base"/>\n</robot>\n'
NODE = "def main():\n    print('publie')\n"


def package_xml(name: str = PKG, build_type: str | None = "ament_python", depends: str = "",
                maintainer: str = MAINTAINER) -> str:
    export = f"  <export>\n    <build_type>{build_type}</build_type>\n  </export>\n" if build_type else ""
    return (f'<?xml version="1.0"?>\n<package format="3">\n  <name>{name}</name>\n  <version>0.0.1</version>\n'
            f"  <description>Le bras</description>\n  {maintainer}\n  <license>Apache-2.0</license>\n"
            f"{depends}{export}</package>\n")


def setup_py(name: str = "package_name", data_files: str | None = None, scripts: str = "",
             entry_points: str = "'publie = bras_description.publie:main'", packages: str = "[package_name]",
             head: str = "") -> str:
    if data_files is None:
        data_files = ("('share/ament_index/resource_index/packages', ['resource/' + package_name]),\n"
                      "        ('share/' + package_name, ['package.xml']),\n"
                      "        ('share/' + package_name + '/urdf', glob('urdf/*.urdf')),")
    return (f"import os\nfrom glob import glob\nfrom setuptools import setup\n{head}\n"
            f"package_name = '{PKG}'\n\nsetup(\n    name={name},\n    version='0.0.1',\n"
            f"    packages={packages},\n    data_files=[\n        {data_files}\n    ],\n"
            f"    install_requires=['setuptools'],\n    zip_safe=True,\n{scripts}"
            f"    entry_points={{'console_scripts': [{entry_points}]}},\n)\n")


def package(folder: str = PKG, **changes: str | None) -> dict[str, str]:
    """The tutorial's ament_python package under src/``folder``, with ``changes`` (None: no such file)."""
    files: dict[str, str | None] = {
        "package.xml": package_xml(),
        "setup.py": setup_py(),
        "setup.cfg": SETUP_CFG,
        f"resource/{PKG}": "",
        f"{PKG}/__init__.py": "",
        f"{PKG}/publie.py": NODE,
        "urdf/bras.urdf": URDF,
    }
    files.update(changes)
    return {f"{folder}/{path}": text for path, text in files.items() if text is not None}


DEPENDS = ("  <buildtool_depend>ament_python</buildtool_depend>\n  <build_depend>urdf</build_depend>\n"
           "  <depend>sensor_msgs</depend>\n  <exec_depend>rclpy</exec_depend>\n"
           "  <exec_depend>robot_state_publisher</exec_depend>\n  <build_export_depend>tf2</build_export_depend>\n"
           "  <test_depend>ament_flake8</test_depend>\n")

VARIANTS: dict[str, dict[str, str]] = {
    "tutorial": package(),
    "setup_cfg_missing": package(**{"setup.cfg": None}),
    "setup_cfg_dash_keys": package(**{"setup.cfg": SETUP_CFG.replace("script_dir", "script-dir")
                                      .replace("install_scripts", "install-scripts")}),
    "setup_cfg_develop_only": package(**{"setup.cfg": f"[develop]\nscript_dir=$base/lib/{PKG}\n"}),
    "name_differs": package(**{"setup.py": setup_py(name="'bras_desc'")}),
    "ament_cmake_with_setup_py": package(**{"package.xml": package_xml(build_type="ament_cmake")}),
    "no_build_type": package(**{"package.xml": package_xml(build_type=None)}),
    "run_dependencies": package(**{"package.xml": package_xml(depends=DEPENDS)}),
    "resource_marker_missing": package(**{f"resource/{PKG}": None}),
    "marker_not_in_data_files": package(**{"setup.py": setup_py(data_files=(
        "('share/' + package_name, ['package.xml']),\n"
        "        ('share/' + package_name + '/urdf', glob('urdf/*.urdf')),"))}),
    "package_xml_missing": package(**{"package.xml": None}),
    "data_files_folder": package(**{"setup.py": setup_py(data_files=(
        "('share/ament_index/resource_index/packages', ['resource/' + package_name]),\n"
        "        ('share/' + package_name, ['package.xml']),\n"
        "        ('share/' + package_name, ['urdf']),"))}),
    "data_files_glob_two_kinds": package(**{"launch/affiche.launch.py": "# lancement\n",
                                            "urdf/bras.xacro": "<robot/>\n",
                                            "setup.py": setup_py(data_files=(
        "('share/ament_index/resource_index/packages', ['resource/' + package_name]),\n"
        "        ('share/' + package_name, ['package.xml']),\n"
        "        (os.path.join('share', package_name, 'launch'), glob('launch/*.launch.py')),\n"
        "        ('share/' + package_name + '/urdf', glob('urdf/*')),"))}),
    "data_files_missing_file": package(**{"setup.py": setup_py(data_files=(
        "('share/ament_index/resource_index/packages', ['resource/' + package_name]),\n"
        "        ('share/' + package_name, ['package.xml']),\n"
        "        ('share/' + package_name + '/urdf', ['urdf/bras.urdf', 'urdf/poignet.urdf']),"))}),
    "data_files_glob_matches_nothing": package(**{"setup.py": setup_py(data_files=(
        "('share/ament_index/resource_index/packages', ['resource/' + package_name]),\n"
        "        ('share/' + package_name, ['package.xml']),\n"
        "        ('share/' + package_name + '/rviz', glob('rviz/*.rviz')),"))}),
    "entry_points_two": package(**{f"{PKG}/bouge.py": NODE, "setup.py": setup_py(
        entry_points="'publie = bras_description.publie:main', 'bouge = bras_description.bouge:main'")}),
    "no_entry_points": package(**{"setup.py": setup_py(entry_points="")}),
    "in_subfolder_of_src": package(folder=f"bras/{PKG}"),
    "two_packages": {**package(), **package(folder="bras_bringup", **{
        "package.xml": package_xml(name="bras_bringup", depends=f"  <exec_depend>{PKG}</exec_depend>\n"),
        "setup.py": setup_py().replace(f"package_name = '{PKG}'", "package_name = 'bras_bringup'")
        .replace("bras_description.publie", "bras_bringup.publie"),
        "resource/bras_bringup": "", f"resource/{PKG}": None,
        f"{PKG}/__init__.py": None, f"{PKG}/publie.py": None,
        "bras_bringup/__init__.py": "", "bras_bringup/publie.py": NODE})},
    "folder_name_differs": package(folder="mon_bras"),
    # kept aside: run last, unseen while build.py was fixed
    "invalid_maintainer_email": package(**{"package.xml": package_xml(
        maintainer='<maintainer email="eleve@ecole">Élève</maintainer>')}),
    "scripts_file": package(**{"scripts/outil": "#!/usr/bin/env python3\nprint('outil')\n",
                               "setup.py": setup_py(scripts="    scripts=['scripts/outil'],\n")}),
    "data_files_nested_target": package(**{"meshes/base.stl": "solid base\nendsolid base\n",
                                           "setup.py": setup_py(data_files=(
        "('share/ament_index/resource_index/packages', ['resource/' + package_name]),\n"
        "        ('share/' + package_name, ['package.xml']),\n"
        "        ('share/' + package_name + '/models/meshes/visual', ['meshes/base.stl']),"))}),
    "setup_py_raises": package(**{"setup.py": setup_py(head="raise ValueError('version manquante')\n")}),
}

def manifest_with(old: str, new: str) -> str:
    """The tutorial's package.xml with ``old`` replaced by ``new`` (it must be there)."""
    text = package_xml()
    assert old in text, old
    return text.replace(old, new)


def data_files(*entries: str) -> str:
    return ",\n        ".join(entries) + ","


MARKER = "('share/ament_index/resource_index/packages', ['resource/' + package_name])"
MANIFEST = "('share/' + package_name, ['package.xml'])"
URDFS = "('share/' + package_name + '/urdf', glob('urdf/*.urdf'))"

# Round 2, one or more per category of colcon's source, beyond the 24 above (issue 57). Each names
# what it exercises: catkin_pkg's refusals (package.py, parse_package_string and Package.validate),
# format 3's conditions (condition.py), build types (get_build_type), data_files' shapes and
# failures (install_data, get_data_files_mapping), setup.cfg's keys (_get_install_scripts), plain
# Python packages (colcon-python-setup-py), the hooks colcon's environment extensions write, the
# order packages are sourced in (_local_setup_util_sh.py, order_packages).
GENERATED: dict[str, dict[str, str]] = {
    # catkin_pkg refuses the manifest: colcon builds a plain Python package
    "package_xml_version_two_parts": package(**{"package.xml": manifest_with("0.0.1", "1.0")}),
    "package_xml_no_license": package(**{"package.xml": manifest_with("  <license>Apache-2.0</license>\n", "")}),
    "package_xml_maintainer_without_email": package(**{"package.xml": manifest_with(
        ' email="eleve@example.com"', "")}),
    "package_xml_not_xml": package(**{"package.xml": package_xml().replace("</package>", "")}),
    "package_xml_unknown_tag": package(**{"package.xml": manifest_with("<license>", "<licence>x</licence>\n  <license>")}),
    "package_xml_condition_in_format_2": package(**{"package.xml": manifest_with('format="3"', 'format="2"').replace(
        "  <export>", '  <exec_depend condition="$ROS_VERSION == 2">rclpy</exec_depend>\n  <export>')}),
    "package_xml_depends_on_itself": package(**{"package.xml": manifest_with(
        "  <export>", f"  <exec_depend>{PKG}</exec_depend>\n  <export>")}),
    "two_build_types": package(**{"package.xml": manifest_with(
        "<build_type>ament_python</build_type>", "<build_type>ament_python</build_type>\n    <build_type>ament_cmake</build_type>")}),
    # format 3's conditions, against the environment colcon runs in (ROS_VERSION unset here)
    "condition_false_when_unset": package(**{"package.xml": manifest_with("  <export>", (
        '  <exec_depend condition="$ROS_VERSION == 2">rclpy</exec_depend>\n'
        '  <exec_depend condition="$ROS_VERSION == 1">rospy</exec_depend>\n  <export>'))}),
    "condition_true_when_unset": package(**{"package.xml": manifest_with("  <export>", (
        '  <exec_depend condition="$ROS_VERSION != 1">launch_ros</exec_depend>\n'
        '  <depend condition="$ROS_DISTRO == \'\' or $ROS_DISTRO == jazzy">tf2_ros</depend>\n  <export>'))}),
    "format_1_run_depend": package(**{"package.xml": manifest_with('format="3"', 'format="1"').replace(
        "  <export>", "  <run_depend>rclpy</run_depend>\n  <build_depend>urdf</build_depend>\n  <export>")}),
    # build types colcon-ros hands to CMake
    "build_type_cmake": package(**{"package.xml": package_xml(build_type="cmake")}),
    # data_files' shapes
    "data_files_plain_string": package(**{"setup.py": setup_py(data_files=data_files(MARKER, MANIFEST, URDFS,
                                                                                       "'urdf/bras.urdf'"))}),
    "data_files_same_file_twice": package(**{"setup.py": setup_py(data_files=data_files(
        MARKER, MANIFEST, URDFS, "('share/' + package_name + '/urdf', ['urdf/bras.urdf'])"))}),
    "data_files_first_of_two_missing": package(**{"rviz/vue.rviz": "Panels: []\n", "setup.py": setup_py(data_files=data_files(
        MARKER, MANIFEST, "('share/' + package_name + '/rviz', ['rviz/absente.rviz', 'rviz/vue.rviz'])", URDFS))}),
    "data_files_shared_library": package(**{"lib/libbras.so": "not really a library\n", "setup.py": setup_py(
        data_files=data_files(MARKER, MANIFEST, "('lib', ['lib/libbras.so'])"))}),
    "data_files_cmake_config": package(**{"cmake/brasConfig.cmake": "# cmake\n", "setup.py": setup_py(
        data_files=data_files(MARKER, MANIFEST, "('share/' + package_name + '/cmake', ['cmake/brasConfig.cmake'])"))}),
    # setup.cfg's keys
    "setup_cfg_install_only": package(**{"setup.cfg": f"[install]\ninstall_scripts=$base/lib/{PKG}\n"}),
    "setup_cfg_both_install_keys": package(**{"setup.cfg": SETUP_CFG + "install-scripts=$base/bin\n"}),
    # plain Python packages (no package.xml)
    "plain_python_without_package_xml": package(**{"package.xml": None, "setup.py": setup_py(
        data_files=data_files(MARKER, URDFS))}),
    # packages sourced in order: bringup runs on description, which runs on nothing here
    "three_packages": {**package(), **{
        path.replace(PKG, name): text.replace(PKG, name).replace(
            "  <export>", f"  <exec_depend>{dep}</exec_depend>\n  <export>") if path.endswith("package.xml")
        else text.replace(PKG, name)
        for name, dep in (("cellule_bringup", "bras_moteur"), ("bras_moteur", PKG))
        for path, text in package().items() if not path.endswith("urdf/bras.urdf")}},
    # kept aside: written with the others, run only once the rest agreed
    "package_xml_name_with_space": package(**{"package.xml": package_xml(name="bras description")}),
    "condition_parenthesised": package(**{"package.xml": manifest_with("  <export>", (
        '  <exec_depend condition="($ROS_VERSION == 2 or $ROS_VERSION == \'\') and $X != y">rclpy</exec_depend>\n'
        "  <export>"))}),
    "data_files_into_bin": package(**{"scripts/outil": "#!/bin/sh\necho outil\n", "setup.py": setup_py(
        data_files=data_files(MARKER, MANIFEST, "('bin', ['scripts/outil'])"))}),
    "plain_python_setup_py_fails_half_way": package(**{"package.xml": None, "setup.py": setup_py(
        data_files=data_files(MARKER, "('share/' + package_name, ['LISEZMOI.md'])", URDFS))}),
    "package_xml_author_bad_email": package(**{"package.xml": manifest_with(
        "  <license>", '  <author email="auteur@ecole">Auteur</author>\n  <license>')}),
}
VARIANTS.update(GENERATED)

ASIDE = ("invalid_maintainer_email", "scripts_file", "data_files_nested_target", "setup_py_raises")
ASIDE_GENERATED = ("package_xml_name_with_space", "condition_parenthesised", "data_files_into_bin",
                   "plain_python_setup_py_fails_half_way", "package_xml_author_bad_email")
