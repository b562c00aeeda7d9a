# The same through arguments=: after '--ros-args', '--log-level warn' is one unknown argument.
from launch import LaunchDescription
from launch_ros.actions import Node


def generate_launch_description():
    return LaunchDescription([
        Node(package='rviz2', executable='rviz2', arguments=['--ros-args', '--log-level warn']),
    ])
