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
        msg = JointState()
        msg.header.stamp = self.get_clock().now().to_msg()
        msg.name = ['epaule', 'coude']
        # Du repos à la cible en 2 s, en ligne droite dans l'espace des articulations
        s = 1.0
        msg.position = [0.7 * s, 1.2 * s]
        self.pub.publish(msg)
        self.t += 0.05

def main(args=None):
    rclpy.init(args=args)
    noeud = Animation()
    rclpy.spin(noeud)
    noeud.destroy_node()
    rclpy.shutdown()

if __name__ == '__main__':
    main()
