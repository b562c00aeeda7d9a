# Command with its parts apart (['xacro', ' ', path]) and a namespace on every node (namespace=).
from launch import LaunchDescription
from launch.substitutions import Command, PathJoinSubstitution
from launch_ros.actions import Node
from launch_ros.parameter_descriptions import ParameterValue
from launch_ros.substitutions import FindPackageShare


def generate_launch_description():
    xacro_file = PathJoinSubstitution([FindPackageShare('bras_description'), 'urdf', 'bras.urdf.xacro'])
    description = ParameterValue(Command(['xacro', ' ', xacro_file]), value_type=str)
    return LaunchDescription([
        Node(package='robot_state_publisher', executable='robot_state_publisher', namespace='bras',
             parameters=[{'robot_description': description}]),
        Node(package='joint_state_publisher_gui', executable='joint_state_publisher_gui', namespace='bras'),
    ])
