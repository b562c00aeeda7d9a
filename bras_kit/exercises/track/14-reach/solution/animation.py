"""Anime le bras : un JointState publié à chaque tic d'un timer."""

import math

import rclpy
from rclpy.node import Node
from sensor_msgs.msg import JointState


class BrasAnime(Node):
    """Un publisher de JointState et un timer qui le nourrit."""

    def __init__(self):
        super().__init__('animation_bras')
        self.pub = self.create_publisher(JointState, 'joint_states', 10)
        self.timer = self.create_timer(0.05, self.tick)
        self.t = 0.0  # secondes depuis le départ, un pas par tic

    def tick(self):
        msg = JointState()
        msg.header.stamp = self.get_clock().now().to_msg()
        msg.name = ['epaule', 'coude']
        # Du repos à la cible en 2 s, en ligne droite dans l'espace des articulations
        s = min(1.0, self.t / 2.0)
        msg.position = [0.7 * s, 1.2 * s]
        self.pub.publish(msg)
        self.t += 0.05


def main(args=None):
    rclpy.init(args=args)
    bras = BrasAnime()
    try:
        rclpy.spin(bras)
    except KeyboardInterrupt:
        pass  # Ctrl-C : rclpy a déjà arrêté son contexte
    bras.destroy_node()
    rclpy.try_shutdown()


if __name__ == '__main__':
    main()
