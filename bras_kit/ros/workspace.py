"""The colcon workspace a command is typed in: its root, its packages by name, their build order.

The tutorial types ``colcon build`` in ``~/ros2_cellule_ws`` and ``ros2 launch bras_description
affichage.launch.py`` from there or from any folder below it (after ``source install/setup.bash``).
``bras-kit build``, ``bras-kit launch PKG FILE`` and ``bras-kit run PKG EXE`` find the workspace
the same way here, walking up from the current folder to the first one holding ``src/``, and
find a package by the name its ``package.xml`` gives, as colcon lists them:

- colcon-recursive-crawl (``package_discovery/recursive_crawl.py``, lines 60-83) walks the base
  path, stops below a folder it identified as a package, skips folders starting with a dot;
- a folder holding ``COLCON_IGNORE`` (colcon-core ``package_identification/ignore.py``, lines
  26-29), ``AMENT_IGNORE`` or ``CATKIN_IGNORE`` (colcon-ros ``package_identification/ros.py``,
  lines 49-52) is skipped with everything below it;
- packages build in topological order of their dependencies, ties by name (colcon-core
  ``topological_order.py``).

Outside any workspace, the one whose ``install/setup.bash`` was sourced in this shell is used
(COLCON_PREFIX_PATH), as ``ros2 launch`` finds a sourced workspace's packages from anywhere.

::

    from ..ros.workspace import find_workspace, resolve_package
    workspace = find_workspace(".")             # None outside a workspace
    [p.name for p in workspace.packages]        # ['bras_description', 'cellule_bringup'], build order
    folder, workspace = resolve_package("bras_description")
"""

from __future__ import annotations

import os
from collections.abc import Iterable
from dataclasses import dataclass
from typing import Any

from ..core.errors import ParameterError
from ..core.message import M

IGNORE_MARKERS = ("COLCON_IGNORE", "AMENT_IGNORE", "CATKIN_IGNORE")
# package.xml's dependency tags colcon orders a build by (build and run categories of catkin_pkg)
DEPEND_TAGS = ("depend", "build_depend", "buildtool_depend", "build_export_depend", "exec_depend",
               "buildtool_export_depend")
MAX_DEPTH = 64  # how far up a workspace root is looked for


@dataclass(frozen=True)
class WorkspacePackage:
    """A package of the workspace: its name, folder and the workspace packages it depends on."""

    name: str  # package.xml's <name> (the folder's name when it has none)
    folder: str  # absolute
    depends: tuple[str, ...] = ()


@dataclass(frozen=True)
class Workspace:
    """A colcon workspace: its root folder and its packages, in build order."""

    root: str  # absolute: the folder holding src/ (where colcon build is typed)
    packages: tuple[WorkspacePackage, ...]  # in build order

    @property
    def src(self) -> str:
        return os.path.join(self.root, "src")

    @property
    def install(self) -> str:
        return os.path.join(self.root, "install")

    def package(self, name: str) -> WorkspacePackage | None:
        return next((p for p in self.packages if p.name == name), None)

    def holding(self, folder: str) -> WorkspacePackage | None:
        """The package whose folder is ``folder``."""
        full = os.path.realpath(folder)
        return next((p for p in self.packages if os.path.realpath(p.folder) == full), None)

    @property
    def names(self) -> list[str]:
        return [p.name for p in self.packages]


def _manifest(folder: str, root: str | None = None) -> tuple[str, tuple[str, ...]]:
    """(name, dependencies) from ``folder/package.xml``, read through the one reader beneath
    ``root`` (default: the folder itself): no link out of it, never a pipe or a device. The
    folder's name when it cannot be read (the build then says what is wrong with it)."""
    from ..core.errors import BrasKitError
    from ..model.xmlio import read_xml

    try:
        xml = read_xml(os.path.join(os.path.abspath(folder), "package.xml"),
                       (os.path.abspath(root if root is not None else folder),))
    except (BrasKitError, OSError):
        return os.path.basename(folder), ()
    name = xml.find("name")
    depends = tuple(sorted({(node.text or "").strip() for tag in DEPEND_TAGS for node in xml.findall(tag)} - {""}))
    text = (name.text or "").strip() if name is not None else ""
    return text or os.path.basename(folder), depends


def _setup_py_name(folder: str) -> str:
    """A plain Python package's name: setup.py's ``name=`` read without running it (colcon-python-setup-py
    runs it; the build does too, and says the name it got), else the folder's."""
    from .staticpy import Evaluator, call_name, calls, keyword, known, parse_python

    tree, _why, _line = parse_python(os.path.join(folder, "setup.py"), folder)
    if tree is not None:
        evaluator = Evaluator(tree, folder)
        for call in calls(tree):
            if call_name(call.func) in ("setup", "setuptools.setup"):
                node = keyword(call, "name")
                value = evaluator.value(node, evaluator.names) if node is not None else None
                if isinstance(value, str) and known(value) and value:
                    return value
    return os.path.basename(folder)


def package_name(folder: str) -> str:
    """The name colcon gives the package at ``folder`` (its package.xml's, else setup.py's, else the folder's)."""
    if not os.path.isfile(os.path.join(folder, "package.xml")) and os.path.isfile(os.path.join(folder, "setup.py")):
        return _setup_py_name(folder)
    return _manifest(folder)[0]


MAX_CRAWLED = 100_000  # folders of src/ looked into


def read_packages(src: str) -> list[WorkspacePackage]:
    """The packages below ``src``, found as colcon finds them (see the module's notes), by name.
    Folders are listed through the one reader, by descriptor: a link to a folder is followed
    when it stays inside ``src`` (colcon follows links), never out of it; a folder reached twice
    (a link back up) is crawled once."""
    from ..trust.beneath import FOLDER, Outside, open_beneath
    from ..trust.learner_files import is_folder, list_folder

    top = os.path.abspath(src)
    found: list[WorkspacePackage] = []
    seen: set[tuple[int, int]] = set()
    todo = [top]
    while todo and len(seen) < MAX_CRAWLED:
        folder = todo.pop()
        try:
            fd = open_beneath(top, folder, want=FOLDER)
        except Outside:
            continue
        try:
            info = os.fstat(fd)
        finally:
            os.close(fd)
        if (info.st_dev, info.st_ino) in seen:
            continue
        seen.add((info.st_dev, info.st_ino))
        try:
            entries = list_folder(folder, (top,))
        except OSError:
            continue
        names = {name for name, _kind in entries}
        if any(marker in names for marker in IGNORE_MARKERS):
            continue
        if "package.xml" in names:
            name, depends = _manifest(folder, top)
            found.append(WorkspacePackage(name, folder, depends))
            continue  # packages do not nest
        if "setup.py" in names:  # no package.xml: colcon-python-setup-py's plain Python package
            found.append(WorkspacePackage(_setup_py_name(folder), folder))
            continue
        todo.extend(os.path.join(folder, name) for name, kind in reversed(entries) if not name.startswith(".")
                    and (kind == "folder" or kind == "link" and is_folder(os.path.join(folder, name), (top,))))
    return sorted(found, key=lambda p: p.name)


def build_order(packages: list[WorkspacePackage]) -> list[WorkspacePackage]:
    """Each package after the workspace packages it depends on, ties by name; a cycle is left in
    name order (colcon refuses it; the builds here do not depend on each other's output)."""
    left = {p.name: p for p in packages}
    order: list[WorkspacePackage] = []
    while left:
        ready = sorted(name for name, p in left.items() if not (set(p.depends) & set(left) - {name}))
        for name in ready or sorted(left):
            order.append(left.pop(name))
    return order


def workspace_root(start: str) -> str | None:
    """The first folder from ``start`` up that holds ``src/`` with a package below it."""
    folder = os.path.abspath(start)
    for _ in range(MAX_DEPTH):
        src = os.path.join(folder, "src")
        if os.path.isdir(src) and read_packages(src):
            return folder
        parent = os.path.dirname(folder)
        if parent == folder:
            return None
        folder = parent
    return None


def find_workspace(start: str = ".") -> Workspace | None:
    """The colcon workspace ``start`` is in (its root or any folder below), or None."""
    root = workspace_root(start)
    if root is None:
        return None
    packages = read_packages(os.path.join(root, "src"))
    _refuse_duplicates(root, packages)
    return Workspace(root, tuple(build_order(packages)))


def _refuse_duplicates(root: str, packages: list[WorkspacePackage]) -> None:
    """colcon builds nothing in a workspace where two packages have one name ("Duplicate package
    names not supported", whichever verb): neither does bras-kit, which would build one of them
    without a word (a copy kept as a backup in ``src/``, say, instead of the one being edited)."""
    folders: dict[str, list[str]] = {}
    for package in packages:
        folders.setdefault(package.name, []).append(os.path.relpath(package.folder, root))
    twice = {name: sorted(found) for name, found in sorted(folders.items()) if len(found) > 1}
    if twice:
        first = next(iter(twice.values()))
        raise ParameterError(
            M("two packages of the workspace {root} have one name: {names}", root=root,
              names="; ".join(f"{name} ({', '.join(found)})" for name, found in twice.items())),
            path=os.path.join(root, first[-1], "package.xml"), element="name",
            hint=M("colcon builds none of them (Duplicate package names not supported): keep one folder per name, "
                   "by moving the other out of src/, giving it a name of its own in its package.xml, or putting an "
                   "empty file named COLCON_IGNORE in it"))


def sourced_workspace(environ: Any = None) -> Workspace | None:
    """The workspace whose ``install/setup.bash`` was sourced in this shell: colcon's setup files
    put its install folder on COLCON_PREFIX_PATH (bras-kit build writes one that does the same)."""
    for prefix in (os.environ if environ is None else environ).get("COLCON_PREFIX_PATH", "").split(os.pathsep):
        if prefix and os.path.basename(os.path.normpath(prefix)) == "install":
            root = os.path.dirname(os.path.normpath(prefix))
            if workspace_root(root) == os.path.abspath(root):
                return find_workspace(root)
    return None


def current_workspace() -> Workspace | None:
    """The workspace of the current folder (its root or below), else the one sourced in this shell."""
    return find_workspace(".") or sourced_workspace()


def is_package_folder(folder: str) -> bool:
    return os.path.isfile(os.path.join(folder, "package.xml"))


def is_package(path: str) -> bool:
    """A folder holding ``package.xml`` and ``setup.py`` (an ament_python package). Nothing is
    read here: a manifest that is a link out is still a package, which the package model then
    refuses to read (BK600 says so), never a folder passed over in silence."""
    return all(os.path.lexists(os.path.join(path, name)) and not os.path.isdir(os.path.join(path, name))
               for name in ("package.xml", "setup.py"))


def find_packages(paths: Iterable[str]) -> list[str]:
    """The ament_python packages among ``paths`` and below them (hidden folders skipped), walked
    through the one reader: a link to a folder is never walked into."""
    from ..trust.learner_files import walk

    out: list[str] = []
    for path in paths:
        if not os.path.isdir(path):
            continue
        for folder, dirs, _ in walk(path, (path,)):  # both named from the current folder, as typed
            dirs[:] = sorted(d for d in dirs if not d.startswith("."))
            if is_package(folder):
                out.append(folder)
                dirs[:] = []  # packages do not nest
    return out


def resolve_package(where: str, *, command: str = "launch") -> tuple[str, Workspace | None]:
    """The package folder ``where`` names for ``bras-kit launch|run WHERE``, and its workspace:
    a package folder as given, else a package's name in the workspace of the current folder (its
    source in ``src/``, which bras-kit builds as colcon does). A clear error otherwise; its hint
    never repeats the command that failed."""
    if os.path.isdir(where) and is_package_folder(where):
        return where, find_workspace(where)
    workspace = current_workspace()
    named = workspace.package(where) if workspace is not None and os.sep not in where.strip(os.sep) else None
    if named is None and workspace is not None and where in (".", ""):
        named = _around(workspace, ".")  # typed inside a package's folder, as the tutorial's `cd bras_description`
    if named is not None:
        return _shown(named.folder), workspace
    if workspace is not None:
        built = os.path.isdir(os.path.join(workspace.install, where, "share", where))
        if built:
            raise ParameterError(
                M("package '{name}' is in the workspace's install/ but its source is not in {src}",
                  name=where, src=workspace.src),
                hint=M("bras-kit builds each package from its source, as colcon does: put the package "
                       "folder back under {src}", src=workspace.src))
        if where in (".", "") or os.path.isdir(where):
            raise ParameterError(
                M("{folder} is not a package folder (no package.xml)", folder=where),
                hint=M("name a package of the workspace {root}: {names}", root=workspace.root,
                       names=", ".join(workspace.names)))
        raise ParameterError(
            M("package '{name}' not found in the workspace {root}", name=where, root=workspace.root),
            hint=M("its packages, by the name in their package.xml: {names}", names=", ".join(workspace.names)))
    if os.path.isdir(where):
        raise ParameterError(
            M("{folder} is not a package folder (no package.xml), and no colcon workspace (a folder with src/) "
              "holds the current folder", folder=where),
            hint=M("type the command in your workspace (cd ~/ros2_cellule_ws) or give the path of a package "
                   "folder (with package.xml)"))
    raise ParameterError(
        M("package '{name}' not found: no such folder here, and no colcon workspace (a folder with src/) "
          "holds the current folder", name=where),
        hint=M("type the command in your workspace (cd ~/ros2_cellule_ws) or give the path of a package "
               "folder (with package.xml)"))


def _around(workspace: Workspace, folder: str) -> WorkspacePackage | None:
    """The package of ``workspace`` whose folder holds ``folder``."""
    full = os.path.realpath(folder)
    for package in workspace.packages:
        root = os.path.realpath(package.folder)
        if full == root or full.startswith(root + os.sep):
            return package
    return None


def _shown(path: str) -> str:
    """``path`` relative to the current folder when it is below it, else as it is."""
    full = os.path.abspath(path)
    here = os.path.abspath(".")
    if full == here:
        return "."
    if full.startswith(here + os.sep):
        return os.path.relpath(full, here)
    return full


def others(workspace: Workspace | None, folder: str) -> list[str]:
    """The workspace's packages other than the one at ``folder``, in build order: what colcon
    builds beside it, so that get_package_share_directory and FindPackageShare find them."""
    if workspace is None:
        return []
    full = os.path.realpath(folder)
    return [p.folder for p in workspace.packages if os.path.realpath(p.folder) != full]


def build_others(folders: list[str], install_base: str) -> tuple[list[str], list[str]]:
    """``folders`` built into ``install_base`` (one build_package each): the prefixes of those
    built, and the names of those whose build stopped (``bras-kit build`` says why)."""
    from .build import build_package

    prefixes, failed = [], []
    for folder in folders:
        record = build_package(folder, install_base)
        if record.failure is None:
            prefixes.append(record.prefix)
        else:
            failed.append(record.package)
    return prefixes, failed


def stale_install(workspace: Workspace | None, package: str, fresh_prefix: str) -> list[str] | None:
    """The files of the workspace's ``install/PACKAGE`` that differ from a build of the sources as
    they are now (``fresh_prefix``: bras-kit's build, colcon's layout), package-relative under the
    prefix (``share/PKG/launch/x.launch.py``); [] when none differs; None when the workspace has
    no install of the package (colcon build never ran, or no workspace). ``ros2 launch`` reads
    that install tree, never the sources: a file saved since ``colcon build`` is not used.
    An install made with --symlink-install links to the sources, and is current but for new files."""
    from ..trust.learner_files import read_bytes, walk

    if workspace is None:
        return None
    old = os.path.join(workspace.install, package)
    if not os.path.isdir(os.path.join(old, "share", package)):
        return None
    # --symlink-install: share/ holds links into the sources, and the Python package is installed
    # in develop mode (colcon-ros's ament_python build runs setup.py develop): its modules are the sources
    linked = any(os.path.islink(os.path.join(root, name))
                 for root, _dirs, files in walk(os.path.join(old, "share"), (old,)) for name in files)
    differ = []
    files = set(_installed_files(fresh_prefix, package)) | set(_installed_files(old, package))
    for relative in sorted(f for f in files if not (linked and f.startswith("lib" + os.sep))):
        try:
            now = read_bytes(os.path.join(fresh_prefix, relative), (fresh_prefix,))
        except OSError:
            now = None
        try:  # the old tree's links lead into the sources (--symlink-install): followed within the workspace
            before = read_bytes(os.path.join(old, relative), (old, workspace.root))
        except OSError:
            before = None
        if now != before:
            differ.append(relative)
    return differ


def _installed_files(prefix: str, package: str) -> list[str]:
    """The files of an install prefix that ros2 launch and ros2 run read for ``package``: its share
    folder (launch files, URDF, .rviz) and its Python package (lib/pythonX.Y/site-packages/PKG)."""
    from ..trust.learner_files import walk

    out = []
    for top in (os.path.join(prefix, "share", package), os.path.join(prefix, "lib")):
        if not os.path.isdir(top):
            continue
        for root, dirs, files in walk(top, (prefix,)):
            dirs[:] = sorted(d for d in dirs if d != "__pycache__" and not d.endswith(".egg-info"))
            for name in sorted(files):
                path = os.path.relpath(os.path.join(root, name), prefix)
                if path.startswith("lib" + os.sep) and f"{os.sep}site-packages{os.sep}{package}{os.sep}" not in path:
                    continue  # lib/PKG/ holds the console scripts colcon writes, the same for a same setup.cfg
                if name.endswith((".pyc", ".dsv", ".ps1", ".sh", ".bash", ".zsh")):
                    continue
                out.append(path)
    return out
