# RViz started once robot_state_publisher has started (RegisterEventHandler + OnProcessStart).
import os

from ament_index_python.packages import get_package_share_directory
from launch import LaunchDescription
from launch.actions import RegisterEventHandler
from launch.event_handlers import OnProcessStart
from launch_ros.actions import Node


def generate_launch_description():
    share = get_package_share_directory('bras_description')
    with open(os.path.join(share, 'urdf', 'bras.urdf')) as f:
        description = f.read()
    rsp = Node(package='robot_state_publisher', executable='robot_state_publisher',
               parameters=[{'robot_description': description}])
    rviz = Node(package='rviz2', executable='rviz2', arguments=['-d', os.path.join(share, 'rviz', 'bras.rviz')])
    return LaunchDescription([
        rsp,
        Node(package='joint_state_publisher_gui', executable='joint_state_publisher_gui'),
        RegisterEventHandler(OnProcessStart(target_action=rsp, on_start=[rviz])),
    ])
