"""Affiche le bras : robot_state_publisher, la fenêtre des curseurs et RViz."""

import os

from ament_index_python.packages import get_package_share_directory
from launch import LaunchDescription
from launch_ros.actions import Node


def generate_launch_description():
    urdf = os.path.join(get_package_share_directory('bras_description'), 'urdf', 'bras.urdf')
    with open(urdf, encoding='utf-8') as lu:
        description = lu.read()  # le texte de l'URDF, pas son chemin
    return LaunchDescription([
        Node(package='robot_state_publisher', executable='robot_state_publisher'),
        Node(package='joint_state_publisher_gui', executable='joint_state_publisher_gui'),
        Node(package='rviz2', executable='rviz2'),
    ])
