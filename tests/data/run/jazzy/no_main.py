import rclpy
from rclpy.node import Node


class Animation(Node):
    def __init__(self):
        super().__init__('animation_bras')


rclpy.init()
