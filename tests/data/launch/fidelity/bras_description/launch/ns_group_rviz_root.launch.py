# robot_state_publisher pushed into /bras: it publishes /bras/robot_description, and RViz's
# configuration still reads /robot_description (the root topic): the arm is not drawn.
import os

from ament_index_python.packages import get_package_share_directory
from launch import LaunchDescription
from launch.actions import GroupAction
from launch_ros.actions import Node, PushRosNamespace


def generate_launch_description():
    share = get_package_share_directory('bras_description')
    with open(os.path.join(share, 'urdf', 'bras.urdf')) as f:
        description = f.read()
    return LaunchDescription([
        GroupAction([
            PushRosNamespace('bras'),
            Node(package='robot_state_publisher', executable='robot_state_publisher',
                 parameters=[{'robot_description': description}]),
            Node(package='joint_state_publisher_gui', executable='joint_state_publisher_gui'),
        ]),
        Node(package='rviz2', executable='rviz2', arguments=['-d', os.path.join(share, 'rviz', 'bras.rviz')]),
    ])
