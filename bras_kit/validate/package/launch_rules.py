"""BK630-BK634: the package built as colcon builds it and launched as ``ros2 launch`` launches it.

:func:`launch_package` is the one reading used by ``bras-kit launch`` and ``bras-kit validate
PKG_DIR``: setup.py is run (sandboxed) into a temporary install tree (:mod:`bras_kit.ros.build`),
each launch file is evaluated (:mod:`bras_kit.ros.launching`), and robot_state_publisher is fed
its ``robot_description``. Every mistake is a finding at the learner's file and line, with the
words ROS prints (``ros``) and the cause and fix chosen here.
"""

from __future__ import annotations

import os
import re
import tempfile
from collections.abc import Iterator
from dataclasses import dataclass, field
from typing import Any

from ...ros.build import BuildRecord, build_package
from ...ros.launching import (
    LaunchPlan,
    PlannedNode,
    StartProblem,
    plan_launch,
    robot_state_publisher_start,
)
from ..registry import ERROR, Hit
from .rules import _at, package_rule
from .sources import Package, relative

LAUNCH_CHECKS = ("BK630", "BK631", "BK632", "BK633")


@dataclass
class Launched:
    build: BuildRecord
    launch_file: str = ""  # package-relative source of the launch file
    plan: LaunchPlan | None = None
    description: str | None = None  # the URDF robot_state_publisher loads
    problems: list[tuple[PlannedNode, StartProblem]] = field(default_factory=list)
    others: dict[str, Launched] = field(default_factory=dict)  # the other launch files, by source


def _launch_sources(build: BuildRecord) -> list[str]:
    return sorted(i.source for i in build.installed
                  if i.target.startswith(f"share/{build.package}/") and
                  i.source.endswith((".launch.py", "_launch.py", ".launch.xml", ".launch.yaml", ".launch.yml")))


def launch_package(root: str, install_base: str, launch_file: str | None = None,
                   arguments: dict[str, str] | None = None, *, prefixes: tuple[str, ...] = ()) -> Launched:
    """Build ``root`` into ``install_base`` and evaluate ``launch_file`` (a name in its launch/
    folder, default: the first installed one) as ``ros2 launch PKG FILE`` would."""
    build = build_package(root, install_base)
    result = Launched(build)
    if build.failure is not None:
        return result
    sources = _launch_sources(build)
    if launch_file is not None:
        chosen = [s for s in sources if os.path.basename(s) == os.path.basename(launch_file)]
        result.launch_file = chosen[0] if chosen else launch_file
    elif sources:
        result.launch_file = sources[0]
    if not result.launch_file:
        return result
    target = next((i.target for i in build.installed if i.source == result.launch_file), None)
    if target is None:
        return result
    plan = plan_launch(os.path.join(build.prefix, target), [build.prefix, *prefixes], arguments,
                       learner_roots=(root,))
    result.plan = plan
    for node in plan.nodes:
        if node.package == "robot_state_publisher":
            text, problems = robot_state_publisher_start(node)
            result.problems += [(node, p) for p in problems]
            if text is not None and result.description is None:
                result.description = text
    return result


# ------------------------------------------------------------------ reading, once per package

_CACHE: dict[int, Launched] = {}


def launched(pkg: Package) -> Launched | None:
    """The package built and its launch files evaluated (kept on the Package)."""
    kept = getattr(pkg, "_launched", None)
    if kept is not None:
        return kept
    if not os.path.isfile(os.path.join(pkg.root, "package.xml")):
        return None
    with tempfile.TemporaryDirectory(prefix="bras-kit-build-") as base:
        first = launch_package(pkg.root, os.path.join(base, "install"))
        if first.plan is not None:
            for other in _launch_sources(first.build):
                if other != first.launch_file:
                    first.others[other] = launch_package(pkg.root, os.path.join(base, "install"), other)
    pkg._launched = first  # type: ignore[attr-defined]
    return first


def installed_descriptions(packages: list[Package]) -> list[str]:
    """The .urdf files the packages install (what their launch files can load): each is checked as
    the learner wrote it, never as the output of a xacro file beside it."""
    out = []
    for pkg in packages:
        result = launched(pkg)
        if result is not None:
            out += [os.path.join(pkg.shown_root, i.source) for i in result.build.installed if i.source.endswith(".urdf")]
    return out


def _each(result: Launched) -> Iterator[Launched]:
    yield result
    yield from result.others.values()


def _place(result: Launched, file: str, line: int) -> tuple[str, int]:
    """A file of the install tree (or the package) as the package file it came from."""
    if not file:
        return result.launch_file, 0
    source = result.build.source_of(file)
    if source is not None:
        return source, line
    if file.startswith(result.build.root + os.sep):
        return relative(result.build.root, file), line
    return result.launch_file, 0


# ------------------------------------------------------------------ the rules


def build_hits(record: BuildRecord, root: str) -> Iterator[Hit]:
    """BK630's hits for a build that stopped (``bras-kit build`` shows them too)."""
    failure = record.failure
    if failure is None or failure.kind in ("no_setup", "no_setup_call"):
        return  # BK600 says the file is missing or holds no setup(...)
    variant = failure.kind
    if failure.kind == "missing_source" and failure.source == f"resource/{record.package}":
        variant = "marker"
    elif failure.kind == "missing_source" and os.path.isdir(os.path.join(root, failure.source)):
        variant = "folder"
    yield _at(failure.file, failure.line or None, variant, package=record.package,
              colcon="\n".join(failure.colcon), source=failure.source, detail=failure.detail,
              folder=failure.source.rsplit("/", 1)[0] if "/" in failure.source else failure.source)


@package_rule("BK630", "colcon-build-fails", ERROR)
def colcon_build_fails(pkg: Package) -> Iterator[Hit]:
    result = launched(pkg)
    if result is None:
        return
    for found in build_hits(result.build, pkg.root):
        if found.variant == "marker" and _marker_said(pkg):
            continue  # BK603 names the missing marker and the fix
        if found.variant == "setup_raised" and pkg.setup is None:
            continue  # BK600: setup.py cannot even be read (a syntax error)
        yield found


def _marker_said(pkg: Package) -> bool:
    from .rules import ament_index_marker_missing

    return any(True for _ in ament_index_marker_missing(pkg))


_PACKAGE_NOT_FOUND = re.compile(r"package '([^']+)' not found")
_NO_FILE = re.compile(r"No such file or directory: '([^']+)'")
_EXECUTABLE = re.compile(r"executable '([^']+)' not found on the libexec directory")


def _launch_variant(pkg: Package, result: Launched, message: str) -> tuple[str, dict[str, Any]]:
    found = _PACKAGE_NOT_FOUND.search(message)
    if found:
        name = found.group(1)
        known = result.build.package
        return "package", {"missing": name, "known": known}
    found = _EXECUTABLE.search(message)
    if found:
        names = [s[0] for s in result.build.scripts]
        executable = found.group(1)
        if executable.endswith(".py") and executable[:-3] in names:
            return "executable_py", {"executable": executable, "fixed": executable[:-3]}
        return "executable", {"executable": executable, "names": ", ".join(names) or "-"}
    found = _NO_FILE.search(message)
    if found:
        path = found.group(1)
        if not os.path.isabs(path):
            return "relative", {"path": path, "package": result.build.package,
                                "fixed": f"os.path.join(get_package_share_directory('{result.build.package}'), "
                                         f"{', '.join(repr(p) for p in path.split('/'))})"}
        share = os.path.join(result.build.prefix, "share", result.build.package) + os.sep
        if path.startswith(share):
            inside = path[len(share):]
            exists = os.path.isfile(os.path.join(pkg.root, inside))
            return ("not_installed" if exists else "no_file"), {"path": inside, "package": result.build.package}
        return "file", {"path": path}
    if "ParameterValue" in message:
        return "yaml", {}
    return "", {}


def _said_statically(pkg: Package, path: str) -> bool:
    """Whether the static reading already reports ``path`` (share-relative) as not installed."""
    from .rules import folder_not_installed, launch_opens_uninstalled_file

    for found in folder_not_installed(pkg):
        if path in [str(f) for f in found.params.get("files", [])]:  # type: ignore[attr-defined]
            return True
    return any(found.params.get("path") == path for found in launch_opens_uninstalled_file(pkg))


@package_rule("BK631", "ros2-launch-fails", ERROR)
def ros2_launch_fails(pkg: Package) -> Iterator[Hit]:
    top = launched(pkg)
    if top is None:
        return
    seen = set()
    for result in _each(top):
        plan = result.plan
        if plan is None or plan.failure is None:
            continue
        file, line = _place(result, plan.failure.file, plan.failure.line)
        if (file, line, plan.failure.message) in seen:
            continue  # an included file stops the file that includes it at the same line
        seen.add((file, line, plan.failure.message))
        variant, params = _launch_variant(pkg, result, plan.failure.message)
        if variant in ("not_installed", "no_file") and _said_statically(pkg, str(params["path"])):
            continue  # BK601/BK602 already name this file and the data_files entry to add
        if variant == "package" and params["missing"] == result.build.package and _marker_said(pkg):
            continue  # BK603: the package itself is not in the ament index
        yield _at(file, line or None, variant, ros=plan.ros2_launch_error, error=plan.failure.type,
                  launch=result.launch_file, **params)


@package_rule("BK632", "robot-description-rejected", ERROR)
def robot_description_rejected(pkg: Package) -> Iterator[Hit]:
    top = launched(pkg)
    if top is None:
        return
    for result in _each(top):
        for node, problem in result.problems:
            if problem.kind == "file_fallback":
                continue
            file, line = _place(result, node.file, node.line)
            yield _at(file, line or None, problem.kind, ros="\n".join(problem.ros), detail=problem.detail,
                      launch=result.launch_file)


@package_rule("BK633", "package-folders-inside-module", ERROR)
def package_folders_inside_module(pkg: Package) -> Iterator[Hit]:
    """``urdf/`` or ``launch/`` made inside the Python module folder: glob('urdf/*.urdf') in
    setup.py runs from the package folder and finds nothing there."""
    for folder in ("urdf", "launch"):
        inner = os.path.join(pkg.root, pkg.name, folder)
        if os.path.isdir(inner) and os.listdir(inner) and not os.path.isdir(os.path.join(pkg.root, folder)):
            yield _at(f"{pkg.name}/{folder}", None, folder=folder, package=pkg.name)
