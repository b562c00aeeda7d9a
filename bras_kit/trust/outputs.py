"""Every file bras-kit writes goes through :func:`write_to` (or its text form :func:`write_text`).

The rules, for a path named by the user:

* an existing path (a file, a folder, a symlink, even a dangling one) is refused unless
  ``force``; a folder is refused even then;
* with ``force`` the path itself is replaced, never the target of a symlink: the content is
  written to a temporary file in the same folder, then moved over the path with
  :func:`os.replace` (atomic; a reader never sees half a file);
* a missing parent folder is an error naming it, unless the command makes a tree
  (``make_parents=True``: ``new``, ``demo``, ``--frames-dir``);
* every ``OSError`` becomes a one-line :class:`OutputError` with the path.
"""

from __future__ import annotations

import contextlib
import os
import stat
import sys
import tempfile
from collections.abc import Callable, Iterator
from typing import Any

from ..core.errors import BrasKitError, OutputExistsError, os_reason
from ..core.message import M, Message

STDOUT = "-"


class OutputError(BrasKitError):
    """A file cannot be written where the user asked."""


def _describe(mode: int) -> Message:
    if stat.S_ISLNK(mode):
        return M("a symbolic link")
    if stat.S_ISDIR(mode):
        return M("a folder")
    if stat.S_ISREG(mode):
        return M("a file")
    return M("a special file")


def check_output(path: str, force: bool, *, make_parents: bool = False, option: str = "-o") -> None:
    """Raise unless ``path`` may be written (see the module's rules). Creates parents only if asked."""
    if path == STDOUT:
        return
    try:
        info = os.lstat(path)
    except FileNotFoundError:
        info = None
    except OSError as exc:
        raise OutputError(M("cannot write {path}: {reason}", path=path, reason=os_reason(exc))) from None
    if info is not None:
        kind = _describe(info.st_mode)
        if stat.S_ISDIR(info.st_mode):
            raise OutputError(M("{path} is a folder", path=path),
                              hint=M("give a file name to {option}, e.g. {example}", option=option,
                                     example=os.path.join(path, "out")))
        if not force:
            raise OutputExistsError(M("{path} already exists ({kind})", path=path, kind=kind),
                                    hint=M("pass --force to replace it, or choose another {option}", option=option))
        if not (stat.S_ISREG(info.st_mode) or stat.S_ISLNK(info.st_mode)):
            raise OutputError(M("{path} is {kind}; bras-kit replaces only files and links", path=path, kind=kind))
    folder = os.path.dirname(path) or "."
    if not os.path.isdir(folder):
        if os.path.lexists(folder) and not os.path.isdir(folder):
            raise OutputError(M("cannot write {path}: {folder} is not a folder", path=path, folder=folder))
        if not make_parents:
            raise OutputError(M("cannot write {path}: the folder {folder} does not exist", path=path, folder=folder),
                              hint=M("create it first (mkdir -p {folder}) or check the spelling of {option}",
                                     folder=folder, option=option))
        try:
            os.makedirs(folder, exist_ok=True)
        except OSError as exc:
            raise OutputError(M("cannot create the folder {path}: {reason}", path=folder,
                                reason=os_reason(exc))) from None


@contextlib.contextmanager
def staged(path: str, force: bool, *, make_parents: bool = False, option: str = "-o") -> Iterator[str]:
    """A temporary path next to ``path`` to write to; moved onto ``path`` when the block succeeds.

    The temporary file keeps ``path``'s suffix, so writers that choose a format by suffix
    (PNG, GIF, SVG, PDF...) work unchanged. On an error the temporary file is removed.
    """
    check_output(path, force, make_parents=make_parents, option=option)
    folder = os.path.dirname(path) or "."
    name = os.path.basename(path)
    try:
        fd, temporary = tempfile.mkstemp(prefix=f".{name}.", suffix=os.path.splitext(name)[1], dir=folder)
        os.close(fd)
    except OSError as exc:
        raise OutputError(M("cannot write {path}: {reason}", path=path, reason=os_reason(exc))) from None
    try:
        yield temporary
        os.chmod(temporary, 0o666 & ~_umask())
        if not force and os.path.lexists(path):  # appeared meanwhile
            raise OutputExistsError(M("{path} already exists", path=path),
                                    hint=M("pass --force to replace it, or choose another {option}", option=option))
        os.replace(temporary, path)
    except OSError as exc:
        raise OutputError(M("cannot write {path}: {reason}", path=path, reason=os_reason(exc))) from None
    finally:
        if os.path.lexists(temporary):
            with contextlib.suppress(OSError):
                os.unlink(temporary)


def write_to(path: str, force: bool, writer: Callable[[str], Any], *, make_parents: bool = False,
             option: str = "-o", announce: bool = True, lang: str | None = None) -> Any:
    """Check ``path``, let ``writer(temporary_path)`` write the content, then move it into place.

    Returns what ``writer`` returned.
    """
    with staged(path, force, make_parents=make_parents, option=option) as temporary:
        result = writer(temporary)
    if announce:
        from ..core.i18n import say

        print(say(M("wrote {path}", path=path), lang), file=sys.stderr)
    return result


def _umask() -> int:
    mask = os.umask(0)
    os.umask(mask)
    return mask


def write_bytes(path: str | None, data: bytes, force: bool, **options: Any) -> None:
    """``data`` to ``path`` (stdout when None or ``-``)."""
    if path is None or path == STDOUT:
        sys.stdout.buffer.write(data)
        sys.stdout.flush()
        return

    def write(temporary: str) -> None:
        with open(temporary, "wb") as handle:
            handle.write(data)

    write_to(path, force, write, **options)


def write_text(path: str | None, text: str, force: bool, **options: Any) -> None:
    """``text`` to ``path`` (stdout when None or ``-``), ending with a newline."""
    if not text.endswith("\n"):
        text += "\n"
    if path is None or path == STDOUT:
        from .inert import write_document

        write_document(sys.stdout, text)  # as it is to a pipe; a terminal gets it through the gate
        return
    write_bytes(path, text.encode("utf-8"), force, **options)
