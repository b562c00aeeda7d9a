"""The one place bras-kit meets the real rclpy: a read-only participant of the ROS 2 graph.

Run as a script by an interpreter that imports rclpy (a sourced ROS 2 Jazzy, or the ``ros``
extra's wheels); it imports nothing of bras-kit, so bras-kit's own venv never loads the wheels
(their ``.pth`` re-executes every Python process of their venv once). The domain, discovery range
and RMW come from the environment, as ``ros2`` takes them.

    python _probe.py snapshot SECONDS [WAIT]
                                        one JSON object on stdout: the graph watched for SECONDS,
                                        WAIT at most for its first node (default DISCOVERY_FLOOR)
    python _probe.py census SECONDS     the node names only, once they stop joining (other domains)
    python _probe.py stream SECONDS     JSON lines until stdin closes: the description and each
                                        JointState as they arrive, a graph every SECONDS

Nothing here judges: the findings are made by bras-kit from what this prints
(``bras_kit.live.rules``), worded by its registry. The QoS pairs are judged here because
``rclpy.qos.qos_check_compatible`` is rmw's own test (ros2doctor's ``qos_compatibility.py`` does
the same over every publisher/subscription pair).
"""

from __future__ import annotations

import json
import os
import sys
import threading
import time
from typing import Any, cast

# this folder is sys.path[0] when run as a script: keep its modules from shadowing rclpy's imports
if sys.path and os.path.abspath(sys.path[0] or ".") == os.path.dirname(os.path.abspath(__file__)):
    del sys.path[0]

import rclpy  # noqa: E402
from rclpy.executors import SingleThreadedExecutor  # noqa: E402
from rclpy.qos import (  # noqa: E402
    DurabilityPolicy,
    QoSCompatibility,
    QoSProfile,
    ReliabilityPolicy,
    qos_check_compatible,
)

NODE_NAME = f"_bras_kit_probe_{os.getpid()}"  # a leading '_' hides it from ros2 node list
DESCRIPTION = "/robot_description"
JOINT_STATES = "/joint_states"
MAX_JOINT_STATES = 4000  # a 1 kHz publisher watched for 3 s, and some
MAX_TEXT = 4_000_000  # a description bigger than this is cut (its length is still said)
MAX_TRANSFORMS = 20_000  # /tf of a 2-joint arm at 1 kHz for 4 s, and some
MAX_EVENTS = 500
# A publisher is a stranger: what the probe keeps of it is bounded, so its JSON (and bras-kit,
# which reads it) stays small whatever the graph sends. The cuts keep what the judging reads:
# the first names and positions, the order of their two lengths (robot_state_publisher's size
# check, robot_state_publisher.cpp:319), the first description and the latest ones.
MAX_NAMES = 1000  # names (and positions) kept of one JointState; a real arm has tens
MAX_NAME = 256  # characters kept of one name
MAX_JOINT_STATE_BYTES = 16 << 20  # the joint states kept, counted as their names' characters and 8 per number
MAX_DESCRIPTIONS = 16  # different texts kept: the first and the latest
WATCH_EVERY = 0.2  # seconds between two readings of who is on the graph (the timeline's grain)


def kept_sizes(names: int, positions: int) -> tuple[int, int]:
    """How many names and positions of one JointState are kept: at most MAX_NAMES each, and the
    two counts compare as the message's do (equal stays equal, fewer stays fewer), so the size
    check robot_state_publisher makes gives the same answer on what is kept."""
    kept_names, kept_positions = min(names, MAX_NAMES), min(positions, MAX_NAMES)
    if names != positions and kept_names == kept_positions:
        if names < positions:
            kept_names -= 1
        else:
            kept_positions -= 1
    return kept_names, kept_positions


def _policy(value: object) -> str:
    name = getattr(value, "name", str(value)).lower()
    return {"system_default": "system_default", "unknown": "unknown"}.get(name, name)


def _gid(raw: object) -> str:
    try:
        return bytes(raw).hex()  # type: ignore[call-overload]
    except (TypeError, ValueError):
        return ""


def _endpoint(info: object) -> dict[str, object]:
    qos = info.qos_profile  # type: ignore[attr-defined]
    namespace = info.node_namespace or "/"  # type: ignore[attr-defined]
    name = info.node_name  # type: ignore[attr-defined]
    return {
        "node": (namespace.rstrip("/") + "/" + name) if name else "",
        "reliability": _policy(qos.reliability),
        "durability": _policy(qos.durability),
        "depth": int(qos.depth),
        "gid": _gid(info.endpoint_gid),  # type: ignore[attr-defined]
    }


def _stamp(header: object) -> list[int]:
    stamp = header.stamp  # type: ignore[attr-defined]
    return [int(stamp.sec), int(stamp.nanosec)]


class Probe:
    """One hidden node that listens to the description and the joint states, and reads the graph."""

    def __init__(self, emit: object = None) -> None:
        from sensor_msgs.msg import JointState
        from std_msgs.msg import String

        rclpy.init(args=None, signal_handler_options=rclpy.signals.SignalHandlerOptions.NO)
        self.node = rclpy.create_node(NODE_NAME, start_parameter_services=False,
                                      enable_rosout=False)
        self.executor = SingleThreadedExecutor()
        self.executor.add_node(self.node)
        self.emit = emit
        self.lock = threading.Lock()
        self.descriptions: list[dict[str, object]] = []
        self.joint_states: list[dict[str, object]] = []
        self._sizes: list[int] = []  # of each joint state kept (MAX_JOINT_STATE_BYTES)
        self._joint_state_bytes = 0
        self.started = time.time()
        self._clients: dict[str, Any] = {}
        # the timeline: who joined, left, began or ceased publishing the two topics, when
        self.events: list[dict[str, object]] = []
        self._seen_nodes: list[str] | None = None
        self._seen_publishers: dict[str, set[str]] = {}
        self._next_watch = 0.0
        # /tf and /tf_static, where tf2_msgs imports (a sourced ROS; it has no wheel on PyPI):
        # else None, and bras-kit says the transforms were inferred from its model
        self.transforms: list[dict[str, object]] | None = None
        self._subscribe_tf()
        # robot_state_publisher 3.3 latches it: reliable, transient_local, depth 1
        # (src/robot_state_publisher.cpp:133-135); this subscription gets what it holds...
        # (a depth of 10 here, not 1: two publishers' latched texts arrive together, and a reader
        # keeping one would drop the first before it is taken: one robot seen where two run)
        latched = QoSProfile(depth=10, reliability=ReliabilityPolicy.RELIABLE,
                             durability=DurabilityPolicy.TRANSIENT_LOCAL)
        # ...and this one matches any publisher at all (volatile, best effort), as ros2 topic echo may
        anything = QoSProfile(depth=10, reliability=ReliabilityPolicy.BEST_EFFORT,
                              durability=DurabilityPolicy.VOLATILE)
        for qos in (latched, anything):
            # the callback takes the message and its MessageInfo (rclpy 7.1.6 passes both to a
            # two-argument callback); rclpy's own annotation names only the one-argument form
            self.node.create_subscription(String, DESCRIPTION, cast(Any, self._on_description), qos)
        # robot_state_publisher reads /joint_states with SensorDataQoS (best effort), which
        # matches every publisher (src/robot_state_publisher.cpp:144-147)
        self.node.create_subscription(JointState, JOINT_STATES, cast(Any, self._on_joint_state),
                                      QoSProfile(depth=200, reliability=ReliabilityPolicy.BEST_EFFORT))

    def _subscribe_tf(self) -> None:
        try:
            from tf2_msgs.msg import TFMessage
        except ImportError:
            return
        self.transforms = []
        # tf2_ros's listener QoS (tf2_ros/qos.hpp): /tf reliable volatile depth 100, /tf_static
        # reliable transient_local depth 100 (every static publisher's latched message)
        dynamic = QoSProfile(depth=100, reliability=ReliabilityPolicy.RELIABLE, durability=DurabilityPolicy.VOLATILE)
        static = QoSProfile(depth=100, reliability=ReliabilityPolicy.RELIABLE,
                            durability=DurabilityPolicy.TRANSIENT_LOCAL)
        for topic, qos, is_static in (("/tf", dynamic, False), ("/tf_static", static, True)):
            self.node.create_subscription(TFMessage, topic, lambda msg, s=is_static: self._on_tf(msg, s), qos)

    def _on_tf(self, msg: object, static: bool) -> None:
        now = time.time()
        records = [tf_record(t, static, now) for t in msg.transforms]  # type: ignore[attr-defined]
        with self.lock:
            if self.transforms is not None:
                self.transforms.extend(records)
                del self.transforms[:-MAX_TRANSFORMS]

    def watch_graph(self) -> None:
        """Note who joined or left the graph, and who began or ceased publishing the description or
        the joint states, since the last call (at most every WATCH_EVERY seconds)."""
        now = time.monotonic()
        if now < self._next_watch:
            return
        self._next_watch = now + WATCH_EVERY
        stamp = time.time()
        nodes = self.node_instances()
        if self._seen_nodes is not None:
            for name in sorted(set(nodes) | set(self._seen_nodes)):
                before, after = self._seen_nodes.count(name), nodes.count(name)
                for _ in range(after - before):
                    self.events.append({"time": stamp, "kind": "joined", "node": name})
                for _ in range(before - after):
                    self.events.append({"time": stamp, "kind": "left", "node": name})
        self._seen_nodes = nodes
        for topic in (DESCRIPTION, JOINT_STATES):
            # an endpoint whose node is not known yet (its names still on their way) is no one yet
            publishers = {str(_endpoint(i)["node"]) for i in self.node.get_publishers_info_by_topic(topic)
                          if i.node_name not in (NODE_NAME, "", "_NODE_NAME_UNKNOWN_")}
            before_publishers = self._seen_publishers.get(topic)
            if before_publishers is not None:
                for name in sorted(publishers - before_publishers):
                    self.events.append({"time": stamp, "kind": "publishes", "node": name, "topic": topic})
                for name in sorted(before_publishers - publishers):
                    self.events.append({"time": stamp, "kind": "unpublishes", "node": name, "topic": topic})
            self._seen_publishers[topic] = publishers
        del self.events[:-MAX_EVENTS]

    def _on_description(self, msg: object, info: object) -> None:
        text = msg.data  # type: ignore[attr-defined]
        # rclpy's message info has no publisher gid (only timestamps and sequence numbers): a text
        # is told apart by itself, and the publishers are read from the graph
        record = {"received": time.time(), "length": len(text), "text": text[:MAX_TEXT],
                  "sent": _info(info, "source_timestamp")}
        with self.lock:
            if self.descriptions and self.descriptions[-1]["text"] == record["text"]:
                return  # the same text through both subscriptions (a new text is a new description)
            self.descriptions.append(record)
            if len(self.descriptions) > MAX_DESCRIPTIONS:
                del self.descriptions[1]  # the first is kept (what RViz loaded first), then the latest
        if self.emit:
            self.emit({"kind": "description", **record})  # type: ignore[operator]

    def _on_joint_state(self, msg: object, info: object) -> None:
        names, positions = kept_sizes(len(msg.name), len(msg.position))  # type: ignore[attr-defined]
        kept = [str(n)[:MAX_NAME] for n in msg.name[:names]]  # type: ignore[attr-defined]
        record = {
            "received": time.time(),
            "stamp": _stamp(msg.header),  # type: ignore[attr-defined]
            "frame": str(msg.header.frame_id)[:MAX_NAME],  # type: ignore[attr-defined]
            "name": kept,
            "position": [float(v) for v in msg.position[:positions]],  # type: ignore[attr-defined]
            "sent": _info(info, "source_timestamp"),
        }
        size = sum(len(n) for n in kept) + 8 * (names + positions) + 100
        with self.lock:
            self.joint_states.append(record)
            self._sizes.append(size)
            self._joint_state_bytes += size
            while len(self.joint_states) > MAX_JOINT_STATES or (
                    self._joint_state_bytes > MAX_JOINT_STATE_BYTES and len(self.joint_states) > 1):
                self.joint_states.pop(0)
                self._joint_state_bytes -= self._sizes.pop(0)
        if self.emit:
            self.emit({"kind": "joint_state", **record})  # type: ignore[operator]

    def descriptions_missing(self) -> bool:
        """Fewer different texts received than transient-local publishers of the description."""
        latched = [i for i in self.node.get_publishers_info_by_topic(DESCRIPTION)
                   if i.qos_profile.durability == DurabilityPolicy.TRANSIENT_LOCAL]
        with self.lock:
            texts = {str(d["text"]) for d in self.descriptions}
        return len(texts) < len(latched)

    def spin_for(self, seconds: float, until: object = None) -> None:
        end = time.monotonic() + seconds
        while time.monotonic() < end:
            self.executor.spin_once(timeout_sec=min(0.05, max(0.0, end - time.monotonic())))
            self.watch_graph()
            if until is not None and until():  # type: ignore[operator]
                return

    def nodes(self) -> list[str]:
        return sorted(set(self.node_instances()))

    def node_instances(self) -> list[str]:
        """Every node the graph lists, a name twice when two nodes share it (rcl lets them)."""
        names = []
        for name, namespace in self.node.get_node_names_and_namespaces():
            if name.startswith("_"):  # hidden nodes: ours, the ros2 daemon's
                continue
            names.append(namespace.rstrip("/") + "/" + name)
        return names

    def unnamed_endpoints(self) -> bool:
        """An endpoint whose node is not known yet: its participant is discovered, the node names
        it announces (on ros_discovery_info) are still on their way."""
        for topic, _ in self.node.get_topic_names_and_types():
            for info in (*self.node.get_publishers_info_by_topic(topic),
                         *self.node.get_subscriptions_info_by_topic(topic)):
                if info.node_name in ("", "_NODE_NAME_UNKNOWN_"):
                    return True
        return False

    def graph(self) -> dict[str, Any]:
        """Nodes, topics with their endpoints and QoS, the pairs whose QoS cannot match."""
        topics: dict[str, object] = {}
        incompatible: list[dict[str, object]] = []
        for topic, types in self.node.get_topic_names_and_types():
            publishers = [i for i in self.node.get_publishers_info_by_topic(topic) if i.node_name != NODE_NAME]
            subscribers = [i for i in self.node.get_subscriptions_info_by_topic(topic) if i.node_name != NODE_NAME]
            if not publishers and not subscribers:
                continue
            topics[topic] = {"types": list(types), "publishers": [_endpoint(i) for i in publishers],
                             "subscribers": [_endpoint(i) for i in subscribers]}
            for pub in publishers:
                for sub in subscribers:
                    compatibility, reason = qos_check_compatible(pub.qos_profile, sub.qos_profile)
                    if compatibility != QoSCompatibility.ERROR:
                        # WARNING is for a policy left at system default or unknown: the graph
                        # reports the policies in force, so only ERROR says "they never connect"
                        continue
                    incompatible.append({
                        "topic": topic, "publisher": _endpoint(pub), "subscriber": _endpoint(sub),
                        "level": "error" if compatibility == QoSCompatibility.ERROR else "warning",
                        "reason": reason,
                    })
        instances = self.node_instances()
        shared = {name: instances.count(name) for name in sorted(set(instances)) if instances.count(name) > 1}
        return {"nodes": self.nodes(), "shared_names": shared, "topics": topics, "incompatible": incompatible}

    def parameter_clients(self, nodes: list[str]) -> list[tuple[str, Any]]:
        """A client of each node's ``get_parameters`` service, made once: made while the graph is
        watched, its service is discovered by the time it is asked."""
        from rcl_interfaces.srv import GetParameters

        for name in nodes:
            if name not in self._clients:
                self._clients[name] = self.node.create_client(GetParameters, f"{name}/get_parameters")
        return [(name, self._clients[name]) for name in nodes]

    def use_sim_time(self, nodes: list[str], timeout: float = 1.5) -> dict[str, object]:
        """Each node's ``use_sim_time``, asked of its parameter service (None: no answer)."""
        from rcl_interfaces.srv import GetParameters

        answers: dict[str, object] = {name: None for name in nodes}
        pending = {}
        clients = self.parameter_clients(nodes)
        end = time.monotonic() + timeout
        # wait for the services to be discovered, then ask all at once
        while time.monotonic() < end:
            for name, client in clients:
                if name not in pending and client.service_is_ready():
                    pending[name] = client.call_async(GetParameters.Request(names=["use_sim_time"]))
            if len(pending) == len(clients) and all(f.done() for f in pending.values()):
                break
            self.executor.spin_once(timeout_sec=0.05)
        for name, future in pending.items():
            if future.done() and future.result() is not None and future.result().values:
                value = future.result().values[0]
                answers[name] = bool(value.bool_value) if value.type == 1 else None  # PARAMETER_BOOL
        for name in list(self._clients):  # nodes gone: their clients go too (a long stream)
            if name not in nodes:
                self.node.destroy_client(self._clients.pop(name))
        return answers

    def environment(self) -> dict[str, object]:
        return {
            "domain": int(os.environ.get("ROS_DOMAIN_ID") or 0),
            "range": os.environ.get("ROS_AUTOMATIC_DISCOVERY_RANGE", ""),
            "localhost_only": os.environ.get("ROS_LOCALHOST_ONLY", ""),
            "rmw": rclpy.get_rmw_implementation_identifier(),
            "distro": os.environ.get("ROS_DISTRO", ""),
            "rclpy": os.path.dirname(rclpy.__file__),
            "python": sys.executable,
        }

    def close(self) -> None:
        try:
            self.executor.shutdown(timeout_sec=0.5)
            self.node.destroy_node()
        finally:
            rclpy.try_shutdown()


def tf_record(transform: object, static: bool, received: float) -> dict[str, object]:
    """One geometry_msgs/TransformStamped as recorded: its frames, stamp, whether it holds a NaN."""
    t = transform.transform  # type: ignore[attr-defined]
    values = [t.translation.x, t.translation.y, t.translation.z, t.rotation.x, t.rotation.y, t.rotation.z,
              t.rotation.w]
    return {"parent": str(transform.header.frame_id), "child": str(transform.child_frame_id),  # type: ignore[attr-defined]
            "stamp": _stamp(transform.header), "static": static, "received": received,  # type: ignore[attr-defined]
            "nan": any(v != v for v in values)}


def _info(info: object, key: str) -> int | None:
    """One field of rclpy's message info (a dict of nanoseconds and sequence numbers)."""
    try:
        return int(info[key])  # type: ignore[index]
    except (KeyError, TypeError, IndexError, ValueError):
        return None


# Fast DDS finds the nodes of a graph over 0.05-2.3 s (measured in a loopback namespace, 3 nodes,
# a loaded machine): a look shorter than this would miss some of them
DISCOVERY_FLOOR = 3.5
STABLE_GRACE = 3.0


def snapshot(seconds: float, wait: float = DISCOVERY_FLOOR) -> int:
    """Watch ``seconds`` (at least the discovery floor, or ``wait`` for a first node), and longer
    while nodes are still being discovered: the rate and the publishers are measured over the
    whole window."""
    probe = Probe()
    try:
        probe.spin_for(max(seconds, DISCOVERY_FLOOR, wait), until=lambda: bool(probe.nodes()))
        if probe.nodes():  # then at least 2 s of messages, to measure a rate, and until no node
            # has joined for a second (nodes started together are discovered over 1-2.5 s)
            seen, changed = [probe.nodes()], [time.monotonic()]

            def track() -> bool:
                if probe.nodes() != seen[0] or probe.unnamed_endpoints():
                    seen[0], changed[0] = probe.nodes(), time.monotonic()
                    probe.parameter_clients(seen[0])
                return False

            probe.parameter_clients(seen[0])

            end = max(probe.started + seconds, probe.started + DISCOVERY_FLOOR, time.time() + min(seconds, 2.0))
            probe.spin_for(end - time.time(), until=track)
            last = time.monotonic() + STABLE_GRACE
            while time.monotonic() - changed[0] < 1.0 and time.monotonic() < last:
                probe.spin_for(0.1, until=track)
            # each latched description publisher delivers once matched: wait for as many texts as
            # there are of them (two robot_state_publishers with two robots), a grace at most
            last = time.monotonic() + STABLE_GRACE
            while probe.descriptions_missing() and time.monotonic() < last:
                probe.spin_for(0.1)
        graph = probe.graph()
        sim = probe.use_sim_time(list(graph["nodes"]))
        with probe.lock:
            out = {"kind": "snapshot", **probe.environment(), "started": probe.started, "ended": time.time(),
                   **graph, "use_sim_time": sim, "descriptions": probe.descriptions,
                   "joint_states": probe.joint_states, "events": probe.events, "transforms": probe.transforms}
        print(json.dumps(out), flush=True)
    finally:
        probe.close()
    return 0


def census(seconds: float) -> int:
    """The nodes of this domain, as soon as discovery shows one (or after ``seconds``)."""
    probe = Probe()
    try:
        probe.spin_for(seconds, until=lambda: bool(probe.nodes()))
        # then until no node has joined for 2.5 s (each is discovered on its own, 0.05-2.3 s apart
        # measured in a loopback namespace), 6 s at most after the first
        seen, steady = probe.nodes(), time.monotonic()
        end = steady + 6.0
        while seen and time.monotonic() < min(end, steady + 2.5):
            probe.spin_for(0.1)
            now = probe.nodes()
            if now != seen:
                seen, steady = now, time.monotonic()
        print(json.dumps({"kind": "census", **probe.environment(), "nodes": probe.nodes()}), flush=True)
    finally:
        probe.close()
    return 0


def stream(every: float) -> int:
    """JSON lines until stdin closes (the viewer stopped): never a traceback when the graph changes."""
    out_lock = threading.Lock()
    closed = threading.Event()

    def emit(record: dict[str, object]) -> None:
        try:
            with out_lock:
                sys.stdout.write(json.dumps(record) + "\n")
                sys.stdout.flush()
        except (BrokenPipeError, ValueError):
            closed.set()

    def watch_stdin() -> None:
        try:
            while sys.stdin.read(4096):
                pass
        finally:
            closed.set()

    threading.Thread(target=watch_stdin, daemon=True).start()
    probe = Probe(emit)
    emit({"kind": "hello", **probe.environment()})
    try:
        next_graph = time.monotonic() + min(every, 1.5)
        while not closed.is_set():
            probe.spin_for(0.05)
            if time.monotonic() >= next_graph:
                graph = probe.graph()
                sim = probe.use_sim_time(list(graph["nodes"]), timeout=0.5)
                with probe.lock:
                    events, probe.events = probe.events, []
                emit({"kind": "graph", **graph, "use_sim_time": sim, "time": time.time(), "events": events,
                      "tf_read": probe.transforms is not None})
                next_graph = time.monotonic() + every
                with probe.lock:
                    del probe.joint_states[:]
                    if probe.transforms is not None:
                        del probe.transforms[:]
    finally:
        probe.close()
    return 0


def main(argv: list[str]) -> int:
    modes = {"snapshot": (snapshot, 2), "census": (census, 1), "stream": (stream, 1)}  # mode: its most numbers
    mode, most = modes.get(argv[0] if argv else "", (None, 0))
    if mode is None or not 1 <= len(argv) - 1 <= most:
        print("usage: _probe.py snapshot SECONDS [WAIT] | census SECONDS | stream SECONDS", file=sys.stderr)
        return 2
    return mode(*(max(0.1, min(float(arg), 600.0)) for arg in argv[1:]))


if __name__ == "__main__":
    try:
        sys.exit(main(sys.argv[1:]))
    except KeyboardInterrupt:
        sys.exit(130)
