# The package's own node instead of the slider (the tutorial's step 7), named and on screen.
import os

from ament_index_python.packages import get_package_share_directory
from launch import LaunchDescription
from launch_ros.actions import Node


def generate_launch_description():
    share = get_package_share_directory('bras_description')
    with open(os.path.join(share, 'urdf', 'bras.urdf')) as f:
        description = f.read()
    return LaunchDescription([
        Node(package='robot_state_publisher', executable='robot_state_publisher', name='robot_state_publisher',
             output='screen', emulate_tty=True, parameters=[{'robot_description': description}]),
        Node(package='bras_description', executable='animation', name='animation', output='screen'),
        Node(package='rviz2', executable='rviz2', arguments=['-d', os.path.join(share, 'rviz', 'bras.rviz')]),
    ])
