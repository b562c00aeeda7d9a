# Paths from the launch file's own folder (share/PKG/launch once installed): '..' back into share.
import os

from launch import LaunchDescription
from launch_ros.actions import Node

HERE = os.path.dirname(os.path.realpath(__file__))


def generate_launch_description():
    with open(os.path.join(HERE, '..', 'urdf', 'bras.urdf')) as f:
        description = f.read()
    return LaunchDescription([
        Node(package='robot_state_publisher', executable='robot_state_publisher',
             parameters=[{'robot_description': description}]),
        Node(package='joint_state_publisher_gui', executable='joint_state_publisher_gui'),
        Node(package='rviz2', executable='rviz2', arguments=['-d', os.path.join(HERE, '..', 'rviz', 'bras.rviz')]),
    ])
