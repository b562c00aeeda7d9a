"""BK657-BK658: the record of the run, as bras-kit's process read it from the node's (docs/security.md).

The stand-in for rclpy runs in the node's own process, so what that process sends back is a claim
(:mod:`bras_kit.ros.record_wire`): bounded (BK657 counts what was past the bounds) and checked
piece by piece (BK658 counts what is not what the stand-in makes: it was left out).
"""

from __future__ import annotations

from collections.abc import Iterator

from ...findings.registry import ERROR, WARNING, Hit, describe, hit
from ...ros.record_wire import MAX_LINE_BYTES, MAX_MESSAGE_BYTES
from .run_rules import RunContext, run_rule

_KINDS = ("messages", "too_big", "logs")


@run_rule("BK657", "record-past-its-bounds", WARNING)
def record_past_its_bounds(run: RunContext) -> Iterator[Hit]:
    overflow = run.recording.overflow
    for kind in _KINDS:
        if overflow.get(kind):
            yield hit("file", None, None, kind, file=run.recording.source, count=overflow[kind],
                      mib=(MAX_LINE_BYTES if kind == "too_big" else MAX_MESSAGE_BYTES) >> 20)
    rest = sum(count for kind, count in overflow.items() if kind not in _KINDS)
    if rest:
        yield hit("file", None, None, "", file=run.recording.source, count=rest,
                  kinds=", ".join(kind for kind in overflow if kind not in _KINDS))


@run_rule("BK658", "record-not-from-the-stand-in", ERROR)
def record_not_from_the_standin(run: RunContext) -> Iterator[Hit]:
    r = run.recording
    if r.refused_count:
        first = r.refused[0] if r.refused else None
        yield hit("file", None, None, "", file=r.source, count=r.refused_count,
                  what=first.what if first else "-", detail=first.detail if first else "-")


describe(
    "BK657",
    title="the run's record was past its bounds",
    message={
        "messages": "messages that did not fit in the record of the run ({mib} MiB of messages): {count}, "
                    "counted, not kept",
        "too_big": "messages each larger than the record holds for one message ({mib} MiB): {count}, counted, "
                   "not kept",
        "logs": "log lines that did not fit in the record of the run: {count}, counted, not kept",
        "": "pieces of the record of the run past its bounds ({kinds}): {count}, cut or left out",
    },
    hint="a node of the tutorial publishes a few joints 20 times a second; findings about the messages read "
         "only those kept",
    explanation="""\
bras-kit keeps a bounded record of what a node publishes and logs: at most 32 MiB of messages,
1 MiB for one message, 10,000 log lines. What lies past the bounds is counted, never held, so a
node publishing a 2,000-joint message 200,000 times cannot make bras-kit's own process swell
(docs/security.md). The rules that read the messages see the first ones, kept whole.""",
)
describe(
    "BK658",
    title="the run's record is not what bras-kit's stand-in makes",
    message="pieces of the record the node's process sent that are not what bras-kit's stand-in for rclpy "
            "makes: {count}, left out (the first: {what} '{detail}')",
    hint="a node publishes and logs through rclpy: it does not rename itself behind rclpy's back, nor change "
         "rclpy's own lists or functions",
    explanation="""\
The stand-in for rclpy runs in the node's own process, so the node can reach everything the
stand-in keeps: it could rename itself after rclpy checked its name, add publishers or messages
to the stand-in's lists, or replace its functions. bras-kit's own process therefore reads the
record as a claim: every field's type and size is checked, node names, topics and message
types are checked again against ROS 2's rules, and what does not pass is left out and counted
here (docs/security.md). In a class's hand-ins it is at best a very unusual node, at worst an
attempt to plant text in the teacher's terminal or report.""",
)
