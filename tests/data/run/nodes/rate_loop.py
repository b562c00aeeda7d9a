import rclpy
from rclpy.node import Node
from sensor_msgs.msg import JointState


def main():
    rclpy.init()
    node = Node('arm')
    pub = node.create_publisher(JointState, 'joint_states', 10)
    rate = node.create_rate(20)
    while rclpy.ok():
        msg = JointState()
        msg.header.stamp = node.get_clock().now().to_msg()
        msg.name = ['epaule', 'coude']
        msg.position = [0.1, 0.2]
        pub.publish(msg)
        rate.sleep()  # real rclpy: blocks forever, no executor spins the rate's timer
