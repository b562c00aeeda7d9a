"""A class's submissions: one sub-folder, URDF/xacro file or package archive per learner,
unpacked safely (nothing outside the target, no links, size and file-count caps)."""

from __future__ import annotations

import bz2
import contextlib
import errno
import gzip
import hashlib
import io
import lzma
import os
import stat
import struct
import tarfile
import zipfile
import zlib
from collections.abc import Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from ..core.errors import BrasKitError, os_reason
from ..core.message import M
from ..core.wording import quoted

ARCHIVE_SUFFIXES = (".zip", ".tar.gz", ".tgz", ".tar")
FILE_SUFFIXES = (".urdf", ".xacro")
MAX_ARCHIVE_FILES = 2000
MAX_ARCHIVE_BYTES = 64 << 20  # unpacked
MAX_SUBMISSION_BYTES = 64 << 20  # a folder or a file, as handed in
HASH_CHUNK = 1 << 20
# what reading an archive's index may cost before a member is written: a zip's central directory
# (each entry at least 46 bytes), a tar's headers and extended (pax, GNU long name) headers
MAX_ZIP_DIRECTORY_BYTES = MAX_ARCHIVE_FILES * 1024
MAX_TAR_HEADER_BYTES = 8 << 20


class SubmissionError(BrasKitError):
    """A submission that cannot be taken in (an unsafe archive, too large): it scores zero."""


@dataclass(frozen=True)
class Submission:
    """One learner's work: ``path`` is a folder, a robot file or an archive; ``learner`` its name."""

    learner: str
    path: str
    kind: str  # "folder", "file", "archive" or "other"


def learner_name(path: Path) -> str:
    name = path.name
    for suffix in (*ARCHIVE_SUFFIXES, ".urdf.xacro", *FILE_SUFFIXES):
        if name.lower().endswith(suffix) and len(name) > len(suffix):
            return name[: -len(suffix)]
    return name


def find_submissions(folder: str | os.PathLike[str]) -> list[Submission]:
    """Every entry of ``folder`` (hidden ones skipped), by name: each is one learner's submission."""
    root = Path(folder)
    if not root.is_dir():
        raise BrasKitError(M("{folder} is not a folder", folder=str(folder)),
                           hint=M("give the folder holding one entry per learner"))
    out = []
    for entry in sorted(root.iterdir(), key=lambda p: p.name):
        if entry.name.startswith("."):
            continue
        try:
            mode = entry.lstat().st_mode
        except OSError:
            mode = 0
        if stat.S_ISLNK(mode) or not (stat.S_ISDIR(mode) or stat.S_ISREG(mode)):
            kind = "other"  # a link is never followed (it could point anywhere on the teacher's disk), nor a pipe
        elif stat.S_ISDIR(mode):
            kind = "folder"
        elif entry.name.lower().endswith(ARCHIVE_SUFFIXES):
            kind = "archive"
        elif entry.name.lower().endswith(FILE_SUFFIXES):
            kind = "file"
        else:
            kind = "other"
        out.append(Submission(learner_name(entry), str(entry), kind))
    # bras.urdf and bras.zip: keep the full names apart, until no two learners share a name (the
    # entry "bras.zip.tar" is learner "bras.zip", which the archive "bras.zip" became)
    while True:
        names = [s.learner for s in out]
        clashing = [s for s in out if names.count(s.learner) > 1 and s.learner != Path(s.path).name]
        if not clashing:
            return out
        for submission in clashing:
            object.__setattr__(submission, "learner", Path(submission.path).name)


def content_hash(path: str) -> str:
    """SHA-256 over the files of a submission (names and bytes, in name order); links not followed."""
    digest = hashlib.sha256()
    target = Path(path)
    files = [target] if not target.is_dir() else sorted(p for p in target.rglob("*") if p.is_file() and not p.is_symlink())
    for file in files:
        digest.update(str(file.relative_to(target) if target.is_dir() else file.name).encode() + b"\0")
        try:
            with open_regular(str(file)) as handle:  # never a pipe: it would wait for a writer
                while chunk := handle.read(HASH_CHUNK):
                    digest.update(chunk)
        except OSError:
            digest.update(b"<unreadable>")
    return digest.hexdigest()


def open_regular(path: str) -> Any:
    """``path`` opened for reading when it is a regular file, judged on the open descriptor (a
    pipe is opened without waiting for a writer, then refused; a link is not followed); else
    ``OSError``."""
    fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK | getattr(os, "O_NOFOLLOW", 0) | getattr(os, "O_CLOEXEC", 0))
    if not stat.S_ISREG(os.fstat(fd).st_mode):
        os.close(fd)
        raise OSError(errno.EINVAL, "not a regular file", path)
    os.set_blocking(fd, True)
    return os.fdopen(fd, "rb")


def unpack(archive: str, target: str) -> None:
    """Unpack a .zip or .tar(.gz) into ``target`` or raise :class:`SubmissionError`: members
    with absolute paths or ``..``, links and devices, more than :data:`MAX_ARCHIVE_FILES`
    files or :data:`MAX_ARCHIVE_BYTES` unpacked are refused before anything is written."""
    name = archive.lower()
    try:
        if name.endswith(".zip"):
            _unzip(archive, target)
        else:
            _untar(archive, target)
    except (zipfile.BadZipFile, zipfile.LargeZipFile, tarfile.TarError, EOFError, OSError, zlib.error, lzma.LZMAError,
            NotImplementedError, RuntimeError, ValueError) as exc:
        # zipfile's own refusals: an unknown version or method (NotImplementedError), a password
        # (RuntimeError), a broken deflate stream (zlib.error), a name it cannot decode (ValueError)
        raise SubmissionError(M("the archive cannot be read: {reason}",
                                reason=os_reason(exc) if isinstance(exc, OSError) and exc.errno else quoted(str(exc))),
                              path=archive, hint=M("hand in a .zip or .tar.gz made by an archive tool")) from None


def _safe_member(name: str, archive: str) -> str:
    clean = name.replace("\\", "/")
    parts = [p for p in clean.split("/") if p not in ("", ".")]
    if clean.startswith("/") or (len(clean) > 1 and clean[1] == ":") or ".." in parts:
        raise SubmissionError(M("the archive holds '{name}', a path outside its folder: refused", name=name),
                              path=archive,
                              hint=M("archives must only hold relative paths (this one may be a zip-slip attack)"))
    return "/".join(parts)


def _check_totals(count: int, size: int, archive: str) -> None:
    if count > MAX_ARCHIVE_FILES:
        raise SubmissionError(M("the archive holds more than {most} files", most=MAX_ARCHIVE_FILES), path=archive,
                              hint=M("hand in the package only (no build/ or install/ folders)"))
    if size > MAX_ARCHIVE_BYTES:
        raise SubmissionError(M("the archive unpacks to more than {most} MB", most=MAX_ARCHIVE_BYTES >> 20),
                              path=archive, hint=M("hand in the package only (no build/ or install/ folders)"))


@dataclass(frozen=True)
class _ZipEnd:
    """What a zip's end records say (APPNOTE.TXT 4.3.14-4.3.16), read as zipfile reads them."""

    entries: int
    directory_bytes: int
    directory_offset: int  # as written in the record
    directory_start: int  # where zipfile will read it: just before the end records
    zip64: bool


# APPNOTE.TXT: the end of central directory record (4.3.16, 22 bytes and a comment of at most
# 65,535), the ZIP64 locator (4.3.15, 20 bytes just before it) and the ZIP64 end record (4.3.14,
# 56 bytes before the locator, as zipfile assumes: no "extensible data")
_EOCD, _EOCD_SIZE = b"PK\x05\x06", 22
_LOCATOR, _LOCATOR_SIZE = b"PK\x06\x07", 20
_EOCD64, _EOCD64_SIZE = b"PK\x06\x06", 56
CENTRAL_ENTRY_BYTES = 46  # an entry of the central directory, before its name, extra and comment (4.3.12)
LOCAL_HEADER_BYTES = 30  # a member's local header, before its name and extra (4.3.7)


def _zip_end(handle: Any, archive: str) -> _ZipEnd:
    """The end records, found where zipfile looks for them (``_EndRecData``, ``_EndRecData64``)
    and checked against the file's size (fstat on the open descriptor) and
    :data:`MAX_ZIP_DIRECTORY_BYTES` before zipfile parses the directory into one object per
    entry: a zip whose ZIP64 record claims a million entries is refused having read 98 bytes."""
    size = os.fstat(handle.fileno()).st_size
    handle.seek(max(0, size - (_EOCD_SIZE + 0xFFFF)))
    tail = handle.read()
    base = size - len(tail)
    if len(tail) >= _EOCD_SIZE and tail[-_EOCD_SIZE:-_EOCD_SIZE + 4] == _EOCD and tail[-2:] == b"\0\0":
        at = len(tail) - _EOCD_SIZE  # no comment: zipfile's first look
    else:
        at = tail.rfind(_EOCD)
    if at < 0 or len(tail) - at < _EOCD_SIZE:
        raise zipfile.BadZipFile("no end of central directory record")
    (_sig, disk, disk_start, here, entries, directory_bytes, offset,
     _comment) = struct.unpack("<4s4H2LH", tail[at:at + _EOCD_SIZE])
    location = base + at
    zip64 = False
    locator = tail[at - _LOCATOR_SIZE:at] if at >= _LOCATOR_SIZE else b""
    if at < _LOCATOR_SIZE and location >= _LOCATOR_SIZE:  # the comment search started past it
        handle.seek(location - _LOCATOR_SIZE)
        locator = handle.read(_LOCATOR_SIZE)
    if len(locator) == _LOCATOR_SIZE and locator[:4] == _LOCATOR:
        _sig, locator_disk, _record_at, disks = struct.unpack("<4sLQL", locator)
        if locator_disk != 0 or disks > 1:
            _refuse_disks(archive)
        if location >= _LOCATOR_SIZE + _EOCD64_SIZE:
            handle.seek(location - _LOCATOR_SIZE - _EOCD64_SIZE)
            record = handle.read(_EOCD64_SIZE)
            if len(record) == _EOCD64_SIZE and record[:4] == _EOCD64:
                (_sig, _size, _made, _needed, disk, disk_start, here, entries, directory_bytes,
                 offset) = struct.unpack("<4sQ2H2L4Q", record)
                zip64 = True
    if disk != 0 or disk_start != 0 or here != entries:
        _refuse_disks(archive)
    start = location - directory_bytes - (_LOCATOR_SIZE + _EOCD64_SIZE if zip64 else 0)
    return _ZipEnd(entries, directory_bytes, offset, start, zip64)


def _refuse_disks(archive: str) -> None:
    raise SubmissionError(M("the archive says it spans several disks: refused"), path=archive,
                          hint=M("hand in a .zip or .tar.gz made by an archive tool"))


def _refuse_lie(archive: str) -> None:
    raise SubmissionError(M("the archive's end records do not match the archive: refused unread"), path=archive,
                          hint=M("hand in a .zip or .tar.gz made by an archive tool"))


def _check_zip_end(end: _ZipEnd, archive: str) -> None:
    _check_totals(end.entries, 0, archive)
    if end.directory_bytes > MAX_ZIP_DIRECTORY_BYTES:
        _check_totals(MAX_ARCHIVE_FILES + 1, 0, archive)
    # the directory must lie inside the file, before its end records, where its offset says (or
    # after bytes put before the archive: a self-extracting stub), and hold its entries
    if end.directory_start < 0 or end.directory_offset > end.directory_start \
            or end.entries * CENTRAL_ENTRY_BYTES > end.directory_bytes:
        _refuse_lie(archive)


def _check_zip_members(members: list[zipfile.ZipInfo], end: _ZipEnd, archive: str) -> None:
    """The directory as zipfile parsed it, against the end record and itself: as many entries as
    the record says, and each member's bytes (its local header, name and compressed data) before
    the directory and apart from every other member's: overlapping members are a zip bomb's
    shape (one deflated stream counted many times)."""
    if len(members) != end.entries:
        raise SubmissionError(M("the archive's end record says {said} entries, its directory holds {found}: "
                                "refused", said=end.entries, found=len(members)), path=archive,
                              hint=M("hand in a .zip or .tar.gz made by an archive tool"))
    spans = sorted((m.header_offset, m.header_offset + LOCAL_HEADER_BYTES + _name_bytes(m) + m.compress_size)
                   for m in members)
    previous_end = 0
    for start, stop in spans:
        if start < previous_end or start < 0 or stop > end.directory_start:
            raise SubmissionError(M("the archive's members overlap or run into its directory: refused"),
                                  path=archive, hint=M("hand in a .zip or .tar.gz made by an archive tool"))
        previous_end = stop


def _name_bytes(member: zipfile.ZipInfo) -> int:
    """The length of the member's name as written (UTF-8 when flagged, else cp437: APPNOTE 4.4.4)."""
    return len(member.orig_filename.encode("utf-8" if member.flag_bits & 0x800 else "cp437", "replace"))


def _unzip(archive: str, target: str) -> None:
    with open_regular(archive) as handle:
        end = _zip_end(handle, archive)
        _check_zip_end(end, archive)
        _unzip_checked(handle, end, archive, target)


def _unzip_checked(handle: Any, end: _ZipEnd, archive: str, target: str) -> None:
    with zipfile.ZipFile(handle) as bundle:  # the descriptor whose end records were checked
        members = bundle.infolist()
        _check_zip_members(members, end, archive)
        _check_totals(len(members), sum(m.file_size for m in members), archive)
        plan = []
        for member in members:
            mode = member.external_attr >> 16
            if stat.S_ISLNK(mode):
                raise SubmissionError(M("the archive holds a link '{name}': refused", name=member.filename),
                                      path=archive, hint=M("archives must hold plain files"))
            plan.append((member, _safe_member(member.filename, archive)))
        written = 0
        for member, relative in plan:
            if not relative:
                continue
            destination = os.path.join(target, relative)
            if member.is_dir():
                os.makedirs(destination, exist_ok=True)
                continue
            os.makedirs(os.path.dirname(destination), exist_ok=True)
            with bundle.open(member) as source, open(destination, "xb") as sink:
                while chunk := source.read(HASH_CHUNK):
                    written += len(chunk)
                    if written > MAX_ARCHIVE_BYTES:  # the sizes in the directory can lie
                        raise SubmissionError(M("the archive unpacks to more than it says"), path=archive)
                    sink.write(chunk)


class _Capped(io.RawIOBase):
    """A decompressed stream that ends in an error past ``most`` bytes, and, while ``headers`` is
    true, on any one read larger than :data:`MAX_TAR_HEADER_BYTES`: tarfile reads an extended
    header whole, whatever size it claims (a few KB of gzip can claim gigabytes), where it reads a
    member's data in small blocks, and only when extracting."""

    def __init__(self, stream: Any, most: int, archive: str) -> None:
        self._stream, self._most, self._archive = stream, most, archive
        self.headers = True

    def readable(self) -> bool:
        return True

    def seekable(self) -> bool:
        return True

    def read(self, size: int = -1) -> bytes:
        if self.headers and (size is None or size < 0 or size > MAX_TAR_HEADER_BYTES):
            raise SubmissionError(M("the archive holds a header larger than {most} MB: refused",
                                    most=MAX_TAR_HEADER_BYTES >> 20), path=self._archive,
                                  hint=M("hand in a .zip or .tar.gz made by an archive tool"))
        if size is None or size < 0 or self._stream.tell() + size > self._most:
            size = self._most - self._stream.tell() + 1
        data: bytes = self._stream.read(size)
        if self._stream.tell() > self._most:
            raise SubmissionError(M("the archive unpacks to more than it says"), path=self._archive)
        return data

    def seek(self, offset: int, whence: int = os.SEEK_SET) -> int:
        return int(self._stream.seek(offset, whence))

    def tell(self) -> int:
        return int(self._stream.tell())


@contextlib.contextmanager
def _decompressed(archive: str) -> Iterator[Any]:
    """The archive's tar stream: gzip, bzip2 and xz told apart by their magic numbers, as
    tarfile.open does (tarfile.py, TarFile.open's "r:*")."""
    with open_regular(archive) as handle:
        magic = handle.read(6)
        handle.seek(0)
        if magic.startswith(b"\x1f\x8b"):
            opener: Any = gzip.GzipFile(fileobj=handle, mode="rb")
        elif magic.startswith(b"BZh"):
            opener = bz2.BZ2File(handle, "rb")
        elif magic.startswith(b"\xfd7zXZ\x00"):
            opener = lzma.LZMAFile(handle, "rb")
        else:
            yield handle
            return
        with opener as stream:
            yield stream


def _untar(archive: str, target: str) -> None:
    # the headers are read one by one, at most MAX_ARCHIVE_FILES + 1 of them, through a stream
    # that stops past what the members may hold plus their headers
    most = MAX_ARCHIVE_BYTES + MAX_TAR_HEADER_BYTES
    with _decompressed(archive) as stream, tarfile.open(fileobj=(capped := _Capped(stream, most, archive)),
                                                        mode="r:") as bundle:
        members = []
        while (member := bundle.next()) is not None:
            members.append(member)
            if len(members) > MAX_ARCHIVE_FILES:
                break
        capped.headers = False
        _check_totals(len(members), sum(m.size for m in members), archive)
        for member in members:
            _safe_member(member.name, archive)
            if not (member.isfile() or member.isdir()):
                raise SubmissionError(M("the archive holds '{name}', which is not a plain file: refused",
                                        name=member.name),
                                      path=archive, hint=M("archives must hold plain files and folders"))
        bundle.extractall(target, members=members, filter="data")
