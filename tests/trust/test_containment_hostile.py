"""The hostile corpus (tests/data/hostile_code/) run contained: each attack refused, reported at
its line, and nothing on disk changed outside the run's folder.

Oracles: the files of a fake home folder and a fake current folder compared byte for byte
before and after (and paths in /tmp that must not appear), the kernel's own answers (a TCP or
UDP listener on this machine's loopback that receives nothing, a Unix socket never connected,
a pipe whose end of file proves no process still holds it, a signal handler never called),
and the line numbers of the corpus files, read by hand. Two attacks are also run without the
containment, to show that these oracles do see an attack that succeeds.
"""

from __future__ import annotations

import ast
import json
import os
import select
import shutil
import signal
import socket
import uuid

import pytest
from paths import TESTS
from snapshots import snapshot

from bras_kit.ros.script import run_script
from bras_kit.run import run_findings, run_node
from bras_kit.trust.contain import available

CORPUS = TESTS / "data" / "hostile_code"
SECRET = "-----BEGIN OPENSSH PRIVATE KEY----- bras-kit-test-secret"
TMP_TARGETS = ("/tmp/bk-hostile-pwned.txt", "/tmp/bk-hostile-ctypes.txt", "/tmp/bk_pwned.txt")


@pytest.fixture
def world(tmp_path, monkeypatch):
    """A fake home (with a private key), a fake current folder, a file in /tmp to remove, a
    TCP and a UDP listener on loopback, a Unix socket and an abstract one; the snapshot before."""
    assert available().ok, available()
    home, cwd = tmp_path / "home", tmp_path / "cwd"
    (home / ".ssh").mkdir(parents=True)
    (home / ".ssh" / "id_rsa").write_text(SECRET)
    (home / "notes.txt").write_text("the learner's notes\n")
    cwd.mkdir()
    (cwd / "copies.txt").write_text("the teacher's folder\n")
    victim = tmp_path / "victim.txt"
    victim.write_text("keep me\n")
    tcp = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
    tcp.bind(("127.0.0.1", 0))
    tcp.listen(4)
    tcp.setblocking(False)
    port = tcp.getsockname()[1]
    udp = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    udp.bind(("127.0.0.1", port))
    udp.setblocking(False)
    unix = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    unix.bind(str(tmp_path / "daemon.sock"))
    unix.listen(4)
    unix.setblocking(False)
    abstract_name = f"bk-hostile-{uuid.uuid4().hex}"
    abstract = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    abstract.bind("\0" + abstract_name)
    abstract.listen(4)
    abstract.setblocking(False)
    corpus = tmp_path / "corpus"  # the corpus, with the targets of this test beside its files
    shutil.copytree(CORPUS, corpus)
    targets = json.dumps({"port": port, "socket": str(tmp_path / "daemon.sock"), "abstract": abstract_name,
                          "victim": str(victim)})
    for folder in ("nodes", "package"):
        (corpus / folder / "targets.json").write_text(targets)
    monkeypatch.setenv("HOME", str(home))
    monkeypatch.setenv("PWD", str(cwd))
    monkeypatch.chdir(cwd)
    for path in TMP_TARGETS:
        assert not os.path.exists(path), f"{path} is left from an earlier run: remove it"
    before = snapshot(tmp_path)

    class World:
        pass

    w = World()
    w.home, w.cwd, w.root, w.before = home, cwd, tmp_path, before
    w.nodes, w.package = corpus / "nodes", corpus / "package"
    w.listeners = {"tcp": tcp, "udp": udp, "unix": unix, "abstract": abstract}
    yield w
    for listener in w.listeners.values():
        listener.close()
    for path in TMP_TARGETS:  # never left behind, even when a test failed
        if os.path.exists(path):
            os.remove(path)


def received(w) -> list[str]:
    """What reached the listeners: connections accepted, datagrams read."""
    got = []
    for name in ("tcp", "unix", "abstract"):
        try:
            w.listeners[name].accept()
            got.append(name)
        except BlockingIOError:
            pass
    try:
        got.append("udp " + w.listeners["udp"].recv(100).decode())
    except BlockingIOError:
        pass
    return got


def unchanged(w) -> None:
    after = snapshot(w.root)
    assert after == w.before, {k: after.get(k) for k in set(after) ^ set(w.before) | {
        k for k in after if k in w.before and after[k] != w.before[k]}}
    for path in TMP_TARGETS:
        assert not os.path.exists(path)


def run(w, name: str, **options):
    return run_node(str(w.nodes / name), duration=1.0, contain=options.pop("contain", "require"), **options)


def blocked(recording) -> list[tuple[str, str, int]]:
    return [(a.kind, a.path, a.line) for a in recording.blocked]


def reported(recording) -> set[tuple[str, str, int | None]]:
    return {(f.code, f.params["file"], f.line) for f in run_findings(recording, None)}


def failed_at(recording) -> tuple[str, str, int]:
    frame = recording.failure.frames[-1]
    return recording.failure.kind, frame.path, frame.line


# ------------------------------------------------------------------ the disk


def test_writing_in_the_home_folder_is_refused_at_its_line(world):
    recording = run(world, "write_home.py")
    assert failed_at(recording) == ("FileNotFoundError", "write_home.py", 6)  # no home in its view
    assert blocked(recording) == [("write", "write_home.py", 6)]
    assert ("BK659", "write_home.py", 6) in reported(recording)
    unchanged(world)


def test_the_same_node_uncontained_does_write_there_so_the_snapshot_sees_it(world):
    recording = run(world, "write_home.py", contain="off")
    assert recording.failure is None and recording.blocked == []
    assert (world.home / "bk_pwned.txt").read_text() == "pwned\n"
    with pytest.raises(AssertionError):
        unchanged(world)


def test_writing_in_the_current_folder_and_beside_the_run_folder_is_refused(world):
    recording = run(world, "write_cwd.py")
    assert blocked(recording) == [("write", "write_cwd.py", 7), ("write", "write_cwd.py", 10)]
    assert failed_at(recording) == ("FileNotFoundError", "write_cwd.py", 10)
    unchanged(world)


def test_writing_and_removing_in_tmp_is_refused(world):
    recording = run(world, "write_tmp.py")
    assert blocked(recording) == [("write", "write_tmp.py", 10), ("write", "write_tmp.py", 13)]
    assert recording.failure.detail.startswith("[Errno 30] Read-only file system")  # /tmp is not its own
    unchanged(world)


def test_the_private_key_cannot_be_read(world):
    recording = run(world, "read_ssh.py")
    assert failed_at(recording) == ("FileNotFoundError", "read_ssh.py", 6)
    assert blocked(recording) == [("read", "read_ssh.py", 6)]
    assert SECRET not in recording.output and SECRET not in repr(recording)
    unchanged(world)


def test_a_symbolic_link_out_of_its_folder_leads_nowhere(world):
    recording = run(world, "symlink_out.py")
    assert blocked(recording) == [("symlink", "symlink_out.py", 6), ("read", "symlink_out.py", 7)]
    assert failed_at(recording) == ("FileNotFoundError", "symlink_out.py", 7)
    assert SECRET not in repr(recording)
    unchanged(world)


def test_ctypes_writes_no_file_either(world):
    recording = run(world, "ctypes_tricks.py")
    assert blocked(recording) == [("ctypes", "ctypes_tricks.py", 7)]
    assert failed_at(recording) == ("OSError", "ctypes_tricks.py", 10)
    assert recording.failure.detail.startswith("[Errno 30]")  # EROFS, from the kernel, through libc
    unchanged(world)


# ------------------------------------------------------------------ the network


@pytest.mark.parametrize(("name", "line", "error"), [
    ("tcp.py", 10, "[Errno 101] Network is unreachable"),
    ("udp.py", 11, "[Errno 101] Network is unreachable"),
    ("unix.py", 11, "[Errno 2] No such file or directory"),
    ("unix_abstract.py", 11, "[Errno 111] Connection refused"),
])
def test_no_socket_reaches_this_machine(world, name, line, error):
    recording = run(world, name)
    assert failed_at(recording)[1:] == (name, line)
    assert recording.failure.detail == error
    assert blocked(recording) == [("network", name, line)]
    assert ("BK659", name, line) in reported(recording)
    assert received(world) == []
    unchanged(world)


def test_the_tcp_node_uncontained_does_connect_so_the_listener_sees_it(world):
    recording = run(world, "tcp.py", contain="off")
    assert recording.failure is None
    assert received(world) == ["tcp"]


# ------------------------------------------------------------------ other processes


def test_a_grandchild_does_not_outlive_the_run(world):
    """The grandchild sleeps 20 s holding the node's stdout: the pipe's end of file, right after
    the run, proves no process of the run is left."""
    read_end, write_end = os.pipe()
    saved = os.dup(1)
    os.dup2(write_end, 1)
    os.close(write_end)
    try:
        recording = run(world, "grandchild.py")
    finally:
        os.dup2(saved, 1)
        os.close(saved)
    try:
        ready, _, _ = select.select([read_end], [], [], 5.0)
        assert ready and os.read(read_end, 100) == b"", "a process of the run still holds its stdout"
    finally:
        os.close(read_end)
    assert blocked(recording) == [("process", "grandchild.py", 7)]
    assert ("BK659", "grandchild.py", 7) in reported(recording)


def test_a_fork_bomb_stops_at_its_line(world):
    recording = run(world, "fork_bomb.py")
    assert failed_at(recording) == ("BlockingIOError", "fork_bomb.py", 7)
    unchanged(world)


def test_killing_the_parent_and_its_group_reaches_no_one(world):
    signalled = []
    previous = signal.signal(signal.SIGTERM, lambda *_: signalled.append(True))
    try:
        recording = run(world, "kill_parent.py")
    finally:
        signal.signal(signal.SIGTERM, previous)
    assert signalled == []  # and this test process is alive: SIGKILL did not reach it either
    assert recording.failure is None  # the kernel took the signals; they reached only the node itself
    assert blocked(recording) == [("signal", "kill_parent.py", 7), ("signal", "kill_parent.py", 8)]


# ------------------------------------------------------------------ setup.py and launch files


def test_a_hostile_setup_py_writes_nothing_and_connects_nowhere(world):
    ran = run_script(str(world.package / "setup.py"), root=str(world.package), argv=("--name",))
    assert ran.contained and ran.failure is None
    assert ran.output == "bras_description\n"  # setup() did run, after both attacks failed
    assert [(a.kind, a.path, a.line) for a in ran.blocked] == [("write", "setup.py", 11), ("network", "setup.py", 16)]
    assert received(world) == []
    unchanged(world)


def test_a_folder_of_the_callers_sys_path_hidden_by_the_walls_is_not_on_the_childs(world, tmp_path, monkeypatch):
    """A test runner puts its own folder on sys.path; setuptools' setup() lists every folder of
    sys.path for entry points, and used to be stopped at the learner's setup() line for it."""
    hidden = tmp_path / "runner"
    hidden.mkdir()
    monkeypatch.syspath_prepend(str(hidden))
    script = world.package / "show_path.py"
    script.write_text("import sys\nprint(repr(sys.path))\n")
    ran = run_script(str(script), root=str(world.package))
    assert ran.contained and ran.failure is None and ran.blocked == []
    seen = ast.literal_eval(ran.output)
    assert str(hidden) not in seen and str(world.package) in seen


def test_a_hostile_launch_file_writes_nothing_and_sends_nothing(world):
    ran = run_script(str(world.package / "launch" / "hostile.launch.py"), root=str(world.package),
                     call="generate_launch_description")
    assert [(a.kind, a.path, a.line) for a in ran.blocked] == [
        ("network", "launch/hostile.launch.py", 10), ("write", "launch/hostile.launch.py", 14)]
    assert received(world) == []
    unchanged(world)
