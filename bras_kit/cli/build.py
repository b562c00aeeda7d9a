"""bras-kit build: what ``colcon build`` does for ament_python packages (install/PKG/...)."""

from __future__ import annotations

import argparse
import os
import sys

from ..message import M

_EPILOG = """\
Each package's setup.py runs (in the sandbox, setup() recorded rather than installing) and the
install tree is laid out as colcon lays it out: install/PKG/share/PKG/... from data_files, the
ament index marker, one script per console_scripts entry in install/PKG/lib/PKG/.

examples:
  bras-kit build ~/ros2_cellule_ws          every package under src/, into ~/ros2_cellule_ws/install
  bras-kit build bras_description           one package folder, into ./install
"""


def configure(parser: argparse.ArgumentParser) -> None:
    parser.formatter_class = argparse.RawDescriptionHelpFormatter
    parser.epilog = _EPILOG
    parser.add_argument("where", nargs="?", default=".", metavar="WS|PKG_DIR",
                        help="a colcon workspace (with src/) or a package folder (default: .)")
    parser.add_argument("--install-base", metavar="DIR",
                        help="where to lay out the install tree (default: WS/install, or ./install)")


def install_base(where: str) -> str:
    """colcon's install/ for ``where``: the workspace's, else the current folder's."""
    full = os.path.abspath(where)
    if os.path.isdir(os.path.join(full, "src")):
        return os.path.join(full, "install")
    parts = full.split(os.sep)
    if "src" in parts[:-1]:
        at = len(parts) - 1 - parts[::-1].index("src")
        return os.sep.join(parts[:at] + ["install"])
    return os.path.abspath("install")


def run(args: argparse.Namespace) -> int:
    from ..errors import ParameterError
    from ..i18n import current_language, say
    from ..ros.build import build_package
    from ..validate.findings import FileResult, finding
    from ..validate.package import find_packages
    from ..validate.package.launch_rules import build_hits
    from ..validate.registry import RULES
    from ..validate.report import format_text

    lang = args.lang or current_language()
    if not os.path.isdir(args.where):
        raise ParameterError(M("no such folder"), path=args.where,
                             hint=M("give a colcon workspace or a package folder"))
    packages = find_packages([args.where]) or ([args.where] if os.path.isfile(
        os.path.join(args.where, "package.xml")) else [])
    if not packages:
        raise ParameterError(M("no package found in {folder}", folder=args.where),
                             hint=M("a package folder holds package.xml and setup.py"))
    base = args.install_base or install_base(args.where)
    failed = 0
    for folder in packages:
        record = build_package(folder, base)
        print(f"Starting >>> {record.package}")
        if record.failure is None:
            print(f"Finished <<< {record.package}")
            continue
        failed += 1
        results = [FileResult(os.path.join(folder, str(hit.params.get("file", ""))), [finding(RULES["BK630"], hit)])
                   for hit in build_hits(record, folder)]
        sys.stdout.write(format_text(results, lang))
    print(say(M("install tree: {folder}", folder=base), lang))
    return 1 if failed else 0
