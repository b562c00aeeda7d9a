# robot_state_publisher's file argument (deprecated, still works on Jazzy, with a warning)
import os

from ament_index_python.packages import get_package_share_directory
from launch import LaunchDescription
from launch_ros.actions import Node


def generate_launch_description():
    urdf = os.path.join(get_package_share_directory('bras_description'), 'urdf', 'bras.urdf')
    return LaunchDescription([
        Node(package='robot_state_publisher', executable='robot_state_publisher', arguments=[urdf]),
        Node(package='joint_state_publisher_gui', executable='joint_state_publisher_gui'),
    ])
