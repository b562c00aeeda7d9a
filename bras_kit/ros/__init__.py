"""The ROS side the learner's code meets, with no ROS install.

One layer under every command that runs code a learner wrote (``run``, ``build``, ``launch``,
``validate --run``, ``grade``, ``exercises``):

- ``standin/``: the tree put first on ``sys.path`` in the child, one stand-in per ROS Python
  package a learner imports (rclpy, launch, launch_ros, ament_index_python, tf2_ros, the
  message packages, whose classes are generated from rosbags' Jazzy definitions);
- :mod:`.child`: what runs in the one child process (a node's ``main()``; setup.py; a launch file);
- :mod:`.locate`, :mod:`.recording`: what to run, and what it did, as data.

The design is in docs/design/ros-layer.md.
"""
