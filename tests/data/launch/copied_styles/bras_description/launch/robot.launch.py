# included by affichage.launch.py: the robot in the namespace 'bras', its URDF from the share folder
from launch import LaunchDescription
from launch.actions import GroupAction
from launch.substitutions import Command, PathJoinSubstitution
from launch_ros.actions import Node, PushRosNamespace
from launch_ros.parameter_descriptions import ParameterValue
from launch_ros.substitutions import FindPackageShare


def generate_launch_description():
    urdf = PathJoinSubstitution([FindPackageShare('bras_description'), 'urdf', 'bras.urdf'])
    return LaunchDescription([
        GroupAction([
            PushRosNamespace('bras'),
            Node(package='robot_state_publisher', executable='robot_state_publisher',
                 parameters=[{'robot_description': ParameterValue(Command(['cat ', urdf]), value_type=str)}]),
        ]),
    ])
