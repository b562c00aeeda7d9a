"""A class's submissions: one sub-folder, URDF/xacro file or package archive per learner,
unpacked safely (nothing outside the target, no links, size and file-count caps)."""

from __future__ import annotations

import hashlib
import os
import stat
import tarfile
import zipfile
from dataclasses import dataclass
from pathlib import Path

from ..errors import BrasKitError, os_reason
from ..message import M
from ..wording import quoted

ARCHIVE_SUFFIXES = (".zip", ".tar.gz", ".tgz", ".tar")
FILE_SUFFIXES = (".urdf", ".xacro")
MAX_ARCHIVE_FILES = 2000
MAX_ARCHIVE_BYTES = 64 << 20  # unpacked
MAX_SUBMISSION_BYTES = 64 << 20  # a folder or a file, as handed in
HASH_CHUNK = 1 << 20


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
    names = [s.learner for s in out]
    for submission in out:
        if names.count(submission.learner) > 1:  # bras.urdf and bras.zip: keep the full names apart
            object.__setattr__(submission, "learner", Path(submission.path).name)
    return out


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


def _unzip(archive: str, target: str) -> None:
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


def _untar(archive: str, target: str) -> None:
    with tarfile.open(archive) as bundle:
        members = bundle.getmembers()
        _check_totals(len(members), sum(m.size for m in members), archive)
        for member in members:
            _safe_member(member.name, archive)
            if not (member.isfile() or member.isdir()):
                raise SubmissionError(M("the archive holds '{name}', which is not a plain file: refused",
                                        name=member.name),
                                      path=archive, hint=M("archives must hold plain files and folders"))
        bundle.extractall(target, members=members, filter="data")
