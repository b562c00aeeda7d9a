# The target's condition is false: it never starts, so what waits for its start never starts either.
from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument, RegisterEventHandler
from launch.conditions import IfCondition
from launch.event_handlers import OnProcessStart
from launch.substitutions import LaunchConfiguration
from launch_ros.actions import Node


def generate_launch_description():
    gui = Node(package='joint_state_publisher_gui', executable='joint_state_publisher_gui',
               condition=IfCondition(LaunchConfiguration('gui')))
    return LaunchDescription([
        DeclareLaunchArgument('gui', default_value='false'),
        gui,
        RegisterEventHandler(OnProcessStart(target_action=gui, on_start=[Node(package='rviz2', executable='rviz2')])),
    ])
