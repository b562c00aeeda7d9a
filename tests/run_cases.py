"""Cases the run tests share: the Jazzy table (one small node per row, each with what rclpy 7.1
and rosidl_python do with it, cited) and the run rules the record's hostile nodes trigger.
tests/run/test_run_jazzy.py runs the table; tests/run/test_run.py checks that every run rule has
a node that triggers it, these included."""

from __future__ import annotations

# (node, how the run ends, exception class or None, findings [(code, line)], the source that decides)
ROWS = [
    # rosidl_generator_py resource/_msg.py.em:440 (no check unless ROS_PYTHON_CHECK_FIELDS=1),
    # :604 array.array('d', value) takes integers, a tuple, a numpy array
    ("positions_any_sequence.py", "duration", None, []),
    # _idl.py.em:10 + _msg.py.em:440-600: with the variable set, the Humble-style assert
    ("check_fields_on.py", "error", "AssertionError", [("BK640", 15)]),
    # rclpy/timer.py:166-177 Rate.sleep waits for the timer rclpy.spin (main thread) runs
    ("worker_thread_rate.py", "returned", None, []),
    # executors.py:868-892 a pool; callback_groups.py:80-90 Reentrant lets the timers overlap
    ("multithreaded_groups.py", "returned", None, []),
    # node.py:390-533, 861-959: declare_parameters; the on-set callback's result decides
    ("parameters_callback.py", "duration", None, [("BK644", None)]),
    # executors.py:786-797 Executor.__enter__/__exit__ (shutdown)
    ("executor_with.py", "returned", None, [("BK644", None)]),
    # executors.py:714-728: the subscription of the node hears its own /joint_states
    ("subscribe_own_joint_states.py", "returned", None, []),
    # signal_handler.cpp:143-144 shutdown_contexts() on SIGINT; context.cpp:161-164 RCLError
    ("shutdown_after_ctrl_c.py", "error", "RCLError", [("BK644", None), ("BK652", 13)]),
    # node.py (jazzy) defines no __enter__: Python's TypeError at the with statement
    ("with_node.py", "error", "TypeError", [("BK652", 12)]),
    # __init__.py:229-246: only spin runs the timers; main() returning ends the program
    ("spin_forgotten.py", "returned", None, [("BK652", 10)]),
    # node.py:314-321 default_callback_group reads _default_callback_group, set by Node.__init__
    ("super_forgotten.py", "error", "AttributeError", [("BK652", 7)]),
    # node.py:1738-1774: timer_period_sec is a period; 20 means every 20 s
    ("timer_in_hertz.py", "duration", None, [("BK652", 10)]),
    # _msg_support.c.em:195: the class of header.stamp is checked by the C conversion at publish
    ("now_without_to_msg.py", "error", "Aborted", [("BK652", 15)]),
    # _msg_support.c.em:496-499: assert(PyLong_Check(field)) for the int32 sec
    ("stamp_float_seconds.py", "error", "Aborted", [("BK652", 17)]),
    # executors.py:366-372: await_or_execute(tmr.callback) calls None
    ("callback_called.py", "error", "TypeError", [("BK652", 10)]),
    # executors.py:366-372: the bound method is called with the node as its only argument
    ("tick_without_self.py", "error", "TypeError", [("BK652", 12)]),
    # importlib.metadata EntryPoint.load: getattr(module, 'main')
    ("no_main.py", "error", "AttributeError", [("BK652", None)]),
    # builtin_interfaces/msg/Time: sec and nanosec; int(time.time()) leaves nanosec at 0
    ("stamp_whole_seconds.py", "duration", None, [("BK652", 11)]),
]

# the run rules tests/trust/test_record_hostile.py's nodes trigger (each asserted there): nodes
# attacking their own record
RECORD_RULES = ("BK657", "BK658")
