"""The bus between bras-kit processes on this machine: ``bras-kit run`` beside ``bras-kit launch``
as ``ros2 run`` beside ``ros2 launch``.

Zenoh (``eclipse-zenoh``, what ROS 2 Jazzy offers as rmw_zenoh) in peer mode over one Unix
socket in a folder only this user can open (``$XDG_RUNTIME_DIR/bras-kit/``, else
``/tmp/bras-kit-UID/``): no TCP, no multicast scouting, no gossip, so nothing leaves this
machine and no other user's process can join. ``bras-kit launch`` listens on the socket;
``bras-kit run`` connects when it is there and publishes each JointState it records.

::

    from bras_kit.ros.bus import Bus
    with Bus.listen() as bus:                      # bras-kit launch
        bus.on_joint_state(lambda state: print(state.name, state.position))
    bus = Bus.connect()                            # bras-kit run: None when no launch listens
"""

from __future__ import annotations

import json
import os
import socket
import stat
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

JOINT_STATES_KEY = "bras_kit/joint_states"


@dataclass(frozen=True)
class BusJointState:
    name: list[str]
    position: list[float]
    stamp: float  # seconds, the message's header.stamp


def bus_folder() -> str:
    runtime = os.environ.get("XDG_RUNTIME_DIR")
    base = os.path.join(runtime, "bras-kit") if runtime and os.path.isdir(runtime) else \
        os.path.join("/tmp", f"bras-kit-{os.getuid()}")
    return base


def socket_path() -> str:
    return os.path.join(bus_folder(), "bus.sock")


def _private_folder() -> str:
    folder = bus_folder()
    os.makedirs(folder, mode=0o700, exist_ok=True)
    info = os.lstat(folder)
    if not stat.S_ISDIR(info.st_mode) or info.st_uid != os.getuid() or info.st_mode & 0o077:
        from ..errors import BrasKitError
        from ..message import M

        raise BrasKitError(M("{folder} is not a private folder of yours: the bus between bras-kit commands is not "
                             "opened", folder=folder),
                           hint=M("remove it, or set XDG_RUNTIME_DIR to a folder only you can open"))
    return folder


def listening() -> bool:
    """Whether a bras-kit launch listens on this machine's bus (its socket accepts a connection)."""
    path = socket_path()
    if not os.path.exists(path):
        return False
    probe = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    try:
        probe.settimeout(0.5)
        probe.connect(path)
        return True
    except OSError:
        return False
    finally:
        probe.close()


def _zenoh() -> Any:
    try:
        import zenoh
    except ImportError:
        from ..errors import BrasKitError
        from ..message import M

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


class Bus:
    """One Zenoh session on the Unix socket; :meth:`close` ends it (also a context manager)."""

    def __init__(self, session: Any, path: str, owner: bool) -> None:
        self._session = session
        self._path = path
        self._owner = owner
        self._publisher: Any = None
        self._subscribers: list[Any] = []

    @classmethod
    def listen(cls) -> Bus:
        """Listen on this user's socket (the launch side). A socket left by a launch that died is replaced."""
        zenoh = _zenoh()

        path = os.path.join(_private_folder(), "bus.sock")
        if os.path.exists(path) and not listening():
            os.unlink(path)
        return cls(zenoh.open(_config([f"unixsock-stream/{path}"], [])), path, True)

    @classmethod
    def connect(cls) -> Bus | None:
        """Join the launch's bus, or None when no bras-kit launch listens."""
        if not listening():
            return None
        zenoh = _zenoh()

        path = socket_path()
        return cls(zenoh.open(_config([], [f"unixsock-stream/{path}"])), path, False)

    def publish_joint_state(self, state: BusJointState) -> None:
        if self._publisher is None:
            self._publisher = self._session.declare_publisher(JOINT_STATES_KEY)
        self._publisher.put(json.dumps({"name": list(state.name), "position": [float(p) for p in state.position],
                                        "stamp": float(state.stamp)}))

    def on_joint_state(self, callback: Callable[[BusJointState], None]) -> None:
        def receive(sample: Any) -> None:
            try:
                data = json.loads(bytes(sample.payload.to_bytes()))
                state = BusJointState([str(n) for n in data["name"]], [float(p) for p in data["position"]],
                                      float(data.get("stamp", 0.0)))
            except (ValueError, KeyError, TypeError):
                return  # not a joint state of ours: ignored
            callback(state)

        self._subscribers.append(self._session.declare_subscriber(JOINT_STATES_KEY, receive))

    def close(self) -> None:
        for subscriber in self._subscribers:
            subscriber.undeclare()
        self._session.close()
        if self._owner and os.path.exists(self._path):
            os.unlink(self._path)

    def __enter__(self) -> Bus:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()
