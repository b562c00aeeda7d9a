# ParameterValue without value_type: the xacro output is read with YAML rules, as in XML without type="str".
import os

from ament_index_python.packages import get_package_share_directory
from launch import LaunchDescription
from launch.substitutions import Command
from launch_ros.actions import Node
from launch_ros.parameter_descriptions import ParameterValue


def generate_launch_description():
    xacro_file = os.path.join(get_package_share_directory('bras_description'), 'urdf', 'bras_commente.urdf.xacro')
    description = ParameterValue(Command(['xacro ', xacro_file]))
    return LaunchDescription([
        Node(package='robot_state_publisher', executable='robot_state_publisher',
             parameters=[{'robot_description': description}]),
        Node(package='joint_state_publisher_gui', executable='joint_state_publisher_gui'),
    ])
