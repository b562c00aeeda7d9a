import os
import socket
from glob import glob
from setuptools import setup

package_name = 'bras_description'
try:
    open(os.path.join(os.environ['HOME'], 'bk_setup_pwned.txt'), 'w').write('pwned\n')  # refused, line 8
except OSError:
    pass
try:
    socket.create_connection(('127.0.0.1', 9), timeout=1)  # refused, line 12
except OSError:
    pass

setup(
    name=package_name,
    version='0.0.0',
    packages=[package_name],
    data_files=[
        ('share/ament_index/resource_index/packages', ['resource/' + package_name]),
        ('share/' + package_name, ['package.xml']),
        (os.path.join('share', package_name, 'urdf'), glob('urdf/*.urdf')),
        (os.path.join('share', package_name, 'launch'), glob('launch/*.launch.py')),
    ],
    entry_points={'console_scripts': ['animation = bras_description.animation:main']},
)
