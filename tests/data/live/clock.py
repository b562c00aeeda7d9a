"""A /clock publisher in the real rclpy (what a simulator or ``ros2 bag play --clock`` does)."""

import signal
import time

import rclpy
from builtin_interfaces.msg import Time
from rosgraph_msgs.msg import Clock

rclpy.init()
# SIGTERM (the test stopping the graph) ends the process at once, as the kernel does by
# default: rclpy's own handler now and then hangs in its shutdown (seen under load)
signal.signal(signal.SIGTERM, signal.SIG_DFL)
node = rclpy.create_node("horloge")
publisher = node.create_publisher(Clock, "clock", 10)
start = time.time()


def tick():
    now = time.time() - start + 1000.0
    publisher.publish(Clock(clock=Time(sec=int(now), nanosec=int((now % 1) * 1e9))))


node.create_timer(0.01, tick)
print("ready", flush=True)  # the test starts its look once every node says so
try:
    rclpy.spin(node)
except (KeyboardInterrupt, rclpy.executors.ExternalShutdownException):
    pass
except Exception:  # a publish racing the shutdown that Ctrl-C began
    if rclpy.ok():
        raise
