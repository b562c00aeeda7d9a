"""BK639: setup.py or a launch file reached beyond its folder, and the containment stopped it.

Building the package runs its ``setup.py`` and launching it runs its launch files, each in the
contained child (docs/security.md), watched as a node is watched (:mod:`bras_kit.ros.attempts`,
BK659 for nodes): each attempt is one hit at the learner's file and line. A launch file runs
from the install tree; its attempts are shown at the package file it was installed from.
"""

from __future__ import annotations

import os
from collections.abc import Iterable, Iterator

from ...findings.registry import ERROR, Hit, describe
from ...ros.attempts import Attempt
from ...ros.package import Package
from .evaluated import launched
from .launch_rules import _each
from .rules import _at, package_rule


def setup_blocked_hits(blocked: Iterable[Attempt]) -> Iterator[Hit]:
    """BK639's hits for what one build's setup.py tried (``BuildRecord.blocked``: ``bras-kit build``
    and ``bras-kit run`` show them too)."""
    for attempt in blocked:
        yield _at(attempt.path or "setup.py", attempt.line or None, attempt.kind, detail=attempt.detail or "-")


@package_rule("BK639", "setup-or-launch-reached-beyond-its-folder", ERROR)
def setup_or_launch_reached_beyond(pkg: Package) -> Iterator[Hit]:
    top = launched(pkg)
    if top is None:
        return
    yield from setup_blocked_hits(top.build.blocked)
    found = []
    for result in _each(top):
        for attempt in result.plan.blocked if result.plan is not None else []:
            source = result.build.source_of(os.path.join(result.build.prefix, attempt.path)) if attempt.path else None
            found.append((source or result.launch_file, attempt))
    seen: set[tuple[str, int, str, str]] = set()
    for file, attempt in found:
        key = (file, attempt.line, attempt.kind, attempt.detail)
        if key in seen:
            continue  # a file included by another one is evaluated with it, and again on its own
        seen.add(key)
        yield _at(file, attempt.line or None, attempt.kind, detail=attempt.detail or "-")


describe(
    "BK639",
    title="setup.py or a launch file reached beyond its folder and was stopped",
    message={
        "write": "this file tried to write {detail}, outside the folder it runs in: refused",
        "read": "this file tried to read {detail}, outside its package and the Python installation: refused",
        "network": "this file tried to use the network ({detail}): it has none",
        "signal": "this file tried to signal other processes ({detail}): it can reach none",
        "ctypes": "this file loaded a C library through ctypes ({detail}): its calls stay inside the walls",
        "symlink": "this file made a symbolic link out of its folder ({detail}): it leads nowhere",
        "process": "this file left a process running after it ended: it was stopped",
        "": "this file tried {detail}, which its walls forbid",
    },
    hint="setup.py only describes the package to setup(), and a launch file only returns a LaunchDescription: "
         "neither writes files, opens connections or starts processes of its own",
    explanation="""\
`colcon build` runs the package's `setup.py`, and `ros2 launch` runs its launch file, with your
rights. bras-kit runs both inside walls (user, mount, network and PID namespaces: see
docs/security.md): they may read the package, the Python installation and the system libraries,
write only in a temporary folder, have no network and see no other process. `setup.py` should do
nothing but call `setup(...)`, and a launch file nothing but return its `LaunchDescription`; in a
class's hand-ins, anything else is at best a bug, at worst an attack. Each attempt is reported
at the line that made it; the kernel refused it, and the build or the launch went on without it.""",
)
