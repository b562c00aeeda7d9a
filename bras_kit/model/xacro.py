"""Run the real ``xacro`` package without ROS, on files from strangers.

xacro itself is kept (its parser, macros, properties, includes, output), with walls around it
(:mod:`bras_kit.model.xacro_walls`):

* every ``${...}`` and ``$(eval ...)`` expression is interpreted by the allow-list evaluator
  of :mod:`bras_kit.model.xacro_eval`, never by Python's ``eval``;
* every file xacro opens (the main file, includes, ``load_yaml``) must be a regular file of at
  most :data:`~bras_kit.model.xacro_files.MAX_FILE_BYTES` (:mod:`bras_kit.model.xacro_files`),
  inside the file's own folder or a package folder given by the caller, and is first read by
  :mod:`bras_kit.model.xmlio`, so a DTD or an entity is refused before minidom could expand it;
* macro nesting, include nesting, the number of elements processed, the time spent and the
  output size are bounded;
* a file that is not the built-in template is expanded in a child process with CPU, memory
  and wall-clock limits (:mod:`bras_kit.trust.sandbox`), the second wall;
* ``$(find pkg)`` is resolved from package folders given by the caller or the
  ``BRAS_KIT_PACKAGE_PATH`` environment variable (a folder holding packages, a package
  itself, or an install ``share/`` tree), then ``AMENT_PREFIX_PATH`` when ROS is there
  (:mod:`bras_kit.model.package_paths`).

This module drives one expansion (in the sandbox or not); a failure is worded by
:mod:`bras_kit.model.xacro_errors`.
"""

from __future__ import annotations

import contextlib
import io
import os
import threading
from collections.abc import Iterable, Mapping

from ..core.errors import BrasKitError, XacroError
from ..core.message import M
from .package_paths import _FOUND, package_roots
from .xacro_errors import _clean_error
from .xacro_files import check_readable_file
from .xacro_walls import _Hooks

MAX_OUTPUT_CHARS = 64 << 20
SANDBOX_CPU_SECONDS = 20
SANDBOX_WALL_SECONDS = 30.0
SANDBOX_MEMORY_BYTES = 1536 << 20
_lock = threading.Lock()


def expand_xacro(
    path: str | os.PathLike[str],
    mappings: Mapping[str, str] | None = None,
    package_paths: Iterable[str] = (),
    *,
    sandbox: bool | None = None,
    roots: tuple[str, ...] | None = None,
) -> str:
    """Expand a xacro file to URDF text with the real xacro package, behind the walls above.

    ``mappings`` are xacro args (``name:=value`` on xacro's command line). Errors become a
    :class:`XacroError` naming the file, the best-guess line and what to do. ``sandbox``
    (default: every file but the built-in template) runs the expansion in a limited child.
    ``roots``: the folders the robot's files may be read from (with those of the packages
    ``$(find)`` names): every file is then read through the one reader beneath them.
    """
    path = os.fspath(path)
    if not os.path.exists(path):
        raise BrasKitError(M("no such file: {path}", path=path), hint=M("check the path and spelling"))
    if roots is None:
        check_readable_file(path)
    if sandbox is None:
        sandbox = not _is_builtin_template(path)
    if sandbox:
        from ..trust.sandbox import run_limited

        text, found = run_limited(_expand_and_report, path, dict(mappings or {}), tuple(package_paths), roots,
                                  cpu_seconds=SANDBOX_CPU_SECONDS, memory_bytes=SANDBOX_MEMORY_BYTES,
                                  wall_seconds=SANDBOX_WALL_SECONDS, what=f"expanding {path}")
        _FOUND.update(found)  # the child found the packages: remember them here, for --verbose
        return text
    return _expand(path, dict(mappings or {}), tuple(package_paths), roots)


def _expand_and_report(path: str, mappings: Mapping[str, str], package_paths: tuple[str, ...],
                       roots: tuple[str, ...] | None = None) -> tuple[str, dict[str, str]]:
    return _expand(path, mappings, package_paths, roots), dict(_FOUND)


def _is_builtin_template(path: str) -> bool:
    from ..core.resources import robot_template

    try:
        return os.path.samefile(path, robot_template())
    except OSError:
        return False


def _expand(path: str, mappings: Mapping[str, str], package_paths: tuple[str, ...],
            roots: tuple[str, ...] | None = None) -> str:
    import xacro
    import xacro.substitution_args as subst

    hooks = _Hooks(xacro, subst, path, package_roots(package_paths), roots)
    stderr = io.StringIO()
    arguments = _Arguments(mappings)
    with _lock:
        hooks.install()
        try:
            with contextlib.redirect_stderr(stderr):
                doc = xacro.process_file(path, mappings=arguments, verbosity=0)
                arguments.check(path)
                text = doc.toprettyxml(indent="  ")
            if len(text) > MAX_OUTPUT_CHARS:
                raise XacroError(M("the expanded URDF has {count} characters, more than {limit} Mi allowed",
                                   count=len(text), limit=MAX_OUTPUT_CHARS >> 20), path=path)
            return str(text)
        except BrasKitError:
            raise
        except Exception as exc:  # xacro raises many kinds; all become one clean error
            raise _clean_error(xacro, path, exc, hooks.files) from None
        finally:
            hooks.uninstall()
            xacro.init_stacks(None)


class _Arguments(dict[str, str]):
    """The ``name:=value`` arguments as xacro reads them, remembering which names the files ask
    about: ``<xacro:arg name=...>`` tests ``name in args`` and ``$(arg name)`` reads
    ``args[name]`` (xacro/__init__.py, ``eval_all`` and ``substitution_args_context``). A name
    given on the command line that no file asks about is a typo: xacro ignores it without a word,
    and the learner wonders why the arm did not change."""

    def __init__(self, given: Mapping[str, str]) -> None:
        super().__init__(given)
        self.given = tuple(given)
        self.asked: set[str] = set()

    def __contains__(self, name: object) -> bool:
        if isinstance(name, str):
            self.asked.add(name)
        return super().__contains__(name)

    def __getitem__(self, name: str) -> str:
        self.asked.add(name)
        return super().__getitem__(name)

    def check(self, path: str) -> None:
        import difflib

        from ..core.errors import ParameterError

        for name in self.given:
            if name in self.asked:
                continue
            declared = sorted(n for n in self.asked if n not in self.given or n == name)
            close = difflib.get_close_matches(name, declared, n=1, cutoff=0.6)
            valid = (M("the arguments it declares: {names}", names=", ".join(declared)) if declared
                     else M("this file declares no <xacro:arg>"))
            raise ParameterError(
                M("unknown xacro argument '{name}': {path} declares no <xacro:arg name=\"{name}\">", name=name,
                  path=path),
                hint=M("did you mean {close}? {valid}", close=close[0], valid=valid) if close else valid)
