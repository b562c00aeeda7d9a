# '--log-level warn' as one list item: rcl sees one unknown ROS argument and the node dies.
from launch import LaunchDescription
from launch_ros.actions import Node


def generate_launch_description():
    return LaunchDescription([
        Node(package='joint_state_publisher_gui', executable='joint_state_publisher_gui',
             ros_arguments=['--log-level warn']),
        Node(package='rviz2', executable='rviz2', ros_arguments=['--log-level', 'warn']),
    ])
