# urdf_tutorial's display.launch.py shape: the model and the RViz configuration as arguments.
from launch import LaunchDescription
from launch.actions import DeclareLaunchArgument
from launch.substitutions import Command, LaunchConfiguration, PathJoinSubstitution
from launch_ros.actions import Node
from launch_ros.parameter_descriptions import ParameterValue
from launch_ros.substitutions import FindPackageShare


def generate_launch_description():
    share = FindPackageShare('bras_description')
    model = DeclareLaunchArgument('model', default_value=PathJoinSubstitution([share, 'urdf', 'bras.urdf.xacro']),
                                  description='Absolute path to the robot URDF file')
    rviz_config = DeclareLaunchArgument('rvizconfig', default_value=PathJoinSubstitution([share, 'rviz', 'bras.rviz']))
    description = ParameterValue(Command(['xacro ', LaunchConfiguration('model')]), value_type=str)
    return LaunchDescription([
        model,
        rviz_config,
        Node(package='robot_state_publisher', executable='robot_state_publisher',
             parameters=[{'robot_description': description}]),
        Node(package='joint_state_publisher_gui', executable='joint_state_publisher_gui'),
        Node(package='rviz2', executable='rviz2', name='rviz2', output='screen',
             arguments=['-d', LaunchConfiguration('rvizconfig')]),
    ])
