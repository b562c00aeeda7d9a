"""This boot's record of a containment trial that passed (bras_kit.trust.contain): a command reads it
instead of forking a throwaway trial child (issue 43: ``validate PKG_DIR`` waited for that child).

Oracles: whether a trial child runs (the trial itself replaced by one that fails the test), the
record's file in the runtime folder, and the kernel's answer inside a child (its pid is 1 only
inside the walls). The record may only ever let bras-kit try walls: where they fail, nothing runs."""

from __future__ import annotations

import errno
import os

import pytest

from bras_kit.core.errors import BrasKitError
from bras_kit.core.message import M
from bras_kit.trust import contain
from bras_kit.trust.contain import namespaces, probe, record
from bras_kit.trust.sandbox import run_limited


@pytest.fixture
def runtime(tmp_path, monkeypatch):
    """A runtime folder of this user's (0700), as systemd makes $XDG_RUNTIME_DIR, and a sticky
    shared-memory folder for when there is none; no record in either."""
    folder = tmp_path / "runtime"
    folder.mkdir(mode=0o700)
    shared = tmp_path / "shm"
    shared.mkdir()
    shared.chmod(0o1777)
    monkeypatch.setenv("XDG_RUNTIME_DIR", str(folder))
    monkeypatch.setattr(record, "SHARED_MEMORY", str(shared))
    contain.available.cache_clear()
    yield folder
    contain.available.cache_clear()


def _record(runtime) -> str | None:
    path = runtime / "bras-kit" / "containment-trial-passed"
    return path.read_text() if path.exists() else None


def _no_trial(monkeypatch) -> None:
    def trial() -> tuple[str, int]:
        raise AssertionError("a trial child was forked")

    monkeypatch.setattr(probe, "_trial", trial)


def _pid() -> int:
    return os.getpid()


def test_a_passed_trial_is_recorded_and_the_next_command_forks_none(runtime, monkeypatch):
    assert _record(runtime) is None
    assert contain.available().ok
    assert _record(runtime) == record._trial_key()  # the boot, the user, the namespaces, the switches
    contain.available.cache_clear()  # a new command
    _no_trial(monkeypatch)
    assert contain.available().ok
    assert contain.begin_trial() is False  # the worker of validate PKG_DIR: nothing to begin either
    assert probe._begun is None
    assert run_limited(_pid, contain=contain.Containment(str(runtime))) == 1  # walled in all the same


def test_a_record_of_another_boot_or_namespace_is_not_read(runtime, monkeypatch):
    folder = runtime / "bras-kit"
    folder.mkdir(mode=0o700)
    stale = record._trial_key().replace(record._read("/proc/sys/kernel/random/boot_id"), "another-boot")
    assert stale != record._trial_key()
    (folder / "containment-trial-passed").write_text(stale)
    tried = []
    real = probe._trial
    monkeypatch.setattr(probe, "_trial", lambda: tried.append(1) or real())
    assert contain.available().ok and tried == [1]
    assert _record(runtime) == record._trial_key()


def test_a_failed_trial_is_never_recorded(runtime, monkeypatch):
    def refused(flags: int) -> None:
        error = contain.ContainmentError(M("test"))
        error.errno, error.step = errno.EPERM, "unshare"
        raise error

    monkeypatch.setattr(namespaces, "_unshare", refused)  # inherited by the trial's child
    assert not contain.available().ok
    assert _record(runtime) is None


def test_a_record_whose_walls_fail_runs_nothing_and_is_dropped(runtime, monkeypatch, tmp_path):
    """A record that no longer holds (or was written by someone else) makes bras-kit try walls;
    they fail before the code runs, the error is said, and the record goes."""
    assert contain.available().ok and _record(runtime) is not None

    def refused(flags: int) -> None:
        error = contain.ContainmentError(M("the containment could not be set up: {step} failed ({reason})",
                                                   step="unshare", reason="test"))
        error.errno, error.step = errno.EPERM, "unshare"
        raise error

    monkeypatch.setattr(namespaces, "_unshare", refused)
    ran = tmp_path / "ran"
    with pytest.raises(BrasKitError):
        run_limited(ran.touch, contain=contain.Containment(str(runtime)))
    assert not ran.exists()
    assert _record(runtime) is None


def test_without_a_runtime_folder_of_its_own_the_record_goes_to_a_folder_of_its_own_in_memory(runtime, monkeypatch):
    """$XDG_RUNTIME_DIR others can write (or none): the record is kept in SHARED_MEMORY/bras-kit-UID,
    made 0700; where that folder is someone else's or opened to others, there is no record at all."""
    runtime.chmod(0o777)
    assert contain.available().ok
    assert not (runtime / "bras-kit").exists()
    own = runtime.parent / "shm" / f"bras-kit-{os.getuid()}"
    assert (own / "containment-trial-passed").read_text() == record._trial_key()
    assert own.stat().st_mode & 0o777 == 0o700
    monkeypatch.delenv("XDG_RUNTIME_DIR")
    assert record._record_path() == str(own / "containment-trial-passed")
    own.chmod(0o755)  # opened to others (or made by another user who guessed the name)
    assert record._record_path() is None and record._record_path(make=True) is None
    contain.available.cache_clear()
    tried = []
    real = probe._trial
    monkeypatch.setattr(probe, "_trial", lambda: tried.append(1) or real())
    assert contain.available().ok and tried == [1]


def test_doctor_tries_the_walls_for_real(runtime, monkeypatch):
    from bras_kit.doctor.install import check_containment

    assert contain.available().ok and _record(runtime) is not None
    tried = []
    real = probe._trial
    monkeypatch.setattr(probe, "_trial", lambda: tried.append(1) or real())
    check = check_containment()
    assert tried == [1], check
