# parameters= given one dict, not a list of dicts.
import os

from ament_index_python.packages import get_package_share_directory
from launch import LaunchDescription
from launch_ros.actions import Node


def generate_launch_description():
    with open(os.path.join(get_package_share_directory('bras_description'), 'urdf', 'bras.urdf')) as f:
        description = f.read()
    return LaunchDescription([
        Node(package='robot_state_publisher', executable='robot_state_publisher',
             parameters={'robot_description': description}),
    ])
