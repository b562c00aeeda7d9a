"""tf2_ros (geometry2 jazzy, tf2_ros_py), simulated by bras-kit: broadcasters, and a Buffer with
a TransformListener that answer from what the node broadcast and from the robot's joints moved
by its /joint_states (as robot_state_publisher would broadcast them)."""

import _bras_sim

from ._core import (  # noqa: F401
    ConnectivityException,
    ExtrapolationException,
    InvalidArgumentException,
    LookupException,
    TimeoutException,
    TransformException,
)
from .buffer import Buffer  # noqa: F401
from .static_transform_broadcaster import StaticTransformBroadcaster  # noqa: F401
from .transform_broadcaster import TransformBroadcaster  # noqa: F401
from .transform_listener import TransformListener  # noqa: F401


def __getattr__(name):
    raise _bras_sim.not_simulated('tf2_ros', name)
