# OpaqueFunction: the argument read with perform(context), the file opened then.
import os

from ament_index_python.packages import get_package_share_directory
from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument, OpaqueFunction
from launch.substitutions import LaunchConfiguration
from launch_ros.actions import Node


def launch_setup(context, *args, **kwargs):
    name = LaunchConfiguration('urdf_file').perform(context)
    path = os.path.join(get_package_share_directory('bras_description'), 'urdf', name)
    with open(path) as f:
        description = f.read()
    return [
        Node(package='robot_state_publisher', executable='robot_state_publisher',
             parameters=[{'robot_description': description}]),
        Node(package='joint_state_publisher_gui', executable='joint_state_publisher_gui'),
    ]


def generate_launch_description():
    return LaunchDescription([
        DeclareLaunchArgument('urdf_file', default_value='bras.urdf'),
        OpaqueFunction(function=launch_setup),
    ])
