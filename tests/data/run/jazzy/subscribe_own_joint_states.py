import rclpy
from rclpy.node import Node
from sensor_msgs.msg import JointState


class Echo(Node):
    def __init__(self):
        super().__init__('echo')
        self.pub = self.create_publisher(JointState, '/joint_states', 10)
        self.create_subscription(JointState, '/joint_states', self.heard, 10)
        self.create_timer(0.5, self.tick)

    def tick(self):
        msg = JointState(name=['epaule', 'coude'], position=[0.1, 0.2])
        msg.header.stamp = self.get_clock().now().to_msg()
        self.pub.publish(msg)

    def heard(self, msg):
        self.get_logger().info(f'heard {list(msg.position)}')


def main():
    rclpy.init()
    node = Echo()
    try:
        rclpy.spin(node)
    except KeyboardInterrupt:
        pass
    node.destroy_node()
    rclpy.try_shutdown()
