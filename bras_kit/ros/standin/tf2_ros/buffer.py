"""tf2_ros.buffer, simulated (tf2_ros_py/tf2_ros/buffer.py, jazzy)."""

import _bras_sim
from geometry_msgs.msg import TransformStamped

from ._core import NS, STORE, TransformException  # noqa: F401


def _time_ns(time):
    if time is None:
        return 0
    if hasattr(time, 'nanoseconds'):
        return time.nanoseconds
    if hasattr(time, 'sec'):
        return time.sec * NS + time.nanosec
    raise TypeError('time must be a rclpy.time.Time or a builtin_interfaces.msg.Time')


class Buffer:
    """Answers from what was broadcast on /tf and /tf_static and from robot_state_publisher's
    transforms of the robot (the joints of its URDF moved by each /joint_states)."""

    def __init__(self, cache_time=None, node=None):
        self.cache_time = cache_time
        self._node = node

    def set_transform(self, transform, authority):
        _store(transform, False)

    def set_transform_static(self, transform, authority):
        _store(transform, True)

    def lookup_transform(self, target_frame, source_frame, time, timeout=None):
        """buffer.py:133-167: the pose of source_frame in target_frame, as a TransformStamped."""
        t_ns = _time_ns(time)
        (x, y, z), (qx, qy, qz, qw) = STORE.lookup(target_frame, source_frame, t_ns)
        out = TransformStamped()
        out.header.frame_id = target_frame
        out.child_frame_id = source_frame
        stamp = t_ns or (_bras_sim.START_NS + _bras_sim.now_ns())
        out.header.stamp.sec, out.header.stamp.nanosec = divmod(stamp, NS)
        out.transform.translation.x, out.transform.translation.y, out.transform.translation.z = x, y, z
        out.transform.rotation.x, out.transform.rotation.y = qx, qy
        out.transform.rotation.z, out.transform.rotation.w = qz, qw
        return out

    def can_transform(self, target_frame, source_frame, time, timeout=None, return_debug_tuple=False):
        try:
            STORE.lookup(target_frame, source_frame, _time_ns(time))
        except TransformException as exc:
            return (False, str(exc)) if return_debug_tuple else False
        return (True, '') if return_debug_tuple else True

    def all_frames_as_string(self):
        return ''.join(f'Frame {child} exists with parent {STORE.parent_of(child)}.\n'
                       for child in sorted(set(STORE.static) | set(STORE.dynamic)))

    def __getattr__(self, name):
        raise _bras_sim.not_simulated('tf2_ros.Buffer', name)


def _store(transform, static):
    t = transform.transform
    pose = ((t.translation.x, t.translation.y, t.translation.z),
            (t.rotation.x, t.rotation.y, t.rotation.z, t.rotation.w))
    stamp = transform.header.stamp.sec * NS + transform.header.stamp.nanosec
    STORE.set(transform.header.frame_id, transform.child_frame_id, stamp, pose, static)
