"""A zip's end records are read and checked by bras-kit before zipfile parses its directory, and
no learner's file can hold or sink the grading of the class.

Zip, by category (APPNOTE.TXT 4.3.14-4.3.16: the end of central directory record, the ZIP64
locator and the ZIP64 end record, built here byte by byte): a ZIP64 record claiming a directory
of a million entries behind an end record claiming three; counts that lie (more than the
directory can hold, fewer than it holds); a directory larger than the file, or whose offset
lies past it; members that overlap (one deflated stream named twice); several disks; an
archive inside the archive (unpacked as a file, never opened). Oracles: zipfile itself (what it
parses, which these refusals precede), the bytes written here, and the peak memory and time of
a child held by a kernel limit.

The class: a pipe named like an archive, a pipe named ``progress.json`` inside a learner's
folder, a progress file holding a 5,000-digit number or nested 100,000 deep: ``grade`` ends, each
of them is that learner's line, and the other learners are graded."""

from __future__ import annotations

import csv
import os
import shutil
import struct
import subprocess
import sys
import time
import zipfile
from pathlib import Path

import pytest
from paths import TESTS

from bras_kit.grade.submissions import MAX_ARCHIVE_FILES, SubmissionError, find_submissions, unpack
from bras_kit.trust.sandbox import run_limited

TUTORIAL_URDF = TESTS / "data" / "tutorial_package" / "urdf" / "bras.urdf"
UNPACK_MEMORY = 160 << 20


def central_entry(name: bytes, offset: int = 0, compressed: int = 0, size: int = 0) -> bytes:
    """A central directory entry (4.3.12): 46 bytes, then the name."""
    return struct.pack("<4s6H3L5H2L", b"PK\x01\x02", 20, 20, 0, 0, 0, 0, 0, compressed, size, len(name), 0, 0, 0, 0,
                       0, offset) + name


def end_record(entries: int, directory_bytes: int, offset: int, *, disk: int = 0, here: int | None = None) -> bytes:
    return struct.pack("<4s4H2LH", b"PK\x05\x06", disk, 0, entries if here is None else here, entries,
                       directory_bytes, offset, 0)


def zip64_records(entries: int, directory_bytes: int, offset: int, record_at: int) -> bytes:
    """The ZIP64 end record (4.3.14, 56 bytes) and its locator (4.3.15, 20 bytes)."""
    record = struct.pack("<4sQ2H2L4Q", b"PK\x06\x06", 44, 45, 45, 0, 0, entries, entries, directory_bytes, offset)
    locator = struct.pack("<4sLQL", b"PK\x06\x07", 0, record_at, 1)
    return record + locator


def zip64_lying(path: Path, entries: int, *, end_says: int = 3) -> Path:
    """A directory of ``entries`` empty members and a ZIP64 record telling the truth about it,
    behind a classic end record that says ``end_says`` entries of 46 bytes."""
    one = central_entry(b"f")
    with open(path, "wb") as out:
        out.write(one * entries)
        out.write(zip64_records(entries, len(one) * entries, 0, len(one) * entries))
        out.write(end_record(end_says, 46 * end_says, 0))
    return path


def small_zip(path: Path, count: int = 5) -> Path:
    with zipfile.ZipFile(path, "w", zipfile.ZIP_DEFLATED) as bundle:
        for k in range(count):
            bundle.writestr(f"bras_description/f{k}.txt", f"file {k}\n" * 10)
    return path


def rewrite_end(path: Path, **fields: int) -> Path:
    """The zip at ``path`` with fields of its end record replaced: ``entries`` (both counts),
    ``directory_bytes``, ``offset``, ``disk``."""
    data = bytearray(path.read_bytes())
    at = data.rfind(b"PK\x05\x06")
    sig, disk, start, here, entries, size, offset, comment = struct.unpack("<4s4H2LH", data[at:at + 22])
    entries = fields.get("entries", entries)
    data[at:at + 22] = struct.pack("<4s4H2LH", sig, fields.get("disk", disk), start, entries, entries,
                                   fields.get("directory_bytes", size), fields.get("offset", offset), comment)
    path.write_bytes(bytes(data))
    return path


def refused(archive: Path, target: Path) -> str:
    with pytest.raises(SubmissionError) as caught:
        run_limited(unpack, str(archive), str(target), memory_bytes=UNPACK_MEMORY, wall_seconds=60)
    return str(caught.value)


@pytest.fixture
def target(tmp_path: Path) -> Path:
    out = tmp_path / "out"
    out.mkdir()
    return out


# ------------------------------------------------------------------ ZIP64 records that lie


def test_zipfile_parses_every_entry_a_zip64_record_claims(tmp_path):
    """The oracle: zipfile takes the ZIP64 record's directory over the classic record's."""
    with zipfile.ZipFile(zip64_lying(tmp_path / "z.zip", 5000)) as bundle:
        assert len(bundle.infolist()) == 5000


def test_a_zip64_record_claiming_a_million_entries_is_refused_unread(tmp_path, target):
    """Before: refused by the file count only after zipfile parsed 1.3 million entries (497 MiB,
    8 s); here refused from the 98 bytes of the end records, in a child held to 160 MiB."""
    archive = zip64_lying(tmp_path / "million.zip", 1_300_000)
    start = time.monotonic()
    reason = refused(archive, target)
    assert f"more than {MAX_ARCHIVE_FILES} files" in reason
    assert time.monotonic() - start < 5 and os.listdir(target) == []


@pytest.mark.parametrize("entries", [MAX_ARCHIVE_FILES + 1, 0xFFFF, 10 ** 6])
def test_a_zip64_count_past_the_bound_is_refused_whatever_the_classic_record_says(tmp_path, target, entries):
    one = central_entry(b"f")
    archive = tmp_path / "count.zip"
    archive.write_bytes(one + zip64_records(entries, len(one), 0, len(one)) + end_record(1, len(one), 0))
    assert f"more than {MAX_ARCHIVE_FILES} files" in refused(archive, target)


# ------------------------------------------------------------------ counts, sizes and offsets that lie


def test_an_end_record_counting_fewer_entries_than_its_directory_holds_is_refused(tmp_path, target):
    archive = rewrite_end(small_zip(tmp_path / "fewer.zip", 5), entries=3)
    with zipfile.ZipFile(archive) as bundle:  # zipfile reads the five all the same
        assert len(bundle.infolist()) == 5
    assert "says 3 entries, its directory holds 5" in refused(archive, target)
    assert os.listdir(target) == []


def test_an_end_record_counting_more_entries_than_its_directory_can_hold_is_refused_unread(tmp_path, target):
    archive = rewrite_end(small_zip(tmp_path / "more.zip", 5), entries=1500)  # 1,500 x 46 bytes: not in there
    assert "end records do not match the archive" in refused(archive, target)


def test_a_directory_larger_than_the_file_is_refused_unread(tmp_path, target):
    archive = small_zip(tmp_path / "large.zip", 2)
    archive = rewrite_end(archive, directory_bytes=archive.stat().st_size + 10)
    assert "end records do not match the archive" in refused(archive, target)


@pytest.mark.parametrize("offset", [10 ** 6, 0xFFFFFFF0])
def test_a_directory_offset_past_the_file_is_refused_unread(tmp_path, target, offset):
    archive = rewrite_end(small_zip(tmp_path / "offset.zip", 2), offset=offset)
    assert "end records do not match the archive" in refused(archive, target)


def test_a_directory_past_the_bound_is_refused_unread(tmp_path, target):
    """100 entries whose names are 30 kB each: 3 MB of directory, more than the 2 MB bound."""
    with open(tmp_path / "names.zip", "wb") as out:
        entries = b"".join(central_entry(b"n" * 30_000 + str(k).encode()) for k in range(100))
        out.write(entries + end_record(100, len(entries), 0))
    assert f"more than {MAX_ARCHIVE_FILES} files" in refused(tmp_path / "names.zip", target)


def test_an_archive_on_several_disks_is_refused(tmp_path, target):
    archive = rewrite_end(small_zip(tmp_path / "disks.zip", 2), disk=1)
    assert "several disks" in refused(archive, target)


def test_members_sharing_their_bytes_are_refused_before_a_byte_is_written(tmp_path, target):
    """One deflated member named twice in the directory (the overlap of a "better zip bomb")."""
    plain = tmp_path / "one.zip"
    with zipfile.ZipFile(plain, "w", zipfile.ZIP_DEFLATED) as bundle:
        bundle.writestr("bras_description/a.bin", bytes(1 << 20))
    data = plain.read_bytes()
    at = data.rfind(b"PK\x05\x06")
    _sig, _d, _s, _h, _n, size, offset, _c = struct.unpack("<4s4H2LH", data[at:at + 22])
    entry = data[offset:offset + size]
    twin = entry.replace(b"bras_description/a.bin", b"bras_description/b.bin")
    overlapping = data[:offset] + entry + twin + end_record(2, 2 * size, offset)
    archive = tmp_path / "overlap.zip"
    archive.write_bytes(overlapping)
    with zipfile.ZipFile(archive) as bundle:  # the oracle: zipfile lists both, on the same bytes
        infos = bundle.infolist()
        assert [i.header_offset for i in infos] == [0, 0]
    assert "overlap" in refused(archive, target)
    assert os.listdir(target) == []


def test_an_archive_inside_the_archive_is_a_file_never_opened(tmp_path, target):
    inner = tmp_path / "inner.zip"
    with zipfile.ZipFile(inner, "w", zipfile.ZIP_DEFLATED) as bundle:
        bundle.writestr("zeros.bin", bytes(50 << 20))
    outer = tmp_path / "outer.zip"
    with zipfile.ZipFile(outer, "w") as bundle:
        bundle.write(inner, "bras_description/inner.zip")
    run_limited(unpack, str(outer), str(target), memory_bytes=UNPACK_MEMORY, wall_seconds=60)
    written = [p.relative_to(target).as_posix() for p in target.rglob("*") if p.is_file()]
    assert written == ["bras_description/inner.zip"]
    assert (target / "bras_description" / "inner.zip").read_bytes() == inner.read_bytes()


def test_an_honest_zip_still_unpacks(tmp_path, target):
    run_limited(unpack, str(small_zip(tmp_path / "ok.zip", 5)), str(target), memory_bytes=UNPACK_MEMORY,
                wall_seconds=60)
    assert sorted(p.name for p in (target / "bras_description").iterdir()) == [f"f{k}.txt" for k in range(5)]


def test_an_honest_zip64_archive_still_unpacks(tmp_path, target):
    """zipfile writes ZIP64 end records past 65,535 entries or by force; here: a few members whose
    headers are ZIP64, and the end records rebuilt as a ZIP64 archive's (the oracle: zipfile reads it)."""
    archive = small_zip(tmp_path / "z64.zip", 3)
    data = archive.read_bytes()
    at = data.rfind(b"PK\x05\x06")
    _sig, _d, _s, _h, entries, size, offset, _c = struct.unpack("<4s4H2LH", data[at:at + 22])
    rebuilt = data[:at] + zip64_records(entries, size, offset, at) + end_record(0xFFFF, 0xFFFFFFFF, 0xFFFFFFFF)
    archive.write_bytes(rebuilt)
    with zipfile.ZipFile(archive) as bundle:
        assert len(bundle.infolist()) == 3
    run_limited(unpack, str(archive), str(target), memory_bytes=UNPACK_MEMORY, wall_seconds=60)
    assert len(list((target / "bras_description").iterdir())) == 3


def test_a_pipe_named_like_an_archive_is_refused_without_waiting(tmp_path, target):
    os.mkfifo(tmp_path / "pipe.zip")
    start = time.monotonic()
    assert "cannot be read" in refused(tmp_path / "pipe.zip", target)
    assert time.monotonic() - start < 10


# ------------------------------------------------------------------ the class


def _grade_class(klass: Path, out: Path) -> tuple[subprocess.CompletedProcess, float, float]:
    code = ("import resource, subprocess, sys\n"
            "p = subprocess.run(sys.argv[1:], capture_output=True, text=True, timeout=240)\n"
            "sys.stdout.write(p.stdout); sys.stderr.write(p.stderr)\n"
            "print('MAXRSS', resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss)\n"
            "sys.exit(p.returncode)\n")
    start = time.monotonic()
    done = subprocess.run([sys.executable, "-c", code, sys.executable, "-m", "bras_kit", "grade", str(klass),
                           "-o", str(out), "--no-pictures", "--jobs", "1"],
                          capture_output=True, text=True, timeout=300, env={**os.environ, "BRAS_KIT_LANG": "en"})
    peak = int(done.stdout.rsplit("MAXRSS", 1)[1]) / 1024
    return done, peak, time.monotonic() - start


def test_no_learners_file_holds_or_sinks_the_class(tmp_path):
    """Before: the pipe named progress.json held ``grade`` forever, and no report was written."""
    klass = tmp_path / "class"
    klass.mkdir()
    shutil.copy(TUTORIAL_URDF, klass / "alice.urdf")
    os.mkfifo(klass / "bob.zip")  # a pipe named like an archive
    os.mkfifo(klass / "bob.urdf")  # and like a robot file
    for learner, progress in (("carol", None), ("dave", "9" * 5000), ("erin", "[" * 100_000 + "]" * 100_000)):
        folder = klass / learner
        folder.mkdir()
        shutil.copy(TUTORIAL_URDF, folder / "bras.urdf")
        if progress is None:
            os.mkfifo(folder / "progress.json")
        else:
            (folder / "progress.json").write_text(progress, encoding="utf-8")
    done, peak, seconds = _grade_class(klass, tmp_path / "out")
    assert "Traceback" not in done.stderr, done.stderr
    with open(tmp_path / "out" / "grades.csv", encoding="utf-8", newline="") as handle:
        rows = list(csv.reader(handle))
    names = {row[0] for row in rows[1:]}
    assert {"alice", "carol", "dave", "erin", "bob.zip", "bob.urdf"} <= names, rows
    text = (tmp_path / "out" / "grades.csv").read_text(encoding="utf-8")
    assert "not a robot description" in text
    assert seconds < 240 and peak < 600, (seconds, peak)


def test_find_submissions_takes_a_pipe_for_no_archive_and_no_robot(tmp_path):
    os.mkfifo(tmp_path / "x.zip")
    os.mkfifo(tmp_path / "y.urdf")
    (tmp_path / "z.urdf").write_text("<robot/>", encoding="utf-8")
    kinds = {s.learner: s.kind for s in find_submissions(tmp_path)}
    assert kinds == {"x": "other", "y": "other", "z": "file"}

