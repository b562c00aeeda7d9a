"""BK630-BK634: the package built as colcon builds it and launched as ``ros2 launch`` launches it.

:func:`~bras_kit.ros.launched.launch_package` is the one reading used by ``bras-kit launch`` and
``bras-kit validate PKG_DIR`` (:mod:`bras_kit.ros.launched`): setup.py is run (sandboxed) into a
temporary install tree, each launch file is evaluated, and robot_state_publisher is fed its
``robot_description``. Every mistake is a finding at the learner's file and line, with the
words ROS prints (``ros``) and the cause and fix chosen here.
"""

from __future__ import annotations

import os
import re
from collections.abc import Iterator
from typing import Any

from ...findings.registry import ERROR, Hit
from ...ros.build import BuildRecord
from ...ros.launched import Launched
from ...ros.launching import LaunchPlan
from ...ros.package import Package
from .evaluated import launched, place
from .rules import _at, package_rule

LAUNCH_CHECKS = ("BK630", "BK631", "BK632", "BK633", "BK634", "BK635", "BK639")  # BK639: build_reach (what setup.py and launch files tried)


# ------------------------------------------------------------------ reading, once per package


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
    from .install_rules import ament_index_marker_missing

    return any(True for _ in ament_index_marker_missing(pkg))


_PACKAGE_NOT_FOUND = re.compile(r"package '([^']+)' not found")
_NO_FILE = re.compile(r"No such file or directory: '([^']+)'")
_EXECUTABLE = re.compile(r"executable '([^']+)' not found on the libexec directory")


def _launch_variant(pkg: Package, result: Launched, message: str) -> tuple[str, dict[str, Any]]:
    found = _PACKAGE_NOT_FOUND.search(message)
    if found:
        from ...ros.launching import ROS_INSTALL
        from ..structure import closest

        name = found.group(1)
        known = result.build.package
        near = closest(name, [known, *ROS_INSTALL], cutoff=0.75)
        if near is not None and near != known:  # a ROS package misspelled ('robot_state_publiser')
            return "package_near", {"missing": name, "near": near}
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
        path = os.path.normpath(found.group(1)) if os.path.isabs(found.group(1)) else found.group(1)
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
    return _launch_misuse(result, message)


# launch 3.4.3's words for a value, an entity or a description it cannot take (see _launch_misuse)
_YAML_RULES = re.compile(r"using yaml rules: (?:yaml\.safe_load\(\) failed\n(?P<reason>[^\n]*)"
                         r"(?:\n\s*in \"<unicode string>\", line (?P<line>\d+))?|output type is not allowed)")
_MISSING_ATTRIBUTE = re.compile(r"Can not find attribute '(?P<a>[^']+)' in Entity '(?P<e>[^']+)'"
                                r"|Attribute '(?P<a2>[^']+)' of type '.*?' not found in Entity '(?P<e2>[^']+)'")
_UNEXPECTED = re.compile(r"Unexpected (?:attribute\(s\)|key\(s\)|nested tag\(s\)) found in `(?P<e>[^`]+)`: \{(?P<a>[^}]*)\}")
_UNKNOWN_TAG = re.compile(r"Unrecognized entity of the type: (\S+)")
_NO_DESCRIPTION = re.compile(r"'(\w+)' object has no attribute 'get_launch_arguments_with_include_launch_description")
# what learners write from the Python API where the front ends (launch_xml, launch_yaml) read another name
FRONTEND_NAMES = {"executable": "exec", "package": "pkg", "arguments": "args", "ros_arguments": "ros_args",
                  "parameters": "param", "remappings": "remap", "default_value": "default", "launch_arguments": "arg"}


def _frontend_fix(attribute: str, launch_file: str) -> str:
    return f"{attribute}=" if launch_file.endswith(".xml") else f"{attribute}:"


def _launch_misuse(result: Launched, message: str) -> tuple[str, dict[str, Any]]:
    """launch's own refusals: a value read with YAML rules (type_utils.py:255), an attribute the
    front end needs or does not know (launch_xml/entity.py:93, launch_yaml/entity.py:118,
    expose.py:108), a tag it does not know (expose.py:40), launch_arguments given as a dict
    (include_launch_description.py:150), a generate_launch_description() that returns no
    LaunchDescription (include_launch_description.py:156)."""
    launch = result.launch_file
    found = _YAML_RULES.search(message)
    if found:
        fix = {".xml": 'type="str" on the <param>', ".yaml": "type: str under the param",
               ".yml": "type: str under the param"}.get(os.path.splitext(launch)[1],
                                                        "ParameterValue(..., value_type=str)")
        return "yaml_rules", {"reason": found.group("reason") or "not a single value",
                              "text_line": found.group("line") or "?", "fix": fix}
    found = _MISSING_ATTRIBUTE.search(message)
    if found:
        attribute, entity = found.group("a") or found.group("a2"), found.group("e") or found.group("e2")
        written = next((k for k, v in FRONTEND_NAMES.items() if v == attribute), "")
        return "attribute_missing", {"attribute": attribute, "entity": entity, "written": written,
                                     "fix": _frontend_fix(attribute, launch)}
    found = _UNEXPECTED.search(message)
    if found:
        names = [n.strip().strip("'\"") for n in found.group("a").split(",") if n.strip()]
        fixes = [_frontend_fix(FRONTEND_NAMES[n], launch) for n in names if n in FRONTEND_NAMES]
        return ("attribute_renamed" if fixes else "attribute_unexpected"), {
            "entity": found.group("e"), "attributes": ", ".join(names), "fix": ", ".join(fixes)}
    found = _UNKNOWN_TAG.search(message)
    if found:
        return "tag_unknown", {"tag": found.group(1), "fixed": found.group(1).lower()}
    if "values to unpack (expected 2" in message:
        return "include_dict", {}
    if "'Node' expected 'parameters' to be one of [<class 'list'>]" in message:
        return "parameters_not_list", {}
    found = re.search(r"'(\w+)' object is not iterable", message)
    if found:
        return ("not_a_list" if found.group(1)[:1].isupper() else "not_text"), {"given": found.group(1)}
    if "does not contain the required function 'generate_launch_description()'" in message:
        return "no_generate", {}
    found = _NO_DESCRIPTION.search(message)
    if found:
        return "no_description", {"returned": "None" if found.group(1) == "NoneType" else found.group(1)}
    return "", {}


def _ros_words(plan: LaunchPlan, variant: str) -> str:
    """What ros2 launch prints; a value launch could not convert is shown by its first line only
    (it is the whole URDF)."""
    words = plan.ros2_launch_error
    if variant == "yaml_rules":
        words = re.sub(r"Failed to convert '(.*?)' using yaml rules",
                       lambda m: "Failed to convert '" + m.group(1).strip().splitlines()[0][:60] + " ...' using yaml rules",
                       words, count=1, flags=re.S)
    return words


def _where_generate(pkg: Package, result: Launched) -> int:
    """The line of ``def generate_launch_description`` in the launch file (0 if not found)."""
    from ...trust.learner_files import read_text

    try:
        text = read_text(os.path.join(pkg.root, result.launch_file), (pkg.root,), errors="replace")
    except OSError:
        return 0
    found = re.search(r"^\s*def\s+generate_launch_description\b", text, re.M)
    return text.count("\n", 0, found.start()) + 1 if found else 0


def _said_statically(pkg: Package, path: str) -> bool:
    """Whether the static reading already reports ``path`` (share-relative) as not installed."""
    from .install_rules import folder_not_installed, launch_opens_uninstalled_file

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
        file, line = place(result, plan.failure.file, plan.failure.line)
        if (file, line, plan.failure.message) in seen:
            continue  # an included file stops the file that includes it at the same line
        seen.add((file, line, plan.failure.message))
        params: dict[str, Any]
        if plan.failure.type == "Bound":  # bras-kit's own bound on a launch (the stand-in's launch/_plan.py)
            variant, params = ("too_many_nodes" if " nodes" in plan.failure.message else "log_flood"), {}
        else:
            variant, params = _launch_variant(pkg, result, plan.failure.message)
        if variant in ("not_installed", "no_file") and _said_statically(pkg, str(params["path"])):
            continue  # BK601/BK602 already name this file and the data_files entry to add
        if variant == "package" and params["missing"] == result.build.package and _marker_said(pkg):
            continue  # BK603: the package itself is not in the ament index
        if variant == "no_description" and not line:
            file, line = result.launch_file, _where_generate(pkg, result)
        yield _at(file, line or None, variant, ros=_ros_words(plan, variant), error=plan.failure.type,
                  launch=result.launch_file, **params)


@package_rule("BK634", "node-dies-on-its-ros-arguments", ERROR)
def node_dies_on_its_ros_arguments(pkg: Package) -> Iterator[Hit]:
    """A node whose command line rcl cannot read (rcl/src/rcl/arguments.c): '--log-level warn'
    given as one argument after --ros-args is an unknown ROS argument, and the node dies at init."""
    top = launched(pkg)
    if top is None:
        return
    seen = set()
    for result in _each(top):
        for node, problem in result.start_problems:
            file, line = place(result, node.file, node.line)
            if (file, line, problem.detail) in seen:
                continue
            seen.add((file, line, problem.detail))
            words = problem.detail.split(", ")
            fixed = ", ".join(repr(w) for one in words for w in one.split()) if problem.kind == "unknown_ros_args" else ""
            yield _at(file, line or None, problem.kind, ros="\n".join(problem.ros), node=node.shown,
                      unknown=problem.detail, fixed=fixed, launch=result.launch_file)


@package_rule("BK632", "robot-description-rejected", ERROR)
def robot_description_rejected(pkg: Package) -> Iterator[Hit]:
    top = launched(pkg)
    if top is None:
        return
    for result in _each(top):
        for node, problem in result.problems:
            if problem.kind == "file_fallback":
                continue
            file, line = place(result, node.file, node.line)
            yield _at(file, line or None, problem.kind, ros="\n".join(problem.ros), detail=problem.detail,
                      launch=result.launch_file)


@package_rule("BK635", "event-handler-never-fires", ERROR)
def event_handler_never_fires(pkg: Package) -> Iterator[Hit]:
    """OnProcessStart(target_action=X, on_start=[...]) where X never starts (never put in the
    description, or its condition false): the event never happens and what waits never starts
    (launch event_handlers/on_action_event_base.py: the handler matches the started action by identity)."""
    top = launched(pkg)
    if top is None:
        return
    seen = set()
    for result in _each(top):
        if result.plan is None or result.plan.failure is not None:
            continue
        for unfired in result.plan.unfired:
            file, line = place(result, unfired["file"], unfired["line"])
            if (file, line) in seen:
                continue
            seen.add((file, line))
            yield _at(file, line or None, target=unfired["target"], waiting=unfired["waiting"] or ["-"],
                      launch=result.launch_file)


@package_rule("BK633", "package-folders-inside-module", ERROR)
def package_folders_inside_module(pkg: Package) -> Iterator[Hit]:
    """``urdf/`` or ``launch/`` made inside the Python module folder: glob('urdf/*.urdf') in
    setup.py runs from the package folder and finds nothing there."""
    for folder in ("urdf", "launch"):
        inner = os.path.join(pkg.root, pkg.name, folder)
        if os.path.isdir(inner) and os.listdir(inner) and not os.path.isdir(os.path.join(pkg.root, folder)):
            yield _at(f"{pkg.name}/{folder}", None, folder=folder, package=pkg.name)
