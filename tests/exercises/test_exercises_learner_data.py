"""The exercise track is the learner's data: its files and progress.json are read and written
through the one reader and writer (no link followed out of the track, atomic replace), a bad
progress file is a clear message and a non-zero exit (never a traceback, a hang or a 3.8 GB
read) with a copy of it kept aside, and progress recorded by two processes at once is never
lost (issue 52, item 5; issue 53).

Oracles: the bytes of every file outside the track (a canary, which must stay as it was and
appear in no output), the count of checks each process made, and the kernel's own view of what
is a link, a pipe or a device.
"""

from __future__ import annotations

import json
import multiprocessing
import os
import shutil
import subprocess
import sys
import time
from pathlib import Path

import pytest

from bras_kit.exercises import init_track, load_track, open_track, reveal_hint

CANARY = "bras-kit-canary-52e1"
TRACK = load_track()


def bras_kit(*args: str, cwd: Path, timeout: float = 60, lang: str = "en") -> subprocess.CompletedProcess[str]:
    env = {**os.environ, "PATH": f"{Path(sys.executable).parent}:{os.environ['PATH']}", "LANG": "C.UTF-8"}
    return subprocess.run([sys.executable, "-m", "bras_kit", *args, "--lang", lang], cwd=cwd, env=env,
                          capture_output=True, text=True, timeout=timeout, stdin=subprocess.DEVNULL)


@pytest.fixture
def track(tmp_path):
    folder = tmp_path / "exos"
    init_track(folder, lang="en")
    mine = tmp_path / "mine"
    mine.mkdir()
    (mine / "notes.txt").write_text(CANARY)
    return folder, mine


def outside_unchanged(mine: Path) -> None:
    assert sorted(p.name for p in mine.iterdir()) == ["notes.txt"]
    assert (mine / "notes.txt").read_text() == CANARY


# ---------------------------------------------------------------- writes through links


def test_reset_refuses_a_linked_exercise_folder_out_of_the_track(track):
    folder, mine = track
    first = TRACK.exercises[0].id
    shutil.rmtree(folder / first)
    (folder / first).symlink_to(mine)
    done = bras_kit("exercises", "reset", "1", "--force", "-C", str(folder), cwd=folder)
    assert done.returncode == 2, done
    assert "Traceback" not in done.stderr and "leads out of the track" in done.stderr, done.stderr
    assert first in done.stderr
    outside_unchanged(mine)  # it created bras.urdf there before


def test_reset_refuses_a_linked_folder_inside_an_exercise_before_writing_any_file(track):
    folder, mine = track
    sixth = TRACK.exercises[5]
    launch = folder / sixth.id / "bras_description" / "launch"
    shutil.rmtree(launch)
    launch.symlink_to(mine)
    setup = folder / sixth.id / "bras_description" / "setup.py"
    setup.write_text("# mine\n")
    done = bras_kit("exercises", "reset", "6", "--force", "-C", str(folder), cwd=folder)
    assert done.returncode == 2 and "leads out of the track" in done.stderr, done
    assert setup.read_text() == "# mine\n"  # nothing was reset half-way
    outside_unchanged(mine)


def test_reset_follows_a_linked_exercise_folder_that_stays_in_the_track(track):
    folder, _ = track
    first = TRACK.exercises[0].id
    (folder / "mine-01").mkdir()
    shutil.rmtree(folder / first)
    (folder / first).symlink_to("mine-01")
    done = bras_kit("exercises", "reset", "1", "--force", "-C", str(folder), cwd=folder)
    assert done.returncode == 0, done
    assert (folder / "mine-01" / "bras.urdf").read_text() == (TRACK.exercises[0].folder / "start" / "bras.urdf") \
        .read_text()


def test_reset_replaces_a_linked_file_and_never_writes_through_it(track):
    folder, mine = track
    first = TRACK.exercises[0].id
    (folder / first / "bras.urdf").unlink()
    (folder / first / "bras.urdf").symlink_to(mine / "notes.txt")
    done = bras_kit("exercises", "reset", "1", "--force", "-C", str(folder), cwd=folder)
    assert done.returncode == 0, done
    assert not (folder / first / "bras.urdf").is_symlink()
    outside_unchanged(mine)


def test_a_hint_never_writes_through_a_link_planted_where_its_temporary_goes(track):
    folder, mine = track
    # the temporary's name was .progress.json.<pid>.tmp: a link there sent the JSON into the user's file
    (folder / f".progress.json.{os.getpid()}.tmp").symlink_to(mine / "notes.txt")
    track_, progress = open_track(folder)
    assert reveal_hint(progress, track_.exercises[0]) == 1
    outside_unchanged(mine)
    assert json.loads((folder / "progress.json").read_text())["exercises"][TRACK.exercises[0].id]["hints"] == 1


def test_progress_json_linked_out_of_the_track_is_neither_read_nor_written(track):
    folder, mine = track
    (folder / "progress.json").unlink()
    (mine / "notes.txt").write_text(json.dumps({"set": "builtin", "current": "", "exercises": {}, "x": CANARY}))
    (folder / "progress.json").symlink_to(mine / "notes.txt")
    saved = (mine / "notes.txt").read_text()
    for action in (("hint",), ("check",), ("list",)):
        done = bras_kit("exercises", *action, "-C", str(folder), cwd=folder)
        assert done.returncode != 0 and "Traceback" not in done.stderr, done
        assert "symbolic link that leads out of the track" in done.stderr
        assert CANARY not in done.stdout + done.stderr
    assert (mine / "notes.txt").read_text() == saved


# ---------------------------------------------------------------- progress.json that bras-kit did not write

BAD_CONTENTS = {
    "5000 digits": '{"set": "builtin", "current": "", "exercises": {"01-links": {"checks": ' + "9" * 5000 + "}}}",
    "nested deep": '{"set": "builtin", "exercises": ' + "[" * 100_000 + "]" * 100_000 + "}",
    "nested object": '{"set": "builtin", "exercises": {"a": ' + '{"b": ' * 50_000 + "1" + "}" * 50_001 + "}",
    "checks as text": '{"set": "builtin", "current": "", "exercises": {"01-links": {"checks": "many"}}}',
    "hints negative": '{"set": "builtin", "current": "", "exercises": {"01-links": {"hints": -3}}}',
    "passed as text": '{"set": "builtin", "current": "", "exercises": {"01-links": {"passed": "yes"}}}',
    "current a number": '{"set": "builtin", "current": 3, "exercises": {}}',
    "exercises a list": '{"set": "builtin", "current": "", "exercises": [1, 2]}',
    "not utf-8": b'{"set": "builtin", "current": "\xff"}',
    "NaN": '{"set": "builtin", "current": "", "exercises": {"01-links": {"checks": NaN}}}',
    "huge float": '{"set": "builtin", "current": "", "exercises": {"01-links": {"checks": 1e999}}}',
    "not an object": "[]",
    "empty": "",
}


@pytest.mark.parametrize("case", sorted(BAD_CONTENTS))
def test_a_bad_progress_file_is_a_message_and_a_copy_kept_aside(track, case):
    folder, _ = track
    content = BAD_CONTENTS[case]
    data = content.encode() if isinstance(content, str) else content
    (folder / "progress.json").write_bytes(data)
    for action in (("hint",), ("check", "1"), ("list",)):
        done = bras_kit("exercises", *action, "-C", str(folder), cwd=folder, timeout=30)
        assert done.returncode != 0, (action, done)
        assert "Traceback" not in done.stderr and "internal error" not in done.stderr.lower(), done.stderr
        assert "progress.json" in done.stderr, done.stderr
        assert (folder / "progress.json").read_bytes() == data  # never overwritten
    assert (folder / "progress.json.bad-1").read_bytes() == data
    assert "progress.json.bad-1" in done.stderr


@pytest.mark.parametrize("kind", ["dev-zero", "fifo", "dev-urandom", "folder", "loop"])
def test_progress_json_that_is_no_file_is_refused_at_once(track, kind):
    folder, _ = track
    path = folder / "progress.json"
    path.unlink()
    if kind == "dev-zero":
        path.symlink_to("/dev/zero")
    elif kind == "dev-urandom":
        path.symlink_to("/dev/urandom")
    elif kind == "fifo":
        os.mkfifo(path)
    elif kind == "folder":
        path.mkdir()
    else:
        path.symlink_to("progress.json")
    for action in (("list",), ("check",), ("hint",), ()):
        started = time.monotonic()
        done = bras_kit("exercises", *action, "-C", str(folder), cwd=folder, timeout=30)
        assert time.monotonic() - started < 20
        assert done.returncode != 0, (action, done)
        assert "Traceback" not in done.stderr and "progress.json" in done.stderr, done.stderr
    assert os.path.lexists(path) and not os.path.lexists(folder / "progress.json.bad-1")
    if kind == "fifo":  # found from inside the track too (it was "no exercise track here")
        done = bras_kit("exercises", "list", cwd=folder / TRACK.exercises[0].id, timeout=30)
        assert done.returncode != 0 and "named pipe" in done.stderr, done.stderr


# ---------------------------------------------------------------- two processes recording at once


def _writer(folder: str, number: int, times: int) -> None:
    """A process holding the track in memory as a watch does, checking one exercise again and again."""
    from bras_kit.exercises import check_exercise

    track_, progress = open_track(folder)
    for _ in range(times):
        check_exercise(track_, progress, track_.exercises[number - 1], "en")


def test_concurrent_writers_lose_no_record(track):
    folder, _ = track
    context = multiprocessing.get_context("fork")
    numbers = [1, 2, 3]
    processes = [context.Process(target=_writer, args=(str(folder), numbers[i % 3], 4)) for i in range(9)]
    for process in processes:
        process.start()
    for process in processes:
        process.join(300)
        assert process.exitcode == 0
    saved = json.loads((folder / "progress.json").read_text())["exercises"]
    ids = [TRACK.exercises[n - 1].id for n in numbers]
    assert {name: saved[name]["checks"] for name in ids} == {name: 12 for name in ids}
    assert not [p for p in folder.iterdir() if p.name.endswith(".tmp")]


def test_many_interleaved_updates_lose_no_record(track):
    folder, _ = track
    context = multiprocessing.get_context("fork")
    processes = [context.Process(target=_counter, args=(str(folder), f"x{i % 4}", 50)) for i in range(8)]
    for process in processes:
        process.start()
    for process in processes:
        process.join(120)
        assert process.exitcode == 0
    saved = json.loads((folder / "progress.json").read_text())["exercises"]
    assert {f"x{i}": saved[f"x{i}"]["checks"] for i in range(4)} == {f"x{i}": 100 for i in range(4)}


def _counter(folder: str, name: str, times: int) -> None:
    from bras_kit.exercises.progress import update_progress

    _track, progress = open_track(folder)

    def count(fresh):  # type: ignore[no-untyped-def]
        entry = fresh.entry(name)
        entry["checks"] = int(entry.get("checks", 0)) + 1

    for _ in range(times):
        update_progress(progress, count)


def solve(folder: Path, number: int) -> None:
    exercise = TRACK.exercises[number - 1]
    for name in exercise.files:
        shutil.copyfile(exercise.folder / "solution" / name, folder / exercise.id / name)


@pytest.mark.slow
@pytest.mark.parametrize("number", [2, 6])
def test_a_check_beside_the_watch_is_kept_and_shown(track, number):
    """The watch (piped: screens printed as they change) on exercise 1; a second process checks
    exercise N, which passes; the watch shows 1/14 passed without a save, and its own next write
    keeps exercise N."""
    folder, _ = track
    env = {**os.environ, "PATH": f"{Path(sys.executable).parent}:{os.environ['PATH']}"}
    watch = subprocess.Popen([sys.executable, "-m", "bras_kit", "exercises", "--lang", "en", "-C", str(folder)],
                             cwd=folder, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                             stdin=subprocess.DEVNULL)
    try:
        out = _read_until(watch, "0/14 exercises passed")
        solve(folder, number)
        done = bras_kit("exercises", "check", str(number), "-C", str(folder), cwd=folder, timeout=120)
        assert done.returncode == 0, done
        out += _read_until(watch, "1/14 exercises passed")  # noticed, with no save of exercise 1
        first = folder / TRACK.exercises[0].id / "bras.urdf"
        first.write_text(first.read_text() + "\n<!-- saved -->\n")  # the watch checks 1 again, and writes
        deadline = time.monotonic() + 60
        target = TRACK.exercises[0].id
        while time.monotonic() < deadline:
            saved = json.loads((folder / "progress.json").read_text())["exercises"]
            if saved.get(target, {}).get("checks", 0) >= 2:
                break
            time.sleep(0.1)
        assert saved[target]["checks"] >= 2, saved
        assert saved[TRACK.exercises[number - 1].id]["passed"] is True, saved
    finally:
        watch.terminate()
        watch.communicate(timeout=30)


def _read_until(process: subprocess.Popen[str], text: str, timeout: float = 90) -> str:
    import selectors

    seen = ""
    selector = selectors.DefaultSelector()
    assert process.stdout is not None
    selector.register(process.stdout, selectors.EVENT_READ)
    deadline = time.monotonic() + timeout
    while text not in seen:
        left = deadline - time.monotonic()
        assert left > 0, f"{text!r} never shown: {seen[-2000:]!r}"
        if selector.select(left):
            chunk = os.read(process.stdout.fileno(), 65536).decode("utf-8", "replace")
            assert chunk, f"the watch ended: {seen[-2000:]!r}"
            seen += chunk
    return seen
