# robot_state_publisher alone: a file meant to be included by another.
import os

from ament_index_python.packages import get_package_share_directory
from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument
from launch_ros.actions import Node


def generate_launch_description():
    with open(os.path.join(get_package_share_directory('bras_description'), 'urdf', 'bras.urdf')) as f:
        description = f.read()
    return LaunchDescription([
        DeclareLaunchArgument('gui', default_value='true'),
        Node(package='robot_state_publisher', executable='robot_state_publisher',
             parameters=[{'robot_description': description}]),
    ])
