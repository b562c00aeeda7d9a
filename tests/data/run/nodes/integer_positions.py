import rclpy
from rclpy.node import Node
from sensor_msgs.msg import JointState


def main():
    rclpy.init()
    node = Node('arm')
    pub = node.create_publisher(JointState, 'joint_states', 10)
    msg = JointState()
    msg.name = ['epaule', 'coude']
    msg.position = [0, 1]  # integers: Jazzy's setter converts them, array.array('d', [0, 1])
    pub.publish(msg)
