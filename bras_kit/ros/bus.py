"""The bus between bras-kit processes on this machine: ``bras-kit run`` beside ``bras-kit launch``
as ``ros2 run`` beside ``ros2 launch``, scoped as ROS scopes a graph.

Zenoh (``eclipse-zenoh``, what ROS 2 Jazzy offers as rmw_zenoh) in peer mode over Unix sockets,
no TCP, no multicast scouting, no gossip: nothing leaves this machine. As a ROS domain:

- one folder per user and per domain, ``$XDG_RUNTIME_DIR/bras-kit/domain-N/`` (else
  ``/tmp/bras-kit-UID/domain-N/``), that only this user can open: another user's commands, or
  this user's on another ``ROS_DOMAIN_ID``, never meet;
- every ``bras-kit launch`` listens on a socket of its own in that folder (two launches are two
  participants, never two listeners on one socket); a live ``bras-kit run`` connects to every
  launch listening there, so each page shows what the node publishes (every participant of a
  domain sees every other);
- a launch tells its robot's joints on ``bras_kit/launch/<id>/robot`` (a Zenoh queryable): the
  run says which joints it publishes that the page does not have.

::

    from ..ros.bus import Bus
    with Bus.listen() as bus:                      # bras-kit launch
        bus.on_joint_state(lambda state: print(state.name, state.position))
        bus.offer_robot(lambda: {"package": "bras_description", "joints": ["epaule", "coude"]})
    bus = Bus.connect()                            # bras-kit run: None when no launch listens
"""

from __future__ import annotations

import itertools
import json
import os
import re
import socket
import stat
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

JOINT_STATES_KEY = "bras_kit/joint_states"
ROBOT_KEY = "bras_kit/launch/{id}/robot"
DOMAIN_VARIABLE = "ROS_DOMAIN_ID"
MAX_DOMAIN_ID = 232  # the largest domain DDS's port arithmetic allows (ROS 2's "The ROS_DOMAIN_ID" concept page)
SOCKET_SUFFIX = ".sock"  # a launch's socket: PID-N.sock (short: a socket's path holds 107 bytes at most)
ROBOT_QUERY_SECONDS = 2.0
SUN_PATH_BYTES = 108  # sockaddr_un.sun_path on Linux (unix(7))


@dataclass(frozen=True)
class BusJointState:
    name: list[str]
    position: list[float]
    stamp: float  # seconds, the message's header.stamp


MAX_PAYLOAD_BYTES = 1 << 20  # one joint state on the bus (a 2,000-joint one is about 70 KiB)
MAX_JOINTS = 10_000


def joint_state_of(data: Any) -> BusJointState:
    """A joint state read from the bus, typed: names as text, positions as numbers, at most
    :data:`MAX_JOINTS` of them; ValueError (or KeyError, TypeError) for anything else."""
    names, position, stamp = data["name"], data["position"], data.get("stamp", 0.0)
    if not (isinstance(names, list) and isinstance(position, list)) or max(len(names), len(position)) > MAX_JOINTS:
        raise ValueError("not a joint state")
    if not all(isinstance(n, str) for n in names) or isinstance(stamp, bool) or \
            not all(isinstance(p, (int, float)) and not isinstance(p, bool) for p in position):
        raise ValueError("not a joint state")
    return BusJointState(list(names), [float(p) for p in position], float(stamp))


@dataclass(frozen=True)
class LaunchRobot:
    """What a listening launch shows: its package and its robot's movable joints."""

    package: str
    joints: tuple[str, ...]


_STRTOUL = re.compile(r"\s*([+-]?)(0[xX][0-9a-fA-F]+|0[0-7]*|[1-9][0-9]*)")


def domain_id(environ: Any = None) -> int:
    """``ROS_DOMAIN_ID`` as rcl reads it (rcl/src/rcl/domain_id.c, rcl_get_default_domain_id:
    unset or empty is 0; ``strtoul(text, &end, 0)``, refused when nothing is a number), and
    refused past the largest domain DDS can open."""
    from ..core.errors import ParameterError
    from ..core.message import M

    text = (os.environ if environ is None else environ).get(DOMAIN_VARIABLE, "")
    if text == "":
        return 0
    found = _STRTOUL.match(text)
    if found is None:
        raise ParameterError(M("ROS_DOMAIN_ID is not an integral number: '{value}'", value=text),
                             hint=M("give the domain as a whole number, e.g. export ROS_DOMAIN_ID=0"))
    sign, digits = found.groups()
    number = int(digits, 16) if digits[:2].lower() == "0x" else int(digits, 8) if digits.startswith("0") \
        else int(digits)
    if number == 0 and found.end() != len(text):  # rcl takes "5abc" as 5 but refuses "0abc"
        raise ParameterError(M("ROS_DOMAIN_ID is not an integral number: '{value}'", value=text),
                             hint=M("give the domain as a whole number, e.g. export ROS_DOMAIN_ID=0"))
    if (sign == "-" and number) or number > MAX_DOMAIN_ID:
        raise ParameterError(M("ROS_DOMAIN_ID is out of range: '{value}'", value=text),
                             hint=M("a domain is a number from 0 to {max} (0 when unset)", max=MAX_DOMAIN_ID))
    return number


def user_folder() -> str:
    """This user's folder of bras-kit buses (one sub-folder per domain)."""
    runtime = os.environ.get("XDG_RUNTIME_DIR")
    return os.path.join(runtime, "bras-kit") if runtime and os.path.isdir(runtime) else \
        os.path.join("/tmp", f"bras-kit-{os.getuid()}")


def bus_folder(domain: int | None = None) -> str:
    """The folder of this user's bus on ``domain`` (default: ROS_DOMAIN_ID's)."""
    return os.path.join(user_folder(), f"domain-{domain_id() if domain is None else domain}")


def _private(folder: str) -> None:
    """``folder`` made when missing, and refused unless it is a folder of this user's alone."""
    os.makedirs(folder, mode=0o700, exist_ok=True)
    info = os.lstat(folder)
    if not stat.S_ISDIR(info.st_mode) or info.st_uid != os.getuid() or info.st_mode & 0o077:
        from ..core.errors import BrasKitError
        from ..core.message import M

        raise BrasKitError(M("{folder} is not a private folder of yours: the bus between bras-kit commands is not "
                             "opened", folder=folder),
                           hint=M("remove it, or set XDG_RUNTIME_DIR to a folder only you can open"))


def _private_folder(domain: int | None = None) -> str:
    folder = bus_folder(domain)
    _private(os.path.dirname(folder))
    _private(folder)
    return folder


def _accepts(path: str) -> bool:
    """Whether a process listens on the Unix socket ``path``, and is this user's (its credentials)."""
    probe = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    try:
        probe.settimeout(0.5)
        probe.connect(path)
        import struct

        _pid, uid, _gid = struct.unpack("3i", probe.getsockopt(socket.SOL_SOCKET, socket.SO_PEERCRED,
                                                               struct.calcsize("3i")))
        return uid == os.getuid()
    except OSError:
        return False
    finally:
        probe.close()


def _sockets(folder: str) -> list[str]:
    try:
        names = sorted(os.listdir(folder))
    except OSError:
        return []
    return [os.path.join(folder, n) for n in names if n.endswith(SOCKET_SUFFIX)]


def launches(domain: int | None = None) -> list[str]:
    """The sockets of the bras-kit launches listening on this user's bus of ``domain``; nothing when
    the folder is not this user's alone (a run never joins a bus another user could have made)."""
    folder = bus_folder(domain)
    try:
        info = os.lstat(folder)
    except OSError:
        return []
    if not stat.S_ISDIR(info.st_mode) or info.st_uid != os.getuid() or info.st_mode & 0o077:
        return []
    return [path for path in _sockets(folder) if _accepts(path)]


def listening(domain: int | None = None) -> bool:
    """Whether a bras-kit launch listens on this user's bus of ``domain``."""
    return bool(launches(domain))


def _forget_dead(folder: str) -> None:
    """Sockets (and Zenoh's lock files) left by launches that died: nobody accepts on them."""
    for path in _sockets(folder):
        if not _accepts(path):
            for leftover in (path, path + ".lock"):
                try:
                    os.unlink(leftover)
                except OSError:
                    pass


def _zenoh() -> Any:
    try:
        import zenoh
    except ImportError:
        from ..core.errors import BrasKitError
        from ..core.message import M

        raise BrasKitError(M("the bus between bras-kit commands needs Zenoh, which is not installed"),
                           hint=M("pip install eclipse-zenoh")) from None
    return zenoh


def _config(listen: list[str], connect: list[str]) -> Any:
    zenoh = _zenoh()

    config = zenoh.Config()
    config.insert_json5("mode", json.dumps("peer"))
    config.insert_json5("scouting/multicast/enabled", "false")
    config.insert_json5("scouting/gossip/enabled", "false")
    config.insert_json5("listen/endpoints", json.dumps(listen))
    config.insert_json5("connect/endpoints", json.dumps(connect))
    return config


def _endpoint(path: str) -> str:
    return f"unixsock-stream/{path}"


_OPENED = itertools.count(1)  # the launches of this process (a socket name is unique while it is open)


def _open(zenoh: Any, config: Any, path: str) -> Any:
    """A Zenoh session, or a BrasKitError saying why not (Zenoh's own words as the detail): the
    command goes on without the bus."""
    try:
        return zenoh.open(config)
    except Exception as exc:  # noqa: BLE001 - zenoh.ZError, and whatever its Rust side raises
        from ..core.errors import BrasKitError
        from ..core.message import M

        hint = M("the path of a Unix socket holds at most {n} bytes: set XDG_RUNTIME_DIR to a shorter folder",
                 n=SUN_PATH_BYTES - 1) if len(path.encode()) >= SUN_PATH_BYTES else None
        raise BrasKitError(M("the bus between bras-kit commands cannot be opened at {path}: {reason}",
                             path=path, reason=str(exc).split(" at /", 1)[0]), hint=hint) from None


class Bus:
    """One Zenoh session on this user's bus of one domain; :meth:`close` ends it (also a context
    manager)."""

    def __init__(self, session: Any, path: str | None, peers: list[str]) -> None:
        self._session = session
        self.path = path  # the launch's own socket (None for a run)
        self.peers = peers  # the launches' sockets it connected to
        self._publisher: Any = None
        self._declared: list[Any] = []

    @classmethod
    def listen(cls, domain: int | None = None) -> Bus:
        """A launch joins the bus of ``domain`` (default: ROS_DOMAIN_ID's): it listens on a socket of
        its own, beside any other launch's."""
        zenoh = _zenoh()

        folder = _private_folder(domain)
        _forget_dead(folder)
        path = os.path.join(folder, f"{os.getpid()}-{next(_OPENED)}{SOCKET_SUFFIX}")
        return cls(_open(zenoh, _config([_endpoint(path)], []), path), path, [])

    @classmethod
    def connect(cls, domain: int | None = None) -> Bus | None:
        """A run joins every launch listening on the bus of ``domain``; None when none listens."""
        peers = launches(domain)
        if not peers:
            return None
        zenoh = _zenoh()

        return cls(_open(zenoh, _config([], [_endpoint(p) for p in peers]), peers[0]), None, peers)

    def publish_joint_state(self, state: BusJointState) -> None:
        if self._publisher is None:
            self._publisher = self._session.declare_publisher(JOINT_STATES_KEY)
        self._publisher.put(json.dumps({"name": list(state.name), "position": [float(p) for p in state.position],
                                        "stamp": float(state.stamp)}))

    def on_joint_state(self, callback: Callable[[BusJointState], None]) -> None:
        def receive(sample: Any) -> None:
            try:
                payload = sample.payload
                if len(payload) > MAX_PAYLOAD_BYTES:  # its size, before a byte of it is copied
                    return
                state = joint_state_of(json.loads(bytes(payload.to_bytes())))
            except (ValueError, KeyError, TypeError, AttributeError, RecursionError):
                return  # not a joint state of ours: ignored
            callback(state)

        self._declared.append(self._session.declare_subscriber(JOINT_STATES_KEY, receive))

    def offer_robot(self, describe: Callable[[], LaunchRobot | None]) -> None:
        """Answer runs asking which robot this launch shows (``describe()`` at each question: the
        robot may have been reloaded since)."""
        key = ROBOT_KEY.format(id=os.path.basename(self.path or "").removesuffix(SOCKET_SUFFIX) or os.getpid())

        def answer(query: Any) -> None:
            robot = describe()
            if robot is not None:
                query.reply(key, json.dumps({"package": robot.package, "joints": list(robot.joints)}))

        self._declared.append(self._session.declare_queryable(key, answer))

    def robots(self, timeout: float = ROBOT_QUERY_SECONDS) -> list[LaunchRobot]:
        """The robots the launches this bus joined show (one per launch that answered)."""
        out = []
        for reply in self._session.get(ROBOT_KEY.format(id="*"), timeout=timeout):
            try:
                data = json.loads(bytes(reply.ok.payload.to_bytes()))
                out.append(LaunchRobot(str(data["package"]), tuple(str(j) for j in data["joints"])))
            except (ValueError, KeyError, TypeError, AttributeError):
                continue  # an error reply, or not ours
        return sorted(out, key=lambda r: (r.package, r.joints))

    def close(self) -> None:
        for declared in self._declared:
            declared.undeclare()
        self._session.close()
        if self.path is not None:
            for leftover in (self.path, self.path + ".lock"):
                if os.path.exists(leftover):
                    os.unlink(leftover)

    def __enter__(self) -> Bus:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()


def unknown_joints(published: list[str], robot: LaunchRobot) -> list[str]:
    """The joints a node publishes that the launch's robot does not have (robot_state_publisher
    ignores them: the page does not move for them)."""
    return [name for name in published if name not in robot.joints]
