# The issue's own: xacro.process_file on the installed URDF, .toxml(); RViz's -d names a
# configuration the package does not have (RViz logs it and opens its defaults).
import os

import xacro
from ament_index_python.packages import get_package_share_directory
from launch import LaunchDescription
from launch_ros.actions import Node


def generate_launch_description():
    doc = xacro.process_file(os.path.join(get_package_share_directory('bras_description'), 'urdf', 'bras.urdf'))
    return LaunchDescription([
        Node(package='robot_state_publisher', executable='robot_state_publisher',
             parameters=[{'robot_description': doc.toxml()}]),
        Node(package='joint_state_publisher_gui', executable='joint_state_publisher_gui'),
        Node(package='rviz2', executable='rviz2', name='rviz2',
             arguments=['-d', os.path.join(get_package_share_directory('bras_description'), 'config', 'display.rviz')]),
    ])
