# The description is built but never returned.
from launch import LaunchDescription
from launch_ros.actions import Node


def generate_launch_description():
    LaunchDescription([
        Node(package='joint_state_publisher_gui', executable='joint_state_publisher_gui'),
    ])
