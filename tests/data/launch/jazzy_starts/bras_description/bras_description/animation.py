import rclpy
from rclpy.node import Node
from sensor_msgs.msg import JointState
import math

class Animation(Node):
    def __init__(self):
        super().__init__('animation_bras')
        self.pub = self.create_publisher(JointState, 'joint_states', 10)
        self.timer = self.create_timer(0.05, self.tick)
        self.t = 0.0

    def tick(self):
        self.t += 0.05
        msg = JointState()
        msg.header.stamp = self.get_clock().now().to_msg()
        msg.name = ['epaule', 'coude']
        # Deux oscillations sinusoïdales déphasées
        msg.position = [0.8 * math.sin(self.t), 1.2 * math.sin(self.t * 0.7)]
        self.pub.publish(msg)

def main(args=None):
    rclpy.init(args=args)
    noeud = Animation()
    rclpy.spin(noeud)
    noeud.destroy_node()
    rclpy.shutdown()

if __name__ == '__main__':
    main()
