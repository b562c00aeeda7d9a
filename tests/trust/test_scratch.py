"""Where bras-kit makes the folders it throws away (bras_kit/trust/scratch.py): the user's TMPDIR when
set, else a folder in memory that is safe to make folders in, else tempfile's own choice.

The oracles are the folders' own facts, set by each test (mode bits, owner, free space as
os.statvfs reports it) and tempfile.gettempdir() for "tempfile's own choice"."""

from __future__ import annotations

import os
import stat
import subprocess
import sys
import tempfile

from bras_kit.trust import scratch


def _folder(tmp_path, name: str, mode: int) -> str:
    path = tmp_path / name
    path.mkdir()
    os.chmod(path, mode)
    return str(path)


def test_a_folder_only_this_user_can_write_is_usable(tmp_path):
    assert scratch.usable(_folder(tmp_path, "own", 0o700), min_free=0)


def test_a_folder_others_can_write_is_usable_only_when_sticky(tmp_path):
    assert scratch.usable(_folder(tmp_path, "sticky", 0o1777), min_free=0)  # like /tmp and /dev/shm
    assert not scratch.usable(_folder(tmp_path, "open", 0o777), min_free=0)  # anyone could rename what we make
    assert not scratch.usable(_folder(tmp_path, "group", 0o770), min_free=0)


def test_a_folder_with_too_little_room_is_not_usable(tmp_path):
    folder = _folder(tmp_path, "small", 0o700)
    space = os.statvfs(folder)
    free = space.f_bavail * space.f_frsize
    assert scratch.usable(folder, min_free=free)
    assert not scratch.usable(folder, min_free=free + (1 << 30))


def test_a_missing_path_a_file_and_a_folder_of_another_owner_are_not_usable(tmp_path, monkeypatch):
    assert not scratch.usable(str(tmp_path / "missing"), min_free=0)
    (tmp_path / "file").write_text("")
    assert not scratch.usable(str(tmp_path / "file"), min_free=0)
    folder = _folder(tmp_path, "theirs", 0o1777)
    real_stat = os.stat
    other = os.getuid() + 1 if os.getuid() else 4242  # neither root nor this user

    def stat_as_theirs(path, *args, **kwargs):
        info = real_stat(path, *args, **kwargs)
        if os.fspath(path) != folder:
            return info
        fields = list(info)
        fields[stat.ST_UID] = other
        return os.stat_result(fields)

    monkeypatch.setattr(os, "stat", stat_as_theirs)
    assert not scratch.usable(folder, min_free=0)


def test_tmpdir_set_by_the_user_is_kept(tmp_path, monkeypatch):
    chosen = _folder(tmp_path, "chosen", 0o700)
    monkeypatch.setenv("TMPDIR", chosen)
    monkeypatch.setenv("XDG_RUNTIME_DIR", _folder(tmp_path, "memory", 0o700))
    monkeypatch.setattr(tempfile, "tempdir", None)  # tempfile reads TMPDIR again
    assert scratch.scratch_root() is None
    with scratch.folder("bras-kit-test-") as made:
        assert os.path.dirname(made) == tempfile.gettempdir() == chosen
        assert stat.S_IMODE(os.stat(made).st_mode) == 0o700
    assert not os.path.exists(made)


def test_without_tmpdir_the_runtime_folder_is_taken_then_dev_shm(tmp_path, monkeypatch):
    for name in scratch.CHOSEN_BY_USER:
        monkeypatch.delenv(name, raising=False)
    runtime = _folder(tmp_path, "runtime", 0o700)
    monkeypatch.setenv("XDG_RUNTIME_DIR", runtime)
    monkeypatch.setattr(scratch, "MIN_FREE", 0)  # the order of the candidates, whatever room the disk has
    assert scratch.scratch_root() == runtime
    made = scratch.mkdtemp("bras-kit-test-")
    try:
        assert os.path.dirname(made) == runtime
        assert stat.S_IMODE(os.stat(made).st_mode) == 0o700
    finally:
        os.rmdir(made)
    os.chmod(runtime, 0o777)  # no longer safe: the next candidate, or tempfile's choice
    expected = "/dev/shm" if scratch.usable("/dev/shm") else None
    assert scratch.scratch_root() == expected


def test_validate_pkg_dir_makes_its_folders_in_the_scratch_folder_and_leaves_none(tmp_path):
    """The build and launch evaluation of `validate PKG_DIR` (its worker, the containment's
    trial, setup.py's and the launch file's children) makes its folders in the scratch folder
    (here a runtime folder of the test's) and removes them; the trial's record stays. Oracle:
    every folder tempfile made, noted by the process that made it, and the runtime folder's
    listing afterwards."""
    from bras_kit.scaffold.package import scaffold_package

    package = tmp_path / "bras_description"
    scaffold_package(str(package))
    runtime = _folder(tmp_path, "runtime", 0o700)
    # a disk with less than MIN_FREE left: the folders go where tempfile puts them, the fallback
    where = runtime if scratch.usable(runtime) else \
        ("/dev/shm" if scratch.usable("/dev/shm") else tempfile.gettempdir())
    log = tmp_path / "made.txt"
    env = {k: v for k, v in os.environ.items() if k not in scratch.CHOSEN_BY_USER}
    env.update(XDG_RUNTIME_DIR=runtime, LANGUAGE="en", LANG="C.UTF-8")
    done = subprocess.run([sys.executable, "-c", NOTE_FOLDERS, str(log), str(package)], env=env,
                          capture_output=True, text=True, cwd=tmp_path, timeout=120)
    assert done.returncode == 0, done.stderr
    assert "0 errors" in done.stdout
    made = log.read_text().split()
    assert {os.path.basename(p).rsplit("-", 1)[0] for p in made} == \
        {"bras-kit-contain", "bras-kit-build", "bras-kit-setup", "bras-kit-launch"}
    assert {os.path.dirname(p) for p in made} == {where}
    assert not [p for p in made if os.path.exists(p)]
    # what stays is this boot's record of the containment's trial, in a folder of its own (contain/record.py)
    assert os.listdir(runtime) == ["bras-kit"]
    assert os.listdir(os.path.join(runtime, "bras-kit")) == ["containment-trial-passed"]


NOTE_FOLDERS = """
import os, sys, tempfile
log, package = sys.argv[1], sys.argv[2]
made = tempfile.mkdtemp

def noted(*args, **kwargs):
    path = made(*args, **kwargs)
    fd = os.open(log, os.O_WRONLY | os.O_APPEND | os.O_CREAT)
    os.write(fd, (path + "\\n").encode())
    os.close(fd)
    return path

tempfile.mkdtemp = noted
from bras_kit.cli import main
sys.exit(main(["validate", package]))
"""
