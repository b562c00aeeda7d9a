"""What ``colcon build`` does for an ament_python package, as data: the install tree.

colcon (colcon-ros's ament_python task, then setuptools' ``install``) runs the package's
``setup.py`` and lays out ``install/PKG/``: ``share/...`` from ``data_files`` (the ament index
marker among them), the Python packages under ``lib/pythonX.Y/site-packages/`` and one
script per ``console_scripts`` entry under ``lib/PKG/`` (where ``ros2 run`` and launch_ros's
ExecutableInPackage look). Here ``setup.py`` runs in the sandbox child with the real ``os`` and
``glob`` and a ``setuptools`` whose ``setup()`` only records its arguments; the parent then
copies the files. A mistake stops the build as colcon stops it, as data (:class:`BuildFailure`):
the words colcon prints first, the cause and fix chosen by the feature above.

::

    from ..ros.build import build_package
    record = build_package("src/bras_description", "install")
    record.failure            # None when colcon would say "Finished <<< bras_description"
    record.prefix             # install/bras_description
"""

from __future__ import annotations

import errno
import os
import re
import sys
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any, cast

from .attempts import Attempt
from .catkin import Manifest
from .setup_check import CheckedSetup, Installed, Refusal, check_setup, name_problem

__all__ = ["BuildFailure", "BuildRecord", "Installed", "build_package"]

SETUP_CPU_SECONDS = 10
SETUP_WALL_SECONDS = 20.0
SETUP_MEMORY_BYTES = 512 << 20
INDEX = "share/ament_index/resource_index/packages"
PYTHON_LIB = f"lib/python{sys.version_info[0]}.{sys.version_info[1]}/site-packages"
COLCON_MARKER = "share/colcon-core/packages"  # colcon-core writes share/colcon-core/packages/PKG in every prefix


@dataclass(frozen=True)
class BuildFailure:
    """Why colcon would stop. ``kind``: "ament_cmake", "no_setup", "setup_raised", "no_setup_call",
    "missing_source" (the marker when ``source`` is resource/PKG), "outside"; and what bras-kit
    refuses to act on (:mod:`.setup_check`): "name", "source_<why>" (a data_files, packages or
    scripts path outside the package, a link out, a device...), "module", "entry_point", "value",
    "prefix" (install/PKG is not an install tree), "install"; ``colcon``: the lines colcon prints
    (its own words and setuptools'); ``file``/``line`` the learner's place."""

    kind: str
    colcon: tuple[str, ...]
    file: str = ""
    line: int = 0
    source: str = ""
    detail: str = ""


@dataclass
class BuildRecord:
    """A package as ``colcon build`` would have installed it: what went where, its console scripts, or why not."""

    package: str
    root: str  # the package folder (absolute)
    prefix: str  # install/PKG (absolute)
    installed: list[Installed] = field(default_factory=list)
    scripts: list[tuple[str, str, str]] = field(default_factory=list)  # (name, module, function)
    setup_line: int = 0
    data_files_line: int = 0
    failure: BuildFailure | None = None
    blocked: list[Attempt] = field(default_factory=list)  # what setup.py tried that its walls stopped
    script_dir: str = ""  # where the scripts land, relative to the prefix (lib/PKG with the tutorial's setup.cfg)
    run_depends: tuple[str, ...] = ()  # colcon-core's share/colcon-core/packages/PKG
    data_folders: list[str] = field(default_factory=list)  # data_files' target folders
    build: str = ""  # build/PKG, with --symlink-install only: what the install tree's links point to
    ros: bool = False  # colcon-ros identified it (package.xml read by catkin_pkg); else a plain Python package
    refused_manifest: str = ""  # catkin_pkg's words when it refused package.xml (colcon says nothing of it)

    def source_of(self, path: str) -> str | None:
        """The package file installed at ``path`` (absolute, in the install tree), if any."""
        full = os.path.abspath(path)
        for item in self.installed:
            if os.path.join(self.prefix, item.target) == full:
                return item.source
        return None


def _failed(package: str, lines: list[str]) -> tuple[str, ...]:
    return (f"--- stderr: {package}", *lines, "---", f"Failed   <<< {package} [exited with code 1]")


def _manifest(root: str) -> Manifest | None:
    """catkin_pkg's reading of package.xml (:mod:`.catkin`); None when there is none."""
    from ..core.errors import BrasKitError
    from ..model.xmlio import read_xml
    from .catkin import read_manifest

    if not os.path.isfile(os.path.join(root, "package.xml")):
        return None
    try:
        xml = read_xml(os.path.join(root, "package.xml"))
    except (BrasKitError, OSError):
        return Manifest("", "", (), "The manifest contains invalid XML")
    return read_manifest(xml)


def _shown_name(name: str, root: str) -> str:
    """The name shown in colcon's lines: package.xml's when it is a name, else the folder's."""
    return name if name and name_problem(name) is None else os.path.basename(root)


def build_package(root: str, install_base: str, *, meanwhile: Callable[[], object] | None = None,
                  symlink_install: bool = False, build_base: str | None = None) -> BuildRecord:
    """Build the package at ``root`` into ``install_base/PKG`` (replacing what was there).
    Learner mistakes come back as ``record.failure``; only the sandbox's own limits raise.
    Nothing ``setup.py`` returns is acted on before :func:`.setup_check.check_setup` passed it.
    ``meanwhile`` is called while setup.py's child runs (the launch evaluation imports what its
    own child needs then: :func:`.launching.preload_planning`). ``symlink_install``: as ``colcon build
    --symlink-install``, with links in ``build_base/PKG`` (default: build/ beside the install base)."""
    root = os.path.abspath(root)
    install_base = os.path.abspath(install_base)
    builds = build_base or os.path.join(os.path.dirname(install_base), "build")
    manifest = _manifest(root)
    # a package.xml catkin_pkg refuses, or one with two build types, is passed over by colcon-ros
    # (colcon_ros/package_identification/ros.py, identify, lines 54-61): colcon-python-setup-py then
    # builds the folder as a plain Python package, named by setup.py (python_setup_py.py, identify)
    ros = manifest is not None and not manifest.problem and bool(manifest.build_type)
    name = manifest.name if ros and manifest is not None else ""
    package = _shown_name(name, root)
    record = BuildRecord(package, root, os.path.join(install_base, package))
    record.ros = ros
    if manifest is not None and not ros:
        record.refused_manifest = manifest.problem or "Only one <build_type> element is permitted."
    if ros and manifest is not None and manifest.build_type != "ament_python":
        lines = [f"CMake Error: The source directory \"{root}\" does not appear to contain CMakeLists.txt."] \
            if not os.path.isfile(os.path.join(root, "CMakeLists.txt")) else []
        record.failure = BuildFailure("ament_cmake", _failed(package, lines) if lines else (), "package.xml",
                                      _line_of(root, "package.xml", "<build_type>"), detail=manifest.build_type)
        if name_problem(package) is None:
            record.run_depends = manifest.run_depends
            _cmake_prefix(record, manifest.build_type)
        return record
    if not os.path.isfile(os.path.join(root, "setup.py")):
        record.failure = BuildFailure("no_setup", (), "setup.py")
        return record
    called = _run_setup(root, meanwhile)
    record.blocked = [a for a in called.get("blocked", []) if isinstance(a, Attempt)]
    if "error" in called:
        error = called["error"]
        record.failure = BuildFailure("setup_raised", _failed(package, [error["text"]]), "setup.py",
                                      error["line"], detail=error["text"])
        _hooks_before_setup(record)
        return record
    if "setup" not in called or not isinstance(called["setup"], dict):
        record.failure = BuildFailure("no_setup_call", (), "setup.py")
        _hooks_before_setup(record)
        return record
    setup = called["setup"]
    record.setup_line = int(setup.get("_line") or 0)
    record.data_files_line = _line_of(root, "setup.py", "data_files") or record.setup_line
    if symlink_install:  # named by the shown name until the checked one is known
        record.build = os.path.join(builds, package)
    checked = check_setup(setup, root, manifest_name=name or os.path.basename(root),
                          setup_source=_setup_source(root), python_lib=PYTHON_LIB)
    half = checked.partial if isinstance(checked, Refusal) and checked.kind == "missing_source" else None
    found = checked if isinstance(checked, CheckedSetup) else half
    if found is not None:
        # colcon names a ROS package by package.xml (colcon_ros/package_identification/ros.py, identify:
        # desc.name = pkg.name); setup.py's name= only names the Python distribution, and names a plain one
        record.package = name if ros else found.name
        record.prefix = os.path.join(install_base, record.package)  # one checked name: directly under the base
        record.script_dir = (develop_script_folder if symlink_install else script_folder)(root, record.package)
        if symlink_install:
            record.build = os.path.join(builds, record.package)
        record.installed = list(found.installed)
        if ros:
            record.installed += _implicit_installs(record.package, setup.get("data_files"), root)
        record.scripts = list(found.console_scripts)
        # colcon-core's python augmentation: install_requires are a plain package's run dependencies
        # (colcon_core/package_augmentation/python.py, lines 76-84)
        record.run_depends = manifest.run_depends if ros and manifest is not None else \
            _requirement_names(setup.get("install_requires"))
        record.data_folders = _data_folders(setup.get("data_files"))
    if isinstance(checked, Refusal):
        record.failure = _refused(record, checked)
        if half is not None:
            record.data_folders = record.data_folders[:checked.entry + 1]
            stopped = _lay_out(record, half, setup, whole=False)
            record.failure = stopped or record.failure
        return record
    record.failure = _lay_out(record, checked, setup)
    return record


def _requirement_names(requires: Any) -> tuple[str, ...]:
    """The distribution names of setup()'s requirement strings (PEP 508: the name comes first)."""
    items = [requires] if isinstance(requires, str) else requires if isinstance(requires, list) else []
    names = {m.group(0) for m in (re.match(r"[A-Za-z0-9][A-Za-z0-9._-]*", str(item).strip()) for item in items) if m}
    return tuple(sorted(names))


def _hooks_before_setup(record: BuildRecord) -> None:
    """What colcon-ros writes before setup.py runs: the ament_prefix_path hook (colcon_ros/task/
    ament_python/build.py, lines 39-41), left in the prefix when setup.py then fails."""
    from ..trust.learner_files import write_file
    from .colcon_env import Hook, hook_files

    if not record.ros or name_problem(record.package) is not None or _clear_prefix(record) is not None:
        return
    try:
        os.makedirs(record.prefix)
        for relative, text in hook_files(record.package, Hook("ament_prefix_path", "AMENT_PREFIX_PATH", "")):
            write_file(record.prefix, relative, text)
    except OSError:
        pass  # a full disk: the failure already says the package was not built


def _cmake_prefix(record: BuildRecord, build_type: str) -> None:
    """What colcon-ros leaves after CMake failed: the package's environment scripts and colcon-core's
    list of run dependencies, written whatever CMake's exit code (colcon_ros/task/ament_cmake/build.py,
    build, lines 59-86 of colcon-ros 0.5.0: no hook, CMake having installed nothing), and for
    catkin the install base's ``.catkin`` marker (colcon_ros/task/catkin/build.py, lines 128-131)."""
    from ..trust.learner_files import write_file

    if _clear_prefix(record) is not None:
        return  # not a prefix bras-kit or colcon made: left alone
    try:
        os.makedirs(record.prefix)
        _environment_files(record, [])
        if build_type == "catkin":
            write_file(record.prefix, ".catkin", b"")
    except OSError:
        pass  # a full disk: the failure already says the package was not built


def _implicit_installs(package: str, entries: Any, root: str) -> list[Installed]:
    """What colcon-ros installs when data_files does not declare it: the index marker (an empty file)
    and package.xml (colcon_ros/task/ament_python/build.py, AmentPythonBuildTask.build, lines 53-95 of
    colcon-ros 0.5.0: "doesn't explicitly install a marker in the package index"). It reads the
    declared data_files (colcon_core/task/python/__init__.py, get_data_files_mapping, lines 23-48),
    before setup.py installs anything: a declared source that turns out missing still counts."""
    declared: dict[str, str] = {}
    for entry in entries if isinstance(entries, list) else []:
        if isinstance(entry, str):
            declared[entry] = os.path.basename(entry)
        elif isinstance(entry, list) and len(entry) == 2 and isinstance(entry[0], str) and isinstance(entry[1], list):
            for source in entry[1]:
                if isinstance(source, str):
                    declared[source] = os.path.join(entry[0], os.path.basename(source))
    out = []
    if f"{INDEX}/{package}" not in declared.values():
        out.append(Installed(f"{INDEX}/{package}", ""))  # no source: an empty file
    if declared.get("package.xml") != f"share/{package}/package.xml" \
            and os.path.isfile(os.path.join(root, "package.xml")):
        out.append(Installed(f"share/{package}/package.xml", "package.xml"))
    return out


def _data_folders(entries: Any) -> list[str]:
    """Every (folder, files) target of data_files: setuptools' install_data makes each one, files or
    none (setuptools/_distutils/command/install_data.py, run: ``self.mkpath(dir)`` before the copies)."""
    from .setup_check import _relative_target

    folders = []
    for entry in entries if isinstance(entries, list) else []:
        if isinstance(entry, list) and len(entry) == 2 and isinstance(entry[0], str):
            folder = _relative_target(entry[0])
            if folder:
                folders.append(folder)
    return folders


def script_folder(root: str, package: str) -> str:
    """Where setuptools puts the package's scripts, relative to its prefix, as colcon passes it.

    colcon-core reads setup.cfg's ``[install]`` ``install-scripts``, else ``install_scripts``, and
    hands it to ``setup.py install --install-scripts`` (colcon_core/task/python/build.py,
    _get_install_scripts, lines 38-50, and build, lines 142-148 of colcon-core 0.21.3): the
    tutorial's ``$base/lib/PKG``. With no such key, setuptools' prefix scheme applies: ``$base/bin``,
    where ``ros2 run`` does not look. A folder named otherwise than ``$base/...`` below the prefix is
    kept as the tutorial's lib/PKG (bras-kit writes nowhere outside the prefix)."""
    def pick(parser: Any) -> str | None:
        value = parser.get("install", "install-scripts", fallback=None)
        return parser.get("install", "install_scripts", fallback=None) if value is None else value

    return _setup_cfg_folder(root, package, pick, keep_case=True)  # as colcon-core: keys as written


def develop_script_folder(root: str, package: str) -> str:
    """Where ``setup.py develop`` (colcon's --symlink-install) puts the scripts, relative to the prefix.
    colcon passes no folder (colcon_core/task/python/build.py, build, lines 174-183); setuptools' develop
    takes setup.cfg's ``[develop]`` ``script_dir``, else the install_scripts command's folder
    (setuptools/command/easy_install.py, finalize_options, lines 296-309): ``[install_scripts]``
    ``install_dir``, else ``[install]`` ``install_scripts`` (setuptools/_distutils/command/
    install_scripts.py, finalize_options, lines 32-39); else the prefix's bin/. setuptools reads a
    dash key as its underscore twin, with its deprecation warning (setuptools/dist.py,
    _enforce_underscore), the later of the two in the file winning."""
    def pick(parser: Any) -> str | None:
        for section, key in (("develop", "script_dir"), ("install_scripts", "install_dir"),
                             ("install", "install_scripts")):
            value = _last_of(parser, section, (key, key.replace("_", "-")))
            if value is not None:
                return value
        return None

    return _setup_cfg_folder(root, package, pick, keep_case=False)


def _last_of(parser: Any, section: str, keys: tuple[str, ...]) -> str | None:
    """The value of the last of ``keys`` written in ``section`` (setuptools reads options in file order)."""
    if not parser.has_section(section):
        return None
    found = None
    for key, value in parser.items(section, raw=True):
        if key in keys:
            found = value
    return found


def _setup_cfg_folder(root: str, package: str, pick: Callable[[Any], str | None], *, keep_case: bool) -> str:
    """The scripts' folder ``pick`` reads from setup.cfg, relative to the prefix: ``bin`` when the
    file or the key is missing (or the file unreadable), a ``$base/...`` folder below the prefix,
    else the tutorial's lib/PKG."""
    from configparser import ConfigParser
    from configparser import Error as ConfigError

    from ..trust.learner_files import read_text
    from .setup_check import _relative_target

    try:
        text = read_text(os.path.join(root, "setup.cfg"), (root,), errors="replace")
    except OSError:
        return "bin"
    parser = ConfigParser(interpolation=None)
    if keep_case:
        parser.optionxform = str  # type: ignore[assignment,method-assign]
    try:
        parser.read_string(text)
    except ConfigError:
        return "bin"
    value = pick(parser)
    if value is None:
        return "bin"
    value = value.strip()
    if value.startswith("$base/"):
        folder = _relative_target(value[len("$base/"):])
        if folder:
            return folder
    return f"lib/{package}"


def _egg_link_name(dist: str) -> str:
    """setuptools' develop names its link file after the distribution's safe name
    (pkg_resources.safe_name: every run of other characters than letters, digits and '.' becomes '-')."""
    import re

    return re.sub(r"[^A-Za-z0-9.]+", "-", dist) + ".egg-link"


def _links_in_build(record: BuildRecord, checked: CheckedSetup, setup: dict[str, Any]) -> None:
    """build/PKG as colcon-core makes it for ``setup.py develop``: a link to each of setup.py, setup.cfg,
    the first-level Python packages, the data_files sources and the scripts of the package folder
    (colcon_core/task/python/build.py, _symlinks_in_build, lines 330-400 of colcon-core 0.21.3)."""
    from ..trust.learner_files import make_link

    items = ["setup.py"]
    if os.path.isfile(os.path.join(record.root, "setup.cfg")):
        items.append("setup.cfg")
    given = setup.get("package_dir")
    package_dir: dict[str, Any] = given if isinstance(given, dict) else {}
    for package in setup.get("packages") or []:
        if not isinstance(package, str) or "." in package:
            continue
        folder = package_dir.get(package) or os.path.join(package_dir.get("", ""), package)
        items.append(folder)
    items += [item.source for item in checked.installed if item.source]
    items += [item.source for item in checked.executables]
    if os.path.islink(record.build) or os.path.islink(os.path.dirname(record.build)):  # never built through
        raise OSError(errno.ELOOP, "a link stands where build/ should be", record.build)
    os.makedirs(record.build, exist_ok=True)
    for item in dict.fromkeys(items):
        source = os.path.join(record.root, item)
        if os.path.lexists(source):
            make_link(record.build, item, source)


def _lay_out_links(record: BuildRecord, checked: CheckedSetup, setup: dict[str, Any]) -> None:
    """The install tree of ``colcon build --symlink-install``: each data file a link to its link in
    build/PKG (colcon_core/distutils/commands/symlink_data.py, lines 12-27: ``os.path.abspath(src)``
    from build/PKG), package.xml installed implicitly a link to the package's own (colcon_core/task/
    __init__.py, install, lines 306-333), the index marker made implicitly an empty file, no module
    copied (``<dist>.egg-link`` names build/PKG, where the hook puts PYTHONPATH), the scripts where
    ``[develop]`` says."""
    from ..trust.learner_files import make_folder, make_link, write_file

    _links_in_build(record, checked, setup)
    for folder in record.data_folders:
        make_folder(record.prefix, folder)
    for item in record.installed:
        if not item.source:
            write_file(record.prefix, item.target, b"")
        elif item.source == "package.xml" and item not in checked.installed:
            make_link(record.prefix, item.target, os.path.join(record.root, item.source))
        else:
            make_link(record.prefix, item.target, os.path.join(record.build, item.source))
    write_file(record.prefix, os.path.join(PYTHON_LIB, _egg_link_name(checked.name)),
               f"{record.build}\n.".encode())
    version = setup.get("version")
    spec = f"{_egg_link_name(checked.name)[:-len('.egg-link')]}=={version if isinstance(version, str) else ''}"
    for item in checked.executables:
        # setuptools' develop wraps each scripts= file (setuptools/script (dev).tmpl): values as Python literals
        name = os.path.basename(item.target)
        wrapper = DEV_SCRIPT.format(spec=repr(spec), name=repr(name), path=repr(os.path.join(record.build, item.source)))
        write_file(record.prefix, f"{record.script_dir}/{name}", wrapper.encode("utf-8"), mode=0o755)
    for name, module, function in checked.console_scripts:
        script = SCRIPT.format(dist=checked.name, name=name, module=module,
                               head=function.partition(".")[0], function=function)
        write_file(record.prefix, os.path.join(record.script_dir, name), script.encode("utf-8"), mode=0o755)


def _setup_source(root: str) -> str:
    from ..trust.learner_files import read_text

    try:
        return read_text(os.path.join(root, "setup.py"), (root,), errors="replace")
    except OSError:
        return ""


def _refused(record: BuildRecord, refusal: Refusal) -> BuildFailure:
    """A refusal of the checked record, as the build's failure at the learner's line."""
    if refusal.kind == "missing_source":  # setuptools' install_data (file_util.copy_file), in its words
        # with --symlink-install colcon's symlink_data names the source by its absolute path in build/PKG
        shown = os.path.join(record.build, refusal.value) if record.build else refusal.value
        message = f"error: can't copy '{shown}': doesn't exist or not a regular file"
        return BuildFailure("missing_source", _failed(record.package, [message]), refusal.file, refusal.line or
                            record.data_files_line, source=refusal.value, detail=refusal.target)
    if refusal.kind == "name":  # catkin_pkg's InvalidPackage, as colcon-ros shows it
        words = name_problem(refusal.value) or refusal.value
        if refusal.file == "setup.py":
            return BuildFailure("name", (words,), refusal.file, refusal.line, detail=refusal.value)
        where = os.path.join(record.root, "package.xml")
        return BuildFailure("name", (f"Error(s) in package '{where}':", words), refusal.file,
                            _line_of(record.root, "package.xml", "<name>"), detail=refusal.value)
    kind = f"source_{refusal.why}" if refusal.kind == "source" else refusal.kind
    return BuildFailure(kind, (), refusal.file, refusal.line or record.setup_line, source=refusal.value,
                        detail=refusal.value)


def _line_of(root: str, relative: str, text: str) -> int:
    from ..trust.learner_files import read_text

    try:
        lines = read_text(os.path.join(root, relative), (root,), errors="replace").splitlines()
    except OSError:
        return 0
    return next((number for number, line in enumerate(lines, 1) if text in line), 0)


SCRIPT = """#!/usr/bin/python3
# EASY-INSTALL-ENTRY-SCRIPT: '{dist}','console_scripts','{name}'
# written by bras-kit build: {module}:{function}
import sys
from {module} import {head}
sys.exit({function}())
"""


DEV_SCRIPT = """#!/usr/bin/python3
# EASY-INSTALL-DEV-SCRIPT: {spec},{name}
__requires__ = {spec}
__import__('pkg_resources').require({spec})
__file__ = {path}
with open(__file__) as f:
    exec(compile(f.read(), __file__, 'exec'))
"""


def _only_python_lib(prefix: str) -> bool:
    """A prefix holding lib/pythonX.Y/site-packages and share/ folders only: what a plain Python
    package's build leaves when setuptools stopped."""
    from ..trust.learner_files import list_folder

    top = {name for name, _kind in list_folder(prefix, (prefix,))}
    return top <= {"lib", "share"} and os.path.isdir(os.path.join(prefix, PYTHON_LIB)) and \
        {name for name, _kind in list_folder(os.path.join(prefix, "lib"), (prefix,))} == {PYTHON_LIB.split("/")[1]}


def _clear_prefix(record: BuildRecord) -> BuildFailure | None:
    """Remove the previous build of this package, and nothing else: a folder directly under the
    install base, named by a checked name, holding colcon's marker for that name (or empty)."""
    prefix = record.prefix
    if not os.path.lexists(prefix):
        return None
    marker = os.path.join(prefix, COLCON_MARKER, record.package)
    # a build that stopped leaves no marker: colcon-ros's first hook, or the Python folder colcon-core
    # made before setup.py, says the prefix is a build's all the same
    hook = os.path.join(prefix, "share", record.package, "hook", "ament_prefix_path.dsv")
    ours = os.path.isdir(prefix) and not os.path.islink(prefix) and (
        any(os.path.isfile(p) and not os.path.islink(p) for p in (marker, hook)) or not os.listdir(prefix)
        or _only_python_lib(prefix))
    if not ours:
        return BuildFailure("prefix", (), "setup.py", record.setup_line, source=prefix, detail=prefix)
    import shutil

    shutil.rmtree(prefix)
    return None


def _lay_out(record: BuildRecord, checked: CheckedSetup, setup: dict[str, Any], *,
             whole: bool = True) -> BuildFailure | None:
    """The install tree from the checked record: every source read through the one reader
    (:mod:`bras_kit.trust.learner_files`), every target a new file under the fresh prefix.
    ``whole`` False: setuptools stopped at a missing data_files source (``checked`` is what it
    had installed by then): the modules, the data files before it, the folders of the entries up
    to it, and no script (setuptools' install_scripts comes after install_data: setuptools/command/
    install.py, lines 30-33 and 145-147; ``setup.py develop`` of --symlink-install writes them before
    colcon's symlink_data runs), no environment file but colcon-ros's first hook, no colcon-core
    marker (written after a build that succeeded: colcon_core/task/python/build.py, lines 157-160
    and 210-212)."""
    from ..trust.learner_files import Unreadable, copy_file, make_folder, write_file

    for path in (os.path.dirname(record.build), record.build) if record.build else ():
        if os.path.islink(path) or (os.path.lexists(path) and not os.path.isdir(path)):
            # --symlink-install writes links in build/PKG: never where a link or a file stands
            return BuildFailure("prefix", (), "setup.py", record.setup_line, source=path, detail=path)
    refused = _clear_prefix(record)
    if refused is not None:
        return refused
    roots = (record.root,)
    try:
        # every file below the prefix is made through its descriptor, no link followed (learner_files)
        os.makedirs(record.prefix)
        make_folder(record.prefix, PYTHON_LIB)  # colcon-core makes it before setup.py (build.py, lines 84-87)
        additional = []
        if record.ros:  # colcon-ros's hook, written before setup.py runs (ament_python/build.py, lines 39-41)
            from .colcon_env import Hook, hook_files

            additional = hook_files(record.package, Hook("ament_prefix_path", "AMENT_PREFIX_PATH", ""))
            for relative, text in additional:
                write_file(record.prefix, relative, text)
        if record.build:
            _lay_out_links(record, checked, setup)
        else:
            scripts = record.script_dir or f"lib/{record.package}"
            executables = [Installed(f"{scripts}/{os.path.basename(item.target)}", item.source)
                           for item in checked.executables] if whole else []
            for folder in record.data_folders:
                make_folder(record.prefix, folder)
            for item in (*record.installed, *checked.modules, *executables):
                if not item.source:  # colcon-ros's implicit index marker
                    write_file(record.prefix, item.target, b"")
                    continue
                # two entries install the same file: the last wins, as in setuptools (replace)
                copy_file(os.path.join(record.root, item.source), roots, os.path.join(record.prefix, item.target),
                          target_root=record.prefix, replace=True,
                          mode=0o755 if item in executables else None)
            for name, module, function in checked.console_scripts if whole else ():  # install_scripts comes last
                script = SCRIPT.format(dist=checked.name, name=name, module=module,
                                       head=function.partition(".")[0], function=function)
                write_file(record.prefix, os.path.join(scripts, name), script.encode("utf-8"), mode=0o755)
        if whole:
            _environment_files(record, [path for path, _text in additional])
    except Unreadable as exc:  # changed between the check and the copy, or too large
        return BuildFailure(f"source_{exc.kind}", (), "setup.py", record.data_files_line,
                            source=os.path.relpath(exc.path, record.root), detail=exc.path)
    except OSError as exc:  # two entries that make a file and a folder of one name, a full disk...
        message = f"error: {exc.strerror or exc}: '{os.path.relpath(exc.filename or record.prefix, record.prefix)}'"
        return BuildFailure("install", _failed(record.package, [message]), "setup.py", record.data_files_line,
                            detail=message)
    return None


def _environment_files(record: BuildRecord, additional: list[str]) -> None:
    """What colcon writes once the package is installed (colcon_core/task/python/build.py, lines
    196-212): a hook for each variable the prefix now extends, then ``additional`` (colcon-ros's,
    relative to the prefix), with --symlink-install ``pythonpath_develop`` in build/PKG; the package
    scripts listing them; and last colcon-core's list of run dependencies
    (colcon_core/environment/__init__.py, create_file_with_runtime_dependencies, lines 159-176:
    ``os.pathsep.join(sorted(...))``), the marker a later build looks for."""
    from ..trust.learner_files import write_file
    from .colcon_env import Hook, hook_files, package_scripts, prefix_hooks

    listed: list[str] = []
    for hook in prefix_hooks(record.prefix, record.package, PYTHON_LIB):
        for relative, text in hook_files(record.package, hook):
            write_file(record.prefix, relative, text)
            listed.append(relative)
    listed += additional
    if record.build:
        develop = Hook("pythonpath_develop", "PYTHONPATH", record.build)
        for relative, text in hook_files(record.package, develop):
            write_file(record.build, relative, text)
            listed.append(os.path.relpath(os.path.join(record.build, relative), record.prefix))
    for relative, text in package_scripts(record.package, record.prefix, listed):
        write_file(record.prefix, relative, text)
    write_file(record.prefix, os.path.join(COLCON_MARKER, record.package), ":".join(record.run_depends).encode())


# ---------------------------------------------------------------- the child


def _run_setup(root: str, meanwhile: Callable[[], object] | None = None) -> dict[str, Any]:
    from ..trust import scratch
    from ..trust.contain import containment
    from ..trust.sandbox import ResourceLimitError, run_limited, start_limited

    with scratch.folder("bras-kit-setup-") as workdir:
        # the learner's setup.py reads its package and writes nowhere (setup() is recorded)
        walls = containment("auto", workdir, (root,))
        limits = {"cpu_seconds": SETUP_CPU_SECONDS, "memory_bytes": SETUP_MEMORY_BYTES,
                  "wall_seconds": SETUP_WALL_SECONDS, "what": f"{root}/setup.py", "contain": walls}
        try:
            if meanwhile is None:
                return run_limited(_run_setup_here, root, walls, **limits)  # type: ignore[arg-type]
            pending = start_limited(_run_setup_here, root, walls, **limits)  # type: ignore[arg-type]
            try:
                meanwhile()
            except BaseException:
                pending.close()
                raise
            return pending.result()
        except ResourceLimitError as exc:  # a setup.py that never ends or eats the memory: as data
            return {"error": {"text": f"setup.py was stopped ({exc.kind} limit of the sandbox)", "line": 0}}


def _find_packages(where: str = ".", exclude: Any = (), include: Any = ("*",)) -> list[str]:
    """setuptools.find_packages (setuptools/discovery.py PackageFinder): folders with __init__.py."""
    from fnmatch import fnmatchcase

    found = []
    for folder, dirs, _files in os.walk(where):
        dirs[:] = sorted(d for d in dirs if not d.startswith(".") and
                         os.path.isfile(os.path.join(folder, d, "__init__.py")))
        for d in dirs:
            name = os.path.relpath(os.path.join(folder, d), where).replace(os.sep, ".")
            if any(fnmatchcase(name, p) for p in include) and not any(fnmatchcase(name, p) for p in exclude):
                found.append(name)
    return found


def _plain(value: Any) -> Any:
    """What setup() got, made of plain data (to cross the pipe)."""
    if isinstance(value, (str, int, float, bool)) or value is None:
        return value
    if isinstance(value, dict):
        return {str(k): _plain(v) for k, v in value.items()}
    if isinstance(value, (list, tuple, set)):
        return [_plain(v) for v in value]
    if isinstance(value, os.PathLike):
        return os.fspath(value)
    return str(value)


def _run_setup_here(root: str, walls: Any = None) -> dict[str, Any]:
    """In the child: ``python setup.py`` with setup() recorded; contained (``walls``), what its
    walls stopped comes back as ``blocked``, at setup.py's lines (BK639)."""
    import runpy
    import traceback
    import types

    watcher = None
    if walls is not None:
        from .attempts import Watcher

        read, write = walls.granted()
        watcher = Watcher(root, tuple(write), tuple(read))
        watcher.install()
    os.chdir(root)
    sys.path.insert(0, root)
    sys.argv = [os.path.join(root, "setup.py"), "build"]
    called: dict[str, Any] = {}
    setup_path = os.path.join(root, "setup.py")

    def setup(**kwargs: Any) -> None:
        # the innermost call made from setup.py (inspect.stack() would read every frame's source: 15 ms)
        line, frame = 0, cast("types.FrameType | None", sys._getframe(1))
        while frame is not None and os.path.abspath(frame.f_code.co_filename) != setup_path:
            frame = frame.f_back
        if frame is not None:
            line = frame.f_lineno
        called["setup"] = {**{k: _plain(v) for k, v in kwargs.items()}, "_line": line}

    fake = types.ModuleType("setuptools")
    fake.setup = setup  # type: ignore[attr-defined]
    fake.find_packages = _find_packages  # type: ignore[attr-defined]
    fake.find_namespace_packages = _find_packages  # type: ignore[attr-defined]
    fake.Command = object  # type: ignore[attr-defined]
    sys.modules["setuptools"] = fake
    distutils = types.ModuleType("distutils.core")
    distutils.setup = setup  # type: ignore[attr-defined]
    sys.modules["distutils.core"] = distutils
    try:
        runpy.run_path(setup_path, run_name="__main__")
    except SystemExit as exc:
        if exc.code not in (None, 0):
            frames = [f for f in traceback.extract_tb(exc.__traceback__) if os.path.abspath(f.filename) == setup_path]
            called["error"] = {"text": str(exc.code), "line": frames[-1].lineno if frames else 0}
    except BaseException as exc:  # noqa: BLE001 - the learner's setup.py, reported as colcon shows it
        frames = [f for f in traceback.extract_tb(exc.__traceback__) if os.path.abspath(f.filename) == setup_path]
        line = frames[-1].lineno if frames else getattr(exc, "lineno", 0) or 0
        called["error"] = {"text": "".join(traceback.format_exception_only(type(exc), exc)).strip(), "line": line}
    if watcher is not None:
        called["blocked"] = watcher.finish()
    return called
