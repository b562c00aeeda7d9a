"""bras-kit build: what ``colcon build`` does for ament_python packages (install/PKG/...)."""

from __future__ import annotations

import argparse
import os
import stat
import sys

from ..core.message import M

_EPILOG = """\
Each package's setup.py runs (in the sandbox, setup() recorded rather than installing) and the
install tree is laid out as colcon lays it out: install/PKG/share/PKG/... from data_files, the
ament index marker, one script per console_scripts entry in install/PKG/lib/PKG/.

Typed in a colcon workspace (the folder holding src/, e.g. ~/ros2_cellule_ws) or any folder below
it, every package of the workspace is built into its install/, in the order of their
dependencies, as 'colcon build' typed at its root; folders holding COLCON_IGNORE are skipped.

examples:
  bras-kit build                                    the workspace you are in, into its install/
  bras-kit build ~/ros2_cellule_ws                  every package under src/, into ~/ros2_cellule_ws/install
  bras-kit build src/bras_description               that package alone (colcon build --packages-select)
"""


def configure(parser: argparse.ArgumentParser) -> None:
    parser.formatter_class = argparse.RawDescriptionHelpFormatter
    parser.epilog = _EPILOG
    parser.add_argument("where", nargs="?", default=None, metavar="WS|PKG_DIR",
                        help="a colcon workspace (with src/) or a package folder (default: the workspace of the "
                             "current folder, else the packages below it)")
    parser.add_argument("--install-base", metavar="DIR",
                        help="where to lay out the install tree (default: WS/install, or ./install)")
    parser.add_argument("--symlink-install", action="store_true",
                        help="as colcon build --symlink-install: the install tree links to build/PKG, which links "
                             "to the package's files, so an edited URDF or launch file needs no new build")


def install_base(where: str) -> str:
    """colcon's install/ for ``where``: its workspace's, else the current folder's."""
    from ..ros.workspace import find_workspace

    workspace = find_workspace(where)
    if workspace is not None:
        return workspace.install
    full = os.path.abspath(where)
    if os.path.isdir(os.path.join(full, "src")):
        return os.path.join(full, "install")
    return os.path.abspath("install")


def packages_to_build(where: str | None) -> tuple[list[str], str]:
    """The package folders ``bras-kit build [WHERE]`` builds, in order, and the install/ they go to."""
    from ..core.errors import ParameterError
    from ..ros.workspace import find_workspace, is_package_folder
    from ..validate.package import find_packages

    folder = "." if where is None else where
    if not os.path.isdir(folder):
        raise ParameterError(M("no such folder"), path=folder,
                             hint=M("give a colcon workspace or a package folder"))
    workspace = find_workspace(folder)
    if where is not None and is_package_folder(where):
        return [where], install_base(where)
    if workspace is not None:
        return [p.folder for p in workspace.packages], workspace.install
    packages = find_packages([folder])
    if not packages:
        raise ParameterError(M("no package found in {folder}", folder=os.path.abspath(folder)),
                             hint=M("a colcon workspace holds its packages in src/; a package folder holds "
                                    "package.xml and setup.py"))
    return packages, install_base(folder)


def run(args: argparse.Namespace) -> int:
    from ..core.i18n import current_language, say
    from ..findings.data import FileResult, finding
    from ..findings.registry import RULES
    from ..findings.report import format_text
    from ..ros.build import build_package
    from ..ros.workspace import package_name
    from ..trust.inert import for_terminal
    from ..validate.package.build_reach import setup_blocked_hits
    from ..validate.package.launch_rules import build_hits

    lang = args.lang or current_language()
    packages, base = packages_to_build(args.where)
    base = os.path.abspath(args.install_base) if args.install_base else base
    failed: list[str] = []
    finished = 0
    for folder in packages:
        print(f"Starting >>> {for_terminal(package_name(folder))}", flush=True)  # the learner's text, inert
        record = build_package(folder, base, symlink_install=args.symlink_install)
        blocked = [FileResult(os.path.join(folder, str(hit.params["file"])), [finding(RULES["BK639"], hit)])
                   for hit in setup_blocked_hits(record.blocked)]
        if blocked:  # what setup.py tried that its walls stopped, at its lines (docs/security.md)
            sys.stdout.write(format_text(blocked, lang))
        if record.refused_manifest:  # colcon passes over it without a word: the learner is told why here
            print(say(M("note: catkin_pkg refuses {file} ({words}), so colcon builds {package} as a plain Python "
                        "package: no AMENT_PREFIX_PATH hook, and ros2 pkg list, ros2 run and ros2 launch do not "
                        "find it; bras-kit validate {folder} says what to change",
                        file=for_terminal(os.path.join(folder, "package.xml")),
                        words=for_terminal(record.refused_manifest.replace("\n", " ")),
                        package=for_terminal(record.package), folder=for_terminal(folder)), lang))
        if record.failure is None:
            print(f"Finished <<< {for_terminal(record.package)}")
            finished += 1
            continue
        failed.append(record.package)
        results = [FileResult(os.path.join(folder, str(hit.params.get("file", ""))), [finding(RULES["BK630"], hit)])
                   for hit in build_hits(record, folder)]
        shown = format_text(results, lang) if results else ""
        if results:
            sys.stdout.write(shown)
            _print_colcon_words(record.package, record.failure.colcon, shown)
        else:  # no setup.py, or no setup() in it: what colcon-ros needs to build an ament_python package
            print(say(M("{package} was not built: {file} is missing or calls no setup()", package=record.package,
                        file=os.path.join(folder, record.failure.file or "setup.py")), lang))
        if f"Failed   <<< {record.package}" not in shown:  # colcon's line for a failed package, once
            print(f"Failed   <<< {for_terminal(record.package)}")
    # colcon writes install/setup.bash once the packages' jobs ended, whatever their outcome
    # (colcon_core/verb/build.py, main, lines 152-156, and _create_prefix_scripts, lines 219-230 of
    # colcon-core 0.21.3): a later `source` then puts install/ on COLCON_PREFIX_PATH
    if packages and not os.path.islink(base):
        try:
            os.makedirs(base, exist_ok=True)
        except OSError:
            pass  # a file where install/ goes: the build above already said what it could not do
        else:
            _write_setup_files(base)
    # colcon's closing lines (colcon-output's summary event handler); the install tree only when whole
    print(f"Summary: {finished} package{'s' if finished != 1 else ''} finished")
    if failed:
        print(f"  {len(failed)} package{'s' if len(failed) != 1 else ''} failed: {for_terminal(' '.join(failed))}")
        return 1
    print(say(M("install tree: {folder}", folder=base), lang))
    return 0


def _print_colcon_words(package: str, colcon: tuple[str, ...], shown: str) -> None:
    """The lines colcon would print on stderr for this failure (CMake's, setuptools'), those the
    finding above did not already quote, in colcon-output's block (``--- stderr: PKG`` ... ``---``)."""
    from ..trust.inert import for_terminal

    words = [line for line in colcon if not line.startswith(("--- stderr:", "Failed   <<<")) and line != "---"
             and line not in shown]
    if words:
        print(f"--- stderr: {for_terminal(package)}")
        for line in words:
            print(for_terminal(line))
        print("---")


SETUP_MARK = "# written by bras-kit build"
SETUP_BASH = SETUP_MARK + """: what colcon's install/local_setup.bash sets for the packages built here:
# install/ on COLCON_PREFIX_PATH, then each package's share/PKG/package.bash (its hooks: AMENT_PREFIX_PATH,
# PYTHONPATH, PATH when it has bin/), packages in the order colcon's _local_setup_util_sh.py sources
# them (each after those it runs on), so that 'source install/setup.bash' works as in the tutorial
_bras_kit_install="$(builtin cd "$(dirname "${{BASH_SOURCE[0]:-$0}}")" > /dev/null && pwd)"
case ":${{COLCON_PREFIX_PATH:-}}:" in
  *":$_bras_kit_install:"*) ;;
  *) export COLCON_PREFIX_PATH="$_bras_kit_install${{COLCON_PREFIX_PATH:+:$COLCON_PREFIX_PATH}}" ;;
esac
for _bras_kit_package in {packages}; do
  if [ -f "$_bras_kit_install/$_bras_kit_package/share/$_bras_kit_package/package.bash" ]; then
    COLCON_CURRENT_PREFIX="$_bras_kit_install/$_bras_kit_package" \\
      . "$_bras_kit_install/$_bras_kit_package/share/$_bras_kit_package/package.bash"
  fi
done
unset _bras_kit_install _bras_kit_package
"""


def source_order(base: str) -> list[str]:
    """The packages of ``base`` colcon's local_setup sources, in its order: those holding colcon-core's
    marker, each after the ones among them its marker lists, ties by name (install/_local_setup_util_sh.py,
    order_packages, as colcon-core 0.21.3 writes it); a cycle is left in name order."""
    from ..trust.learner_files import read_text

    runs: dict[str, set[str]] = {}
    for name in sorted(os.listdir(base)):
        marker = os.path.join(base, name, "share", "colcon-core", "packages", name)
        if os.path.isfile(marker) and not os.path.islink(marker):
            try:
                runs[name] = set(read_text(marker, (base,), errors="replace").split(os.pathsep)) - {""}
            except OSError:
                runs[name] = set()
    for depends in runs.values():
        depends &= set(runs)
    order: list[str] = []
    while runs:
        ready = sorted(name for name, depends in runs.items() if not depends) or sorted(runs)
        order.append(ready[0])
        runs.pop(ready[0])
        for depends in runs.values():
            depends.discard(ready[0])
    return order


def _write_setup_files(base: str) -> None:
    """``install/setup.bash`` (and ``local_setup.bash``), as the tutorial sources it
    after colcon build; a file colcon itself wrote there is left as it is."""
    import shlex

    text = SETUP_BASH.format(packages=" ".join(shlex.quote(p) for p in source_order(base)))
    for name in ("setup.bash", "local_setup.bash"):
        path = os.path.join(base, name)
        try:
            info = os.lstat(path)
        except FileNotFoundError:
            info = None
        if info is not None:
            if not stat.S_ISREG(info.st_mode):
                continue  # a link or anything else planted there is never written through
            with open(path, encoding="utf-8", errors="replace") as handle:
                if handle.read(len(SETUP_MARK)) != SETUP_MARK:
                    continue  # colcon's own: the real one
        descriptor = os.open(path, os.O_WRONLY | os.O_CREAT | os.O_TRUNC | os.O_NOFOLLOW, 0o644)
        with os.fdopen(descriptor, "w", encoding="utf-8") as handle:
            handle.write(text)
