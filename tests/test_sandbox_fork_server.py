"""bras_kit.sandbox.ForkServer: the limited children of a big process (a grading worker)
forked by a small server instead, with run_limited's results, errors and limits.

Oracles: process ids (who is the child's parent), the values and errors the functions below
return or raise by construction, and the kernel's CPU limit."""

from __future__ import annotations

import os
import signal

import pytest

from bras_kit.errors import ParameterError
from bras_kit.message import M
from bras_kit.sandbox import ForkServer, ResourceLimitError


def parent_and_self(extra: int) -> tuple[int, int, int]:
    return os.getppid(), os.getpid(), extra


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
