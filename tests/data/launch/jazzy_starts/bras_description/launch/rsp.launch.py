# Included by include_rsp.launch.py (articubot's rsp.launch.py shape): xacro, use_sim_time.
import os

import xacro
from ament_index_python.packages import get_package_share_directory
from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument
from launch.substitutions import LaunchConfiguration
from launch_ros.actions import Node


def generate_launch_description():
    use_sim_time = LaunchConfiguration('use_sim_time')
    pkg_path = os.path.join(get_package_share_directory('bras_description'))
    robot_description_config = xacro.process_file(os.path.join(pkg_path, 'urdf', 'bras.urdf.xacro'))
    params = {'robot_description': robot_description_config.toxml(), 'use_sim_time': use_sim_time}
    return LaunchDescription([
        DeclareLaunchArgument('use_sim_time', default_value='false', description='Use sim time if true'),
        Node(package='robot_state_publisher', executable='robot_state_publisher', output='screen',
             parameters=[params]),
    ])
