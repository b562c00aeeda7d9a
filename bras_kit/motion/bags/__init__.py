"""ROS 2 bags: record what bras-kit moves, replay what ROS 2 recorded.

* :func:`write_bag` turns joint states (a motion, a simulation, a run) into a rosbag2 folder:
  ``metadata.yaml`` plus one MCAP (or SQLite 3) file holding ``/robot_description``,
  ``/tf_static``, ``/tf`` and ``/joint_states``, CDR-encoded as ROS 2 records them. The
  folder opens in ``ros2 bag info``/``ros2 bag play``, Foxglove and Lichtblick.
* :func:`read_recording` reads ``/joint_states`` (or another JointState topic) back from a
  bag folder, a bare ``.mcap`` or ``.db3`` file; :func:`recorded_tracks` turns it into the
  tracks of a :class:`~bras_kit.motion.Motion` for one robot, with notes on what was odd in
  the recording (unknown joints, stamps out of order, gaps, NaN).

A bag is untrusted input: sizes are capped, its files must stay inside its folder and damaged
files are refused with a message saying which file, what is wrong and what to do.

The rosbag2 formats are read and written by ``rosbags`` (pure Python, both storages); its
import costs about 0.1 s, so it happens only inside these functions.
"""

from __future__ import annotations

from .reader import (
    JOINT_STATE_TYPE,
    MAX_BAG_BYTES,
    MAX_MESSAGES,
    BagError,
    Recording,
    bag_suffix,
    is_bag,
    read_recording,
    recorded_tracks,
)
from .writer import BAG_SUFFIXES, BagSummary, bag_folder, write_bag

__all__ = [
    "BAG_SUFFIXES",
    "JOINT_STATE_TYPE",
    "MAX_BAG_BYTES",
    "MAX_MESSAGES",
    "BagError",
    "BagSummary",
    "Recording",
    "bag_folder",
    "bag_suffix",
    "is_bag",
    "read_recording",
    "recorded_tracks",
    "write_bag",
]
