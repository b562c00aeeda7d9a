"""``bras-kit run``: the learner's own node runs, with no ROS install, and moves the arm.

The counterpart of ``ros2 run PKG EXE``: the executable is found in ``setup.py``
(:mod:`.locate`), its ``main()`` runs in a child process under the sandbox's limits against a
stand-in for the part of rclpy beginner nodes use (``bras_kit/ros/standin/``, injected in that child
only), on a simulated clock, and every message it publishes is recorded (:mod:`.recording`).
:mod:`.findings` turns the recording into validator findings (BK640-BK659).

::

    from bras_kit.run import joint_states, robot_of, run_findings, run_node
    recording = run_node("bras_description", "animation", duration=5)
    states = joint_states(recording)          # what /joint_states carried, as JointStates
    for finding in run_findings(recording, robot_of("bras_description")):
        print(finding.code, finding.text())
"""

from __future__ import annotations

from ..core.lazy import lazy_exports

# name -> module, imported on first use: the face the lessons and notebooks use
_LAZY = {
    "JOINT_STATES": "..ros.topics",
    "NodeFailure": "..ros.recording",
    "Published": "..ros.recording",
    "Recording": "..ros.recording",
    "joint_states": "..ros.recording",
    "stamp_seconds": "..ros.recording",
    "Target": "..ros.locate",
    "locate": "..ros.locate",
    "uncontained_note": "..trust.contain",
    "NodeRunError": ".node",
    "run_node": ".node",
    "robot_of": ".node",
    "parse_parameters": ".node",
    "DEFAULT_DURATION": ".node",
    "MAX_DURATION": ".node",
    "run_findings": ".findings",
}


__getattr__ = lazy_exports(__name__, _LAZY)


__all__ = sorted(_LAZY)
