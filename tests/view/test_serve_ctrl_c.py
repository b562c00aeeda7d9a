"""A serving command (``view``, ``launch``) prints its address with "(Ctrl-C to stop)": a Ctrl-C
that lands at any moment after that line is the stop it announced (exit 0, nothing printed as an
interruption, the page's port freed), even when it lands before the command reached its wait, as
it does on a loaded machine. The signal is made to land at a chosen moment by replacing one
function the command calls after its address with one that raises KeyboardInterrupt, which is
what Python raises in the main thread when SIGINT arrives there."""

from __future__ import annotations

import os
import socket
import subprocess
import sys
from pathlib import Path

import pytest
from pages import free_port as _free_port
from paths import REPO

pytestmark = pytest.mark.slow

ROOT = REPO

# the command run with one function replaced: MODULE.NAME raises KeyboardInterrupt when called
_RUNNER = """
import importlib, sys
def ctrl_c(*args, **kwargs):
    raise KeyboardInterrupt
owner = importlib.import_module(sys.argv[1])
*classes, name = sys.argv[2].split(".")
for cls in classes:
    owner = getattr(owner, cls)
setattr(owner, name, ctrl_c)
from bras_kit.cli import main
sys.exit(main(sys.argv[3:]))
"""


def _interrupted_at(module: str, name: str, argv: list[str], cwd: Path) -> subprocess.CompletedProcess:
    env = {k: v for k, v in os.environ.items() if k not in ("DISPLAY", "WAYLAND_DISPLAY", "BRAS_KIT_LANG")}
    return subprocess.run([sys.executable, "-c", _RUNNER, module, name, *argv], cwd=cwd, env=env,
                          capture_output=True, text=True, timeout=300)


def _port_is_free(port: int) -> bool:
    with socket.socket() as probe:
        try:
            probe.bind(("127.0.0.1", port))
        except OSError:
            return False
    return True


def test_view_stopped_right_after_its_address_exits_0(tmp_path: Path) -> None:
    port = _free_port()
    # has_screen is asked right after the address is printed, before the wait
    done = _interrupted_at("bras_kit.cli._common", "has_screen", ["view", "--port", str(port)], tmp_path)
    assert f"http://127.0.0.1:{port}" in done.stdout, done.stderr
    assert done.returncode == 0, done.stderr
    assert "interrupted" not in done.stderr and "Traceback" not in done.stderr
    assert _port_is_free(port)


@pytest.mark.parametrize(("module", "name"), [
    ("bras_kit.launcher.session", "node_results"),  # the checks that run after the address
    ("bras_kit.run.live", "LiveNodes.start"),  # the package's nodes starting live
])
def test_launch_stopped_right_after_its_address_exits_0(tmp_path: Path, module: str, name: str) -> None:
    from bras_kit.scaffold.package import scaffold_package

    scaffold_package(tmp_path / "bras_description")
    port = _free_port()
    done = _interrupted_at(module, name, ["launch", "bras_description", "--port", str(port), "--duration", "2"],
                           tmp_path)
    assert f"http://127.0.0.1:{port}" in done.stdout, done.stderr
    assert done.returncode == 0, done.stderr
    assert "interrupted" not in done.stderr and "Traceback" not in done.stderr
    assert _port_is_free(port)


def test_ctrl_c_before_the_address_still_says_interrupted(tmp_path: Path) -> None:
    """Before the address there is nothing to stop: the command was interrupted (exit 130)."""
    done = _interrupted_at("bras_kit.cli._common", "check_usable", ["view", "--port", str(_free_port())], tmp_path)
    assert done.returncode == 130, done.stderr
    assert "interrupted" in done.stderr and "http://" not in done.stdout


def _children_of(pid: int) -> list[int]:
    found = []
    for entry in Path("/proc").iterdir():
        if entry.name.isdigit():
            try:
                fields = (entry / "stat").read_text().rsplit(")", 1)[1].split()
            except OSError:
                continue
            if int(fields[1]) == pid:
                found.append(int(entry.name))
    return found


def test_sigterm_ends_a_run_with_its_node_and_its_folder(tmp_path: Path) -> None:
    """SIGTERM (``kill``, an editor's stop button) to a ``bras-kit run`` whose node is busy: the
    command leaves at once with 128 + 15, its child (the node) is gone and so is its temporary
    folder (bras-kit-run-* in TMPDIR), as after Ctrl-C."""
    import signal
    import time

    node = ROOT / "tests" / "data" / "run" / "nodes" / "busy_loop.py"
    env = {k: v for k, v in os.environ.items() if k not in ("DISPLAY", "WAYLAND_DISPLAY")}
    env["TMPDIR"] = str(tmp_path)
    process = subprocess.Popen([sys.executable, "-m", "bras_kit", "run", str(node), "--duration", "5"],
                               cwd=tmp_path, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        deadline = time.monotonic() + 60
        # the node runs: its folder is made and a child is forked (a containment probe may come first)
        while time.monotonic() < deadline and not (list(tmp_path.glob("bras-kit-run-*")) and _children_of(process.pid)):
            time.sleep(0.05)
        time.sleep(0.5)  # the node's own child, forked once its folder is laid out
        children = _children_of(process.pid)
        assert children and list(tmp_path.glob("bras-kit-run-*")), "the node never started"
        process.send_signal(signal.SIGTERM)
        _, err = process.communicate(timeout=30)
    finally:
        process.kill()
    assert process.returncode == 128 + signal.SIGTERM, err
    assert "Traceback" not in err
    assert not [pid for pid in children if Path(f"/proc/{pid}").exists()]
    assert list(tmp_path.glob("bras-kit-run-*")) == []
