import rclpy
from rclpy.node import Node
from sensor_msgs.msg import JointState


class Animation(Node):
    def __init__(self):
        super().__init__('animation_bras')
        self.pub = self.create_publisher(JointState, 'joint_states', 10)
        self.timer = self.create_timer(0.05, self.tick())

    def tick(self):
        msg = JointState(name=['epaule', 'coude'], position=[0.1, 0.2])
        msg.header.stamp = self.get_clock().now().to_msg()
        self.pub.publish(msg)


def main():
    rclpy.init()
    rclpy.spin(Animation())
