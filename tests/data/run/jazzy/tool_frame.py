import rclpy
from geometry_msgs.msg import TransformStamped
from rclpy.node import Node
from rclpy.time import Time
from sensor_msgs.msg import JointState
from std_msgs.msg import String
from tf2_ros import StaticTransformBroadcaster, TransformException
from tf2_ros.buffer import Buffer
from tf2_ros.transform_listener import TransformListener


class Outil(Node):
    def __init__(self):
        super().__init__('outil')
        self.pub = self.create_publisher(JointState, 'joint_states', 10)
        self.said = self.create_publisher(String, 'outil', 10)
        self.static = StaticTransformBroadcaster(self)
        tool = TransformStamped()
        tool.header.stamp = self.get_clock().now().to_msg()
        tool.header.frame_id = 'avant_bras'
        tool.child_frame_id = 'outil'
        tool.transform.translation.z = 0.5
        self.static.sendTransform(tool)
        self.buffer = Buffer()
        self.listener = TransformListener(self.buffer, self)
        self.create_timer(0.05, self.tick)
        self.create_timer(1.0, self.where)

    def tick(self):
        msg = JointState(name=['epaule', 'coude'], position=[0.5, 0.3])
        msg.header.stamp = self.get_clock().now().to_msg()
        self.pub.publish(msg)

    def where(self):
        try:
            t = self.buffer.lookup_transform('base', 'outil', Time())
        except TransformException as exc:
            self.said.publish(String(data=f'no: {exc}'))
            return
        p = t.transform.translation
        self.said.publish(String(data=f'{p.x:.9f} {p.y:.9f} {p.z:.9f}'))


def main():
    rclpy.init()
    rclpy.spin(Outil())
