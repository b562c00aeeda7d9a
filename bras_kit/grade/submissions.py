"""A class's submissions: one sub-folder, URDF/xacro file or package archive per learner,
unpacked safely (nothing outside the target, no links, size and file-count caps)."""

from __future__ import annotations

import bz2
import gzip
import hashlib
import io
import lzma
import os
import stat
import struct
import tarfile
import zipfile
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from ..errors import BrasKitError, os_reason
from ..message import M
from ..wording import quoted

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
        if entry.is_symlink():
            kind = "other"  # never followed: a link could point anywhere on the teacher's disk
        elif entry.is_dir():
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
            with open(file, "rb") as handle:
                while chunk := handle.read(HASH_CHUNK):
                    digest.update(chunk)
        except OSError:
            digest.update(b"<unreadable>")
    return digest.hexdigest()


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
    except (zipfile.BadZipFile, tarfile.TarError, EOFError, OSError) as exc:
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


def _zip_directory(archive: str) -> tuple[int, int]:
    """(entries, size of the central directory) as the end record says, read before zipfile
    parses the directory into one object per entry (a zip of a million empty entries would
    take the grading process's memory first). APPNOTE.TXT 4.3.16: the end record is the last
    22 bytes, after a comment of at most 65,535."""
    with open(archive, "rb") as handle:
        handle.seek(0, os.SEEK_END)
        size = handle.tell()
        handle.seek(max(0, size - (22 + 0xFFFF)))
        tail = handle.read()
    at = tail.rfind(b"PK\x05\x06")
    if at < 0 or len(tail) - at < 22:
        raise zipfile.BadZipFile("no end of central directory record")
    _sig, _disk, _start, _here, entries, directory_bytes, _offset, _comment = struct.unpack(
        "<4s4H2LH", tail[at:at + 22])
    return entries, directory_bytes


def _unzip(archive: str, target: str) -> None:
    entries, directory_bytes = _zip_directory(archive)
    # 0xFFFF entries or 0xFFFFFFFF bytes: a ZIP64 archive, larger than any accepted one anyway
    _check_totals(entries, 0, archive)
    if directory_bytes > MAX_ZIP_DIRECTORY_BYTES:
        _check_totals(MAX_ARCHIVE_FILES + 1, 0, archive)
    with zipfile.ZipFile(archive) as bundle:
        members = bundle.infolist()
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


def _decompressed(archive: str) -> Any:
    """The archive's tar stream: gzip, bzip2 and xz told apart by their magic numbers, as
    tarfile.open does (tarfile.py, TarFile.open's "r:*")."""
    with open(archive, "rb") as handle:
        magic = handle.read(6)
    if magic.startswith(b"\x1f\x8b"):
        return gzip.open(archive, "rb")
    if magic.startswith(b"BZh"):
        return bz2.open(archive, "rb")
    if magic.startswith(b"\xfd7zXZ\x00"):
        return lzma.open(archive, "rb")
    return open(archive, "rb")


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
