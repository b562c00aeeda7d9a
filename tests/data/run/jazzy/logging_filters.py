import rclpy
from rclpy.node import Node
from rclpy.time import Time
from sensor_msgs.msg import JointState
from tf2_ros import TransformException
from tf2_ros.buffer import Buffer
from tf2_ros.transform_listener import TransformListener


class Journal(Node):
    def __init__(self):
        super().__init__('journal')
        self.pub = self.create_publisher(JointState, 'joint_states', 10)
        self.buffer = Buffer()
        self.listener = TransformListener(self.buffer, self)
        self.create_timer(0.05, self.tick)
        self.k = 0

    def tick(self):
        self.k += 1
        msg = JointState(name=['epaule', 'coude'], position=[0.5, 0.3])
        msg.header.stamp = self.get_clock().now().to_msg()
        self.pub.publish(msg)
        log = self.get_logger()
        log.info(f'tick {self.k}', once=True)
        log.info(f'every second {self.k}', throttle_duration_sec=1.0)
        log.info(f'after the first {self.k}', skip_first=True, once=True)
        try:
            t = self.buffer.lookup_transform('base', 'avant_bras', Time())
        except TransformException as exc:
            log.warn(str(exc), throttle_duration_sec=1.0)
            return
        log.info(f'avant_bras z={t.transform.translation.z:.6f}', once=True)


def main():
    rclpy.init()
    rclpy.spin(Journal())
