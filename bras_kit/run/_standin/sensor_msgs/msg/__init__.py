"""sensor_msgs/msg, simulated (bras-kit run): JointState only."""
from _bras_msgs import message

JointState = message("sensor_msgs", "JointState", [
    ("header", "std_msgs/Header"), ("name", "string[]"), ("position", "float64[]"),
    ("velocity", "float64[]"), ("effort", "float64[]")])


def __getattr__(name):
    from _bras_sim import not_simulated
    raise not_simulated("sensor_msgs.msg", name)
