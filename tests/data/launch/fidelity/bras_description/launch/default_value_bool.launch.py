# A launch argument's default given as a Python bool, not as text.
from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument


def generate_launch_description():
    return LaunchDescription([
        DeclareLaunchArgument('gui', default_value=True),
    ])
