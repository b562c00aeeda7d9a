# The function is named otherwise: ros2 launch finds no generate_launch_description().
from launch import LaunchDescription
from launch_ros.actions import Node


def generer():
    return LaunchDescription([Node(package='joint_state_publisher_gui', executable='joint_state_publisher_gui')])
