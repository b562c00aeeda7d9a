import rclpy
from rclpy.node import Node
from sensor_msgs.msg import JointState


class Arm(Node):
    def __init__(self):
        super().__init__('arm')
        self.pub = self.create_publisher(JointState, 'joint_states', 10)
        self.create_timer(0.05, self.tick)

    def tick(self):
        for _ in range(3):  # three messages per tick
            msg = JointState()
            msg.header.stamp = self.get_clock().now().to_msg()
            msg.name = ['epaule', 'coude']
            msg.position = [0.1, 0.2]
            self.pub.publish(msg)


def main():
    rclpy.init()
    rclpy.spin(Arm())
