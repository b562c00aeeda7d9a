"""BK6xx: the whole ROS 2 package, for the three pitfalls a URDF file alone cannot show.

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

from ...findings.registry import ERROR, INFO, Hit, hit, rule
from ...ros.joint_publishers import Publisher
from ...ros.launch_source import NodeCall
from ...ros.package import (
    INDEX_FOLDER,
    JOINT_STATE_PUBLISHERS,
    PACKAGE_XML,
    SETUP_PY,
    Package,
    share_targets,
)
from ...ros.staticpy import ShareFile, known

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


# ---------------------------------------------------------------- "file not found"


@package_rule("BK600", "package-file-unreadable", ERROR)
def package_file_unreadable(pkg: Package) -> Iterator[Hit]:
    # reading everything once records the files that could not be read
    pkg.manifest, pkg.setup, pkg.launch_files, pkg.publishers  # noqa: B018
    for source, _, _ in _rviz_files(pkg):
        pkg.rviz(source)
    for problem in pkg.problems:
        variant = "missing" if problem.detail == "missing" else ""
        yield _at(problem.path, _inside(pkg, problem.path, problem.line), variant, detail=problem.detail)
    from .setup_cfg import SETUP_CFG, _read

    _text, why = _read(pkg)  # a setup.cfg that is a pipe or a device: colcon and setuptools would wait on it
    if why is not None and why != "missing":
        yield _at(SETUP_CFG, None, "", detail=why)


def _inside(pkg: Package, relative: str, line: int | None) -> int | None:
    """``line``, or the file's last line when a parser points past the end ("no element found")."""
    if line is None or line <= 1:
        return line
    from ...trust.learner_files import read_bytes

    try:
        count = len(read_bytes(os.path.join(pkg.root, relative), (pkg.root,)).splitlines())
    except OSError:
        return line
    return min(line, max(count, 1))


@package_rule("BK601", "folder-not-installed", ERROR)
def folder_not_installed(pkg: Package) -> Iterator[Hit]:
    installed = pkg.installed()
    if installed is None or pkg.setup is None:
        return
    sources = set(installed.values())
    for folder, suffixes in REQUIRED_FOLDERS:
        files = pkg.files(folder, suffixes)
        left = [f for f in files if f not in sources]
        elsewhere = next((entry for entry in pkg.setup.data_files or []
                          if any(f in entry.sources for f in left)), None)
        if left and elsewhere is not None:  # listed, but into another folder ('share/' + name + 'urdf')
            slash = os.path.normpath(elsewhere.destination).replace(os.sep, "/") == f"share/{pkg.name}{folder}"
            yield _at(SETUP_PY, elsewhere.line, "slash" if slash else "elsewhere", folder=folder, files=left, package=pkg.name,
                      destination=elsewhere.destination, target=f"share/{pkg.name}/{folder}",
                      entry=_destination_text(pkg, folder))
            continue
        if left:
            pattern = next((f"*{s}" for s in suffixes if all(f.endswith(s) for f in left)), "*")
            yield _at(SETUP_PY, pkg.setup.data_files_line, "all" if len(left) == len(files) else "some",
                      folder=folder, files=left, package=pkg.name,
                      entry=_data_files_entry(pkg, folder, pattern, left))


def _destination_text(pkg: Package, folder: str) -> str:
    """share/PKG/folder as this setup.py would write it (os.path.join when it imports os)."""
    assert pkg.setup is not None
    defined = pkg.setup.defined
    name = "package_name" if defined.get("package_name") == "value" else repr(pkg.name)
    if defined.get("os") == "module":
        return f"os.path.join('share', {name}, '{folder}')"
    return f"'share/' + {name} + '/{folder}'" if name == "package_name" else f"'share/{pkg.name}/{folder}'"


def _data_files_entry(pkg: Package, folder: str, pattern: str, files: list[str]) -> str:
    """A data_files entry that works pasted into this very setup.py: it uses os, glob and
    package_name only when the file defines them (a ``ros2 pkg create`` setup.py imports neither)."""
    assert pkg.setup is not None
    defined = pkg.setup.defined
    target = _destination_text(pkg, folder)
    if defined.get("glob") == "value":
        sources = f"glob('{folder}/{pattern}')"
    elif defined.get("glob") == "module":
        sources = f"glob.glob('{folder}/{pattern}')"
    else:
        sources = "[" + ", ".join(repr(f) for f in files) + "]"
    return f"({target}, {sources})"


@package_rule("BK607", "setup-py-name-undefined", ERROR)
def setup_py_name_undefined(pkg: Package) -> Iterator[Hit]:
    """setup.py is a Python program: a name it never imports or defines stops colcon build."""
    if pkg.setup is None:
        return
    fixes = {"os": "import os", "glob": "from glob import glob", "package_name": f"package_name = '{pkg.name}'",
             "find_packages": "from setuptools import find_packages"}
    for name, line in pkg.setup.undefined:
        yield _at(SETUP_PY, line, "known" if name in fixes else "", undefined=name, fix=fixes.get(name, ""))


@package_rule("BK608", "next-step-not-written", INFO)
def next_step_not_written(pkg: Package) -> Iterator[Hit]:
    """What a package made as the tutorial makes it (``ros2 pkg create``, then one file per step)
    does not hold yet: the next step, not a mistake. Only the first missing step is named."""
    if pkg.setup is None:
        return
    if not pkg.files("urdf", REQUIRED_FOLDERS[0][1]):
        yield _at(SETUP_PY, None, "urdf", package=pkg.name)
    elif not pkg.files("launch", REQUIRED_FOLDERS[1][1]):
        yield _at(SETUP_PY, None, "launch", package=pkg.name)
    for script in pkg.setup.scripts or []:
        if _not_written(pkg, script.module):
            yield _at(SETUP_PY, script.line, "node", executable=script.name, module=script.module,
                      node_file=_module_file(script.module), package=pkg.name)


def _module_file(module: str) -> str:
    return module.replace(".", "/") + ".py"


def _not_written(pkg: Package, module: str) -> bool:
    """An entry's module that does not exist while no node of the package is left without an
    entry and no file of its name sits elsewhere: the node is still to write. Beside a node no
    entry runs, it is a misspelling; a file of its name elsewhere, a misplaced node (BK622)."""
    if _module_written(pkg, module) or _misplaced(pkg, module):
        return False
    listed = {s.module for s in (pkg.setup.scripts if pkg.setup is not None else None) or []}
    return not any(p.has_main and p.module not in listed for p in pkg.publishers)


def _module_written(pkg: Package, module: str) -> bool:
    return pkg.module_written(module)


def _misplaced(pkg: Package, module: str) -> list[str]:
    return pkg.misplaced(module)


@package_rule("BK602", "launch-opens-uninstalled-file", ERROR)
def launch_opens_uninstalled_file(pkg: Package) -> Iterator[Hit]:
    installed = pkg.installed()
    if installed is None:
        return
    for launch, share, line in share_targets(pkg):
        if share.relative in installed or any(k.startswith(share.relative.rstrip("/") + "/") for k in installed):
            continue
        folder = os.path.dirname(share.relative)
        if folder in dict(REQUIRED_FOLDERS) and not any(k.startswith(folder + "/") for k in installed):
            continue  # BK601 already says the whole folder is not installed
        if share.relative.endswith(".rviz"):
            continue  # given to rviz2 -d: RViz logs that it cannot load it and opens its defaults (BK613)
        there = sorted(k for k in installed if os.path.dirname(k) == folder)
        exists = os.path.isfile(os.path.join(pkg.root, share.relative))
        yield _at(launch.path, line, "exists" if exists else ("other" if there else ""),
                  path=share.relative, package=pkg.name, installed=there or ["-"], folder=folder or ".")


@package_rule("BK603", "ament-index-marker-missing", ERROR)
def ament_index_marker_missing(pkg: Package) -> Iterator[Hit]:
    name = pkg.name
    marker = f"resource/{name}"
    if not os.path.isfile(os.path.join(pkg.root, marker)):
        yield _at(marker, None, "file", package=name, marker=marker)
    setup = pkg.setup
    if setup is None or setup.data_files is None:
        return
    registered = any(os.path.normpath(e.destination).replace(os.sep, "/") == INDEX_FOLDER
                     and marker in e.sources for e in setup.data_files)
    if not registered:
        yield _at(SETUP_PY, setup.data_files_line, "entry", package=name, marker=marker)


@package_rule("BK604", "package-name-mismatch", ERROR)
def package_name_mismatch(pkg: Package) -> Iterator[Hit]:
    manifest, setup = pkg.manifest, pkg.setup
    if manifest is None or setup is None or not isinstance(setup.name, str) or manifest.name is None:
        return
    if manifest.name != setup.name:
        yield _at(PACKAGE_XML, manifest.name_line, xml_name=manifest.name, setup_name=setup.name,
                  setup_line=setup.name_line)


@package_rule("BK605", "missing-exec-depend", INFO)
def missing_exec_depend(pkg: Package) -> Iterator[Hit]:
    manifest = pkg.manifest
    if manifest is None:
        return
    seen: set[str] = set()
    for launch in pkg.launch_files:
        for node in launch.nodes:
            dependency = node.package
            if not isinstance(dependency, str) or dependency == pkg.name or dependency in seen:
                continue
            seen.add(dependency)
            if dependency not in manifest.exec_depends:
                yield _at(PACKAGE_XML, manifest.depends_line or manifest.line, dependency=dependency,
                          launch=launch.path, launch_line=node.line)


@package_rule("BK606", "invalid-maintainer-email", ERROR)
def invalid_maintainer_email(pkg: Package) -> Iterator[Hit]:
    manifest = pkg.manifest
    if manifest is None:
        return
    if not manifest.maintainers:
        yield _at(PACKAGE_XML, manifest.line, "none")
    for email, name, line in manifest.maintainers:
        if not email:
            yield _at(PACKAGE_XML, line, "missing", maintainer=name)
        elif not EMAIL.match(email):
            yield _at(PACKAGE_XML, line, "", maintainer=name, email=email)


# ---------------------------------------------------------------- "RViz reste vide"


def _rviz_starts(pkg: Package) -> Iterator[tuple[str, NodeCall]]:
    for launch in pkg.launch_files:
        for node in launch.nodes:
            if node.package == "rviz2":
                yield launch.path, node


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


def _description_topic_mismatches(pkg: Package, source: str, value: str) -> list[tuple[str, list[str], str]] | None:
    """(the topic RViz subscribes to, the topics robot_state_publisher publishes, the launch file)
    for each evaluated launch that gives ``source`` to RViz beside a robot_state_publisher, as rcl
    resolves both names (namespace, remappings, ``~/``: bras_kit/ros/names.py). None when no
    evaluated launch tells (then the root topic /robot_description is the reference)."""
    from .evaluated import description_topics, evaluations, rviz_uses

    told = False
    out = []
    for use in rviz_uses(pkg, evaluations(pkg) or []):
        published = description_topics(use.result)
        if use.source != source or not published:
            continue
        told = True
        heard = use.node.resolve(value)
        if heard not in published:
            out.append((heard, sorted(published), use.launch))
    return out if told else None


def _rviz_lines(lines: list[str], key: str, start: int = 0) -> int | None:
    for k in range(start, len(lines)):
        if lines[k].strip().startswith(key):
            return k + 1
    return None


@package_rule("BK610", "rviz-fixed-frame-not-a-link", ERROR)
def rviz_fixed_frame_not_a_link(pkg: Package) -> Iterator[Hit]:
    from ...ros.rviz.config import fixed_frame_of

    robot = pkg.robot
    if robot is None:
        return
    links = [link.name for link in robot.links if link.name]
    if any(launch.includes for launch in pkg.launch_files):
        return  # other frames may be published (static transforms, included launch files)
    root = _root(robot) or (links[0] if links else "base")
    forced: set[str | None] = set()  # the .rviz files whose Fixed Frame rviz2's -f replaces
    said = set()
    for result, start in _rviz_started(pkg):
        if not start.fixed_frame:
            continue
        if start.file is not None:
            forced.add(result.build.source_of(os.path.normpath(start.file)))
        file, line = _place(result, start.node.file, start.node.line)
        if start.config.fixed_frame not in links and (file, line) not in said:
            said.add((file, line))
            yield _at(file, line or None, "argument", frame=start.config.fixed_frame, links=links, root=root)
    for source, _, _ in _rviz_files(pkg):
        if source in forced:
            continue
        parsed = pkg.rviz(source)
        if parsed is None:
            continue
        data, lines = parsed
        # the Fixed Frame as RViz takes it from the file (the page reads it the same way)
        frame, set_in_file = fixed_frame_of(data)
        if frame in links:
            continue
        if not set_in_file:
            yield _at(source, _rviz_lines(lines, "Global Options:"), "missing", frame=frame, root=root)
        else:
            yield _at(source, _rviz_lines(lines, "Fixed Frame:"), frame=str(frame), links=links, root=root)


def _rviz_started(pkg: Package) -> Iterator[tuple[Any, Any]]:
    """(evaluated launch, how its rviz2 starts: ros.rviz.started) for each evaluated launch with rviz2."""
    from ...ros.rviz.started import started
    from .evaluated import evaluations

    for result in evaluations(pkg) or []:
        start = started(result.plan)
        if start is not None:
            yield result, start


def _place(result: Any, file: str, line: int) -> tuple[str, int]:
    from .evaluated import place

    return place(result, file, line)


def _root(robot: Any) -> str | None:
    children = {j.child for j in robot.joints}
    return next((link.name for link in robot.links if link.name and link.name not in children), None)


@package_rule("BK611", "rviz-robot-model-not-shown", ERROR)
def rviz_robot_model_not_shown(pkg: Package) -> Iterator[Hit]:
    for source, _, _ in _rviz_files(pkg):
        parsed = pkg.rviz(source)
        if parsed is None:
            continue
        _, lines = parsed
        # the page's reading, RViz's (bras_kit.ros.rviz.config): every scalar a string, a display
        # unchecked unless Value/Enabled say so and Enabled read last (display.cpp:277-291), an
        # unknown Description Source read as Topic (enum_property.cpp:65-73)
        from ...ros.rviz.config import read_config

        models = [d for d in read_config("\n".join(lines)).displays if d.kind.endswith("/RobotModel")]
        if not models:
            yield _at(source, _rviz_lines(lines, "Displays:"), "missing")
            continue
        model = models[0]
        start = (_rviz_lines(lines, "Class: rviz_default_plugins/RobotModel") or 1) - 1
        if not model.enabled:
            yield _at(source, start + 1, "disabled")
        if model.description_source != "Topic":
            continue
        value = model.description_topic
        line = _rviz_lines(lines, "Description Topic:", start) or start + 1
        mismatches = _description_topic_mismatches(pkg, source, str(value)) if isinstance(value, str) and value \
            else None
        if mismatches is None:
            if value != ROBOT_DESCRIPTION:
                yield _at(source, line, "topic", topic=str(value if value is not None else ""))
            continue
        for heard, published, launch in dict.fromkeys((h, tuple(p), lf) for h, p, lf in mismatches):
            plain = list(published) == [ROBOT_DESCRIPTION]
            yield _at(source, line, "topic" if plain and heard == value else "namespace", topic=heard,
                      published=", ".join(published), launch=launch)


@package_rule("BK612", "rviz-no-tf-display", INFO)
def rviz_no_tf_display(pkg: Package) -> Iterator[Hit]:
    for source, _, _ in _rviz_files(pkg):
        parsed = pkg.rviz(source)
        if parsed is None:
            continue
        _, lines = parsed
        from ...ros.rviz.config import TF, read_config

        if not any(d.kind == TF for d in read_config("\n".join(lines)).displays):  # RViz's reading (the page's)
            yield _at(source, _rviz_lines(lines, "Displays:"))


@package_rule("BK613", "rviz-without-configuration", INFO)
def rviz_without_configuration(pkg: Package) -> Iterator[Hit]:
    """RViz opens its default configuration: the launch's rviz2 as :mod:`bras_kit.ros.rviz.started`
    starts it (the page's RViz is that same start), or, with no evaluation, as the Python launch
    files read."""
    from .evaluated import evaluations

    results = evaluations(pkg)
    if results is None:
        yield from _rviz_default_in_sources(pkg)
        return
    yield from _rviz_default_started(pkg)


def _rviz_default_started(pkg: Package) -> Iterator[Hit]:
    said = set()
    for result, start in _rviz_started(pkg):
        if start.read:
            continue
        file, line = _place(result, start.node.file, start.node.line)
        if (file, line) in said:
            continue  # an included launch file's rviz2, said once
        said.add((file, line))
        if start.given is None:  # no -d (visualization_frame.cpp:345-349): the default, empty
            configs = pkg.files("rviz", (".rviz",))
            yield _at(file, line or None, "unused" if configs else "", config=configs[0] if configs else "",
                      package=pkg.name)
            continue
        # a -d RViz cannot load: it logs so and opens its default (visualization_frame.cpp:674-676)
        share = os.path.join(result.build.prefix, "share", pkg.name) + os.sep
        config = os.path.normpath(start.given)
        if not config.startswith(share) or result.build.source_of(config) is not None:
            continue  # another package's file, a folder of the learner's, or installed yet unreadable
        inside = config[len(share):]
        variant = "not_installed" if os.path.isfile(os.path.join(pkg.root, inside)) else "missing"
        yield _at(file, line or None, variant, config=inside, package=pkg.name)


def _rviz_default_in_sources(pkg: Package) -> Iterator[Hit]:
    """BK613 read from the Python launch files, when no launch was evaluated (``validate`` without
    ``--launch``): -d to a file of the package's share folder, or no -d."""
    installed = pkg.installed()
    for path, node in _rviz_starts(pkg):
        target = _config_argument(node)
        if isinstance(target, ShareFile) and target.package == pkg.name and target.relative.endswith(".rviz"):
            if not os.path.isfile(os.path.join(pkg.root, target.relative)):
                yield _at(path, node.line, "missing", config=target.relative, package=pkg.name)
            elif installed is not None and target.relative not in installed:
                yield _at(path, node.line, "not_installed", config=target.relative, package=pkg.name)
            continue
        if not known(node.arguments) or target is not None:
            continue
        configs = pkg.files("rviz", (".rviz",))
        yield _at(path, node.line, "unused" if configs else "", config=configs[0] if configs else "",
                  package=pkg.name)


@package_rule("BK615", "rviz-not-started", INFO)
def rviz_not_started(pkg: Package) -> Iterator[Hit]:
    """robot_state_publisher started, no rviz2 (ros.rviz.started finds none: the page opens no RViz)."""
    from ...ros.rviz.started import started
    from .evaluated import evaluations, standing_alone

    for result in standing_alone(evaluations(pkg) or []):
        rsp = [n for n in result.plan.nodes if n.package == "robot_state_publisher"]
        if not rsp or started(result.plan) is not None or _included(pkg, result.launch_file):
            continue
        if result.plan.included or result.plan.processes:
            continue  # an included launch file, or a process bras-kit does not know, may start RViz
        file, line = _place(result, rsp[0].file, rsp[0].line)
        yield _at(file, line or None)


# ---------------------------------------------------------------- "le robot ne bouge pas"


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


def _own_executables(pkg: Package) -> list[tuple[str, NodeCall]]:
    return [(launch.path, node) for launch in pkg.launch_files for node in launch.nodes
            if node.package == pkg.name]


def _publisher_for(pkg: Package, executable: Any) -> Publisher | None:
    scripts = pkg.setup.scripts if pkg.setup is not None else None
    for script in scripts or []:
        if script.name == executable:
            return next((p for p in pkg.publishers if p.module == script.module), None)
    return None


@package_rule("BK620", "no-joint-state-source", ERROR)
def no_joint_state_source(pkg: Package) -> Iterator[Hit]:
    from .evaluated import (
        evaluations,
        joint_state_sources,
        joint_state_topics,
        place,
        standing_alone,
    )

    results = evaluations(pkg) or []
    movable = [j.name for j in pkg.robot.movable_joints()] if pkg.robot is not None else []
    heard = [p for p in pkg.publishers if _on_joint_states(p.topic)]  # BK624 speaks of the others
    # evaluated: each launch as ros2 launch runs it, an included file judged with the file that includes it
    for result in standing_alone(results):
        if _included(pkg, result.launch_file):
            continue  # judged with the file that includes it (BK631 when that one stops)
        rsp = [n for n in result.plan.nodes if n.package == "robot_state_publisher"]
        if not rsp:
            continue
        file, line = place(result, rsp[0].file, rsp[0].line)
        if not joint_state_sources(result, lambda executable: _publisher_for(pkg, executable) is not None):
            yield _at(file, line or None, "nodes" if heard else "", joints=movable or ["?"],
                      node=heard[0].module if heard else "")
            continue
        # rcl's names: the sliders at the root beside a namespaced robot_state_publisher are not heard
        listens, sources = joint_state_topics(result, lambda executable: _publisher_for(pkg, executable))
        in_code = {n.full_name for n in result.plan.nodes if n.package == pkg.name
                   and (p := _publisher_for(pkg, n.executable)) is not None and not _on_joint_states(p.topic)}
        if all(who in in_code for who, _ in sources):
            continue  # BK624 names the topic written in the node
        if sources and all(topic is not None and topic not in listens for _, topic in sources):
            yield _at(file, line or None, "topic", joints=movable or ["?"], listens=", ".join(sorted(listens)),
                      sources=", ".join(f"{who} -> {topic}" for who, topic in sources))
    evaluated = {r.launch_file for r in results}
    for launch in pkg.launch_files:  # the Python launch files no evaluation judged
        if launch.path in evaluated:
            continue
        nodes = launch.nodes
        starts_rsp = any(n.package == "robot_state_publisher" for n in nodes)
        if not starts_rsp or launch.includes or _included(pkg, launch.path):
            continue  # another launch file or process may publish the joint states
        if any(n.package in JOINT_STATE_PUBLISHERS or not isinstance(n.package, str) for n in nodes):
            continue
        own = [n for n in nodes if n.package == pkg.name]
        if any(not isinstance(n.executable, str) or _publisher_for(pkg, n.executable) is not None for n in own):
            continue
        line = next(n.line for n in nodes if n.package == "robot_state_publisher")
        yield _at(launch.path, line, "nodes" if heard else "", joints=movable or ["?"],
                  node=heard[0].module if heard else "")


@package_rule("BK621", "joint-state-names-mismatch", ERROR)
def joint_state_names_mismatch(pkg: Package) -> Iterator[Hit]:
    robot = pkg.robot
    if robot is None:
        return
    movable = [j.name for j in robot.movable_joints() if j.name]
    for publisher in pkg.publishers:
        if publisher.names is None:
            continue
        unknown = [n for n in publisher.names if n not in movable]
        missing = [n for n in movable if n not in publisher.names]
        line = publisher.names_line or publisher.line
        if unknown:
            yield _at(publisher.path, line, "unknown_one" if len(unknown) == 1 else "unknown", names=unknown,
                      joints=movable)
        if missing:
            yield _at(publisher.path, line, "missing_one" if len(missing) == 1 else "missing", names=missing,
                      published=publisher.names or ["-"])


@package_rule("BK622", "node-entry-point-missing", ERROR)
def node_entry_point_missing(pkg: Package) -> Iterator[Hit]:
    setup = pkg.setup
    if setup is None or setup.scripts is None:
        return
    scripts = {s.name: s for s in setup.scripts}
    for path, node in _own_executables(pkg):
        if isinstance(node.executable, str) and node.executable.endswith(".py") and node.executable[:-3] in scripts:
            continue  # BK631: the executable is the console_scripts name, without .py
        if isinstance(node.executable, str) and node.executable not in scripts:
            yield _at(path, node.line, "launch", executable=node.executable, package=pkg.name,
                      entry=_entry_text(node.executable, f"{pkg.name}.{node.executable}"))
    listed = {s.module for s in setup.scripts}
    misplaced = {script.module: _misplaced(pkg, script.module) for script in setup.scripts
                 if not _module_written(pkg, script.module)}
    for publisher in pkg.publishers:
        if any(publisher.path in files for files in misplaced.values()):
            continue  # the node an entry names, in the wrong folder: said below
        if publisher.has_main and publisher.module not in listed:
            executable = publisher.module.rsplit(".", 1)[-1]
            yield _at(SETUP_PY, setup.scripts_line, "node", module=publisher.module, node_file=publisher.path,
                      package=pkg.name, executable=executable, entry=_entry_text(executable, publisher.module))
    for script in setup.scripts:
        if _not_written(pkg, script.module):
            continue  # BK608: the node is the learner's next step
        if misplaced.get(script.module):
            yield _at(SETUP_PY, script.line, "elsewhere", executable=script.name, module=script.module,
                      node_file=_module_file(script.module), found=misplaced[script.module],
                      moved=misplaced[script.module][0], package=pkg.name)
            continue
        tree = pkg.module_tree(script.module)
        if tree is None:
            yield _at(SETUP_PY, script.line, "module", executable=script.name, module=script.module)
        elif script.function and not any(getattr(n, "name", None) == script.function for n in tree.body):
            yield _at(SETUP_PY, script.line, "function", executable=script.name, module=script.module,
                      function=script.function)


def _entry_text(executable: str, module: str) -> str:
    return f"'{executable} = {module}:main'"


@package_rule("BK623", "node-motion-outside-limits", ERROR)
def node_motion_outside_limits(pkg: Package) -> Iterator[Hit]:
    robot = pkg.robot
    if robot is None:
        return
    movable = {j.name for j in robot.movable_joints()}
    for publisher in pkg.publishers:
        if publisher.degrees:
            continue  # BK626 names the cause: the node's angles are in degrees
        formulas = {joint: text for joint, text in publisher.formulas.items() if joint in movable}
        for joint, text, violation in _violations(robot, formulas):
            yield _at(publisher.path, publisher.formulas_line or publisher.line, violation.side,
                      joint=joint, formula=text, value=round(violation.value, 3), time=round(violation.time, 2),
                      bound=violation.bound, unit=violation.unit)


def _violations(robot: Any, formulas: dict[str, str]) -> Iterator[tuple[str, str, Any]]:
    """Position limit violations of each formula, as the motion module's sampling and checks find
    them (followed with Python floats: validating a package needs no numpy, issue 43)."""
    if not formulas:
        return
    from ...core.errors import BrasKitError
    from ...motion.formula_limits import formula_position_violations

    for joint, text in formulas.items():
        try:
            violations = formula_position_violations(robot, joint, text, MOTION_SECONDS)
        except BrasKitError:
            continue  # not a formula the motion module accepts: not literal enough to judge
        for violation in violations:
            yield joint, text, violation


@package_rule("BK614", "robot-description-not-given", ERROR)
def robot_description_not_given(pkg: Package) -> Iterator[Hit]:
    """robot_state_publisher needs the URDF text in its robot_description parameter."""
    for launch in pkg.launch_files:
        for node in launch.nodes:
            if node.package != "robot_state_publisher" or node.parameters is None:
                continue  # parameters built in a way only running the file would tell
            if node.arguments:
                continue  # robot_state_publisher reads a file argument (its deprecated fallback): BK632 checks it
            if "robot_description" not in node.parameters:
                yield _at(launch.path, node.line, "" if node.has_parameters else "none",
                          fix="parameters=[{'robot_description': description}]")


# ---------------------------------------------------------------- the node, read without running it


def _on_joint_states(topic: Any) -> bool:
    return not isinstance(topic, str) or topic.strip().lstrip("/") == "joint_states"


@package_rule("BK624", "joint-state-topic-wrong", ERROR)
def joint_state_topic_wrong(pkg: Package) -> Iterator[Hit]:
    """robot_state_publisher listens on /joint_states only: any other literal topic is heard by nobody
    — unless a launch file remaps it (or namespaces both) so that rcl resolves it to the topic
    robot_state_publisher listens on (evaluated launches only: names.py)."""
    heard_through_launch = _topics_heard_through_launch(pkg)
    for publisher in pkg.publishers:
        if publisher.module in heard_through_launch:
            continue
        if not _on_joint_states(publisher.topic):
            yield _at(publisher.path, publisher.topic_line, topic=publisher.topic,
                      fix="self.create_publisher(JointState, 'joint_states', 10)")


def _topics_heard_through_launch(pkg: Package) -> set[str]:
    """The modules whose JointState topic an evaluated launch makes robot_state_publisher hear."""
    from .evaluated import evaluations, joint_state_topics

    out = set()
    for result in evaluations(pkg) or []:
        listens, _ = joint_state_topics(result, lambda executable: None)
        for node in result.plan.nodes:
            publisher = _publisher_for(pkg, node.executable) if node.package == pkg.name else None
            if publisher is not None and isinstance(publisher.topic, str) and publisher.topic \
                    and node.resolve(publisher.topic) in listens:
                out.add(publisher.module)
    return out


@package_rule("BK625", "joint-state-never-sent", ERROR)
def joint_state_never_sent(pkg: Package) -> Iterator[Hit]:
    """A JointState publisher whose message is never published, or whose callback nothing runs."""
    for publisher in pkg.publishers:
        if not publisher.publishes:
            yield _at(publisher.path, publisher.line, "publish", fix="self.pub.publish(msg)")
        elif not publisher.scheduled:
            yield _at(publisher.path, publisher.line, "timer", fix="self.timer = self.create_timer(0.05, self.tick)")


@package_rule("BK626", "joint-state-in-degrees", ERROR)
def joint_state_in_degrees(pkg: Package) -> Iterator[Hit]:
    """JointState positions are radians (metres for prismatic joints); degrees turn the arm 57 times too far."""
    for publisher in pkg.publishers:
        for line, what in publisher.degrees:
            yield _at(publisher.path, line, what=what)
