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
        self.t += 0.05
        msg = JointState()
        msg.header.stamp = self.get_clock().now().to_msg()
        msg.name = ['epaule', 'coude']
        # Une pose fixe : la pointe en (0.8375, 0, 0.5806)
        msg.position = [0.6, 0.9]
        self.pub.publish(msg)


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
