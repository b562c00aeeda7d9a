import math

import rclpy
from rclpy.node import Node
from sensor_msgs.msg import JointState
from std_srvs.srv import SetBool


class Animation(Node):
    def __init__(self):
        super().__init__('animation_bras')
        self.pub = self.create_publisher(JointState, 'joint_states', 10)
        self.srv = self.create_service(SetBool, 'pause', self.on_pause)
        self.timer = self.create_timer(0.05, self.tick)
        self.paused = False
        self.t = 0.0

    def on_pause(self, request, response):
        self.paused = request.data
        response.success = True
        response.message = 'pause' if self.paused else 'reprise'
        return response

    def tick(self):
        if self.paused:
            return
        self.t += 0.05
        msg = JointState()
        msg.header.stamp = self.get_clock().now().to_msg()
        msg.name = ['epaule', 'coude']
        msg.position = [0.8 * math.sin(self.t), 1.2 * math.sin(self.t * 0.7)]
        self.pub.publish(msg)


def main():
    rclpy.init()
    noeud = Animation()
    rclpy.spin(noeud)
    noeud.destroy_node()
    rclpy.shutdown()
