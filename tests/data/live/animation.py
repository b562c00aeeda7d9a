"""The tutorial's animation node (simuler-bras-ros2, step 6), word for word when run without
options; each option is one of the mistakes learners make with it.

    python animation.py [--names epaule,coude] [--zero-stamps] [--period 0.05] [--use-sim-time]
                        [--scale 1.0] [--name animation_bras] [--stamp-offset 0] [--positions N]
                        [--late SECONDS] [--stamp once|seconds] [--nan JOINT] [--stop-after SECONDS]
                        [--topic joint_states] [--float-array] [--degrees]

``--late`` is the only one that is no learner's mistake: a hidden node (``_``) holds the process's
DDS participant from the start and the node itself comes SECONDS later, as a node whose discovery
a busy computer delays looks to whoever watches the graph.
"""

import argparse
import math
import signal
import time

import rclpy
from rclpy.duration import Duration
from rclpy.node import Node
from rclpy.parameter import Parameter
from sensor_msgs.msg import JointState

parser = argparse.ArgumentParser()
parser.add_argument("--names", default="epaule,coude")
parser.add_argument("--zero-stamps", action="store_true")
parser.add_argument("--period", type=float, default=0.05)
parser.add_argument("--use-sim-time", action="store_true")
parser.add_argument("--scale", type=float, default=1.0, help="multiplies the amplitudes (3: past the limits)")
parser.add_argument("--name", default="animation_bras")
parser.add_argument("--stamp-offset", type=float, default=0.0, help="seconds added to each stamp (a hand-made clock)")
parser.add_argument("--positions", type=int, default=None, help="send only the first N positions")
parser.add_argument("--late", type=float, default=None, help="make the node SECONDS after the participant")
parser.add_argument("--stamp", choices=["now", "once", "seconds"], default="now",
                    help="once: the stamp taken at start and reused; seconds: the clock's seconds only")
parser.add_argument("--nan", default=None, help="this joint's position is NaN")
parser.add_argument("--stop-after", type=float, default=None,
                    help="the callback raises SECONDS after a second reader (the doctor) joined robot_state_publisher")
parser.add_argument("--topic", default="joint_states")
parser.add_argument("--float-array", action="store_true", help="publish Float64MultiArray, not JointState")
parser.add_argument("--degrees", action="store_true", help="positions in degrees")
parser.add_argument("--flood", type=int, default=0,
                    help="a stranger's message: N more names, each 1,000 characters, and N positions")
options = parser.parse_args()


class Animation(Node):
    def __init__(self):
        super().__init__(options.name, parameter_overrides=[
            Parameter("use_sim_time", Parameter.Type.BOOL, options.use_sim_time)])
        if options.float_array:
            from std_msgs.msg import Float64MultiArray
            self.pub = self.create_publisher(Float64MultiArray, options.topic, 10)
        else:
            self.pub = self.create_publisher(JointState, options.topic, 10)
        self.timer = self.create_timer(options.period, self.tick)
        self.t = 0.0
        self.start = self.get_clock().now()
        self.matched = None  # when the doctor's probe became a second reader

    def tick(self):
        self.t += 0.05
        if options.stop_after is not None:
            if self.matched is None and self.pub.get_subscription_count() >= 2:
                self.matched = self.get_clock().now()
            if self.matched is not None and (self.get_clock().now() - self.matched).nanoseconds > options.stop_after * 1e9:
                raise RuntimeError("the learner's bug: the node ends here")
        if options.float_array:
            from std_msgs.msg import Float64MultiArray
            self.pub.publish(Float64MultiArray(data=[0.8 * math.sin(self.t), 1.2 * math.sin(self.t * 0.7)]))
            return
        msg = JointState()
        if not options.zero_stamps:
            now = self.start if options.stamp == "once" else self.get_clock().now()
            msg.header.stamp = (now + Duration(seconds=options.stamp_offset)).to_msg()
            if options.stamp == "seconds":
                msg.header.stamp.nanosec = 0
        msg.name = options.names.split(",")
        # Deux oscillations sinusoïdales déphasées
        msg.position = [options.scale * 0.8 * math.sin(self.t), options.scale * 1.2 * math.sin(self.t * 0.7)]
        if options.degrees:
            msg.position = [math.degrees(v) for v in msg.position]
        if options.positions is not None:
            msg.position = msg.position[:options.positions]
        if options.flood:
            msg.name = list(msg.name) + [f"j{i:05d}" + "x" * 994 for i in range(options.flood)]
            msg.position = (list(msg.position) + [0.0] * options.flood)[:options.positions]
        if options.nan in msg.name:
            msg.position[msg.name.index(options.nan)] = float("nan")
        self.pub.publish(msg)


def main(args=None):
    rclpy.init(args=args)
    # SIGTERM (the test stopping the graph) ends the process at once, as the kernel does by
    # default: rclpy's own handler now and then hangs in its shutdown (seen under load)
    signal.signal(signal.SIGTERM, signal.SIG_DFL)
    if options.late is not None:
        # hidden (ros2 node list and the doctor skip a leading '_'); kept: rmw closes the participant with its last node
        participant = rclpy.create_node("_participant")  # noqa: F841
        print("ready", flush=True)
        time.sleep(options.late)
    noeud = Animation()
    if options.late is None:
        print("ready", flush=True)  # the test starts its look once every node says so
    try:
        rclpy.spin(noeud)
    except (KeyboardInterrupt, rclpy.executors.ExternalShutdownException):
        pass
    except Exception:  # a publish racing the shutdown that Ctrl-C began
        if rclpy.ok():
            raise


if __name__ == '__main__':
    main()
