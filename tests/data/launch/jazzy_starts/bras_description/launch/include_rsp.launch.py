# The robot_state_publisher part in a file of its own (rsp.launch.py), included with an argument.
import os

from ament_index_python.packages import get_package_share_directory
from launch import LaunchDescription
from launch.actions import IncludeLaunchDescription
from launch.launch_description_sources import PythonLaunchDescriptionSource
from launch_ros.actions import Node


def generate_launch_description():
    share = get_package_share_directory('bras_description')
    rsp = IncludeLaunchDescription(
        PythonLaunchDescriptionSource([os.path.join(share, 'launch'), '/rsp.launch.py']),
        launch_arguments={'use_sim_time': 'false'}.items())
    return LaunchDescription([
        rsp,
        Node(package='joint_state_publisher_gui', executable='joint_state_publisher_gui'),
        Node(package='rviz2', executable='rviz2', arguments=['-d', os.path.join(share, 'rviz', 'bras.rviz')]),
    ])
