"""bras_kit.trust.sandbox.ForkServer: the limited children of a big process (a grading worker)
forked by a small server instead, with run_limited's results, errors and limits.

Oracles: process ids (who is the child's parent), the values and errors the functions below
return or raise by construction, and the kernel's CPU limit."""

from __future__ import annotations

import os
import signal

import pytest

from bras_kit.core.errors import ParameterError
from bras_kit.core.message import M
from bras_kit.trust.sandbox import ForkServer, ResourceLimitError


def parent_and_self(extra: int) -> tuple[int, int, int]:
    return os.getppid(), os.getpid(), extra


def parent_of(_anything: object) -> int:
    return os.getppid()


def refuse(name: str) -> None:
    raise ParameterError(M("joint '{name}' is not in this robot", name=name), path="bras.urdf", line=12)


def spin() -> None:
    while True:
        pass


@pytest.fixture
def server():
    started = ForkServer()
    yield started
    started.close()


def test_the_child_is_forked_by_the_server_not_by_its_owner(server):
    parent, child, extra = server.run(parent_and_self, 7)
    assert extra == 7
    assert parent == server._pid and parent != os.getpid() and child not in (os.getpid(), server._pid)


def test_an_error_in_the_child_comes_back_as_run_limited_gives_it(server):
    with pytest.raises(ParameterError) as caught:
        server.run(refuse, "poignet")
    assert str(caught.value.message) == "joint 'poignet' is not in this robot"
    assert (caught.value.path, caught.value.line) == ("bras.urdf", 12)


def test_a_child_past_its_cpu_limit_is_stopped_and_said_so(server):
    with pytest.raises(ResourceLimitError) as caught:
        server.run(spin, cpu_seconds=1, wall_seconds=20.0, what=M("checking {name}", name="boucle"))
    assert caught.value.kind == "cpu" and "boucle" in str(caught.value.message)
    assert server.run(parent_and_self, 1)[0] == server._pid  # the server goes on


def test_without_its_server_the_owner_forks_the_child_itself(server):
    os.kill(server._pid, signal.SIGKILL)
    parent, _, extra = server.run(parent_and_self, 3)
    assert (parent, extra) == (os.getpid(), 3)
    assert server._pid == 0  # the dead server was reaped


def test_the_server_ends_when_its_owner_closes_it():
    started = ForkServer()
    pid = started._pid
    started.close()
    with pytest.raises(ProcessLookupError):
        os.kill(pid, 0)  # gone and reaped


# ---------------------------------------------------------------- children_from_a_server

HOLDER = "holder of an import"


def import_and_read(name: str) -> int:
    import importlib

    return importlib.import_module(name).VALUE  # type: ignore[no-any-return]


def _slow_module(folder, flag) -> str:
    """A module whose import, in the thread named HOLDER only, waits for ``flag`` to exist."""
    name = f"slow_module_{os.getpid()}_{len(os.listdir(folder))}"
    (folder / f"{name}.py").write_text(
        "import os, threading, time\n"
        f"while threading.current_thread().name == {HOLDER!r} and not os.path.exists({str(flag)!r}):\n"
        "    time.sleep(0.01)\n"
        "VALUE = 42\n")
    return name


def _importing_in_a_thread(name: str):  # type: ignore[no-untyped-def]
    import sys
    import threading
    import time

    thread = threading.Thread(target=__import__, args=(name,), name=HOLDER)
    thread.start()
    end = time.monotonic() + 10
    while name not in sys.modules and time.monotonic() < end:  # its import has begun: its lock is held
        time.sleep(0.01)
    assert name in sys.modules
    return thread


def test_a_child_forked_while_a_thread_imports_waits_for_that_import_forever(tmp_path, monkeypatch):
    """Why children_from_a_server exists: the control. Forked from a process whose other thread is
    importing a module, the child waits for that module's lock, which nobody in it will release."""
    from bras_kit.trust.sandbox import run_limited

    monkeypatch.syspath_prepend(str(tmp_path))
    flag = tmp_path / "go"
    name = _slow_module(tmp_path, flag)
    thread = _importing_in_a_thread(name)
    try:
        with pytest.raises(ResourceLimitError) as caught:
            run_limited(import_and_read, name, wall_seconds=3.0)
        assert caught.value.kind == "wall"
    finally:
        flag.touch()
        thread.join(10)


def test_inside_children_from_a_server_that_child_is_forked_by_the_server_and_imports(tmp_path, monkeypatch):
    """The server was forked before the thread existed: its child imports the module at once, and
    comes from the server, not from the process whose thread holds the lock."""
    from bras_kit.trust import sandbox

    monkeypatch.syspath_prepend(str(tmp_path))
    flag = tmp_path / "go"
    name = _slow_module(tmp_path, flag)
    with sandbox.children_from_a_server():
        server = sandbox._server
        assert server is not None
        thread = _importing_in_a_thread(name)
        try:
            assert sandbox.run_limited(import_and_read, name, wall_seconds=20.0) == 42
            assert sandbox.run_limited(parent_and_self, 3)[0] == server._pid
        finally:
            flag.touch()
            thread.join(10)
    assert sandbox._server is None and server._pid == 0  # closed on the way out
    assert sandbox.run_limited(parent_and_self, 3)[0] == os.getpid()  # forked from here again


def test_a_call_the_server_cannot_be_sent_is_forked_from_here_and_the_server_stays(tmp_path):
    """A function with keyword arguments, or arguments pickle refuses (a lock), is run as before."""
    import threading

    from bras_kit.trust import sandbox

    with sandbox.children_from_a_server():
        server = sandbox._server
        lock = threading.Lock()
        assert sandbox.run_limited(parent_of, lock) == os.getpid()
        assert sandbox.run_limited(parent_and_self, extra=5)[0] == os.getpid()
        assert sandbox.run_limited(parent_and_self, 5)[0] == server._pid
