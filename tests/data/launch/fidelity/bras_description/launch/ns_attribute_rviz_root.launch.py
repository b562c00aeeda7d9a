# namespace='bras' on robot_state_publisher only: /bras/robot_description, RViz reads /robot_description.
import os

from ament_index_python.packages import get_package_share_directory
from launch import LaunchDescription
from launch_ros.actions import Node


def generate_launch_description():
    share = get_package_share_directory('bras_description')
    with open(os.path.join(share, 'urdf', 'bras.urdf')) as f:
        description = f.read()
    return LaunchDescription([
        Node(package='robot_state_publisher', executable='robot_state_publisher', namespace='bras',
             parameters=[{'robot_description': description}]),
        Node(package='joint_state_publisher_gui', executable='joint_state_publisher_gui', namespace='bras'),
        Node(package='rviz2', executable='rviz2', arguments=['-d', os.path.join(share, 'rviz', 'bras.rviz')]),
    ])
