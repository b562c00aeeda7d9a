# Substitutions all the way: FindPackageShare, PathJoinSubstitution, Command(['xacro ', ...]).
from launch import LaunchDescription
from launch.substitutions import Command, PathJoinSubstitution
from launch_ros.actions import Node
from launch_ros.parameter_descriptions import ParameterValue
from launch_ros.substitutions import FindPackageShare


def generate_launch_description():
    pkg = FindPackageShare('bras_description')
    urdf = PathJoinSubstitution([pkg, 'urdf', 'bras.urdf.xacro'])
    rviz = PathJoinSubstitution([pkg, 'rviz', 'bras.rviz'])
    return LaunchDescription([
        Node(package='robot_state_publisher', executable='robot_state_publisher',
             parameters=[{'robot_description': ParameterValue(Command(['xacro ', urdf]), value_type=str)}]),
        Node(package='joint_state_publisher_gui', executable='joint_state_publisher_gui'),
        Node(package='rviz2', executable='rviz2', arguments=['-d', rviz]),
    ])
