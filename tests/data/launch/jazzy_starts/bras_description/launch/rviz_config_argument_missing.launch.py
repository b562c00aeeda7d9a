# RViz's configuration as an argument whose default the package does not have (RViz opens its defaults).
from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument
from launch.substitutions import Command, LaunchConfiguration, PathJoinSubstitution
from launch_ros.actions import Node
from launch_ros.parameter_descriptions import ParameterValue
from launch_ros.substitutions import FindPackageShare


def generate_launch_description():
    share = FindPackageShare('bras_description')
    return LaunchDescription([
        DeclareLaunchArgument('rvizconfig', default_value=PathJoinSubstitution([share, 'rviz', 'urdf.rviz'])),
        Node(package='robot_state_publisher', executable='robot_state_publisher',
             parameters=[{'robot_description': ParameterValue(
                 Command(['xacro ', PathJoinSubstitution([share, 'urdf', 'bras.urdf.xacro'])]), value_type=str)}]),
        Node(package='joint_state_publisher_gui', executable='joint_state_publisher_gui'),
        Node(package='rviz2', executable='rviz2', arguments=['-d', LaunchConfiguration('rvizconfig')]),
    ])
