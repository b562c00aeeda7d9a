# './' and '..' inside the share folder: the system resolves them, the files open.
import os

from ament_index_python.packages import get_package_share_directory
from launch import LaunchDescription
from launch_ros.actions import Node


def generate_launch_description():
    share = get_package_share_directory('bras_description')
    with open(os.path.join(share, './urdf', 'bras.urdf')) as f:
        description = f.read()
    return LaunchDescription([
        Node(package='robot_state_publisher', executable='robot_state_publisher',
             parameters=[{'robot_description': description}]),
        Node(package='joint_state_publisher_gui', executable='joint_state_publisher_gui'),
        Node(package='rviz2', executable='rviz2',
             arguments=['-d', os.path.join(share, 'launch', '..', 'rviz', 'bras.rviz')]),
    ])
