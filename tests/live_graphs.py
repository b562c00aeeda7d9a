"""Helpers shared by the tests (moved from test_live_doctor.py, which still uses them)."""

from __future__ import annotations

import json
import os
import shlex
import signal
import subprocess
import sys
from pathlib import Path

from realros import graph_env, new_domain, oracle_python, shell_in_loopback_namespace

DATA = Path(__file__).parent / "data" / "live"


URDF = str(DATA / "bras.urdf")


WATCH = "3"  # seconds each doctor watches (the least a look can take: discovery takes up to 2.5 s)


def _script(nodes: list[list[str]], doctors: list[list[str]], ros_python: str, doctor_env: str = "") -> str:
    """One shell script for one namespace: start the nodes, poll until each says it is ready, run
    the first doctor on the live graph (saving what it saw), stop the nodes, then word the same
    look again with each other doctor (``--from``: the French report of the very same graph)."""
    lines = ["set -u", "T=$(mktemp -d)", "pids=''"]
    for i, node in enumerate(nodes):
        env = [part for part in node if "=" in part and part.split("=")[0].isupper()]  # ROS_DOMAIN_ID=7 first
        argv = node[len(env):]
        lines.append(f"{shlex.join(env)} {shlex.quote(ros_python)} {shlex.join(argv)} > $T/node{i} 2>&1 "
                     "& pids=\"$pids $!\"")
    ready = " && ".join(f"grep -q ready $T/node{i}" for i in range(len(nodes))) or "true"
    lines.append(f"n=0; until {ready}; do n=$((n+1)); [ $n -gt 1200 ] && break; sleep 0.05; done")
    doctor = f"{shlex.quote(sys.executable)} -m bras_kit doctor --ros"
    lines.append(f"{doctor_env} {doctor} --duration {WATCH} {shlex.join(doctors[0])} --save $T/look.json "
                 "> $T/out0 2> $T/err0; "
                 "echo $? > $T/code0")
    lines.append("kill $pids 2>/dev/null; for p in $pids; do timeout 5 tail --pid=$p -f /dev/null; done; "
                 "kill -9 $pids 2>/dev/null; wait")
    for j, other in enumerate(doctors[1:], start=1):
        lines.append(f"{doctor} --from $T/look.json {shlex.join(other)} > $T/out{j} 2> $T/err{j}; echo $? > $T/code{j}")
    for j in range(len(doctors)):
        lines.append(f"echo '=== {j}'; cat $T/code{j} $T/out{j} $T/err{j}")
    lines.append("echo '+++ look'; cat $T/look.json 2>/dev/null; echo")  # what the first doctor saw
    for i in range(len(nodes)):
        lines.append(f"echo '--- node{i}'; tail -5 $T/node{i}")
    lines.append("rm -rf $T")
    return "\n".join(lines)


def _run(nodes: list[list[str]], doctors: list[list[str]], doctor_env: str = "") -> tuple[list[tuple[int, str]], str]:
    out, logs, _look = run_with_look(nodes, doctors, doctor_env)
    return out, logs


def run_with_look(nodes: list[list[str]], doctors: list[list[str]], doctor_env: str = ""
                  ) -> tuple[list[tuple[int, str]], str, dict | None]:
    """As :func:`_run`, with the look the first doctor saved (None when it saved none)."""
    python = oracle_python()
    with subprocess.Popen(shell_in_loopback_namespace(_script(nodes, doctors, python, doctor_env)), cwd=DATA,
                          env=graph_env(new_domain(), BRAS_KIT_ROS_PYTHON=python), stdout=subprocess.PIPE,
                          stderr=subprocess.PIPE, text=True, start_new_session=True) as shell:
        try:
            stdout, stderr = shell.communicate(timeout=180)
        except subprocess.TimeoutExpired:
            os.killpg(shell.pid, signal.SIGKILL)  # the nodes too: they are in the shell's session
            raise
    assert shell.returncode == 0, stderr + stdout
    stdout, _, look = stdout.partition("+++ look\n")
    look, _, nodes_part = look.partition("--- node")
    stdout += ("--- node" + nodes_part) if nodes_part else ""
    out = []
    for part in stdout.split("=== ")[1:]:
        body = part.split("--- node")[0].split("\n", 1)[1]
        code, _, text = body.partition("\n")
        out.append((int(code), text))
    assert len(out) == len(doctors), stdout
    logs = "--- node" + stdout.split("--- node", 1)[1] if "--- node" in stdout else ""
    try:
        saved = json.loads(look) if look.strip() else None
    except json.JSONDecodeError:
        saved = None
    return out, logs, saved


def _json(output: str) -> dict:
    return json.loads(output[: output.rindex("}") + 1])


def _codes(document: dict, severity: str | None = None) -> list[str]:
    return sorted(f["code"] for f in document["findings"] if severity is None or f["severity"] == severity)


def _finding(document: dict, code: str) -> dict:
    return next(f for f in document["findings"] if f["code"] == code)


STATE_PUBLISHER = ["state_publisher.py", URDF]


ANIMATION = ["animation.py"]
