import rclpy
from rclpy.node import Node
from sensor_msgs.msg import JointState


class Animation(Node):
    def __init__(self):
        self.pub = self.create_publisher(JointState, 'joint_states', 10)


def main():
    rclpy.init()
    rclpy.spin(Animation())
