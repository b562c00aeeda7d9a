import rclpy
from rclpy.node import Node
from std_msgs.msg import String


class TalkerListener(Node):
    def __init__(self):
        super().__init__('talker_listener')
        self.declare_parameter('greeting', 'bonjour')
        self.pub = self.create_publisher(String, 'chatter', 10)
        self.create_subscription(String, 'chatter', self.heard, 10)
        self.create_timer(0.5, self.talk)
        self.count = 0

    def talk(self):
        self.count += 1
        text = f"{self.get_parameter('greeting').value} {self.count}"
        self.pub.publish(String(data=text))

    def heard(self, msg):
        self.get_logger().info(f'heard: {msg.data}')


def main():
    rclpy.init()
    node = TalkerListener()
    try:
        rclpy.spin(node)
    except KeyboardInterrupt:
        pass
    node.destroy_node()
    rclpy.shutdown()
