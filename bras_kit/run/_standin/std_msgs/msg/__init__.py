"""std_msgs/msg, simulated (bras-kit run)."""
from _bras_msgs import message

Header = message("std_msgs", "Header", [("stamp", "builtin_interfaces/Time"), ("frame_id", "string")])
String = message("std_msgs", "String", [("data", "string")])
Bool = message("std_msgs", "Bool", [("data", "bool")])
Float64 = message("std_msgs", "Float64", [("data", "float64")])
Float32 = message("std_msgs", "Float32", [("data", "float32")])
Int32 = message("std_msgs", "Int32", [("data", "int32")])
Int64 = message("std_msgs", "Int64", [("data", "int64")])
Empty = message("std_msgs", "Empty", [])
Float64MultiArray = message("std_msgs", "Float64MultiArray", [("data", "float64[]")])


def __getattr__(name):
    from _bras_sim import not_simulated
    raise not_simulated("std_msgs.msg", name)
