"""What the package rules read: the files of one ament_python package, parsed once, never run.

``package.xml`` through :mod:`bras_kit.model.xmlio`, ``setup.py``, launch files and nodes through
:mod:`ast` (:mod:`.staticpy`), ``.rviz`` files as YAML (``yaml.safe_load``), and the robot
description the launch file opens through :func:`bras_kit.model.authoring.load`.
"""

from __future__ import annotations

import ast
import os
from collections.abc import Callable
from dataclasses import dataclass, field
from functools import cached_property
from typing import Any

from ..core.message import M, Message
from ..model.robot import Robot
from .staticpy import (
    UNKNOWN,
    Evaluator,
    ShareFile,
    call_name,
    calls,
    keyword,
    known,
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


@dataclass(frozen=True)
class DataEntry:
    """One (destination, [sources]) entry of setup.py's data_files, and its line."""

    destination: str  # "share/PKG/urdf"
    sources: list[str]  # relative to the package folder
    line: int


@dataclass(frozen=True)
class EntryPoint:
    """One console_scripts entry: ``name = module:function``, and its line."""

    name: str
    module: str
    function: str
    line: int


@dataclass
class Setup:
    """What the rules read of setup.py, statically: the name, data_files and console scripts."""

    name: Any  # str, or UNKNOWN
    name_line: int
    line: int  # the setup( call
    data_files: list[DataEntry] | None  # None when not all of it could be read
    data_files_line: int
    scripts: list[EntryPoint] | None  # None when console_scripts could not be read
    scripts_line: int  # entry_points=, else the setup( call
    undefined: list[tuple[str, int]] = field(default_factory=list)  # names setup( uses that Python will not find
    defined: dict[str, str] = field(default_factory=dict)  # module-level names: "module" (import x) or "value"


@dataclass(frozen=True)
class NodeCall:
    """A ``Node(package=..., executable=...)`` of a launch file."""

    package: Any
    executable: Any
    arguments: Any
    line: int
    parameters: Any = None  # the parameters= list as far as it can be read (None: not given)
    has_parameters: bool = False


@dataclass(frozen=True)
class LaunchFile:
    """A Python launch file read statically: its Node(...) calls and the share files it names."""

    path: str  # relative to the package folder
    nodes: list[NodeCall]
    share_files: list[tuple[ShareFile, int]]  # files of share/ the launch file builds a path to
    includes: bool = False  # includes other launch files or publishes frames itself (tf2_ros)


@dataclass(frozen=True)
class Publisher:
    """A Python module of the package that publishes sensor_msgs/JointState."""

    path: str  # relative to the package folder
    module: str  # dotted name, e.g. bras_description.animation
    line: int  # the create_publisher call
    names: list[str] | None  # joint names when written literally (or as a constant)
    names_line: int | None
    formulas: dict[str, str] = field(default_factory=dict)  # joint -> formula in t
    formulas_line: int | None = None
    has_main: bool = False
    topic: Any = None  # the topic name when written literally (or as a module constant)
    topic_line: int | None = None
    scheduled: bool = True  # a timer or a loop calls something: False when nothing ever runs the callback
    publishes: bool = True  # some .publish(...) call exists
    degrees: list[tuple[int, str]] = field(default_factory=list)  # (line, what) of angles written in degrees


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
            data_files=_data_files(evaluator, data_node),
            data_files_line=data_node.lineno if data_node is not None else call.lineno,
            scripts=_console_scripts(evaluator, entry_node),
            scripts_line=entry_node.lineno if entry_node is not None else call.lineno,
            undefined=_undefined_names(tree, call),
            defined=_module_names(tree),
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
            out.append(_launch(tree, rel, self.root))
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
            found = _publisher(self, tree, rel)
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


# ---------------------------------------------------------------- setup.py details


def _module_names(tree: ast.Module) -> dict[str, str]:
    """Names a module defines at its top level: ``import os`` -> os: module; assignments, defs -> value."""
    out: dict[str, str] = {}
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            for alias in node.names:
                out[alias.asname or alias.name.split(".")[0]] = "module"
        elif isinstance(node, ast.ImportFrom):
            for alias in node.names:
                out[alias.asname or alias.name] = "value"
        elif isinstance(node, (ast.FunctionDef, ast.AsyncFunctionDef)):
            out[node.name] = "value"
            out.update((a.arg, "value") for a in ast.walk(node.args) if isinstance(a, ast.arg))
        elif isinstance(node, ast.ClassDef):
            out[node.name] = "value"
        elif isinstance(node, ast.Name) and isinstance(node.ctx, ast.Store):
            out.setdefault(node.id, "value")
    return out


def _undefined_names(tree: ast.Module, call: ast.Call) -> list[tuple[str, int]]:
    """Names read by the ``setup(...)`` call that neither the module nor Python's builtins define:
    running setup.py (colcon build) stops there with NameError."""
    import builtins

    defined = _module_names(tree)
    seen: dict[str, int] = {}
    for node in ast.walk(call):
        if isinstance(node, ast.Name) and isinstance(node.ctx, ast.Load) and node.id not in defined \
                and not hasattr(builtins, node.id):
            seen.setdefault(node.id, node.lineno)
    return sorted(seen.items(), key=lambda item: item[1])


def _data_files(evaluator: Evaluator, node: ast.expr | None) -> list[DataEntry] | None:
    if node is None:
        return []
    if not isinstance(node, (ast.List, ast.Tuple)):
        value = evaluator.value(node)
        return _entries(value, node.lineno) if known(value) else None
    out = []
    for element in node.elts:
        value = evaluator.value(element)
        entries = _entries([value], element.lineno) if known(value) else None
        if entries is None:
            return None
        out += entries
    return out


def _entries(value: Any, line: int) -> list[DataEntry] | None:
    if not isinstance(value, (list, tuple)):
        return None
    out = []
    for item in value:
        if not (isinstance(item, (list, tuple)) and len(item) == 2 and isinstance(item[0], str)
                and isinstance(item[1], (list, tuple)) and all(isinstance(s, str) for s in item[1])):
            return None
        out.append(DataEntry(item[0], list(item[1]), line))
    return out


def _console_scripts(evaluator: Evaluator, node: ast.expr | None) -> list[EntryPoint] | None:
    if node is None:
        return []
    if isinstance(node, ast.Dict):
        for key, value in zip(node.keys, node.values):
            if key is not None and evaluator.value(key) == "console_scripts":
                return _scripts(evaluator, value)
        return [] if all(k is not None and known(evaluator.value(k)) for k in node.keys) else None
    return None


def _scripts(evaluator: Evaluator, node: ast.expr) -> list[EntryPoint] | None:
    elements = node.elts if isinstance(node, (ast.List, ast.Tuple)) else None
    if elements is None:
        return None
    out = []
    for element in elements:
        text = evaluator.value(element)
        if not isinstance(text, str):
            return None
        name, _, target = text.partition("=")
        module, _, function = target.strip().partition(":")
        out.append(EntryPoint(name.strip(), module.strip(), function.strip(), element.lineno))
    return out


# ---------------------------------------------------------------- launch file details


def _launch(tree: ast.Module, rel: str, root: str) -> LaunchFile:
    evaluator = Evaluator(tree, root)
    scope = dict(evaluator.names)
    for function in evaluator.functions.values():
        scope.update(evaluator.scope_of(function))
    nodes = []
    share_files = []
    includes = False
    for call in calls(tree):
        name = call_name(call.func)
        if name.rsplit(".", 1)[-1] == "Node":
            arguments = keyword(call, "arguments")
            parameters = keyword(call, "parameters")
            nodes.append(NodeCall(evaluator.value(keyword(call, "package"), scope),
                                  evaluator.value(keyword(call, "executable"), scope),
                                  [] if arguments is None else evaluator.value(arguments, scope), call.lineno,
                                  _parameter_keys(parameters), parameters is not None))
            includes = includes or nodes[-1].package == "tf2_ros"
        elif name.rsplit(".", 1)[-1] in ("IncludeLaunchDescription", "ExecuteProcess", "OpaqueFunction"):
            includes = True
        elif name in ("os.path.join", "path.join", "join", "PathJoinSubstitution"):
            value = evaluator.value(call, scope)
            if isinstance(value, ShareFile) and value.relative:
                share_files.append((value, call.lineno))
    return LaunchFile(rel, nodes, share_files, includes)


def _parameter_keys(node: ast.expr | None) -> Any:
    """The parameter names a ``parameters=[{...}, ...]`` list gives, as a set; None when a part of
    it cannot be read without running the file (a YAML path, a variable, a substitution)."""
    if node is None:
        return set()
    if not isinstance(node, (ast.List, ast.Tuple)):
        return None
    keys: set[str] = set()
    for item in node.elts:
        if not isinstance(item, ast.Dict) or any(k is None or not isinstance(k, ast.Constant) for k in item.keys):
            return None
        keys |= {str(k.value) for k in item.keys if isinstance(k, ast.Constant)}
    return keys


# ---------------------------------------------------------------- nodes publishing JointState


def _publisher(package: Package, tree: ast.Module, rel: str) -> Publisher | None:
    create = next((c for c in calls(tree) if call_name(c.func).endswith("create_publisher") and c.args
                   and call_name(c.args[0]).rsplit(".", 1)[-1] == "JointState"), None)
    if create is None:
        return None
    evaluator = Evaluator(tree, package.root, _imported_names(package, tree, rel))
    # the JointState messages: variables assigned JointState(), and JointState(name=..., position=...)
    messages = {ast.unparse(n.targets[0]) for n in ast.walk(tree) if isinstance(n, ast.Assign)
                and len(n.targets) == 1 and isinstance(n.value, ast.Call)
                and call_name(n.value.func).rsplit(".", 1)[-1] == "JointState"}
    name_nodes: list[ast.expr] = []
    position_nodes: list[ast.expr] = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Assign) and len(node.targets) == 1 and isinstance(node.targets[0], ast.Attribute) \
                and ast.unparse(node.targets[0].value) in messages:
            if node.targets[0].attr == "name":
                name_nodes.append(node.value)
            elif node.targets[0].attr == "position":
                position_nodes.append(node.value)
        elif isinstance(node, ast.Call) and call_name(node.func).rsplit(".", 1)[-1] == "JointState":
            name_nodes += [k.value for k in node.keywords if k.arg == "name"]
            position_nodes += [k.value for k in node.keywords if k.arg == "position"]
    names: list[str] | None = None
    names_line = formulas_line = None
    if len(name_nodes) == 1:  # several assignments: which one is sent is not known statically
        value = evaluator.value(name_nodes[0])
        names_line = name_nodes[0].lineno
        if isinstance(value, (list, tuple)) and all(isinstance(v, str) for v in value):
            names = list(value)
    positions: list[ast.expr] | None = None
    time_scope: dict[str, Any] = {}
    if len(position_nodes) == 1:
        formulas_line = position_nodes[0].lineno
        positions, time_scope = _position_expressions(package, evaluator, position_nodes[0], rel)
    formulas: dict[str, str] = {}
    if names is not None and positions is not None and len(positions) == len(names):
        from .formulas import formula

        for joint, expression in zip(names, positions):
            text = formula(expression, time_scope)
            if text is not None:
                formulas[joint] = text
    has_main = any(isinstance(n, ast.FunctionDef) and n.name == "main" for n in tree.body)
    module = rel[:-3].replace("/", ".")
    topic_node = create.args[1] if len(create.args) > 1 else keyword(create, "topic")
    topic = evaluator.value(topic_node) if topic_node is not None else None
    scheduled = any(call_name(c.func).rsplit(".", 1)[-1] in ("create_timer", "Timer", "create_rate")
                    for c in calls(tree)) or any(isinstance(n, (ast.While, ast.For)) and any(
                        isinstance(m, ast.Call) for m in ast.walk(n)) for n in ast.walk(tree))
    publishes = any(call_name(c.func).rsplit(".", 1)[-1] == "publish" for c in calls(tree))
    degrees = [found for node in position_nodes for found in _in_degrees(node)]
    if positions is not None and names is not None and package.robot is not None:
        for joint, expression in zip(names, positions):
            robot_joint = package.robot.joint(joint) if hasattr(package.robot, "joint") else None
            if robot_joint is not None and robot_joint.type == "revolute":
                degrees += _large_amplitudes(expression)
    return Publisher(rel, module, create.lineno, names, names_line, formulas, formulas_line, has_main,
                     topic, getattr(topic_node, "lineno", create.lineno), scheduled, publishes,
                     _one_per_line(degrees))


def _one_per_line(found: list[tuple[int, str]]) -> list[tuple[int, str]]:
    """The first way of writing degrees seen on each line (a conversion before the 180 inside it)."""
    out: dict[int, str] = {}
    for line, what in found:
        out.setdefault(line, what)
    return sorted(out.items())


def _in_degrees(node: ast.expr) -> list[tuple[int, str]]:
    """``math.degrees(...)``, ``np.rad2deg(...)``, ``* 180 / math.pi``: angles turned into degrees."""
    out = []
    for inner in ast.walk(node):
        if isinstance(inner, ast.Call) and call_name(inner.func).rsplit(".", 1)[-1] in ("degrees", "rad2deg"):
            out.append((inner.lineno, ast.unparse(inner.func) + "(...)"))
        elif isinstance(inner, ast.BinOp) and isinstance(inner.op, (ast.Mult, ast.Div)):
            text = ast.unparse(inner)
            if "180" in text and "pi" in text and isinstance(inner.op, ast.Div) \
                    and ast.unparse(inner.right).endswith("pi"):
                out.append((inner.lineno, text))
    return out


def _large_amplitudes(node: ast.expr) -> list[tuple[int, str]]:
    """Numbers beyond 2 pi multiplying or added to an angle of a revolute joint: degrees, not radians."""
    import math

    out = []
    for inner in ast.walk(node):
        if isinstance(inner, ast.BinOp) and isinstance(inner.op, (ast.Mult, ast.Add, ast.Sub)):
            for side in (inner.left, inner.right):
                if isinstance(side, ast.Constant) and isinstance(side.value, (int, float)) \
                        and not isinstance(side.value, bool) and abs(side.value) > 2 * math.pi \
                        and not (isinstance(inner.op, ast.Mult) and _is_time_factor(inner)):
                    out.append((inner.lineno, ast.unparse(inner)))
        elif isinstance(inner, ast.Constant) and inner is node and isinstance(inner.value, (int, float)) \
                and not isinstance(inner.value, bool) and abs(inner.value) > 2 * math.pi:
            out.append((inner.lineno, ast.unparse(inner)))
    return out


def _is_time_factor(node: ast.BinOp) -> bool:
    """``2 * pi * f * t`` inside sin(): a frequency, not an amplitude (the product sits in a call's argument)."""
    return any(isinstance(n, ast.Name) and n.id in ("t", "time") or isinstance(n, ast.Attribute) and n.attr in ("t", "time")
               for n in (node.left, node.right))


def _imported_names(package: Package, tree: ast.Module, rel: str) -> dict[str, Any]:
    """Constants imported from sibling modules (``from PKG.motion import JOINT_NAMES``)."""
    out: dict[str, Any] = {}
    here = rel.split("/")[0]
    for node in tree.body:
        if not isinstance(node, ast.ImportFrom) or node.module is None:
            continue
        module = f"{here}.{node.module}" if node.level == 1 else node.module
        if not module.startswith(here + "."):
            continue
        other = package.module_tree(module)
        if other is None:
            continue
        names = Evaluator(other, package.root).names
        for alias in node.names:
            if alias.name in names:
                out[alias.asname or alias.name] = names[alias.name]
            elif any(isinstance(n, ast.FunctionDef) and n.name == alias.name for n in other.body):
                out[alias.asname or alias.name] = ("function", module, alias.name)
    return out


def _position_expressions(package: Package, evaluator: Evaluator, node: ast.expr,
                          rel: str) -> tuple[list[ast.expr] | None, dict[str, Any]]:
    """The per-joint expressions of ``msg.position = ...`` and the constants they may use.

    Either a literal list (``[0.8 * math.sin(self.t), ...]``), or a call to a function of the
    package whose body returns such a list or a comprehension over a constant table.
    """
    if isinstance(node, ast.List):
        return list(node.elts), dict(evaluator.names)
    if isinstance(node, ast.Call) and isinstance(node.func, ast.Name):
        target = evaluator.names.get(node.func.id)
        if isinstance(target, tuple) and len(target) == 3 and target[0] == "function":
            tree = package.module_tree(target[1])
            if tree is None:
                return None, {}
            return _returned_expressions(Evaluator(tree, package.root), tree, target[2])
        if node.func.id in evaluator.functions:
            return _returned_expressions(evaluator, None, node.func.id)
    return None, {}


def _returned_expressions(evaluator: Evaluator, tree: ast.Module | None,
                          function_name: str) -> tuple[list[ast.expr] | None, dict[str, Any]]:
    function = evaluator.functions.get(function_name)
    if function is None:
        return None, {}
    returned = next((s.value for s in function.body if isinstance(s, ast.Return)), None)
    time = [a.arg for a in function.args.args]
    scope = dict(evaluator.names)
    if isinstance(returned, ast.List):
        return list(returned.elts), {**scope, "__time__": time}
    if isinstance(returned, ast.ListComp) and len(returned.generators) == 1 and not returned.generators[0].ifs:
        generator = returned.generators[0]
        rows = evaluator.value(generator.iter)
        if not isinstance(rows, (list, tuple)):
            return None, {}
        expressions: list[ast.expr] = []
        from .formulas import substitute

        for row in rows:
            bound: dict[str, Any] = {}
            evaluator._bind(generator.target, row, bound)
            if not all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in bound.values()):
                return None, {}
            expressions.append(substitute(returned.elt, bound))
        return expressions, {**scope, "__time__": time}
    return None, {}


def share_targets(package: Package) -> list[tuple[LaunchFile, ShareFile, int]]:
    """Every file of this package's share/ folder that a launch file builds a path to."""
    return [(launch, share, line) for launch in package.launch_files
            for share, line in launch.share_files if share.package == package.name]


