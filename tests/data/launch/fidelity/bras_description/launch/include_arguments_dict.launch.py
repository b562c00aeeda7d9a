# launch_arguments given as a dict, not dict.items(): launch unpacks each key into (name, value).
import os

from ament_index_python.packages import get_package_share_directory
from launch import LaunchDescription
from launch.actions import IncludeLaunchDescription
from launch.launch_description_sources import PythonLaunchDescriptionSource


def generate_launch_description():
    share = get_package_share_directory('bras_description')
    return LaunchDescription([
        IncludeLaunchDescription(
            PythonLaunchDescriptionSource(os.path.join(share, 'launch', 'rsp_only.launch.py')),
            launch_arguments={'gui': 'false'}),
    ])
