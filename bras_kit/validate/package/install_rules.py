""""file not found" at launch (BK600-BK608): what ``setup.py`` installs, what the launch file
opens, the ament index marker, the names, the dependencies, the maintainer's email.

Registered on import (:mod:`bras_kit.validate.package`); every hit carries ``file``.
"""

from __future__ import annotations

import os
from collections.abc import Iterator

from ...findings.registry import ERROR, INFO, Hit
from ...ros.package import (
    INDEX_FOLDER,
    PACKAGE_XML,
    SETUP_PY,
    Package,
    share_targets,
)
from .rules import (
    EMAIL,
    REQUIRED_FOLDERS,
    _at,
    _module_file,
    _not_written,
    _rviz_files,
    package_rule,
)

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
