"""BK659: the node reached beyond its folder, and the containment stopped it (docs/security.md).

A contained run (:mod:`bras_kit.trust.contain`) records what the node tried that its walls
forbid (:mod:`bras_kit.ros.attempts`): each attempt is one hit, at the learner's line.
"""

from __future__ import annotations

from collections.abc import Iterator

from ...findings.registry import ERROR, Hit, describe, hit
from .run_rules import RunContext, run_rule


@run_rule("BK659", "node-reached-beyond-its-folder", ERROR)
def node_reached_beyond(run: RunContext) -> Iterator[Hit]:
    for attempt in run.recording.blocked:
        yield hit("file", None, attempt.line or None, attempt.kind, file=attempt.path or run.recording.source,
                  detail=attempt.detail or "-")


describe(
    "BK659",
    title="the node reached beyond its folder and was stopped",
    message={
        "write": "the node tried to write {detail}, outside the folder it runs in: refused",
        "read": "the node tried to read {detail}, outside its package and the Python installation: refused",
        "network": "the node tried to use the network ({detail}): it has none",
        "signal": "the node tried to signal other processes ({detail}): it can reach none",
        "ctypes": "the node loaded a C library through ctypes ({detail}): its calls stay inside the walls",
        "symlink": "the node made a symbolic link out of its folder ({detail}): it leads nowhere",
        "process": "the node left a process running after the end of the run: it was stopped",
        "": "the node tried {detail}, which its walls forbid",
    },
    hint="a node publishes, subscribes and logs: it writes files only in the folder it runs in, and talks to "
         "other nodes through topics",
    explanation="""\
bras-kit runs a node it did not write inside walls (user, mount, network and PID namespaces:
see docs/security.md): the node may read its package, the Python installation and the system
libraries, write only in the temporary folder it runs in, has no network (not even 127.0.0.1),
sees no other process, and every process it forks ends with the run. `ros2 run` has no such
walls, so a node that writes in the home folder, opens a socket or forks a process that
outlives it would do so there; in a class's hand-ins it is at best a bug, at worst an attack.
Each attempt is reported at the line that made it; the kernel refused it.""",
)
