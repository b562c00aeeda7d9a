"""What ``bras-kit run`` says about a run, as messages (worded where shown)."""

from __future__ import annotations

from ..core.message import M, Message, Mn
from ..ros.recording import Recording
from ..trust.inert import for_terminal


def ending(recording: Recording) -> Message:
    """How the node's run ended (one message id per ending, for the catalog)."""
    time, ended = recording.end, recording.ended
    if ended == "duration":
        return M("stopped at the end of the run (t={time} s), as Ctrl-C stops ros2 run", time=time)
    if ended == "stopped":
        return M("kept running after the end of the run was signalled (it catches KeyboardInterrupt) "
                 "and was stopped at t={time} s", time=time)
    if ended == "storm":
        return M("published thousands of messages while no time passed (a loop without sleep?) "
                 "and was stopped at t={time} s", time=time)
    if ended == "error":
        return M("raised an exception at t={time} s", time=time)
    if ended == "not_simulated":
        return M("used something bras-kit does not simulate, at t={time} s", time=time)
    return M("returned from main() at t={time} s", time=time)


def summary(recording: Recording) -> list[Message]:
    """A few lines: what ran, how long, what each node made, what each topic carried, the end."""
    r = recording
    lines = [M("{target} ({source}, {function}()): {time} s of simulated time in {wall} s",
               target=for_terminal(r.target), source=for_terminal(r.source), function=for_terminal(r.function),
               time=r.end, wall=round(r.wall_seconds, 3))]
    for node in dict.fromkeys(r.nodes):
        publishes = [for_terminal(f"{p.topic} ({p.type.rsplit('/', 1)[-1]})") for p in r.publishers if p.node == node]
        periods = [t.period for t in r.timers if t.node == node]
        topics = publishes or M("no topic")
        if periods:
            lines.append(M("node '{node}': publishes on {topics}; timers every {periods} s", node=node,
                           topics=topics, periods=periods))
        else:
            lines.append(M("node '{node}': publishes on {topics}; no timer", node=node, topics=topics))
    counts = r.topics()
    for topic, count in counts.items():
        times = [m.time for m in r.messages if m.topic == topic]
        rate = (len(times) - 1) / (times[-1] - times[0]) if len(times) > 1 and times[-1] > times[0] else None
        if rate is None:
            lines.append(Mn("{topic}: {n} message", "{topic}: {n} messages", count, topic=topic))
        else:
            lines.append(Mn("{topic}: {n} message at {rate} Hz", "{topic}: {n} messages at {rate} Hz", count,
                            topic=topic, rate=round(rate, 2)))
    if not counts:
        lines.append(M("nothing was published"))
    if r.dropped:
        lines.append(M("{n} more messages were published and counted, not kept", n=r.dropped))
    if r.output_dropped:
        lines.append(not_shown(r))
    lines.append(M("the node {ending}", ending=ending(r)))
    return lines


def failure_lines(recording: Recording) -> list[str]:
    """The learner's traceback: their files and lines only, then the exception; every piece is
    the learner's text, so its control characters are shown, not obeyed by the terminal."""
    failure = recording.failure
    if failure is None:
        return []
    out = []
    for frame in failure.frames:
        out.append(f'  File "{frame.path}", line {frame.line}, in {frame.function}' if frame.function
                   else f'  File "{frame.path}", line {frame.line}')
        if frame.text:
            out.append(f"    {frame.text}")
    out.append(f"{failure.kind}: {failure.detail}" if failure.detail else failure.kind)
    return [for_terminal(line) for line in out]


def not_shown(recording: Recording) -> Message:
    """What the node printed beyond the first and last 64 KiB kept (bras_kit.ros.capture)."""
    return Mn("the node printed more than was kept: {size} ({n} line) between its first and last 64 KiB "
              "not shown", "the node printed more than was kept: {size} ({n} lines) between its first and last "
              "64 KiB not shown", recording.output_dropped_lines, size=size_text(recording.output_dropped))


def size_text(count: int) -> Message:
    """A count of characters as people read sizes: 1.9 GB, 640.0 kB, 12 B (decimal units, as ls -h --si)."""
    if count >= 10**9:
        return M("{n} GB", n=round(count / 10**9, 1))
    if count >= 10**6:
        return M("{n} MB", n=round(count / 10**6, 1))
    if count >= 10**3:
        return M("{n} kB", n=round(count / 10**3, 1))
    return M("{n} B", n=count)
