"""Run the probe (``_probe.py``) with an interpreter that imports the real rclpy, and read it.

Which interpreter, first found wins:

1. ``BRAS_KIT_ROS_PYTHON``, when set;
2. this one, when it can import rclpy (ROS sourced: ``source /opt/ros/jazzy/setup.bash`` puts the
   system's rclpy on ``PYTHONPATH``; or the ``ros`` extra installed beside bras-kit);
3. a venv of bras-kit's own in the cache folder, ``ros-jazzy-pyX.Y`` (the error below gives the
   two commands that make it).

Else :class:`RosUnavailable` (exit code :data:`NO_ROS_EXIT`: "could not look", neither "healthy"
nor "problems found"). The probe is a subprocess: the wheels' ``.pth`` re-executes every Python
process of their venv once, and rclpy's import costs a second; bras-kit's other commands never
pay either.
"""

from __future__ import annotations

import concurrent.futures
import importlib.util
import json
import os
import subprocess
import sys
from collections.abc import Iterator, Mapping
from typing import IO, Any

from ..core.errors import BrasKitError
from ..core.message import M
from ..ros.bus import domain_id
from ..ros.graph import Elsewhere, Snapshot, snapshot_from_json

NO_ROS_EXIT = 3  # could not look: no rclpy to join the graph with
PROBE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "_probe.py")
START_SLACK = 30.0  # seconds allowed for the probe's own start (rclpy's import, the re-exec) and its end
RANGES = ("LOCALHOST", "SUBNET")
# what bras-kit reads of the probe: its bounds (_probe.py's MAX_*) keep a snapshot near 100 MiB
# at the very most (16 descriptions of 4 MB, 16 MiB of joint states, 20,000 transforms, as JSON)
MAX_PROBE_OUTPUT = 160 << 20
MAX_PROBE_LINE = 32 << 20  # one stream record: a description of 4 MB, escaped as JSON
# RTPS's default ports (DDSI-RTPS 2.5, 9.6.1 "Default Port Numbers"): PB 7400 + DG 250 x domain; every participant
# of a domain binds ports in its block, so the blocks in use name the domains of this computer
PORT_BASE, DOMAIN_GAIN, MAX_DOMAIN = 7400, 250, 232
# How long a look waits for a first node on a domain some process here already takes part in (its
# ports are bound): Fast DDS repeats a discovery exchange it missed about 2.3 s later, and on a busy
# computer it misses some (first node after 0-0.1 s or 2.2-2.5 s, measured in a loopback namespace
# beside 8 busy processes on 2 cores; CI once saw none in 3.5 s). Ten seconds outlast three misses;
# a look stops waiting as soon as a node shows, and an empty domain keeps the probe's 3.5 s.
OCCUPIED_WAIT = 10.0


class RosUnavailable(BrasKitError):
    """No interpreter here imports rclpy: bras-kit could not look at the graph."""

    exit_code = NO_ROS_EXIT


class ProbeFailed(BrasKitError):
    """The probe started but did not report (rclpy failed to start, the RMW is missing...)."""

    exit_code = NO_ROS_EXIT


def cached_venv_python() -> str:
    from ..core.cachedir import cache_home

    minor = f"{sys.version_info[0]}.{sys.version_info[1]}"
    return os.path.join(cache_home(), f"ros-jazzy-py{minor}", "bin", "python")


# the real rclpy of Jazzy on PyPI, pinned as the `ros` extra pins it (ros-rclpy also holds Kilted's 9.1.2)
WHEELS = "'ros-jazzy-rclpy[fastrtps]==7.1.6' ros-jazzy-sensor-msgs==5.3.6 ros-jazzy-std-msgs==5.3.6"


def ros_python(environ: Mapping[str, str] | None = None) -> str:
    """The interpreter that runs the probe (see the module's text), or :class:`RosUnavailable`."""
    env = os.environ if environ is None else environ
    given = env.get("BRAS_KIT_ROS_PYTHON", "").strip()
    if given:
        if not os.access(given, os.X_OK):
            raise RosUnavailable(M("BRAS_KIT_ROS_PYTHON names {path}, which is not a program that can run",
                                   path=given),
                                 hint=M("point it at a Python that imports rclpy, or unset it"))
        return given
    if importlib.util.find_spec("rclpy") is not None:
        return sys.executable
    cached = cached_venv_python()
    if os.access(cached, os.X_OK):
        return cached
    venv = os.path.dirname(os.path.dirname(cached))
    raise RosUnavailable(
        M("no rclpy here: bras-kit cannot join the ROS 2 graph"),
        hint=M("source ROS 2 first (source /opt/ros/jazzy/setup.bash), or install the real rclpy's wheels once: "
               "python3 -m venv {venv} && {venv}/bin/pip install {wheels}", venv=venv, wheels=WHEELS))


def probe_env(domain: int | None = None, discovery_range: str | None = None) -> dict[str, str]:
    """This process's environment for the probe, with another domain or discovery range if asked."""
    env = dict(os.environ)
    env["PYTHONUNBUFFERED"] = "1"
    env.pop("PYTHONSTARTUP", None)
    if domain is not None:
        env["ROS_DOMAIN_ID"] = str(domain)
    if discovery_range is not None:
        env["ROS_AUTOMATIC_DISCOVERY_RANGE"] = discovery_range
        env.pop("ROS_LOCALHOST_ONLY", None)  # deprecated in Jazzy; it would override the range
    return env


def _run_probe(python: str, mode: str, seconds: float, env: Mapping[str, str], wait: float | None = None
               ) -> dict[str, Any]:
    import tempfile

    argv = [python, PROBE, mode, f"{seconds:g}"] + ([f"{wait:g}"] if wait is not None else [])
    # into files, not pipes held in memory: the probe's output is read only once its size is known
    with tempfile.TemporaryFile() as out, tempfile.TemporaryFile() as err:
        try:
            done = subprocess.run(argv, env=dict(env), stdout=out, stderr=err,
                                  timeout=max(seconds, wait or 0.0) + START_SLACK, stdin=subprocess.DEVNULL)
        except subprocess.TimeoutExpired as exc:
            raise ProbeFailed(M("the ROS 2 probe did not answer in {seconds:.0f} s", seconds=exc.timeout),
                              hint=M("run again; if it persists, try 'ros2 node list' in the same terminal")) from None
        except OSError as exc:
            raise RosUnavailable(M("{python} cannot run: {reason}", python=python, reason=exc.strerror or str(exc)),
                                 hint=M("point BRAS_KIT_ROS_PYTHON at a Python that imports rclpy")) from None
        if os.fstat(out.fileno()).st_size > MAX_PROBE_OUTPUT:
            raise ProbeFailed(M("the ROS 2 probe printed more than {most} MiB", most=MAX_PROBE_OUTPUT >> 20),
                              hint=M("a node of the graph sends more than bras-kit keeps; stop the other nodes "
                                     "and look again"))
        out.seek(0)
        stdout = out.read().decode("utf-8", "replace")
        err.seek(max(0, os.fstat(err.fileno()).st_size - 4096))  # its last words only
        stderr = err.read().decode("utf-8", "replace")
    lines = [line for line in stdout.splitlines() if line.startswith("{")]
    if done.returncode != 0 or not lines:
        last = (stderr.strip().splitlines() or ["(nothing)"])[-1][:500]
        raise ProbeFailed(M("{python} could not join the ROS 2 graph: {detail}", python=python, detail=last),
                          hint=M("check that this Python imports rclpy and sensor_msgs (python3 -c 'import rclpy, "
                                 "sensor_msgs'), with ROS 2 Jazzy sourced or the 'ros' extra installed"))
    try:
        data = json.loads(lines[-1])
    except json.JSONDecodeError:
        raise ProbeFailed(M("the ROS 2 probe printed something unreadable"),
                          hint=M("run again; if it persists, report it")) from None
    return data if isinstance(data, dict) else {}


def look(seconds: float, python: str | None = None) -> dict[str, Any]:
    """Watch this terminal's ROS 2 graph for ``seconds``: the probe's JSON object; when the graph
    is empty, with ``elsewhere``: the nodes found on other domains or with the other range."""
    python = python or ros_python()
    env = probe_env()
    # someone is on this domain already: the look gives discovery time to find them
    occupied = domain_id(env) in domains_in_use()
    data = _run_probe(python, "snapshot", seconds, env, OCCUPIED_WAIT if occupied else None)
    from .rviz_process import launched_rviz, running_rviz

    # where RViz's Fixed Frame comes from: the rviz2 running here, else the one the workspace's
    # launch file would start
    data["rviz"] = list(running_rviz(env))
    if not data["rviz"]:
        launched = launched_rviz()
        data["rviz"] = [launched] if launched is not None else []
    if not snapshot_from_json(data).nodes:
        data["elsewhere"] = [{"domain": e.domain, "range": e.discovery_range, "nodes": list(e.nodes)}
                             for e in look_elsewhere(python, snapshot_from_json(data))]
    return data


def domains_in_use(own: int | None = None) -> list[int]:
    """The ROS domains some process of this computer takes part in, read from the UDP ports bound
    (``/proc/net/udp``, ``udp6``): a domain's block of RTPS ports, as Fast DDS and Cyclone DDS
    bind them. Empty where /proc is not Linux's."""
    low_ephemeral = 32768
    try:
        with open("/proc/sys/net/ipv4/ip_local_port_range", encoding="ascii") as file:
            low_ephemeral = int(file.read().split()[0])
    except (OSError, ValueError, IndexError):
        pass
    domains: set[int] = set()
    for table in ("/proc/net/udp", "/proc/net/udp6"):
        try:
            with open(table, encoding="ascii") as file:
                rows = file.read().splitlines()[1:]
        except OSError:
            continue
        for row in rows:
            fields = row.split()
            if len(fields) < 2 or ":" not in fields[1]:
                continue
            try:
                port = int(fields[1].rsplit(":", 1)[1], 16)
            except ValueError:
                continue
            if PORT_BASE <= port < low_ephemeral:
                domain, offset = divmod(port - PORT_BASE, DOMAIN_GAIN)
                if domain <= MAX_DOMAIN and (offset < 2 or offset >= 10):  # multicast d0/d2, unicast d1/d3 + 2 x pid
                    domains.add(domain)
    return sorted(d for d in domains if d != own)


def _census(python: str, env: Mapping[str, str], seconds: float) -> dict[str, Any] | None:
    """The nodes of the domain and range ``env`` gives, waiting ``seconds`` at most for a first one."""
    try:
        return _run_probe(python, "census", seconds, env)
    except BrasKitError:
        return None


def look_elsewhere(python: str, snapshot: Snapshot, seconds: float = 3.0) -> Iterator[Elsewhere]:
    """Nodes this terminal cannot see: on the other domains in use here, or with the other
    discovery range on this domain (one short probe each, in parallel)."""
    ours = snapshot.discovery_range.upper() or "SUBNET"
    other_range = "SUBNET" if ours == "LOCALHOST" else "LOCALHOST"
    # a domain whose ports are bound has someone on it: as long a wait as for the terminal's own
    tries: list[tuple[int, str, float]] = [(d, ours, OCCUPIED_WAIT) for d in domains_in_use(snapshot.domain)][:8]
    tries.append((snapshot.domain, other_range, seconds))
    with concurrent.futures.ThreadPoolExecutor(max_workers=len(tries)) as pool:
        futures = [pool.submit(_census, python, probe_env(domain, rng), wait) for domain, rng, wait in tries]
        for (domain, rng, _), future in zip(tries, futures):
            found = future.result()
            nodes = found.get("nodes") if found else None
            if isinstance(nodes, list) and nodes:
                yield Elsewhere(domain, rng, tuple(str(n)[:300] for n in nodes[:50]))


def open_stream(python: str, every: float = 2.0) -> subprocess.Popen[str]:
    """The probe in stream mode (``view --ros``): JSON lines on its stdout until its stdin closes."""
    return subprocess.Popen([python, PROBE, "stream", f"{every:g}"], env=probe_env(), stdin=subprocess.PIPE,
                            stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True, bufsize=1)


def read_records(stream: IO[str]) -> Iterator[dict[str, Any]]:
    """The probe's JSON lines as dicts (a line that does not parse, or longer than
    MAX_PROBE_LINE, is skipped: read in pieces, never held whole)."""
    while True:
        line = stream.readline(MAX_PROBE_LINE)
        if not line:
            return
        if not line.endswith("\n") and len(line) >= MAX_PROBE_LINE:
            while line and not line.endswith("\n"):  # the rest of the over-long line, dropped as it comes
                line = stream.readline(MAX_PROBE_LINE)
            continue
        if not line.startswith("{"):
            continue
        try:
            record = json.loads(line)
        except json.JSONDecodeError:
            continue
        if isinstance(record, dict):
            yield record
