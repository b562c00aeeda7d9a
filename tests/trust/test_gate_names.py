"""Names that become files (bras_kit.trust.inert.file_stem, docs/security.md "Names that become
files"): two learners never share a report page, a picture or a results file, on any file
system; the same learner always gets the same one.

Oracles: the file systems' own rules (a name is one path component, at most 255 bytes, not
hidden, not a Windows device; a case-insensitive or normalising file system folds case and
composes accents: Python's str.casefold and unicodedata.normalize stand for it), and the
report each learner's page shows (its own name and grade) after a real ``bras-kit grade``."""

from __future__ import annotations

import json
import subprocess
import sys
import unicodedata

import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st
from paths import REPO

from bras_kit.core.errors import BrasKitError
from bras_kit.trust.inert import file_stem

# names a class hands in: ASCII and not, spaces, dots, slashes, case twins, digest look-alikes
pieces = st.one_of(st.sampled_from(["bob", "Bob", "BOB", "smith", " ", "_", "-", ".", "/", "..", "é", "e\u0301",
                                    "\u202e", "\x1b", "con", "nul", "com1", "lpt\u00b9", "7e50351d", "7e50351d7a4c5116", "ß", "ı"]),
                   st.text(min_size=1, max_size=4))
names = st.lists(pieces, min_size=1, max_size=6).map("".join)


def _folded(stem: str) -> str:
    """The file a case-insensitive, normalising file system (macOS, Windows, a USB key) makes of ``stem``."""
    return unicodedata.normalize("NFC", unicodedata.normalize("NFD", stem)).casefold()


def _is_one_file_name(stem: str) -> bool:
    return (bool(stem) and "/" not in stem and "\x00" not in stem and not stem.startswith(".")
            and len((stem + ".html").encode("utf-8", "surrogatepass")) <= 255
            and stem.split(".")[0].lower() not in _WINDOWS_DEVICES)


# Windows reserves these names with any extension ("CON.txt" too): Microsoft's "Naming Files, Paths, and Namespaces"
_WINDOWS_DEVICES = {"con", "prn", "aux", "nul"} | {f"{p}{n}" for p in ("com", "lpt") for n in "123456789¹²³"}


@settings(max_examples=500, deadline=None)
@given(names, names)
def test_two_different_names_never_share_a_file_even_where_case_is_folded(first, second):
    if first == second:
        assert file_stem(first) == file_stem(second)
    else:
        assert _folded(file_stem(first)) != _folded(file_stem(second)), (first, second)


@settings(max_examples=300, deadline=None)
@given(names)
@example("con.bob")  # found by CI: a slug whose first part is a device name
@example("Lpt¹.x y")
def test_a_stem_is_one_plain_file_name_and_always_the_same(name):
    stem = file_stem(name)
    assert _is_one_file_name(stem), stem
    assert file_stem(name) == stem
    assert stem.encode("utf-8")  # no lone surrogate: every file system can store it


@pytest.mark.parametrize(("first", "second"), [
    ("bob smith", "bob_smith-7e50351d"),  # the pair (the old form of "bob smith")
    ("bob smith", "bob_smith-7e50351d7a4c5116"),  # and the new form, handed in as a name
    ("Bob", "bob"), ("élève", "e\u0301le\u0300ve"), ("a/b", "a_b"), ("../x", "x"), ("con", "con-"),
])
def test_names_that_clashed_or_could_clash_keep_files_of_their_own(first, second):
    assert _folded(file_stem(first)) != _folded(file_stem(second))


def test_plain_names_are_kept_and_others_are_readable():
    assert [file_stem(n) for n in ("alice", "a_b", "arm3", "bob.smith")] == ["alice", "a_b", "arm3", "bob.smith"]
    assert file_stem("bob smith") == "bob_smith-7e50351d7a4c5116"  # sha256("bob smith")[:16]
    assert file_stem("Élève Martin").startswith("Élève_Martin-")


def test_a_class_where_two_learners_would_share_a_page_is_refused(monkeypatch, tmp_path):
    """The net under file_stem (a SHA-256 collision): refused, both named, nothing written."""
    from bras_kit.grade import report
    from bras_kit.grade.rubric import load_rubric

    monkeypatch.setattr(report, "_file_name", lambda learner: "same.html")
    results = [{"learner": name, "score": 1.0, "max": 2.0, "items": {}, "status": "graded"} for name in ("a", "b")]
    with pytest.raises(BrasKitError) as caught:
        report.write_reports(str(tmp_path / "out"), results, load_rubric(), "en")
    assert "'a'" in str(caught.value) and "'b'" in str(caught.value)
    assert not (tmp_path / "out" / "learners").exists()


def test_entries_of_one_class_never_share_a_learner_name(tmp_path):
    """bob/, bob.zip and bob.zip.tar: three learners (the archive's full name, bob.zip, was
    the learner name of the third)."""
    from bras_kit.grade.submissions import find_submissions

    (tmp_path / "bob").mkdir()
    (tmp_path / "bob.zip").write_bytes(b"")
    (tmp_path / "bob.zip.tar").write_bytes(b"")
    (tmp_path / "bob.urdf").write_text("")
    learners = [s.learner for s in find_submissions(tmp_path)]
    assert len(set(learners)) == len(learners) == 4, learners


def test_two_learners_named_alike_each_see_their_own_page_and_results(tmp_path):
    """The issue's class: 'bob smith' hands in the tutorial arm, 'bob_smith-7e50351d' a broken
    file. Each link of the index opens that learner's own page; Gradescope gets two files."""
    from bras_kit.model.authoring import arm_urdf

    klass = tmp_path / "class"
    klass.mkdir()
    (klass / "bob smith.urdf").write_text(arm_urdf())
    (klass / "bob_smith-7e50351d.urdf").write_text(arm_urdf()[:200])
    out = tmp_path / "report"
    done = subprocess.run([sys.executable, "-m", "bras_kit", "grade", str(klass), "-o", str(out), "--gradescope",
                           "--jobs", "1"], capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stderr
    pages = sorted(p.name for p in (out / "learners").glob("*.html"))
    assert len(pages) == 2, pages
    index = (out / "index.html").read_text()
    scores = {}
    for page in pages:
        assert f"learners/{page}" in index
        text = (out / "learners" / page).read_text()
        learner = "bob smith" if "<h1>bob smith:" in text else "bob_smith-7e50351d"
        assert f"<h1>{learner}:" in text
        scores[learner] = text.split(f"<h1>{learner}: ", 1)[1].split(" /", 1)[0]
    assert float(scores["bob smith"]) > 0 and float(scores["bob_smith-7e50351d"]) == 0
    graded = sorted((out / "gradescope").glob("*.json"))
    assert len(graded) == 2
    assert sorted(json.loads(p.read_text())["score"] for p in graded) == sorted(float(s) for s in scores.values())


def test_exercises_sharing_a_folder_on_a_case_folding_file_system_are_refused(tmp_path):
    import shutil

    from bras_kit.exercises.manifest import load_track

    source = REPO / "bras_kit" / "exercises" / "track"
    exercise_set = tmp_path / "set"
    (exercise_set).mkdir()
    shutil.copytree(source / "01-links", exercise_set / "01-links")
    shutil.copytree(source / "01-links", exercise_set / "01-Links")
    (exercise_set / "track.yaml").write_text("name: twins\nexercises: [01-links, 01-Links]\n")
    with pytest.raises(BrasKitError) as caught:
        load_track(exercise_set)
    assert "01-Links" in str(caught.value)
