# The arm in a namespace (GroupAction + PushRosNamespace), its slider with it; no RViz.
import os

from ament_index_python.packages import get_package_share_directory
from launch import LaunchDescription
from launch.actions import GroupAction
from launch_ros.actions import Node, PushRosNamespace


def generate_launch_description():
    urdf = os.path.join(get_package_share_directory('bras_description'), 'urdf', 'bras.urdf')
    with open(urdf) as f:
        description = f.read()
    return LaunchDescription([
        GroupAction([
            PushRosNamespace('bras'),
            Node(package='robot_state_publisher', executable='robot_state_publisher',
                 parameters=[{'robot_description': description}]),
            Node(package='joint_state_publisher_gui', executable='joint_state_publisher_gui'),
        ]),
    ])
