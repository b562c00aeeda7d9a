"""The topics the tutorial's graph is about, and the message its arm moves by, by their ROS names.

A module of names only: the rules that read a run's recording (BK64x) or a live graph (BK8xx)
name these topics without importing the records those are made of.
"""

DESCRIPTION = "/robot_description"  # robot_state_publisher publishes the URDF it was given here
JOINT_STATES = "/joint_states"  # the node, or joint_state_publisher(_gui), publishes the joints here
JOINT_STATE_TYPE = "sensor_msgs/msg/JointState"
CLOCK = "/clock"  # simulated time (use_sim_time), published by a simulator
