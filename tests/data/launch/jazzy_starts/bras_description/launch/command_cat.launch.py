# The plain URDF through Command(['cat ', ...]), kept as text by ParameterValue.
import os

from ament_index_python.packages import get_package_share_directory
from launch import LaunchDescription
from launch.substitutions import Command
from launch_ros.actions import Node
from launch_ros.parameter_descriptions import ParameterValue


def generate_launch_description():
    urdf = os.path.join(get_package_share_directory('bras_description'), 'urdf', 'bras.urdf')
    return LaunchDescription([
        Node(package='robot_state_publisher', executable='robot_state_publisher',
             parameters=[{'robot_description': ParameterValue(Command(['cat ', urdf]), value_type=str)}]),
        Node(package='joint_state_publisher_gui', executable='joint_state_publisher_gui'),
    ])
