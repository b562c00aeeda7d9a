"""The bus scoped as ROS scopes a graph: one per user and per ROS_DOMAIN_ID, every launch a
participant of its own (two launches at once), a run joining them only when it is live, batch
runs in simulated time whatever is open.

Oracles: rcl's reading of ROS_DOMAIN_ID (rcl/src/rcl/domain_id.c, rcl_get_default_domain_id:
strtoul(text, &end, 0), refused when it reads 0 and stops before the end); the kernel's file
permissions and process credentials (a process of another uid); the nodes' own formulas and
joint names (tests/data/workspace/cellule_bringup: trois_axes publishes epaule, coude and poignet
at 20 Hz); the wall clock for "until Ctrl-C" (a live run outlives its 10 s default)."""

from __future__ import annotations

import os
import re
import select
import shutil
import signal
import socket
import subprocess
import sys
import time
from pathlib import Path

import pytest
from pages import ended as _ended
from pages import free_port as _free_port
from pages import launch_url
from pages import wait as _wait
from paths import TESTS

DATA = TESTS / "data"
TUTORIAL = DATA / "launch" / "tutorial" / "bras_description"
BRINGUP = DATA / "workspace" / "cellule_bringup"


def _state(k: int):  # type: ignore[no-untyped-def]
    from bras_kit.ros.bus import BusJointState

    return BusJointState(["epaule", "coude"], [0.1 * k, -0.1 * k], 0.05 * k)


# ------------------------------------------------------------------ ROS_DOMAIN_ID, as rcl reads it


@pytest.mark.parametrize(("text", "domain"), [("", 0), ("0", 0), ("7", 7), ("0x10", 16), ("010", 8), (" 3", 3),
                                              ("5abc", 5), ("232", 232)])
def test_the_domain_is_read_as_rcl_reads_it(text, domain):
    from bras_kit.ros.bus import domain_id

    assert domain_id({"ROS_DOMAIN_ID": text}) == domain


@pytest.mark.parametrize(("text", "said"), [("abc", "not an integral number"), ("0abc", "not an integral number"),
                                            ("  ", "not an integral number"), ("-1", "out of range"),
                                            ("233", "out of range")])
def test_a_domain_rcl_refuses_is_refused_with_its_words(text, said):
    from bras_kit.core.errors import ParameterError
    from bras_kit.ros.bus import domain_id

    with pytest.raises(ParameterError) as caught:
        domain_id({"ROS_DOMAIN_ID": text})
    assert f"ROS_DOMAIN_ID is {said}" in str(caught.value.message)


# ------------------------------------------------------------------ participants


def test_two_launches_listen_side_by_side_and_a_run_reaches_both(private_runtime):
    from bras_kit.ros.bus import Bus, launches

    got: list[list[object]] = [[], []]
    with Bus.listen() as first, Bus.listen() as second:
        first.on_joint_state(got[0].append)
        second.on_joint_state(got[1].append)
        assert launches() == sorted([first.path, second.path]) and first.path != second.path
        run = Bus.connect()
        assert run is not None and run.peers == launches()
        try:
            time.sleep(0.3)  # the subscriptions reach the run's session
            for k in range(1, 6):
                run.publish_joint_state(_state(k))
            assert _wait(lambda: len(got[0]) == len(got[1]) == 5, 10), got
        finally:
            run.close()
    assert got[0] == got[1] == [_state(k) for k in range(1, 6)]
    assert launches() == []


def test_a_run_joins_only_the_launches_of_its_domain(private_runtime, monkeypatch):
    from bras_kit.ros.bus import Bus, listening

    monkeypatch.setenv("ROS_DOMAIN_ID", "3")
    with Bus.listen():
        monkeypatch.delenv("ROS_DOMAIN_ID")  # domain 0, the default
        assert not listening() and Bus.connect() is None
        monkeypatch.setenv("ROS_DOMAIN_ID", "4")
        assert Bus.connect() is None
        monkeypatch.setenv("ROS_DOMAIN_ID", "03")  # octal 3, as strtoul(..., 0) reads it
        run = Bus.connect()
        assert run is not None
        run.close()


def test_a_launch_left_by_a_process_that_died_is_not_joined_and_its_socket_goes(private_runtime):
    from bras_kit.ros.bus import Bus, bus_folder, launches

    os.makedirs(bus_folder(), mode=0o700)
    os.chmod(os.path.dirname(bus_folder()), 0o700)
    dead = os.path.join(bus_folder(), "1-1.sock")
    left = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    left.bind(dead)  # bound, never listening: what a killed launch leaves
    left.close()
    assert launches() == [] and Bus.connect() is None
    with Bus.listen() as bus:
        assert not os.path.exists(dead) and launches() == [bus.path]


def test_the_robot_a_launch_shows_is_told_to_a_run_with_the_joints_it_lacks(private_runtime):
    from bras_kit.ros.bus import Bus, LaunchRobot, unknown_joints

    with Bus.listen() as launch:
        launch.offer_robot(lambda: LaunchRobot("bras_description", ("epaule", "coude")))
        run = Bus.connect()
        assert run is not None
        try:
            robots = run.robots()
        finally:
            run.close()
    assert robots == [LaunchRobot("bras_description", ("epaule", "coude"))]
    assert unknown_joints(["epaule", "coude", "poignet"], robots[0]) == ["poignet"]


# ------------------------------------------------------------------ the user


def test_a_bus_folder_others_can_open_is_neither_joined_nor_listened_on(private_runtime):
    from bras_kit.core.errors import BrasKitError
    from bras_kit.ros.bus import Bus, bus_folder, launches

    with Bus.listen():
        os.chmod(bus_folder(), 0o755)
        try:
            assert launches() == [] and Bus.connect() is None
            with pytest.raises(BrasKitError) as caught:
                Bus.listen()
            assert "is not a private folder of yours" in str(caught.value.message)
        finally:
            os.chmod(bus_folder(), 0o700)


@pytest.mark.skipif(os.getuid() != 0, reason="only root can start a process of another user; "
                    "test_a_bus_folder_others_can_open_is_neither_joined_nor_listened_on covers the folder")
def test_a_process_of_another_user_never_sees_the_launch(private_runtime):
    """A process of uid 65534 (nobody), given this user's runtime folder or its own: no launch."""
    from bras_kit.ros.bus import Bus, launches

    with Bus.listen():
        assert launches()
        for runtime in (str(private_runtime), ""):
            read, write = os.pipe()
            pid = os.fork()
            if pid == 0:  # the other user
                try:
                    os.close(read)
                    os.setgid(65534)
                    os.setuid(65534)
                    os.environ["XDG_RUNTIME_DIR"] = runtime
                    os.write(write, repr(launches()).encode())
                finally:
                    os._exit(0)
            os.close(write)
            with os.fdopen(read) as seen:
                assert seen.read() == "[]"
            os.waitpid(pid, 0)


# ------------------------------------------------------------------ in a terminal


def _preexec() -> None:
    signal.signal(signal.SIGINT, signal.SIG_DFL)  # Ctrl-C as a terminal delivers it, whoever started the tests


def _start(cwd: Path, *argv: str) -> subprocess.Popen:
    env = {k: v for k, v in os.environ.items() if k not in ("DISPLAY", "WAYLAND_DISPLAY")}
    return subprocess.Popen([sys.executable, "-m", "bras_kit", *argv], cwd=cwd, env=env, stdout=subprocess.PIPE,
                            stderr=subprocess.PIPE, text=True, preexec_fn=_preexec)


def _url(process: subprocess.Popen) -> str:
    return launch_url(process, None, seconds=240)


def _lines_until(stream, pattern: str, seconds: float) -> str:  # type: ignore[no-untyped-def]
    """What ``stream`` says until a line matches ``pattern`` (or ``seconds`` pass). Read from its
    descriptor, never through the text stream: a ``readline`` reads ahead into the stream's buffer,
    where ``select`` no longer sees the lines waiting (and a later read through the stream still finds
    what is not read here)."""
    import codecs

    decoder = codecs.getincrementaldecoder("utf-8")(errors="replace")
    said = ""
    end = time.monotonic() + seconds
    while time.monotonic() < end:
        ready, _, _ = select.select([stream.fileno()], [], [], 0.5)
        if ready:
            chunk = os.read(stream.fileno(), 65536)
            said += decoder.decode(chunk, final=not chunk)
            if not chunk or any(re.search(pattern, line) for line in said.splitlines()):
                break
    return said


@pytest.mark.slow
def test_two_launches_beside_a_batch_run_and_a_live_run(private_runtime, tmp_path):
    """In the tutorial's workspace: two bras-kit launch open at once (French and English); a batch
    run of another package (three joints) keeps its simulated speed and reaches no page; a live
    run of it joins both, is told the joint the pages lack, outlives its 10 s default and ends on
    Ctrl-C; then both launches end cleanly."""
    from bras_kit.ros.bus import Bus, launches

    root = tmp_path / "ros2_cellule_ws"
    shutil.copytree(TUTORIAL, root / "src" / "bras_description")
    shutil.copytree(BRINGUP, root / "src" / "cellule_bringup")
    first = _start(root, "launch", "bras_description", "affichage.launch.py", "--port", str(_free_port()),
                   "--lang", "fr")
    second = _start(root / "src" / "bras_description", "launch", "bras_description", "affichage.launch.py",
                    "--port", str(_free_port()), "--lang", "en")
    received: list[object] = []
    try:
        _url(first)
        _url(second)
        assert len(launches()) == 2
        with Bus.listen() as page:  # a third page: what the launches' pages are sent
            page.on_joint_state(received.append)
            batch = subprocess.run([sys.executable, "-m", "bras_kit", "run", "cellule_bringup", "trois_axes", "--json",
                                    "--quiet", "-o", str(tmp_path / "etats.csv"), "--lang", "fr"],
                                   cwd=root, capture_output=True, text=True, timeout=300, preexec_fn=_preexec)
            # checked against the tutorial arm (the package has no robot of its own): poignet is an error
            assert batch.returncode == 1 and "poignet" in batch.stdout, batch.stdout + batch.stderr
            assert (tmp_path / "etats.csv").is_file()
            assert "est ouvert sur ce domaine ROS" in batch.stderr  # the launches are left alone, and it says so
            simulated = re.search(r"10 s de temps simulé en ([0-9.]+) s", batch.stderr)
            assert simulated and float(simulated.group(1)) < 9.0, batch.stderr  # on the wall clock: 10 s or more
            time.sleep(0.5)
            assert received == []

            live = _start(root / "src" / "cellule_bringup", "run", "cellule_bringup", "trois_axes", "--lang", "en")
            started = time.monotonic()
            try:
                said = _lines_until(live.stderr, r"poignet", 120)
                assert "joined the running bras-kit launch (ROS domain 0)" in said, said
                assert "publishes joints 'poignet'" in said and "bras_description" in said, said
                assert _wait(lambda: len(received) >= 20, 60), len(received)
                assert received[0].name == ["epaule", "coude", "poignet"]  # type: ignore[attr-defined]
                assert _wait(lambda: time.monotonic() - started > 12, 30)
                assert live.poll() is None, "a live run ends on Ctrl-C, not after its 10 s default"
                count = len(received)
                assert _wait(lambda: len(received) > count, 5), "it still publishes after 10 s"
            finally:
                live.send_signal(signal.SIGINT)
                out, err = _ended(live)
            assert live.returncode == 0, err
            assert "stopped by Ctrl-C" in err and "Traceback" not in err
        for launch in (first, second):
            assert launch.poll() is None, "both launches stay open side by side"
    finally:
        for launch in (first, second):
            launch.send_signal(signal.SIGINT)
        ends = [_ended(launch) for launch in (first, second)]
    for launch, (_, err) in zip((first, second), ends):
        assert launch.returncode == 0, err
        assert "ZError" not in err and "Traceback" not in err, err
    assert launches() == []
