import os
from ament_index_python.packages import get_package_share_directory
from launch import LaunchDescription
from launch.actions import IncludeLaunchDescription
from launch.launch_description_sources import PythonLaunchDescriptionSource
from launch_ros.actions import Node


def generate_launch_description():
    affichage = os.path.join(get_package_share_directory('bras_description'), 'launch', 'affichage.launch.py')
    return LaunchDescription([
        IncludeLaunchDescription(PythonLaunchDescriptionSource(affichage)),
        Node(package='cellule_bringup', executable='pilote'),
    ])
