"""The bus between bras-kit commands (Zenoh on a private Unix socket): bras-kit run beside
bras-kit launch. Oracles: the tutorial node's own formula (0.8 sin t, 1.2 sin 0.7t at its 20 Hz
ticks) and the wall clock."""

from __future__ import annotations

import math
import os
import stat
import threading
import time

import pytest
from paths import TESTS

TUTORIAL = TESTS / "data" / "launch" / "tutorial" / "bras_description"


def test_no_launch_no_bus(private_runtime):
    from bras_kit.ros.bus import Bus, listening

    assert not listening()
    assert Bus.connect() is None


def test_the_socket_is_private_and_removed_at_the_end(private_runtime):
    from bras_kit.ros.bus import Bus, bus_folder, listening

    with Bus.listen() as bus:
        assert listening()
        assert os.path.dirname(bus.path) == bus_folder() == str(private_runtime / "bras-kit" / "domain-0")
        for folder in (bus_folder(), os.path.dirname(bus_folder())):
            assert stat.S_IMODE(os.stat(folder).st_mode) == 0o700
        assert stat.S_ISSOCK(os.stat(bus.path).st_mode)
    assert not os.path.exists(bus.path) and not listening()


def test_run_beside_launch_publishes_each_joint_state_on_the_wall_clock(private_runtime):
    from bras_kit.ros.bus import Bus
    from bras_kit.run import run_node

    received: list[tuple[float, object]] = []
    done = threading.Event()
    with Bus.listen() as bus:
        bus.on_joint_state(lambda state: (received.append((time.perf_counter(), state)),
                                          len(received) >= 20 and done.set()))
        started = time.perf_counter()
        recording = run_node(str(TUTORIAL), "animation", duration=1.0, live=True)
        done.wait(5)
    assert recording.failure is None
    assert len(received) == 20  # 1 s at the node's 0.05 s timer
    for k, (_, state) in enumerate(received, 1):
        t = 0.05 * k  # the node's own self.t after k ticks
        assert state.name == ["epaule", "coude"]
        assert state.position == pytest.approx([0.8 * math.sin(t), 1.2 * math.sin(0.7 * t)], abs=1e-12)
    # paced: the last message is not sent before 1 s of wall time (it would be within ~0.1 s unpaced)
    assert received[-1][0] - started >= 0.9
