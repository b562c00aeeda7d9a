"""The node read without running it (BK624-BK626): whether it really sends its messages, on
the right topic, in radians.

Registered on import (:mod:`bras_kit.validate.package`); every hit carries ``file``.
"""

from __future__ import annotations

from collections.abc import Iterator

from ...findings.registry import ERROR, Hit
from ...ros.package import (
    Package,
)
from .rules import (
    _at,
    _on_joint_states,
    _publisher_for,
    package_rule,
)

# ---------------------------------------------------------------- the node, read without running it




@package_rule("BK624", "joint-state-topic-wrong", ERROR)
def joint_state_topic_wrong(pkg: Package) -> Iterator[Hit]:
    """robot_state_publisher listens on /joint_states only: any other literal topic is heard by nobody
    — unless a launch file remaps it (or namespaces both) so that rcl resolves it to the topic
    robot_state_publisher listens on (evaluated launches only: names.py)."""
    heard_through_launch = _topics_heard_through_launch(pkg)
    for publisher in pkg.publishers:
        if publisher.module in heard_through_launch:
            continue
        if not _on_joint_states(publisher.topic):
            yield _at(publisher.path, publisher.topic_line, topic=publisher.topic,
                      fix="self.create_publisher(JointState, 'joint_states', 10)")


def _topics_heard_through_launch(pkg: Package) -> set[str]:
    """The modules whose JointState topic an evaluated launch makes robot_state_publisher hear."""
    from .evaluated import evaluations, joint_state_topics

    out = set()
    for result in evaluations(pkg) or []:
        listens, _ = joint_state_topics(result, lambda executable: None)
        for node in result.plan.nodes:
            publisher = _publisher_for(pkg, node.executable) if node.package == pkg.name else None
            if publisher is not None and isinstance(publisher.topic, str) and publisher.topic \
                    and node.resolve(publisher.topic) in listens:
                out.add(publisher.module)
    return out


@package_rule("BK625", "joint-state-never-sent", ERROR)
def joint_state_never_sent(pkg: Package) -> Iterator[Hit]:
    """A JointState publisher whose message is never published, or whose callback nothing runs."""
    for publisher in pkg.publishers:
        if not publisher.publishes:
            yield _at(publisher.path, publisher.line, "publish", fix="self.pub.publish(msg)")
        elif not publisher.scheduled:
            yield _at(publisher.path, publisher.line, "timer", fix="self.timer = self.create_timer(0.05, self.tick)")


@package_rule("BK626", "joint-state-in-degrees", ERROR)
def joint_state_in_degrees(pkg: Package) -> Iterator[Hit]:
    """JointState positions are radians (metres for prismatic joints); degrees turn the arm 57 times too far."""
    for publisher in pkg.publishers:
        for line, what in publisher.degrees:
            yield _at(publisher.path, line, what=what)
