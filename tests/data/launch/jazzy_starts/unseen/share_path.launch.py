# get_package_share_path (a pathlib.Path), the xacro expanded in the launch file.
import xacro
from ament_index_python.packages import get_package_share_path
from launch import LaunchDescription
from launch_ros.actions import Node


def generate_launch_description():
    share = get_package_share_path('bras_description')
    description = xacro.process_file(str(share / 'urdf' / 'bras.urdf.xacro')).toxml()
    return LaunchDescription([
        Node(package='robot_state_publisher', executable='robot_state_publisher',
             parameters=[{'robot_description': description}]),
        Node(package='joint_state_publisher_gui', executable='joint_state_publisher_gui'),
        Node(package='rviz2', executable='rviz2', arguments=['-d', str(share / 'rviz' / 'bras.rviz')]),
    ])
