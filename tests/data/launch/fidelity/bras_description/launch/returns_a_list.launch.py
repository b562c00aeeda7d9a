# A list of nodes returned where launch expects a LaunchDescription.
from launch_ros.actions import Node


def generate_launch_description():
    return [
        Node(package='joint_state_publisher_gui', executable='joint_state_publisher_gui'),
    ]
