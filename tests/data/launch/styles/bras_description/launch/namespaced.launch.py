# A robot in a namespace, the included display, a delayed node and an OpaqueFunction.
import os

from ament_index_python.packages import get_package_share_directory
from launch import LaunchDescription
from launch.actions import GroupAction, IncludeLaunchDescription, OpaqueFunction, TimerAction
from launch.launch_description_sources import PythonLaunchDescriptionSource
from launch_ros.actions import Node, PushRosNamespace


def animation(context):
    return [Node(package='bras_description', executable='animation', name='animation_bras')]


def generate_launch_description():
    share = get_package_share_directory('bras_description')
    with open(os.path.join(share, 'urdf', 'bras.urdf')) as f:
        description = f.read()
    display = IncludeLaunchDescription(
        PythonLaunchDescriptionSource(os.path.join(share, 'launch', 'docs_style.launch.py')),
        launch_arguments={'gui': 'false'}.items())
    return LaunchDescription([
        GroupAction([
            PushRosNamespace('bras'),
            Node(package='robot_state_publisher', executable='robot_state_publisher',
                 parameters=[{'robot_description': description}]),
        ]),
        display,
        TimerAction(period=2.0, actions=[OpaqueFunction(function=animation)]),
    ])
