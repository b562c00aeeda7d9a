# A .xacro expanded in the launch file, written out with toprettyxml.
import os

import xacro
from ament_index_python.packages import get_package_share_directory
from launch import LaunchDescription
from launch_ros.actions import Node


def generate_launch_description():
    pkg_path = os.path.join(get_package_share_directory('bras_description'))
    xacro_file = os.path.join(pkg_path, 'urdf', 'bras.urdf.xacro')
    robot_description_config = xacro.process_file(xacro_file)
    params = {'robot_description': robot_description_config.toprettyxml(indent='  '), 'use_sim_time': False}
    return LaunchDescription([
        Node(package='robot_state_publisher', executable='robot_state_publisher', output='screen',
             parameters=[params]),
        Node(package='joint_state_publisher_gui', executable='joint_state_publisher_gui'),
        Node(package='rviz2', executable='rviz2', output='screen'),
    ])
