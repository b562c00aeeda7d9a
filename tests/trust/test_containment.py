"""bras_kit.trust.contain and run_limited(contain=...): what the contained child sees and may do.

Oracles: the kernel's answers inside the child (its pid in its namespace, the errno of a
mount, of a write, of a connection; the network interfaces it has), files seen from outside
after the run, and a result crafted to run a command when unpickled (the file it would create
must not exist)."""

from __future__ import annotations

import ctypes
import errno
import os
import socket
import sys

import pytest
from paths import DATA as DATA_DIR

from bras_kit.core.errors import BrasKitError
from bras_kit.core.message import M
from bras_kit.trust import contain as contain_module
from bras_kit.trust.contain import (
    Containment,
    ContainmentUnavailable,
    Status,
    available,
    modes,
    namespaces,
)
from bras_kit.trust.sandbox import ForkServer, _rebuild_error, run_limited

TUTORIAL = os.path.join(DATA_DIR, "tutorial_package")


@pytest.fixture
def walls(tmp_path):
    assert available().ok, available()
    work = tmp_path / "work"
    work.mkdir()
    return Containment(str(work))


def look_around(workdir: str) -> dict:
    with open(os.path.join(workdir, "made.txt"), "w") as handle:
        handle.write("inside\n")
    errors = {}
    for name, attempt in {
        "tmp": lambda: open("/tmp/bk-contain-test.txt", "w"),
        "etc": lambda: open("/etc/passwd"),
        "proc": lambda: os.listdir("/proc"),
        "connect": lambda: socket.create_connection(("127.0.0.1", 9), timeout=1),
    }.items():
        try:
            attempt()
            errors[name] = 0
        except OSError as exc:
            errors[name] = exc.errno
    libc = ctypes.CDLL(None, use_errno=True)
    mounted = libc.mount(b"tmpfs", workdir.encode(), b"tmpfs", 0, None)
    ways = {}
    for granted in (workdir, sys.base_prefix, sys.prefix):
        parent = os.path.dirname(granted)
        while parent != "/":
            ways[parent] = sorted(os.listdir(parent))
            parent = os.path.dirname(parent)
    return {"ways": ways, "pid": os.getpid(), "uid": os.getuid(), "cwd": os.getcwd(), "top": sorted(os.listdir("/")),
            "folder": sorted(os.listdir(workdir)),
            "interfaces": [name for _, name in socket.if_nameindex()], "errors": errors,
            "mount": (mounted, ctypes.get_errno()), "sid": os.getsid(0)}


def test_the_contained_child_is_alone_in_its_own_world(walls):
    seen = run_limited(look_around, walls.workdir, contain=walls)
    assert seen["pid"] == 1 and seen["sid"] == 1  # the init of its own PID namespace, its own session
    # a user keeps its uid (its files keep their owner); root runs the code as the overflow user,
    # whom the kernel counts in RLIMIT_NPROC (it never counts root)
    overflow = int(open("/proc/sys/kernel/overflowuid").read())
    assert seen["uid"] == (os.getuid() or overflow)
    assert seen["interfaces"] == ["lo"]  # a network namespace of its own (and lo is down)
    assert seen["errors"] == {"tmp": errno.EROFS, "etc": errno.ENOENT, "proc": errno.ENOENT,
                              "connect": errno.ENETUNREACH}
    assert seen["mount"] == (-1, errno.EPERM)  # no capability left, even in its own namespace
    granted = ("/usr", walls.workdir, *contain_module.python_paths())
    tops = {path.strip("/").split("/")[0] for path in granted}
    assert set(seen["top"]) <= tops | {"bin", "sbin", "lib", "lib64", "lib32", "libx32", "etc", "dev"}
    assert "home" not in seen["top"] and "proc" not in seen["top"] and "run" not in seen["top"]
    # each folder on the way to a granted one holds only that way (no ~/.ssh beside ~/.pyenv)
    for path, entries in seen["ways"].items():
        assert all(any(g == os.path.join(path, e) or g.startswith(os.path.join(path, e) + "/") for g in granted)
                   for e in entries), (path, entries)
    # what it wrote is in its folder, a tmpfs of its own: nothing reached the disk, nothing was left
    assert seen["folder"] == ["made.txt"]
    assert os.listdir(walls.workdir) == []


def test_the_folders_it_is_given_to_read_are_read_only(walls, tmp_path):
    package = tmp_path / "pkg"
    package.mkdir()
    (package / "node.py").write_text("print('hi')\n")
    readable = Containment(walls.workdir, (str(package),))

    def read_then_write(path: str):
        text = open(path).read()
        try:
            open(path, "a").write("pwned")
        except OSError as exc:
            return text, exc.errno
        return text, 0

    # a read-only mount (EROFS); root's code runs as the overflow user, refused before (EACCES)
    refused = errno.EROFS if os.getuid() else errno.EACCES
    assert run_limited(read_then_write, str(package / "node.py"), contain=readable) == ("print('hi')\n", refused)
    assert (package / "node.py").read_text() == "print('hi')\n"


def test_inherited_file_descriptors_are_closed(walls, tmp_path):
    secret = open(tmp_path / "secret.txt", "w")  # noqa: SIM115 - held open across the fork on purpose

    def probe(fd: int) -> int:
        try:
            os.fstat(fd)
        except OSError as exc:
            return exc.errno or 0
        return 0

    try:
        assert run_limited(probe, secret.fileno()) == 0  # uncontained: the descriptor is inherited
        assert run_limited(probe, secret.fileno(), contain=walls) == errno.EBADF
    finally:
        secret.close()


class Crafted:
    """Unpickled, it would run a command (the classic pickle attack)."""

    def __init__(self, path: str) -> None:
        self.path = path

    def __reduce__(self):
        return os.system, (f"touch {self.path}",)


def test_a_crafted_result_is_refused_not_run(walls, tmp_path):
    target = tmp_path / "ran.txt"
    with pytest.raises(BrasKitError) as caught:
        run_limited(Crafted, str(target), contain=walls)
    assert "unreadable result" in str(caught.value)
    assert not target.exists()


def test_an_error_naming_a_module_outside_bras_kit_does_not_import_it():
    sys.modules.pop("this", None)
    error = _rebuild_error("this", "Anything", {"message": "boom", "path": None, "line": None,
                                                "element": None, "hint": None, "extra": {}})
    assert type(error) is BrasKitError and "this" not in sys.modules


def test_the_fork_server_forwards_the_containment(walls):
    server = ForkServer()
    try:
        seen = server.run(look_around, walls.workdir, contain=walls)
    finally:
        server.close()
    assert seen["pid"] == 1 and seen["errors"]["tmp"] == errno.EROFS


def test_require_refuses_where_containment_is_missing(monkeypatch, tmp_path):
    from bras_kit.run import run_node

    missing = Status(False, M("test"), M("unprivileged user namespaces"),
                     M("enable them"))
    monkeypatch.setattr(modes, "available", lambda: missing)
    with pytest.raises(ContainmentUnavailable) as caught:
        run_node(TUTORIAL, "animation", duration=0.5, contain="require")
    assert caught.value.hint is not None
    recording = run_node(TUTORIAL, "animation", duration=0.5, contain="auto")  # runs, uncontained
    assert recording.ended == "duration" and recording.blocked == []


def test_the_tutorial_node_runs_the_same_contained(tmp_path):
    from bras_kit.run import run_node

    contained = run_node(TUTORIAL, "animation", duration=2.0, contain="require")
    free = run_node(TUTORIAL, "animation", duration=2.0, contain="off")
    assert contained.blocked == [] and contained.failure is None
    assert [m.fields for m in contained.messages] == [m.fields for m in free.messages]
    assert len(contained.messages) == 40  # 20 Hz for 2 s, the tutorial's timer


def test_the_probe_names_the_step_the_kernel_refused(monkeypatch, tmp_path):
    runtime = tmp_path / "runtime"
    runtime.mkdir(mode=0o700)
    monkeypatch.setenv("XDG_RUNTIME_DIR", str(runtime))  # no record of an earlier trial: this one runs

    def refused(flags: int) -> None:
        error = contain_module.ContainmentError(M("test"))
        error.errno, error.step = errno.EPERM, "unshare"
        raise error

    monkeypatch.setattr(namespaces, "_unshare", refused)  # inherited by the probe's child
    status = available.__wrapped__()
    assert not status.ok and status.missing.id == "unprivileged user namespaces"
    assert status.found.params["reason"] == os.strerror(errno.EPERM)
    assert status.how is not None


def make_temporary_file() -> tuple[str, bool]:
    import tempfile

    fd, path = tempfile.mkstemp()
    os.close(fd)
    return path, os.path.isfile(path)


def test_temporary_files_go_to_the_run_folder(walls):
    made, there = run_limited(make_temporary_file, contain=walls)
    assert os.path.dirname(made) == walls.workdir and there
    assert not os.path.exists(made)  # the folder it saw is a tmpfs of its own, gone with the run


def environment() -> dict:
    return dict(os.environ)


def test_tokens_in_the_environment_stay_outside(walls, monkeypatch):
    monkeypatch.setenv("GITHUB_TOKEN", "ghp_not_for_learners")
    monkeypatch.setenv("ROS_DOMAIN_ID", "7")
    inside = run_limited(environment, contain=walls)
    assert "GITHUB_TOKEN" not in inside
    assert inside["ROS_DOMAIN_ID"] == "7" and inside["PATH"] == os.environ["PATH"]
    assert inside["TMPDIR"] == walls.workdir


IMPORT_PYSECCOMP = """
import ctypes.util, json, sys
spawned = []
sys.addaudithook(lambda event, args: spawned.append(str(args[1])) if event == "subprocess.Popen" else None)
from bras_kit.trust.contain import seccomp as contain
contain.SONAMES.update(json.loads(sys.argv[1]))
looked_up = ctypes.util.find_library
contain._import_pyseccomp()
with open("/proc/self/maps") as maps:
    mapped = sorted({line.split()[-1].rsplit("/", 1)[-1] for line in maps if "libseccomp" in line})
print(json.dumps({"spawned": spawned, "mapped": mapped, "restored": ctypes.util.find_library is looked_up}))
"""


@pytest.mark.parametrize("sonames, asks_ldconfig", [
    ({}, False),  # the sonames the loader knows: no ldconfig on the way to every contained child
    ({"c": "libc.so.0-none", "seccomp": "libseccomp.so.0-none"}, True),  # unknown ones: find_library as before
])
def test_libseccomp_is_loaded_by_soname_or_found_as_before(sonames, asks_ldconfig):
    """Oracles: the kernel's map of the process (libseccomp loaded) and the interpreter's audit
    events (whether a process was spawned to find it)."""
    import json
    import subprocess

    done = subprocess.run([sys.executable, "-c", IMPORT_PYSECCOMP, json.dumps(sonames)],
                          capture_output=True, text=True, timeout=60)
    assert done.returncode == 0, done.stderr
    seen = json.loads(done.stdout)
    assert seen["mapped"] and all(name.startswith("libseccomp.so.2") for name in seen["mapped"]), seen
    assert seen["restored"]
    assert bool(seen["spawned"]) is asks_ldconfig, seen
    if asks_ldconfig:
        assert any("ldconfig" in argv for argv in seen["spawned"]), seen
