"""What the package rules read: the files of one ament_python package, parsed once, never run.

``package.xml`` through :mod:`bras_kit.model.xmlio`, ``setup.py`` (:mod:`.setup_py`), launch files
(:mod:`.launch_source`) and the nodes publishing JointState (:mod:`.joint_publishers`) through
:mod:`ast` (:mod:`.staticpy`), ``.rviz`` files as YAML (the bounded gate), and the robot
description the launch file opens through :func:`bras_kit.model.authoring.load`.
"""

from __future__ import annotations

import ast
import os
from collections.abc import Callable
from dataclasses import dataclass
from functools import cached_property
from typing import Any

from ..core.message import M, Message
from ..model.robot import Robot
from .joint_publishers import Publisher, read_publisher
from .launch_source import LaunchFile, read_launch_file
from .setup_py import (
    Setup,
    module_names,
    read_console_scripts,
    read_data_files,
    undefined_names,
)
from .staticpy import (
    UNKNOWN,
    Evaluator,
    ShareFile,
    call_name,
    calls,
    keyword,
    parse_python,
)

PACKAGE_XML = "package.xml"
SETUP_PY = "setup.py"
INDEX_FOLDER = "share/ament_index/resource_index/packages"
NOT_SOURCE_FOLDERS = ("build", "install", "log", "__pycache__")  # colcon's own, and Python's cache
SOURCE_FILES_LIMIT = 20000
DESCRIPTION_SUFFIXES = (".urdf", ".xacro")
JOINT_STATE_PUBLISHERS = ("joint_state_publisher", "joint_state_publisher_gui")


@dataclass(frozen=True)
class Problem:
    """A file that could not be read: the package rules report it (BK600) and skip what needs it."""

    path: str
    line: int | None
    detail: str | Message


@dataclass(frozen=True)
class Manifest:
    """What the rules read of package.xml: the name, the maintainers, the run dependencies."""

    name: str | None
    name_line: int | None
    line: int
    maintainers: list[tuple[str | None, str, int]]  # (email, name, line)
    exec_depends: set[str]
    depends_line: int | None  # where a new <exec_depend> goes (the last dependency tag)


def module_file(module: str) -> str:
    """The file of a dotted module name, relative to the folder on sys.path: a/b.py for a.b."""
    return module.replace(".", "/") + ".py"


def relative(root: str, path: str) -> str:
    return os.path.relpath(path, root).replace(os.sep, "/")


class Package:
    """One package folder; every property is read on first use and kept."""

    def __init__(self, root: str) -> None:
        self.root = os.path.abspath(root)
        self.shown_root = root.rstrip("/\\") or root
        self.problems: list[Problem] = []
        self.read: set[str] = set()  # files (relative) the rules have read
        # the build and launch evaluation begun ahead in a worker (bras_kit.ros.ahead.evaluate_ahead):
        # its answer for a package folder, None where it has none
        self.ahead: Callable[[str], Any] | None = None
        # set by validate_package(launch=True): the rules that judge whole launches wait for the
        # evaluation where they first need it (the others run meanwhile)
        self.evaluate = False
        # the package built and its launch files evaluated (bras_kit.ros.launched.Launched), once read
        # (bras_kit.validate.package.evaluated.launched) or given by bras-kit launch
        self.launched: Any = None

    def path(self, relative_path: str) -> str:
        """The path as shown to the user: under the folder given on the command line."""
        return os.path.join(self.shown_root, relative_path)

    def _problem(self, relative_path: str, line: int | None, detail: str | Message) -> None:
        self.problems.append(Problem(relative_path, line, detail))

    # ------------------------------------------------------------ package.xml

    @cached_property
    def manifest(self) -> Manifest | None:
        from ..core.errors import BrasKitError
        from ..model.xmlio import parse_xml
        from ..trust.learner_files import Unreadable, read_bytes, refusal

        full = os.path.join(self.root, PACKAGE_XML)
        if not os.path.lexists(full):
            self._problem(PACKAGE_XML, None, "missing")
            return None
        self.read.add(PACKAGE_XML)
        try:  # the one reader: a package.xml linked out of the package is not read
            root = parse_xml(read_bytes(full, (self.root,)), self.path(PACKAGE_XML))
        except Unreadable as exc:
            self._problem(PACKAGE_XML, None, refusal(exc.kind))
            return None
        except BrasKitError as exc:
            self._problem(PACKAGE_XML, exc.line, str(exc.message))
            return None
        name = root.find("name")
        maintainers = [(m.get("email"), (m.text or "").strip(), m.line) for m in root.findall("maintainer")]
        depends = [n for n in root.children if n.tag in ("exec_depend", "depend", "run_depend")]
        all_depends = depends or [n for n in root.children if n.tag.endswith("depend")]
        return Manifest(
            name=(name.text or "").strip() if name is not None else None,
            name_line=name.line if name is not None else None,
            line=root.line,
            maintainers=maintainers,
            exec_depends={(n.text or "").strip() for n in depends},
            depends_line=all_depends[-1].line if all_depends else None,
        )

    # ------------------------------------------------------------ setup.py

    @cached_property
    def setup(self) -> Setup | None:
        full = os.path.join(self.root, SETUP_PY)
        if not os.path.lexists(full):
            self._problem(SETUP_PY, None, "missing")
            return None
        self.read.add(SETUP_PY)
        tree, reason, line = parse_python(full, self.root)
        if tree is None:
            self._problem(SETUP_PY, line, reason or "")
            return None
        evaluator = Evaluator(tree, self.root)
        call = next((c for c in calls(tree) if call_name(c.func).rsplit(".", 1)[-1] == "setup"), None)
        if call is None:
            self._problem(SETUP_PY, None, "no setup(...) call")
            return None
        name_node = keyword(call, "name")
        data_node = keyword(call, "data_files")
        entry_node = keyword(call, "entry_points")
        return Setup(
            name=evaluator.value(name_node) if name_node is not None else UNKNOWN,
            name_line=name_node.lineno if name_node is not None else call.lineno,
            line=call.lineno,
            data_files=read_data_files(evaluator, data_node),
            data_files_line=data_node.lineno if data_node is not None else call.lineno,
            scripts=read_console_scripts(evaluator, entry_node),
            scripts_line=entry_node.lineno if entry_node is not None else call.lineno,
            undefined=undefined_names(tree, call),
            defined=module_names(tree),
        )

    @property
    def name(self) -> str:
        """The package name: setup.py's, else package.xml's, else the folder's."""
        setup = self.setup
        if setup is not None and isinstance(setup.name, str):
            return setup.name
        if self.manifest is not None and self.manifest.name:
            return self.manifest.name
        return os.path.basename(self.root)

    def installed(self) -> dict[str, str] | None:
        """Installed path below share/PKG -> source path (relative), or None when unknown."""
        setup = self.setup
        if setup is None or setup.data_files is None:
            return None
        prefix = f"share/{self.name}"
        out: dict[str, str] = {}
        for entry in setup.data_files:
            destination = os.path.normpath(entry.destination).replace(os.sep, "/")
            if destination != prefix and not destination.startswith(prefix + "/"):
                continue
            folder = destination[len(prefix) + 1:]
            for source in entry.sources:
                target = f"{folder}/{os.path.basename(source)}" if folder else os.path.basename(source)
                out.setdefault(target, source)
        return out

    @cached_property
    def source_files(self) -> list[str]:
        """Every file of the package folder (relative, sorted), out of colcon's build, install and log
        folders (a build run in the package folder), caches and hidden folders; at most
        SOURCE_FILES_LIMIT entries are looked at (a package holds tens)."""
        from ..trust.learner_files import Unreadable, walk

        out: list[str] = []
        seen = 0
        try:  # through the one reader: a folder linked out of the package is never walked into
            for folder, dirs, names in walk(self.root, (self.root,)):
                dirs[:] = sorted(d for d in dirs if not d.startswith(".") and d not in NOT_SOURCE_FOLDERS)
                seen += len(dirs) + len(names)
                out += [relative(self.root, os.path.join(folder, n)) for n in names]
                if seen > SOURCE_FILES_LIMIT:
                    break
        except (Unreadable, OSError):
            pass
        return sorted(out)

    def files(self, folder: str, suffixes: tuple[str, ...]) -> list[str]:
        """Files of ``folder`` (relative) ending with one of ``suffixes``, sorted."""
        from ..trust.learner_files import Unreadable, is_file, list_folder

        full = os.path.join(self.root, folder)
        try:  # listed through the folder's descriptor: a folder linked out of the package lists nothing
            entries = list_folder(full, (self.root,))
        except Unreadable:
            return []
        return sorted(f"{folder}/{name}" for name, kind in entries if name.endswith(suffixes) and kind in (
            "file", "link") and is_file(os.path.join(full, name), (self.root,)))

    # ------------------------------------------------------------ launch files

    @cached_property
    def launch_files(self) -> list[LaunchFile]:
        out = []
        for rel in self.files("launch", (".launch.py", "_launch.py")):
            self.read.add(rel)
            tree, reason, line = parse_python(os.path.join(self.root, rel), self.root)
            if tree is None:
                self._problem(rel, line, reason or "")
                continue
            out.append(read_launch_file(tree, rel, self.root))
        return out

    # ------------------------------------------------------------ nodes

    @cached_property
    def publishers(self) -> list[Publisher]:
        """Modules of the package's Python code that publish JointState."""
        out = []
        for rel in self.python_modules():
            self.read.add(rel)
            tree, reason, line = parse_python(os.path.join(self.root, rel), self.root)
            if tree is None:
                self._problem(rel, line, reason or "")
                continue
            found = read_publisher(self, tree, rel)
            if found is not None:
                out.append(found)
        return out

    def python_modules(self) -> list[str]:
        from ..trust.learner_files import Unreadable, is_file, list_folder

        out = []
        roots = (self.root,)
        for entry, _kind in list_folder(self.root, roots):
            folder = os.path.join(self.root, entry)
            if entry.startswith((".", "test")) or not is_file(os.path.join(folder, "__init__.py"), roots):
                continue
            try:
                out += [f"{entry}/{f}" for f, kind in list_folder(folder, roots) if f.endswith(".py")
                        and kind in ("file", "link")]
            except Unreadable:
                continue
        return out

    def module_written(self, module: str) -> bool:
        """The module's file is where the import looks for it, in this very case: Python's import
        compares names exactly, even on a file system that does not (macOS, Windows)."""
        from ..trust.learner_files import Unreadable, is_file, list_folder

        folder = self.root
        for part in module_file(module).split("/"):
            try:
                if part not in {name for name, _kind in list_folder(folder, (self.root,))}:
                    return False
            except (Unreadable, OSError):
                return False
            folder = os.path.join(folder, part)
        return is_file(folder, (self.root,))

    def misplaced(self, module: str) -> list[str]:
        """The package's files named as the module's file (in any case, or without ``.py``) in another
        folder than the one the module names. setuptools' ``packages=[package_name]`` installs the
        package folder's own ``.py`` files and nothing else: a file at the root, in launch/, in a
        subfolder or in a folder of another name is not importable once installed."""
        own = module_file(module)
        wanted = {own.rsplit("/", 1)[-1].casefold(), module.rsplit(".", 1)[-1].casefold()}
        return [f for f in self.source_files if f != own and f.rsplit("/", 1)[-1].casefold() in wanted]

    def module_tree(self, module: str) -> ast.Module | None:
        from ..trust.learner_files import is_file

        rel = module.replace(".", "/") + ".py"
        full = os.path.join(self.root, rel)
        if not is_file(full, (self.root,)):
            return None
        return parse_python(full, self.root)[0]

    # ------------------------------------------------------------ the robot

    def description_source(self) -> str | None:
        """The robot description the launch file reads (its source in the package), else the
        first ``urdf/*.urdf``, else the first ``urdf/*.xacro``."""
        from ..trust.learner_files import is_file

        installed = self.installed() or {}
        for launch in self.launch_files:
            for share, _ in launch.share_files:
                if share.package == self.name and share.relative.endswith(DESCRIPTION_SUFFIXES):
                    source = installed.get(share.relative, share.relative)
                    if is_file(os.path.join(self.root, source), (self.root,)):
                        return source
        for suffix in DESCRIPTION_SUFFIXES:
            found = self.files("urdf", (suffix,))
            if found:
                return found[0]
        return None

    @cached_property
    def robot(self) -> Robot | None:
        """The robot, or None when there is none or it cannot be read (the URDF rules say why)."""
        from ..core.errors import BrasKitError
        from ..model.authoring import load
        from .launching import MAX_DESCRIPTION_CHARS

        source = self.description_source()
        if source is None:
            return None
        full = os.path.join(self.root, source)
        size = _size_beneath(full, self.root)
        if size > MAX_DESCRIPTION_CHARS:  # as robot_state_publisher's: the rules that need the robot are skipped
            self._problem(source, None, M("it holds {size} MiB, more than the {most} MiB bras-kit reads in a robot "
                                          "description", size=round(size / (1 << 20), 1),
                                          most=MAX_DESCRIPTION_CHARS >> 20))
            return None
        try:
            # read beneath the package (and the packages $(find) names): never through a link out,
            # and a folder swapped for a link while it loads reads nothing outside
            return load(full, package_paths=[os.path.dirname(self.root)], roots=(self.root,))
        except BrasKitError:
            return None

    # ------------------------------------------------------------ rviz

    def rviz(self, rel: str) -> Any:
        """The parsed .rviz file (a dict), or None when unreadable (reported as a problem)."""
        import yaml

        from ..trust import yaml_gate
        from ..trust.learner_files import Unreadable, read_text, refusal

        cache = self.__dict__.setdefault("_rviz", {})
        if rel not in cache:
            cache[rel] = None
            self.read.add(rel)
            try:
                text = read_text(os.path.join(self.root, rel), (self.root,))  # the one reader: no device, no link out
                data = yaml_gate.load(text)  # bounded: no alias bomb, no nesting past 100
            except Unreadable as exc:  # its words, never the file's bytes nor the reader's English
                self._problem(rel, None, refusal(exc.kind))
            except (OSError, UnicodeDecodeError) as exc:
                self._problem(rel, None, str(exc))
            except yaml_gate.YamlRefused as exc:  # a bound of the gate: its words, in the reader's language
                self._problem(rel, exc.line, exc.message)
            except yaml.YAMLError as exc:
                mark = getattr(exc, "problem_mark", None)
                self._problem(rel, mark.line + 1 if mark is not None else None,
                              str(getattr(exc, "problem", "") or exc))
            else:
                if isinstance(data, dict):
                    cache[rel] = (data, text.splitlines())
                else:
                    self._problem(rel, None, "not an RViz configuration (no 'Visualization Manager')")
        return cache[rel]


def _size_beneath(path: str, root: str) -> int:
    """The size of the regular file ``path`` reached beneath ``root`` by the one reader (0 when it
    is none: the loader then says why)."""
    from ..trust.beneath import Outside, open_beneath

    try:
        fd = open_beneath(root, path)
    except Outside:
        return 0
    try:
        return os.fstat(fd).st_size
    finally:
        os.close(fd)


def share_targets(package: Package) -> list[tuple[LaunchFile, ShareFile, int]]:
    """Every file of this package's share/ folder that a launch file builds a path to."""
    return [(launch, share, line) for launch in package.launch_files
            for share, line in launch.share_files if share.package == package.name]


