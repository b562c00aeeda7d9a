"""builtin_interfaces/msg, simulated (bras-kit run)."""
from _bras_msgs import message

Time = message("builtin_interfaces", "Time", [("sec", "int32"), ("nanosec", "uint32")])
Duration = message("builtin_interfaces", "Duration", [("sec", "int32"), ("nanosec", "uint32")])
