# The tutorial's way: os.path.join in the share folder, the URDF read with open().read().
import os

from ament_index_python.packages import get_package_share_directory
from launch import LaunchDescription
from launch_ros.actions import Node


def generate_launch_description():
    share = get_package_share_directory('bras_description')
    with open(os.path.join(share, 'urdf', 'bras.urdf'), 'r') as f:
        robot_desc = f.read()
    return LaunchDescription([
        Node(package='robot_state_publisher', executable='robot_state_publisher', output='screen',
             parameters=[{'robot_description': robot_desc}]),
        Node(package='joint_state_publisher_gui', executable='joint_state_publisher_gui'),
        Node(package='rviz2', executable='rviz2', arguments=['-d', os.path.join(share, 'rviz', 'bras.rviz')]),
    ])
