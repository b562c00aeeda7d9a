"""Stand-in for the xacro package as a launch file uses it: ``xacro.process_file(path).toxml()``
and the ``xacro FILE NAME:=VALUE`` program that ``Command(['xacro ', path])`` runs. Both expand
with the real xacro behind bras-kit's walls (bras_kit.model.xacro), imported past the stand-in's
import hook the first time a file is expanded (``_REAL``): a launch file that expands none never
pays for it."""

from __future__ import annotations

import contextlib
import sys
from collections.abc import Iterator
from typing import Any

_REAL: dict[str, Any] = {}  # the real xacro modules, once imported (_load_real)


class XacroException(Exception):
    def __init__(self, msg: str | None = None, suffix: str | None = None, exc: Any = None, macro: Any = None):
        super().__init__(msg)
        self.suffix = suffix


def _ours() -> dict[str, Any]:
    """The modules named xacro or xacro.* in sys.modules now (the stand-in's, or the real ones)."""
    return {name: sys.modules[name] for name in list(sys.modules) if name == 'xacro' or name.startswith('xacro.')}


def _load_real() -> None:
    """Import the real xacro (and xacro.substitution_args, which bras-kit's expansion reads) with the
    stand-in's hook set aside, keep its modules in ``_REAL``, and put the stand-in's back."""
    from bras_kit.ros.finder import StandinFinder

    ours = _ours()
    hooks = [finder for finder in sys.meta_path if isinstance(finder, StandinFinder)]
    for name in ours:
        del sys.modules[name]
    for finder in hooks:
        sys.meta_path.remove(finder)
    try:
        import xacro.substitution_args  # noqa: F401 - the real one: nothing else answers for the name now

        _REAL.update(_ours())
    except ImportError:
        pass  # no real xacro: the expansion says so
    finally:
        sys.meta_path[:0] = hooks
        for name in _ours():
            del sys.modules[name]
        sys.modules.update(ours)


@contextlib.contextmanager
def _real_modules() -> Iterator[None]:
    if not _REAL:
        _load_real()
    ours = _ours()
    sys.modules.update(_REAL)
    try:
        yield
    finally:
        for name in _REAL:
            sys.modules.pop(name, None)
        sys.modules.update(ours)


def _expand(path: str, mappings: dict[str, str]) -> str:
    from bras_kit.model.xacro import _expand as expand

    with _real_modules():
        return expand(path, mappings, ())


def _error_text(exc: BaseException) -> str:
    return str(exc)


def process_file(input_file_name: str, **kwargs: Any) -> Any:
    from xml.dom import minidom

    try:
        text = _expand(str(input_file_name), dict(kwargs.get('mappings') or {}))
    except Exception as exc:  # noqa: BLE001 - as xacro raises it
        raise XacroException(_error_text(exc)) from None
    return minidom.parseString(text)


def _run_command(words: list[str]) -> tuple[int, str, str]:
    """``xacro FILE [NAME:=VALUE ...]`` as the program: (exit code, stdout, stderr)."""
    import os

    program = os.path.basename(words[0])
    if program == 'cat':  # Command(['cat ', path]): the file's text
        try:
            out = ''
            for name in words[1:]:
                with open(name, encoding='utf-8') as handle:
                    out += handle.read()
            return 0, out, ''
        except OSError as exc:
            return 1, '', f'cat: {exc.filename}: {exc.strerror}\n'
    if program not in ('xacro', 'xacro.py'):
        import _bras_sim

        raise _bras_sim.NotSimulated(f"Command: {words[0]}")
    files = [w for w in words[1:] if ':=' not in w and not w.startswith('-')]
    mappings = dict(w.split(':=', 1) for w in words[1:] if ':=' in w)
    if not files:
        return 2, '', 'usage: xacro [-h] [-o FILE] ... input\nxacro: error: the following arguments are required: input\n'
    try:
        return 0, _expand(files[0], mappings), ''
    except Exception as exc:  # noqa: BLE001
        return 2, '', _error_text(exc) + '\n'
