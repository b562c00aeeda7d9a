"""Folders on the way to a learner's file, and time between a check and a use (issue 53): a
package whose urdf/ folder or package.xml is a link out of it, and a process swapping a folder
for a link while bras-kit builds (data_files copied into install/) or hands robot_state_publisher
its file. Nothing outside the package is ever read: a canary in the outside files appears in no
output, no install tree and no report.

Oracles: the canary's bytes (written here, outside the package), the install tree as the kernel
lists it, and a real racing process (multiprocessing, flipping a folder and a link as fast as it
can) run for many tries (the check-then-open reader lost the race within 8-11 tries).
"""

from __future__ import annotations

import multiprocessing
import os
import shutil
import subprocess
import sys
import time
from pathlib import Path

import pytest

CANARY = "CANARYd41c"


def bras_kit(*args: str, cwd: Path, timeout: float = 300) -> subprocess.CompletedProcess[str]:
    env = {**os.environ, "PATH": f"{Path(sys.executable).parent}:{os.environ['PATH']}"}
    return subprocess.run([sys.executable, "-m", "bras_kit", *args], cwd=cwd, env=env, capture_output=True,
                          text=True, timeout=timeout, stdin=subprocess.DEVNULL)


@pytest.fixture(scope="module")
def made(tmp_path_factory) -> Path:
    base = tmp_path_factory.mktemp("made")
    done = bras_kit("new", str(base / "ws" / "src" / "bras_description"), cwd=base)
    assert done.returncode == 0, done
    return base / "ws" / "src" / "bras_description"


@pytest.fixture
def package(made, tmp_path) -> tuple[Path, Path]:
    """A fresh copy of the package in ws/src/, and outside/ beside ws/ with canary copies of its files."""
    root = tmp_path / "ws" / "src" / "bras_description"
    shutil.copytree(made, root, symlinks=True)
    outside = tmp_path / "outside"
    outside.mkdir()
    urdf = (root / "urdf" / "bras.urdf").read_text()
    (outside / "bras.urdf").write_text(urdf.replace('name="base"', f'name="{CANARY}"')
                                       .replace('<robot name="bras"', f'<robot name="{CANARY}"'))
    (outside / "package.xml").write_text((root / "package.xml").read_text()
                                         .replace("<name>bras_description", f"<name>{CANARY}")
                                         .replace("<description>", f"<description>{CANARY} "))
    assert CANARY in (outside / "bras.urdf").read_text() and CANARY in (outside / "package.xml").read_text()
    return root, outside


def link_urdf_out(root: Path, outside: Path) -> None:
    shutil.rmtree(root / "urdf")
    (root / "urdf").symlink_to(outside)


def link_manifest_out(root: Path, outside: Path) -> None:
    (root / "package.xml").unlink()
    (root / "package.xml").symlink_to(outside / "package.xml")


def no_canary_under(folder: Path) -> None:
    for path in folder.rglob("*"):
        if path.is_file() and not path.is_symlink():
            assert CANARY.encode() not in path.read_bytes(), path


@pytest.mark.parametrize("link", [link_urdf_out, link_manifest_out])
def test_validate_reads_nothing_through_a_folder_or_manifest_linked_out(package, link):
    root, outside = package
    link(root, outside)
    done = bras_kit("validate", str(root), cwd=root.parent)
    assert CANARY not in done.stdout + done.stderr, done.stdout
    assert "Traceback" not in done.stderr and done.returncode != 0


@pytest.mark.parametrize("link", [link_urdf_out, link_manifest_out])
def test_grade_reads_nothing_through_a_folder_or_manifest_linked_out(package, tmp_path, link):
    root, outside = package
    submissions = tmp_path / "subs" / "alice"
    submissions.mkdir(parents=True)
    shutil.move(str(root), submissions / "bras_description")
    link(submissions / "bras_description", outside)
    done = bras_kit("grade", str(tmp_path / "subs"), "-o", str(tmp_path / "report"), cwd=tmp_path)
    assert "Traceback" not in done.stderr, done.stderr
    assert CANARY not in done.stdout + done.stderr
    no_canary_under(tmp_path / "report")


# ---------------------------------------------------------------- a racing process


def _flip(folder: str, outside: str, stop) -> None:  # type: ignore[no-untyped-def]
    real, link, spare = folder, folder + ".link", folder + ".real"
    os.symlink(outside, link)
    while not stop.is_set():
        os.rename(real, spare)
        os.rename(link, real)  # a link out
        os.rename(real, link)
        os.rename(spare, real)  # the folder back


def racing(folder: Path, outside: Path):  # type: ignore[no-untyped-def]
    context = multiprocessing.get_context("fork")
    stop = context.Event()
    process = context.Process(target=_flip, args=(str(folder), str(outside), stop), daemon=True)
    process.start()
    return stop, process


@pytest.mark.slow
def test_build_never_installs_the_outside_file_while_a_folder_is_swapped(package, tmp_path, monkeypatch):
    """setup.py runs once for real (contained); its record is then replayed, so that each of the
    300 builds is the check (setup_check) then the copy into install/, raced."""
    from bras_kit.ros import build

    root, outside = package
    install = tmp_path / "ws" / "install"
    recorded = build._run_setup(str(root))
    assert "setup" in recorded, recorded
    monkeypatch.setattr(build, "_run_setup", lambda *args, **kwargs: recorded)
    stop, process = racing(root / "urdf", outside)
    built = refused = 0
    try:
        for _ in range(300):
            record = build.build_package(str(root), str(install))
            no_canary_under(install)
            if record.failure is None:
                built += 1
            else:
                refused += 1
    finally:
        stop.set()
        process.join(10)
    assert built > 10 and refused > 10, (built, refused)  # the race was run, both ways


@pytest.mark.slow
def test_robot_state_publisher_never_gets_the_outside_file_while_a_folder_is_swapped(package):
    from bras_kit.ros.launching import PlannedNode, robot_state_publisher_start
    from bras_kit.trust.learner_files import Unreadable

    root, outside = package
    path = str(root / "urdf" / "bras.urdf")
    node = PlannedNode("robot_state_publisher", "robot_state_publisher", None, None, {}, [], [], [path], 0.0,
                       str(root / "launch" / "x.launch.py"), 1)
    stop, process = racing(root / "urdf", outside)
    given = 0
    try:
        deadline = time.monotonic() + 6
        while time.monotonic() < deadline:
            try:
                text, problems = robot_state_publisher_start(node, roots=(str(root),))
            except Unreadable:  # pragma: no cover - the function answers with problems, never raises
                raise
            assert CANARY not in (text or "") and CANARY not in repr(problems)
            given += text is not None
    finally:
        stop.set()
        process.join(10)
    assert given > 10


def test_a_folder_given_to_validate_is_walked_without_entering_linked_folders(tmp_path):
    """validate DIR lists the .urdf files of the folder through the one reader: a link to a folder
    outside (holding a broken URDF with the canary) is never walked into."""
    outside = tmp_path / "outside"
    outside.mkdir()
    (outside / "piege.urdf").write_text(f"<robot name='{CANARY}'><link name='a'/><joint/></robot>")
    inside = tmp_path / "mine"
    inside.mkdir()
    (inside / "ok.urdf").write_text("<robot name='ok'><link name='base'/></robot>")
    (inside / "dehors").symlink_to(outside, target_is_directory=True)
    done = bras_kit("validate", str(inside), cwd=tmp_path)
    assert CANARY not in done.stdout + done.stderr and "piege" not in done.stdout + done.stderr
    assert "ok.urdf" in done.stdout + done.stderr


def test_a_submission_is_measured_without_counting_what_links_reach(tmp_path):
    """The grader's size limit counts the submission's own files: a link to a big file outside
    adds nothing (os.stat of the kernel is the oracle), a file inside counts its bytes."""
    from bras_kit.trust.learner_files import folder_size

    big = tmp_path / "big.bin"
    big.write_bytes(b"\0" * 100_000)
    sub = tmp_path / "eleve"
    (sub / "urdf").mkdir(parents=True)
    (sub / "urdf" / "bras.urdf").write_text("<robot name='r'/>")
    (sub / "urdf" / "lien.bin").symlink_to(big)
    (sub / "lien_dossier").symlink_to(tmp_path, target_is_directory=True)
    assert folder_size(str(sub), (str(tmp_path),)) == os.stat(sub / "urdf" / "bras.urdf").st_size
