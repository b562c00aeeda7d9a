"""The rviz2 processes of this machine that are on this terminal's graph, and the configuration each
loaded: where RViz takes its Fixed Frame from (github.com/ros2/rviz, jazzy, commit 591594e).

rviz2 reads its options with Qt's command-line parser (rviz_common/src/rviz_common/visualizer_app.cpp):
``-d``/``--display-config FILE`` (lines 95-99), ``-f``/``--fixed-frame FRAME`` (lines 101-103, set after
the file is loaded, lines 165-169). Without ``-d`` it loads ``~/.rviz2/default.rviz`` of the user
running it (visualization_frame.cpp:345-349, 382). A relative ``-d`` is relative to its working folder.

A process is on this graph when it shares this process's network namespace and its ROS_DOMAIN_ID
(two rviz2 of one user on two domains are two graphs). Read from ``/proc``; elsewhere, none found.
"""

from __future__ import annotations

import os
from collections.abc import Iterator, Mapping
from typing import Any

RVIZ_FILE_LIMIT = 1 << 20  # a .rviz past 1 MiB (or a device, a FIFO) is not read, as the launch's reader does
PROGRAM = "rviz2"


def _read(path: str, limit: int = 1 << 16) -> bytes | None:
    try:
        with open(path, "rb") as file:
            return file.read(limit)
    except OSError:
        return None


def _namespace(pid: str) -> str | None:
    try:
        return os.readlink(f"/proc/{pid}/ns/net")
    except OSError:
        return None


def _is_rviz(argv: list[str]) -> int | None:
    """The index of rviz2's own name in ``argv`` (0 for the program, 1 when an interpreter runs a
    script named rviz2), None when this is no rviz2."""
    for index in (0, 1):
        if index < len(argv) and os.path.basename(argv[index]) == PROGRAM:
            return index
    return None


def options(arguments: list[str]) -> tuple[str | None, str]:
    """(the -d file, the -f frame) as Qt's parser reads them: ``-d F``, ``-dF``, ``--display-config F``,
    ``--display-config=F``; ``--ros-args`` ends rviz2's own options (rcl takes the rest)."""
    config, frame = None, ""
    k = 0
    while k < len(arguments):
        item = arguments[k]
        if item == "--ros-args":
            break
        for short, long in (("-d", "--display-config"), ("-f", "--fixed-frame")):
            value = None
            if item in (short, long) and k + 1 < len(arguments):
                value = arguments[k + 1]
                k += 1
            elif item.startswith(long + "="):
                value = item[len(long) + 1:]
            elif item.startswith(short) and len(item) > 2 and not item.startswith("--"):
                value = item[2:]
            if value is not None:
                if short == "-d":
                    config = value
                else:
                    frame = value
        k += 1
    return config, frame


def _environ(pid: str) -> dict[str, str]:
    raw = _read(f"/proc/{pid}/environ", 1 << 20) or b""
    env = {}
    for entry in raw.split(b"\0"):
        key, sep, value = entry.partition(b"=")
        if sep:
            env[key.decode("utf-8", "replace")] = value.decode("utf-8", "replace")
    return env


def running_rviz(environ: Mapping[str, str] | None = None, proc: str = "/proc") -> Iterator[dict[str, Any]]:
    """Each rviz2 of this graph, as the look records it (the file's text is read now: a look saved
    with --save is judged again with the Fixed Frame it had)."""
    env = os.environ if environ is None else environ
    domain = (env.get("ROS_DOMAIN_ID") or "0").strip() or "0"
    ours = _namespace("self")
    try:
        pids = sorted((p for p in os.listdir(proc) if p.isdigit()), key=int)
    except OSError:
        return
    for pid in pids:
        raw = _read(f"{proc}/{pid}/cmdline")
        if not raw:
            continue
        argv = [a.decode("utf-8", "replace") for a in raw.rstrip(b"\0").split(b"\0")]
        at = _is_rviz(argv)
        if at is None or (ours is not None and _namespace(pid) not in (ours, None)):
            continue
        theirs = _environ(pid)
        if ((theirs.get("ROS_DOMAIN_ID") or "0").strip() or "0") != domain:
            continue
        config, frame = options(argv[at + 1:])
        try:
            cwd = os.readlink(f"{proc}/{pid}/cwd")
        except OSError:
            cwd = ""
        if config is not None:
            path = os.path.join(cwd, os.path.expanduser(config)) if cwd else config
        else:
            home = theirs.get("HOME") or ""
            path = os.path.join(home, ".rviz2", "default.rviz") if home else ""
        yield {"pid": int(pid), "argv": argv[:64], "config": path, "given": config is not None,
               "text": _config_text(path), "fixed_frame": frame}


def _config_text(path: str) -> str | None:
    """The .rviz's text through the one reader of learner files (never a device or a FIFO)."""
    if not path:
        return None
    from ..trust.learner_files import read_text

    try:
        return read_text(path, (os.path.dirname(os.path.abspath(path)),), limit=RVIZ_FILE_LIMIT, errors="replace")
    except (OSError, ValueError):
        return None


MAX_LAUNCH_FILES = 8


def launched_rviz(start: str = ".") -> dict[str, Any] | None:
    """When no rviz2 runs here: the rviz2 the workspace's launch files would start (the first
    installed launch file, by name, whose plan starts one), recorded as :func:`running_rviz`
    records a process (pid 0, ``launch`` the launch file). Evaluated as ``ros2 launch`` would,
    contained (:func:`bras_kit.ros.launching.plan_launch`); None outside a built workspace."""
    import glob

    from ..ros.launching import plan_launch
    from ..ros.workspace import workspace_root

    root = workspace_root(start)
    if root is None:
        return None
    install = os.path.join(root, "install")
    prefixes = sorted(p for p in glob.glob(os.path.join(install, "*")) if os.path.isdir(os.path.join(p, "share")))
    launch_files = sorted(glob.glob(os.path.join(install, "*", "share", "*", "launch", "*.launch.py")))
    for launch_file in launch_files[:MAX_LAUNCH_FILES]:
        plan = plan_launch(launch_file, prefixes, learner_roots=(root,))
        node = next((n for n in plan.nodes if n.package == PROGRAM), None)
        if node is None:
            continue
        config, frame = options([a for a in node.arguments if isinstance(a, str)])
        if config is not None:
            path = config
        else:  # rviz2 started by this user would load their saved default
            path = os.path.join(os.path.expanduser("~"), ".rviz2", "default.rviz")
        return {"pid": 0, "argv": [PROGRAM, *[a for a in node.arguments if isinstance(a, str)][:60]],
                "config": path, "given": config is not None, "text": _config_text(path), "fixed_frame": frame,
                "launch": launch_file}
    return None
