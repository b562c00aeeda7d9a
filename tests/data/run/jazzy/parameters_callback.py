import rclpy
from rcl_interfaces.msg import SetParametersResult
from rclpy.node import Node
from rclpy.parameter import Parameter
from std_msgs.msg import Float64


class Animation(Node):
    def __init__(self):
        super().__init__('animation_bras')
        self.declare_parameters('', [('amplitude', 0.8), ('frequency', 1.0)])
        self.add_on_set_parameters_callback(self.on_set)
        self.pub = self.create_publisher(Float64, 'amplitude', 10)
        self.create_timer(0.5, self.tick)
        self.ticks = 0

    def on_set(self, parameters):
        for parameter in parameters:
            if parameter.name == 'amplitude' and not 0.0 <= parameter.value <= 1.5:
                return SetParametersResult(successful=False, reason='amplitude out of [0, 1.5]')
        return SetParametersResult(successful=True)

    def tick(self):
        self.ticks += 1
        if self.ticks == 2:
            self.set_parameters([Parameter('amplitude', value=5.0)])  # refused by on_set
        if self.ticks == 3:
            self.set_parameters([Parameter('amplitude', value=1.2)])
        self.pub.publish(Float64(data=self.get_parameter('amplitude').value))


def main():
    rclpy.init()
    rclpy.spin(Animation())
