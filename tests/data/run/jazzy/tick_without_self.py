import rclpy
from rclpy.node import Node
from sensor_msgs.msg import JointState


class Animation(Node):
    def __init__(self):
        super().__init__('animation_bras')
        self.pub = self.create_publisher(JointState, 'joint_states', 10)
        self.timer = self.create_timer(0.05, self.tick)

    def tick():
        pass


def main():
    rclpy.init()
    rclpy.spin(Animation())
