"""Package variants a learner makes, by category, for comparing ``bras-kit build`` with the real colcon.

Each variant is a workspace as files: ``{path under src/: text}``. The categories come from what
colcon-core 0.21.3 and colcon-ros 0.5.0 read (colcon_ros/package_identification/ros.py: package.xml
and its build type; colcon_ros/task/ament_python/build.py: the index marker and package.xml, installed
implicitly when data_files does not; colcon_core/task/python/build.py: setup.cfg's [install]
install-scripts or install_scripts; colcon_core/environment/__init__.py: the run dependencies in
share/colcon-core/packages/PKG) and from what setuptools' install_data does with data_files.
``ASIDE`` names the variants kept out of sight while build.py was fixed; the test runs them last.
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

ASIDE = ("invalid_maintainer_email", "scripts_file", "data_files_nested_target", "setup_py_raises")
