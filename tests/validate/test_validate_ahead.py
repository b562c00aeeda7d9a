"""`bras-kit validate PKG_DIR` begins the package's build and launch evaluation in a worker of its
own (bras_kit.ros.ahead.evaluate_ahead) while it imports the rules: the answer is the one the
rules would have computed themselves (oracles: the same evaluation run in this process, and the
package findings of validate_package run in this process with no worker), a worker in trouble
changes nothing (the rules evaluate the package themselves), and a worker nobody waits for is not
left behind.

``start_limited`` is the sandbox's child begun and not waited for: the same answers and errors as
``run_limited``, and the child killed when its caller closes it or ends."""

from __future__ import annotations

import json
import os
import pickle
import subprocess
import sys
import textwrap
import time
from pathlib import Path

import pytest

from bras_kit.core.errors import BrasKitError
from bras_kit.ros.ahead import evaluate_ahead
from bras_kit.ros.launched import evaluate_package
from bras_kit.scaffold.package import scaffold_package
from bras_kit.trust.sandbox import ResourceLimitError, run_limited, start_limited

PKG = "bras_description"


def _shape(launched) -> tuple:  # type: ignore[no-untyped-def]
    """What the rules read of an evaluation, without the temporary folders it was made in."""
    plan = launched.plan
    return (launched.build.package, launched.build.failure, sorted((i.source, i.target) for i in launched.build.installed),
            launched.launch_file, launched.description,
            None if plan is None else sorted((n.package, n.executable) for n in plan.nodes),
            None if plan is None else plan.failure, sorted(launched.others))


# in a fresh interpreter: the worker is begun only where no other thread runs, and a test process
# may keep threads of earlier tests (the guard itself is tested below)
AHEAD = """
import json, os, pickle, sys, threading
import bras_kit.ros.launched as launched_module
from bras_kit.ros.ahead import evaluate_ahead

root, broken = sys.argv[1], sys.argv[2] == "broken"
if broken:
    def evaluate_package(root):
        raise RuntimeError("a bug of the worker's")
    launched_module.evaluate_package = evaluate_package  # the forked worker inherits it
answer = evaluate_ahead([os.path.dirname(root)])
sys.stdout.buffer.write(pickle.dumps((answer(root), answer(os.path.dirname(root) + "/elsewhere"),
                                      threading.active_count())))
"""


def _ahead(root: Path, broken: bool = False) -> tuple:  # type: ignore[type-arg]
    done = subprocess.run([sys.executable, "-c", AHEAD, str(root), "broken" if broken else "fine"],
                          capture_output=True, timeout=120)
    assert done.returncode == 0, done.stderr.decode()
    return pickle.loads(done.stdout)  # noqa: S301 - this test's own child


def test_the_answer_ahead_is_the_evaluation_the_rules_would_make(tmp_path):
    root = tmp_path / PKG
    scaffold_package(str(root))
    ahead, elsewhere, threads = _ahead(root)
    here = evaluate_package(str(root))
    assert ahead is not None and here is not None
    assert _shape(ahead) == _shape(here)
    assert ahead.plan is not None and {n.package for n in ahead.plan.nodes} >= {"robot_state_publisher"}
    assert elsewhere is None  # not a package it was given
    assert threads == 1


def test_a_worker_in_trouble_leaves_the_evaluation_to_the_rules(tmp_path):
    from bras_kit.validate.package import Package, launched

    root = tmp_path / PKG
    scaffold_package(str(root))
    ahead, _, _ = _ahead(root, broken=True)
    assert ahead is None
    package = Package(str(root))
    package.ahead = lambda folder: ahead
    assert _shape(launched(package)) == _shape(evaluate_package(str(root)))


def test_beside_another_thread_no_worker_is_forked(tmp_path, monkeypatch):
    """A fork beside a thread that holds an import lock would wait for it forever: no worker then."""
    import threading

    import bras_kit.trust.sandbox as sandbox

    root = tmp_path / PKG
    scaffold_package(str(root))
    forked: list[object] = []
    monkeypatch.setattr(sandbox, "_start", lambda *args: forked.append(args))
    stop = threading.Event()
    other = threading.Thread(target=stop.wait, daemon=True)
    other.start()
    try:
        answer = evaluate_ahead([str(root)])
    finally:
        stop.set()
        other.join()
    assert answer(str(root)) is None and forked == []


def _cli(*args: str, cwd: Path) -> subprocess.CompletedProcess[str]:
    return subprocess.run([sys.executable, "-m", "bras_kit", *args], capture_output=True, text=True, cwd=cwd,
                          timeout=120)


@pytest.mark.parametrize("broken", ["none", "launch_file", "setup_py"])
def test_validate_finds_what_the_rules_find_evaluating_the_package_themselves(tmp_path, broken):
    """Oracle: validate_package in this process (no worker: the rules build and launch the package
    themselves); the command's package findings (BK6xx) are the same, file, code and line."""
    from bras_kit.validate.package import validate_package

    root = tmp_path / PKG
    scaffold_package(str(root))
    if broken == "launch_file":
        launch = next((root / "launch").glob("*.launch.py"))
        launch.write_text(launch.read_text().replace("robot_state_publisher", "robot_state_publiser"))
    elif broken == "setup_py":
        setup = root / "setup.py"
        setup.write_text(setup.read_text().replace("setup(", "raise SystemExit('arrêt')\nsetup(", 1))
    done = _cli("validate", "--format", "json", PKG, cwd=tmp_path)
    assert done.stderr == ""
    shown = {(result["path"], finding["code"], finding["line"]) for result in json.loads(done.stdout)["files"]
             for finding in result["findings"] if finding["code"].startswith("BK6")}
    serial = {(os.path.relpath(result.path, tmp_path), finding.code, finding.line)
              for result in validate_package(str(root), launch=True) for finding in result.findings}
    assert shown == serial
    evaluated = {code for _, code, _ in shown if code.startswith("BK63")}
    assert bool(evaluated) == (broken != "none"), shown  # the evaluation's own findings, where it fails
    assert done.returncode == (0 if broken == "none" else 1)


def test_a_worker_nobody_waits_for_is_killed_when_its_process_ends(tmp_path):
    marker = tmp_path / "pid"
    script = textwrap.dedent(f"""
        import os, time
        from bras_kit.trust.sandbox import start_limited

        def long(path):
            with open(path, "w") as handle:
                handle.write(str(os.getpid()))
            time.sleep(60)

        start_limited(long, {str(marker)!r}, wall_seconds=120)
        while not os.path.exists({str(marker)!r}) or not open({str(marker)!r}).read():
            time.sleep(0.01)
    """)
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=60)
    assert done.returncode == 0, done.stderr
    pid = int(marker.read_text())
    deadline = time.monotonic() + 5
    while time.monotonic() < deadline and _alive(pid):
        time.sleep(0.05)
    assert not _alive(pid)


def _alive(pid: int) -> bool:
    try:
        with open(f"/proc/{pid}/stat") as handle:
            return handle.read().split(") ")[1][0] != "Z"
    except FileNotFoundError:
        return False


def _square(x: int) -> int:
    return x * x


def _fails() -> None:
    raise BrasKitError("said by the child")


def _sleeps() -> None:
    time.sleep(30)


def test_start_limited_answers_as_run_limited_does():
    pending = start_limited(_square, 7)
    assert pending.result() == run_limited(_square, 7) == 49
    with pytest.raises(RuntimeError):
        pending.result()  # once
    with pytest.raises(BrasKitError, match="said by the child"):
        start_limited(_fails).result()
    with pytest.raises(ResourceLimitError) as caught:
        start_limited(_sleeps, wall_seconds=0.5).result()
    assert caught.value.kind == "wall"


def test_the_wall_clock_counts_from_the_start_not_from_the_wait():
    pending = start_limited(_sleeps, wall_seconds=0.5)
    time.sleep(0.6)
    started = time.monotonic()
    with pytest.raises(ResourceLimitError):
        pending.result()
    assert time.monotonic() - started < 0.3


def test_closing_a_pending_child_kills_and_reaps_it():
    pending = start_limited(_sleeps, wall_seconds=60)
    pid = pending._child[0]  # type: ignore[index]
    pending.close()
    assert not _alive(pid)
    with pytest.raises(ChildProcessError):
        os.waitpid(pid, os.WNOHANG)


def test_the_evaluation_crosses_the_pipe_whole(tmp_path):
    """What the worker sends back is plain data: it pickles and unpickles to the same shape."""
    root = tmp_path / PKG
    scaffold_package(str(root))
    here = evaluate_package(str(root))
    assert _shape(pickle.loads(pickle.dumps(here))) == _shape(here)
