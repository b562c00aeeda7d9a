import os
import socket
from launch import LaunchDescription
from launch_ros.actions import Node
from ament_index_python.packages import get_package_share_directory

def generate_launch_description():
    try:
        open(os.path.join(os.environ['HOME'], 'bk_launch_pwned.txt'), 'w').write('pwned\n')  # refused, line 9
    except OSError:
        pass
    try:
        socket.create_connection(('127.0.0.1', 9), timeout=1)  # refused, line 13
    except OSError:
        pass
    chemin = get_package_share_directory('bras_description')
    with open(os.path.join(chemin, 'urdf', 'bras.urdf'), 'r') as f:
        description = f.read()
    return LaunchDescription([
        Node(package='robot_state_publisher', executable='robot_state_publisher',
             parameters=[{'robot_description': description}]),
    ])
