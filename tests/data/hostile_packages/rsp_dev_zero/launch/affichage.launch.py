from launch import LaunchDescription
from launch_ros.actions import Node


def generate_launch_description():
    # robot_state_publisher's old fallback: a file name as its first argument
    return LaunchDescription([
        Node(package='robot_state_publisher', executable='robot_state_publisher',
             arguments=['/dev/zero']),
        Node(package='joint_state_publisher_gui', executable='joint_state_publisher_gui'),
    ])
