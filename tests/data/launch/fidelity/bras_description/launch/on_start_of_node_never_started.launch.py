# RViz waits for robot_state_publisher to start, but that Node is never put in the description.
import os

from ament_index_python.packages import get_package_share_directory
from launch import LaunchDescription
from launch.actions import RegisterEventHandler
from launch.event_handlers import OnProcessStart
from launch_ros.actions import Node


def generate_launch_description():
    with open(os.path.join(get_package_share_directory('bras_description'), 'urdf', 'bras.urdf')) as f:
        description = f.read()
    rsp = Node(package='robot_state_publisher', executable='robot_state_publisher',
               parameters=[{'robot_description': description}])
    rviz = Node(package='rviz2', executable='rviz2')
    return LaunchDescription([
        Node(package='joint_state_publisher_gui', executable='joint_state_publisher_gui'),
        RegisterEventHandler(OnProcessStart(target_action=rsp, on_start=[rviz])),
    ])
