"""BK6xx: the whole ROS 2 package, for the three pitfalls a URDF file alone cannot show. This
module registers a package rule (:func:`package_rule`) and holds what the families share; the
rules themselves are in their family's module: ``install_rules``, ``rviz_rules``,
``motion_rules``, ``node_code_rules`` (and ``launch_rules``, ``run_rules``...).

* "file not found" at launch (BK600-BK606): what ``setup.py`` installs, what the launch file
  opens, the ament index marker, the names, the dependencies, the maintainer's email.
* "RViz reste vide" (BK610-BK613): the ``.rviz`` configuration the launch file gives RViz.
* "Le robot apparaît mais ne bouge pas" (BK620-BK626): who publishes ``/joint_states``, with
  which names and within which limits, whether ``ros2 run`` can find the node, and whether the
  node really sends its messages, on the right topic, in radians.

Every hit carries ``file`` (relative to the package folder): the finding is reported there.
"""

from __future__ import annotations

import os
import re
from collections.abc import Callable, Iterable, Iterator
from typing import Any

from ...findings.registry import Hit, hit, rule
from ...ros.joint_publishers import Publisher
from ...ros.launch_source import NodeCall
from ...ros.package import Package
from ...ros.staticpy import ShareFile

# catkin_pkg's own test of a maintainer's email (catkin_pkg.package.Person.validate)
EMAIL = re.compile(r"^[-a-zA-Z0-9_%+]+(\.[-a-zA-Z0-9_%+]+)*@[-a-zA-Z0-9%]+(\.[-a-zA-Z0-9%]+)*\.[a-zA-Z]{2,}$")
# the launch files ros2 launch reads: Python, XML and YAML (launch/launch_description_sources)
LAUNCH_SUFFIXES = (".launch.py", "_launch.py", ".launch.xml", "_launch.xml", ".launch.yaml", "_launch.yaml",
                   ".launch.yml", "_launch.yml")
REQUIRED_FOLDERS = (("urdf", (".urdf", ".xacro")), ("launch", LAUNCH_SUFFIXES))
ROBOT_DESCRIPTION = "/robot_description"
MOTION_SECONDS = 60.0  # how long a node's sine formulas are followed (every tutorial wave repeats within)

PackageCheck = Callable[[Package], Iterable[Hit]]
PACKAGE_CHECKS: dict[str, PackageCheck] = {}  # code -> the check, called with a Package


def package_rule(code: str, name: str, severity: str) -> Callable[[PackageCheck], PackageCheck]:
    """Register a package rule: it runs on a :class:`Package`, never on a single robot file."""

    def decorate(check: PackageCheck) -> PackageCheck:
        def on_context(context: Any) -> Iterable[Hit]:
            return check(context) if isinstance(context, Package) else ()

        rule(code, name, severity)(on_context)
        PACKAGE_CHECKS[code] = check
        return check

    return decorate


def _at(file: str, line: int | None, variant: str = "", **params: object) -> Hit:
    return hit("file", None, line, variant, file=file, **params)


def _included(pkg: Package, path: str) -> bool:
    """Whether another launch file of the package names this one (IncludeLaunchDescription): the
    nodes it starts are only part of the launch, checked with the file that includes it."""
    from ...trust.learner_files import read_text

    name = os.path.basename(path)
    named = re.compile(r"(?<![\w.-])" + re.escape(name) + r"(?![\w.-])")
    for other in pkg.files("launch", LAUNCH_SUFFIXES):  # an XML or YAML file includes Python ones too
        if other == path:
            continue
        try:
            text = read_text(os.path.join(pkg.root, other), (pkg.root,), errors="replace")
        except OSError:
            continue
        if named.search(text):  # 'name', ".../launch/name", $(find-pkg-share p)/launch/name
            return True
    return False


def _misplaced(pkg: Package, module: str) -> list[str]:
    return pkg.misplaced(module)


def _module_file(module: str) -> str:
    return module.replace(".", "/") + ".py"


def _module_written(pkg: Package, module: str) -> bool:
    return pkg.module_written(module)


def _not_written(pkg: Package, module: str) -> bool:
    """An entry's module that does not exist while no node of the package is left without an
    entry and no file of its name sits elsewhere: the node is still to write. Beside a node no
    entry runs, it is a misspelling; a file of its name elsewhere, a misplaced node (BK622)."""
    if _module_written(pkg, module) or _misplaced(pkg, module):
        return False
    listed = {s.module for s in (pkg.setup.scripts if pkg.setup is not None else None) or []}
    return not any(p.has_main and p.module not in listed for p in pkg.publishers)


def _on_joint_states(topic: Any) -> bool:
    return not isinstance(topic, str) or topic.strip().lstrip("/") == "joint_states"


def _publisher_for(pkg: Package, executable: Any) -> Publisher | None:
    scripts = pkg.setup.scripts if pkg.setup is not None else None
    for script in scripts or []:
        if script.name == executable:
            return next((p for p in pkg.publishers if p.module == script.module), None)
    return None


def _rviz_files(pkg: Package) -> list[tuple[str, str, int]]:
    """(source .rviz, launch file, line) for each -d of this package that the package holds: from
    every evaluated launch (XML and YAML too) when evaluated, the files RViz really loads (BK613
    says when it loads none); else read from the Python launch files."""
    from .evaluated import evaluations, rviz_uses

    evaluated = evaluations(pkg)
    if evaluated is not None:  # the files rviz2 really reads (installed, given with -d): as the page
        out, seen = [], set()
        for use in rviz_uses(pkg, evaluated):
            if use.source not in seen:
                seen.add(use.source)
                out.append((use.source, use.launch, use.line))
        return out
    installed = pkg.installed() or {}
    out = []
    for path, node in _rviz_starts(pkg):
        target = _config_argument(node)
        if isinstance(target, ShareFile) and target.package == pkg.name:
            source = installed.get(target.relative, target.relative)
            if os.path.isfile(os.path.join(pkg.root, source)):
                out.append((source, path, node.line))
    return out


def _config_argument(node: NodeCall) -> Any:
    """What follows ``-d`` in the node's arguments: a ShareFile, another value, or None (no -d)."""
    arguments = node.arguments
    if not isinstance(arguments, (list, tuple)):
        return None
    for k, item in enumerate(arguments):
        if item == "-d" and k + 1 < len(arguments):
            return arguments[k + 1]
        if isinstance(item, str) and item.startswith("-d") and len(item) > 2:
            return item[2:].strip()
    return None


def _rviz_starts(pkg: Package) -> Iterator[tuple[str, NodeCall]]:
    for launch in pkg.launch_files:
        for node in launch.nodes:
            if node.package == "rviz2":
                yield launch.path, node
