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

    from bras_kit.ros.build import build_package
    record = build_package("src/bras_description", "install")
    record.failure            # None when colcon would say "Finished <<< bras_description"
    record.prefix             # install/bras_description
"""

from __future__ import annotations

import os
import shutil
import sys
from dataclasses import dataclass, field
from typing import Any

SETUP_CPU_SECONDS = 10
SETUP_WALL_SECONDS = 20.0
SETUP_MEMORY_BYTES = 512 << 20
INDEX = "share/ament_index/resource_index/packages"
PYTHON_LIB = f"lib/python{sys.version_info[0]}.{sys.version_info[1]}/site-packages"


@dataclass(frozen=True)
class Installed:
    target: str  # relative to the package's prefix, e.g. share/bras_description/urdf/bras.urdf
    source: str  # relative to the package folder


@dataclass(frozen=True)
class BuildFailure:
    """Why colcon would stop. ``kind``: "ament_cmake", "no_setup", "setup_raised", "no_setup_call",
    "missing_source" (the marker when ``source`` is resource/PKG), "outside"; ``colcon``: the lines
    colcon prints (its own words and setuptools'); ``file``/``line`` the learner's place."""

    kind: str
    colcon: tuple[str, ...]
    file: str = ""
    line: int = 0
    source: str = ""
    detail: str = ""


@dataclass
class BuildRecord:
    package: str
    root: str  # the package folder (absolute)
    prefix: str  # install/PKG (absolute)
    installed: list[Installed] = field(default_factory=list)
    scripts: list[tuple[str, str, str]] = field(default_factory=list)  # (name, module, function)
    setup_line: int = 0
    data_files_line: int = 0
    failure: BuildFailure | None = None

    def source_of(self, path: str) -> str | None:
        """The package file installed at ``path`` (absolute, in the install tree), if any."""
        full = os.path.abspath(path)
        for item in self.installed:
            if os.path.join(self.prefix, item.target) == full:
                return item.source
        return None


def _failed(package: str, lines: list[str]) -> tuple[str, ...]:
    return (f"--- stderr: {package}", *lines, "---", f"Failed   <<< {package} [exited with code 1]")


def _manifest(root: str) -> tuple[str, str]:
    """(name, build_type) from package.xml; ("", "") when it cannot be read."""
    from ..errors import BrasKitError
    from ..xmlio import read_xml

    try:
        xml = read_xml(os.path.join(root, "package.xml"))
    except (BrasKitError, OSError):
        return "", ""
    name = xml.find("name")
    export = xml.find("export")
    build_type = export.find("build_type") if export is not None else None
    return ((name.text or "").strip() if name is not None else "",
            (build_type.text or "").strip() if build_type is not None else "")


def build_package(root: str, install_base: str) -> BuildRecord:
    """Build the package at ``root`` into ``install_base/PKG`` (replacing what was there).
    Learner mistakes come back as ``record.failure``; only the sandbox's own limits raise."""
    root = os.path.abspath(root)
    name, build_type = _manifest(root)
    package = name or os.path.basename(root)
    record = BuildRecord(package, root, os.path.abspath(os.path.join(install_base, package)))
    if build_type and build_type != "ament_python":
        lines = [f"CMake Error: The source directory \"{root}\" does not appear to contain CMakeLists.txt."] \
            if not os.path.isfile(os.path.join(root, "CMakeLists.txt")) else []
        record.failure = BuildFailure("ament_cmake", _failed(package, lines) if lines else (), "package.xml",
                                      _line_of(root, "package.xml", "<build_type>"), detail=build_type)
        return record
    if not os.path.isfile(os.path.join(root, "setup.py")):
        record.failure = BuildFailure("no_setup", (), "setup.py")
        return record
    called = _run_setup(root)
    if "error" in called:
        error = called["error"]
        record.failure = BuildFailure("setup_raised", _failed(package, [error["text"]]), "setup.py",
                                      error["line"], detail=error["text"])
        return record
    if "setup" not in called:
        record.failure = BuildFailure("no_setup_call", (), "setup.py")
        return record
    setup = called["setup"]
    record.setup_line = setup.get("_line", 0)
    record.data_files_line = _line_of(root, "setup.py", "data_files") or record.setup_line
    if isinstance(setup.get("name"), str) and setup["name"]:
        record.package = setup["name"]
        record.prefix = os.path.abspath(os.path.join(install_base, record.package))
    failure = _plan_install(record, setup)
    if failure is not None:
        record.failure = failure
        return record
    _lay_out(record, setup)
    return record


def _line_of(root: str, relative: str, text: str) -> int:
    try:
        with open(os.path.join(root, relative), encoding="utf-8", errors="replace") as handle:
            for number, line in enumerate(handle, 1):
                if text in line:
                    return number
    except OSError:
        pass
    return 0


def _plan_install(record: BuildRecord, setup: dict[str, Any]) -> BuildFailure | None:
    """What install_data would copy (setuptools/_distutils/command/install_data.py: a missing
    source stops it with distutils' own words, from file_util.copy_file)."""
    for entry in setup.get("data_files") or []:
        if isinstance(entry, str):
            folder, files = "", [entry]
        else:
            folder, files = entry[0], list(entry[1])
        target_folder = os.path.normpath(str(folder)).replace(os.sep, "/")
        if os.path.isabs(target_folder) or target_folder.startswith(".."):
            return BuildFailure("outside", (), "setup.py", record.data_files_line, detail=str(folder))
        for source in files:
            source = str(source)
            full = os.path.join(record.root, source)
            if not os.path.isfile(full):
                message = f"error: can't copy '{source}': doesn't exist or not a regular file"
                return BuildFailure("missing_source", _failed(record.package, [message]), "setup.py",
                                    _line_of(record.root, "setup.py", os.path.basename(source).split("'")[0])
                                    or record.data_files_line, source=source, detail=target_folder)
            target = os.path.join(target_folder, os.path.basename(source)) if target_folder not in ("", ".") \
                else os.path.basename(source)
            record.installed.append(Installed(target.replace(os.sep, "/"),
                                              os.path.relpath(full, record.root).replace(os.sep, "/")))
    for line in _console_scripts(setup):
        left, _, right = line.partition("=")
        module, _, function = right.strip().partition(":")
        record.scripts.append((left.strip(), module.strip(), function.strip()))
    return None


def _console_scripts(setup: dict[str, Any]) -> list[str]:
    entry_points = setup.get("entry_points") or {}
    scripts = entry_points.get("console_scripts", []) if isinstance(entry_points, dict) else []
    if isinstance(scripts, str):
        scripts = [s for s in scripts.splitlines() if s.strip()]
    return [str(s) for s in scripts]


SCRIPT = """#!/usr/bin/python3
# EASY-INSTALL-ENTRY-SCRIPT: '{dist}','console_scripts','{name}'
# written by bras-kit build: {module}:{function}
import sys
from {module} import {function}
sys.exit({function}())
"""


def _lay_out(record: BuildRecord, setup: dict[str, Any]) -> None:
    if os.path.isdir(record.prefix):
        shutil.rmtree(record.prefix)
    os.makedirs(record.prefix)
    for item in record.installed:
        target = os.path.join(record.prefix, item.target)
        os.makedirs(os.path.dirname(target), exist_ok=True)
        shutil.copyfile(os.path.join(record.root, item.source), target)
    for package in setup.get("packages") or []:
        source = os.path.join(record.root, *str(package).split("."))
        if not os.path.isdir(source):
            continue
        target = os.path.join(record.prefix, PYTHON_LIB, *str(package).split("."))
        os.makedirs(target, exist_ok=True)
        for name in os.listdir(source):
            if name.endswith(".py") and os.path.isfile(os.path.join(source, name)):
                shutil.copyfile(os.path.join(source, name), os.path.join(target, name))
    for name, module, function in record.scripts:
        if not name or "/" in name or name.startswith("."):
            continue
        path = os.path.join(record.prefix, "lib", record.package, name)
        os.makedirs(os.path.dirname(path), exist_ok=True)
        with open(path, "w", encoding="utf-8") as handle:
            handle.write(SCRIPT.format(dist=record.package, name=name, module=module, function=function))
        os.chmod(path, 0o755)
    colcon = os.path.join(record.prefix, "share", "colcon-core", "packages", record.package)
    os.makedirs(os.path.dirname(colcon), exist_ok=True)
    open(colcon, "w").close()


# ---------------------------------------------------------------- the child


def _run_setup(root: str) -> dict[str, Any]:
    import tempfile

    from ..sandbox import ResourceLimitError, run_limited
    from .contain import containment

    with tempfile.TemporaryDirectory(prefix="bras-kit-setup-") as workdir:
        # the learner's setup.py reads its package and writes nowhere (setup() is recorded)
        walls = containment("auto", workdir, (root,))
        try:
            return run_limited(_run_setup_here, root, cpu_seconds=SETUP_CPU_SECONDS, memory_bytes=SETUP_MEMORY_BYTES,
                               wall_seconds=SETUP_WALL_SECONDS, what=f"{root}/setup.py", contain=walls)
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


def _run_setup_here(root: str) -> dict[str, Any]:
    """In the child: ``python setup.py`` with setup() recorded."""
    import inspect
    import runpy
    import traceback
    import types

    os.chdir(root)
    sys.path.insert(0, root)
    sys.argv = [os.path.join(root, "setup.py"), "build"]
    called: dict[str, Any] = {}
    setup_path = os.path.join(root, "setup.py")

    def setup(**kwargs: Any) -> None:
        line = 0
        for frame in inspect.stack():
            if os.path.abspath(frame.filename) == setup_path:
                line = frame.lineno
                break
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
    return called
