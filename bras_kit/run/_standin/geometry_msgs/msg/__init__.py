"""geometry_msgs/msg, simulated (bras-kit run): the basic types."""
from _bras_msgs import message

Vector3 = message("geometry_msgs", "Vector3", [("x", "float64"), ("y", "float64"), ("z", "float64")])
Point = message("geometry_msgs", "Point", [("x", "float64"), ("y", "float64"), ("z", "float64")])
Quaternion = message("geometry_msgs", "Quaternion",
                     [("x", "float64"), ("y", "float64"), ("z", "float64"), ("w", "float64")],
                     defaults={"w": 1.0})
Pose = message("geometry_msgs", "Pose", [("position", "geometry_msgs/Point"),
                                         ("orientation", "geometry_msgs/Quaternion")])
PoseStamped = message("geometry_msgs", "PoseStamped", [("header", "std_msgs/Header"),
                                                       ("pose", "geometry_msgs/Pose")])
Twist = message("geometry_msgs", "Twist", [("linear", "geometry_msgs/Vector3"),
                                           ("angular", "geometry_msgs/Vector3")])
Transform = message("geometry_msgs", "Transform", [("translation", "geometry_msgs/Vector3"),
                                                   ("rotation", "geometry_msgs/Quaternion")])
TransformStamped = message("geometry_msgs", "TransformStamped", [
    ("header", "std_msgs/Header"), ("child_frame_id", "string"), ("transform", "geometry_msgs/Transform")])
PointStamped = message("geometry_msgs", "PointStamped", [("header", "std_msgs/Header"),
                                                         ("point", "geometry_msgs/Point")])


def __getattr__(name):
    from _bras_sim import not_simulated
    raise not_simulated("geometry_msgs.msg", name)
