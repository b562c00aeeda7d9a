"""BK628-BK629: what colcon and setuptools do with ``setup.cfg``.

An ament_python package's ``setup.cfg`` holds two lines that decide where its console scripts
land: ``[develop] script_dir`` and ``[install] install_scripts``, both ``$base/lib/PKG``.
``ros2 run PKG EXE`` looks for EXE in ``<prefix>/lib/PKG`` and nowhere else, so:

* colcon-core (b37a8d4, ``colcon_core/task/python/build.py`` lines 37-49) reads
  ``[install] install-scripts``, then ``install_scripts``, and passes the value to
  ``setup.py install --install-scripts`` (lines 125-131). Without it setuptools installs the
  scripts in its default, ``$base/bin``: the build succeeds and ``ros2 run`` says
  "No executable found" (BK628).
* setuptools still reads a dash-separated key such as ``script-dir`` in one of its sections,
  with a deprecation warning in every build: v68.1.2 (Ubuntu 24.04's, under Jazzy),
  ``setuptools/dist.py`` lines 744 and 770-802, ``warn_dash_deprecation``; the newest
  (7d53128, lines 625-647, ``_enforce_underscore``) words it anew and no longer looks at
  ``options.entry_points`` and ``options.package_data``. Release 78.0.0 refused such keys
  for a few days before 78.0.1 brought them back (BK629).
"""

from __future__ import annotations

import configparser
import os
import re
from collections.abc import Iterator

from ...core.message import Message
from ...findings.registry import ERROR, WARNING, Hit, hit
from ...ros.package import Package
from .rules import package_rule

SETUP_CFG = "setup.cfg"
# setuptools v68.1.2 dist.py lines 770-789: the sections whose keys it normalises (metadata,
# options..., a command of distutils or setuptools), but not these two
SKIPPED_SECTIONS = ("options.extras_require", "options.data_files")
COMMANDS = frozenset((
    # distutils.command.__all__ (the copy setuptools 68.1.2 vendors)
    "build", "build_py", "build_ext", "build_clib", "build_scripts", "clean", "install", "install_lib",
    "install_headers", "install_scripts", "install_data", "sdist", "register", "bdist", "bdist_dumb", "bdist_rpm",
    "check", "upload",
    # setuptools 68.1.2's distutils.commands (its setup.cfg); bdist_wheel is wheel's there, so not judged
    "alias", "bdist_egg", "develop", "dist_info", "easy_install", "editable_wheel", "egg_info",
    "install_egg_info", "rotate", "saveopts", "setopt", "test", "upload_docs",
))
# distutils' subst_vars (setuptools/_distutils/util.py, subst_vars and _subst_compat): "$base" and
# "{base}" name the prefix; "${base}" becomes "$" + the prefix, a folder named "$" in the package
BASE = re.compile(r"^(?:\$base|\{base\})/+lib/+(?P<package>[^/]+)/*$")
SECTION_LINE = re.compile(r"^\s*\[(?P<section>[^\]]+)\]")
KEY_LINE = re.compile(r"^(?P<key>[^\s:=#;][^:=]*?)\s*[:=]")


def _setuptools_section(section: str) -> bool:
    if section in SKIPPED_SECTIONS:
        return False
    return section == "metadata" or section.startswith("options") or section in COMMANDS


def _lines(text: str) -> list[tuple[int, str, str]]:
    """(line, section, key) of each key, as written."""
    found, section = [], ""
    for number, line in enumerate(text.splitlines(), 1):
        head = SECTION_LINE.match(line)
        if head:
            section = head.group("section").strip()
            continue
        key = KEY_LINE.match(line)
        if key and section:
            found.append((number, section, key.group("key").strip()))
    return found


def _read(pkg: Package) -> tuple[str | None, str | Message | None]:
    """(text, None), (None, "missing") or (None, why it cannot be read)."""
    from ...trust.learner_files import Unreadable, read_text, refusal

    full = os.path.join(pkg.root, SETUP_CFG)
    if not os.path.lexists(full):
        return None, "missing"
    try:
        return read_text(full, (pkg.root,), errors="replace"), None
    except Unreadable as exc:
        return None, refusal(exc.kind)


def _parsed(text: str) -> configparser.ConfigParser | str:
    parser = configparser.ConfigParser(interpolation=None)
    parser.optionxform = str  # type: ignore[assignment,method-assign]  # as colcon reads it (build.py line 42)
    try:
        parser.read_string(text, SETUP_CFG)
    except configparser.Error as exc:
        return str(exc).splitlines()[0]
    return parser


@package_rule("BK628", "console-scripts-not-in-lib", ERROR)
def console_scripts_not_in_lib(pkg: Package) -> Iterator[Hit]:
    setup = pkg.setup
    if setup is None or not setup.scripts:
        return  # no console script: setup.cfg decides nothing ros2 run needs
    name = pkg.name
    scripts = sorted(entry.name for entry in setup.scripts)
    common = {"package": name, "executable": scripts[0], "scripts": scripts, "target": f"$base/lib/{name}"}
    text, why = _read(pkg)
    if text is None:
        if why == "missing":
            yield hit("file", None, None, "missing", file=SETUP_CFG, **common)
        return  # a setup.cfg that cannot be read: BK600's business
    pkg.read.add(SETUP_CFG)
    parser = _parsed(text)
    if isinstance(parser, str):
        yield hit("file", None, None, "unparsed", file=SETUP_CFG, detail=parser, **common)
        return
    # colcon's order: the dash key first, then the underscore one (build.py lines 45-48)
    value = parser.get("install", "install-scripts", fallback=None)
    if value is None:
        value = parser.get("install", "install_scripts", fallback=None)
    lines = {(section, key.replace("-", "_")): number for number, section, key in _lines(text)}
    if value is None:
        yield hit("file", None, _section_line(text, "install"), "no_key", file=SETUP_CFG, **common)
        return
    found = BASE.match(value.strip())
    if found is None or found.group("package") != name:
        yield hit("file", None, lines.get(("install", "install_scripts")), "elsewhere", file=SETUP_CFG,
                  value=value.strip(), **common)


def _section_line(text: str, section: str) -> int | None:
    for number, line in enumerate(text.splitlines(), 1):
        head = SECTION_LINE.match(line)
        if head and head.group("section").strip() == section:
            return number
    return None


@package_rule("BK629", "setup-cfg-dash-keys", WARNING)
def setup_cfg_dash_keys(pkg: Package) -> Iterator[Hit]:
    text, _ = _read(pkg)
    if text is None:
        return
    pkg.read.add(SETUP_CFG)
    for number, section, key in _lines(text):
        if "-" in key and _setuptools_section(section):
            yield hit("file", None, number, file=SETUP_CFG, key=key, section=section,
                      underscore=key.replace("-", "_"))
