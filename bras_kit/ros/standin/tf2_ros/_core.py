"""What tf2's BufferCore keeps (tf2_py, geometry2 jazzy), on the simulated clock: the
transforms broadcast on /tf and /tf_static, and those robot_state_publisher would broadcast
from the robot's joints and each /joint_states the node publishes."""

import math

import _bras_sim

NS = 10**9


class TransformException(Exception):
    pass


class LookupException(TransformException):
    pass


class ConnectivityException(TransformException):
    pass


class ExtrapolationException(TransformException):
    pass


class InvalidArgumentException(TransformException):
    pass


class TimeoutException(TransformException):
    pass


# ---------------------------------------------------------------- rigid transforms as (xyz, quaternion xyzw)


def quat_multiply(a, b):
    ax, ay, az, aw = a
    bx, by, bz, bw = b
    return (aw * bx + ax * bw + ay * bz - az * by, aw * by - ax * bz + ay * bw + az * bx,
            aw * bz + ax * by - ay * bx + az * bw, aw * bw - ax * bx - ay * by - az * bz)


def rotate(q, v):
    x, y, z, w = q
    qv = quat_multiply(quat_multiply(q, (v[0], v[1], v[2], 0.0)), (-x, -y, -z, w))
    return qv[:3]


def compose(a, b):
    """a then b: the pose b (expressed in a's frame) in a's parent frame."""
    (ta, qa), (tb, qb) = a, b
    moved = rotate(qa, tb)
    return (ta[0] + moved[0], ta[1] + moved[1], ta[2] + moved[2]), quat_multiply(qa, qb)


def inverse(a):
    t, (x, y, z, w) = a
    qi = (-x, -y, -z, w)
    back = rotate(qi, t)
    return (-back[0], -back[1], -back[2]), qi


def from_rpy(roll, pitch, yaw):
    cr, sr = math.cos(roll / 2), math.sin(roll / 2)
    cp, sp = math.cos(pitch / 2), math.sin(pitch / 2)
    cy, sy = math.cos(yaw / 2), math.sin(yaw / 2)
    return (sr * cp * cy - cr * sp * sy, cr * sp * cy + sr * cp * sy,
            cr * cp * sy - sr * sp * cy, cr * cp * cy + sr * sp * sy)


def about_axis(axis, angle):
    norm = math.sqrt(sum(a * a for a in axis)) or 1.0
    s = math.sin(angle / 2) / norm
    return axis[0] * s, axis[1] * s, axis[2] * s, math.cos(angle / 2)


def _interpolate(a, b, ratio):
    (ta, qa), (tb, qb) = a, b
    t = tuple(x + (y - x) * ratio for x, y in zip(ta, tb))
    dot = sum(x * y for x, y in zip(qa, qb))
    if dot < 0:
        qb, dot = tuple(-v for v in qb), -dot
    if dot > 0.9995:
        q = tuple(x + (y - x) * ratio for x, y in zip(qa, qb))
    else:
        theta = math.acos(dot)
        wa, wb = math.sin((1 - ratio) * theta) / math.sin(theta), math.sin(ratio * theta) / math.sin(theta)
        q = tuple(wa * x + wb * y for x, y in zip(qa, qb))
    norm = math.sqrt(sum(v * v for v in q))
    return t, tuple(v / norm for v in q)


# ---------------------------------------------------------------- the one store every Buffer reads


class _Store:
    def __init__(self):
        self.static = {}  # child -> (parent, pose)
        self.dynamic = {}  # child -> (parent, [(t_ns, pose)...] in time order)
        self.robot_fed = False

    def set(self, parent, child, t_ns, pose, static):
        if static:
            self.static[child] = (parent, pose)
            return
        history = self.dynamic.setdefault(child, (parent, []))[1]
        self.dynamic[child] = (parent, history)
        if history and history[-1][0] > t_ns:
            history.append((t_ns, pose))
            history.sort(key=lambda item: item[0])
        else:
            history.append((t_ns, pose))

    def parent_of(self, frame):
        if frame in self.static:
            return self.static[frame][0]
        if frame in self.dynamic:
            return self.dynamic[frame][0]
        return None

    def frames(self):
        found = set(self.static) | set(self.dynamic)
        found |= {parent for parent, _ in self.static.values()} | {parent for parent, _ in self.dynamic.values()}
        return found

    def pose(self, frame, t_ns):
        """The pose of ``frame`` in its parent at ``t_ns`` (0: the latest)."""
        if frame in self.static:
            return self.static[frame][1]
        history = self.dynamic[frame][1]
        if t_ns == 0:
            return history[-1][1]
        if t_ns < history[0][0] or t_ns > history[-1][0]:
            if len(history) == 1 and history[0][0] == t_ns:
                return history[0][1]
            raise ExtrapolationException(
                f'Lookup would require extrapolation {"into the past" if t_ns < history[0][0] else "into the future"}.'
                f'  Requested time {t_ns / NS:.6f} but the {"earliest" if t_ns < history[0][0] else "latest"} data '
                f'is at time {(history[0][0] if t_ns < history[0][0] else history[-1][0]) / NS:.6f}, '
                f'when looking up transform from frame [{frame}] to frame [{self.dynamic[frame][0]}]')
        for (t0, p0), (t1, p1) in zip(history, history[1:]):
            if t0 <= t_ns <= t1:
                return p0 if t1 == t0 else _interpolate(p0, p1, (t_ns - t0) / (t1 - t0))
        return history[-1][1]

    def chain(self, frame):
        out = [frame]
        while True:
            parent = self.parent_of(out[-1])
            if parent is None or parent in out:
                return out
            out.append(parent)

    def lookup(self, target, source, t_ns):
        """The pose of ``source`` in ``target`` at ``t_ns`` (tf2's lookupTransform)."""
        frames = self.frames()
        for name, role in ((target, 'target_frame'), (source, 'source_frame')):
            if name not in frames:
                raise LookupException(f'"{name}" passed to lookupTransform argument {role} does not exist. ')
        up_source, up_target = self.chain(source), self.chain(target)
        common = next((f for f in up_source if f in up_target), None)
        if common is None:
            raise ConnectivityException(
                f'Could not find a connection between \'{target}\' and \'{source}\' because they are not part '
                'of the same tree.Tf has two or more unconnected trees.')
        in_common = ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0, 1.0))
        for frame in up_source[:up_source.index(common)]:
            in_common = compose(self.pose(frame, t_ns), in_common)
        target_in_common = ((0.0, 0.0, 0.0), (0.0, 0.0, 0.0, 1.0))
        for frame in up_target[:up_target.index(common)]:
            target_in_common = compose(self.pose(frame, t_ns), target_in_common)
        return compose(inverse(target_in_common), in_common)


STORE = _Store()


def joint_states_published(msg):
    """robot_state_publisher: the robot's fixed joints on /tf_static once, each movable joint
    named in the message on /tf, stamped with the message's header."""
    robot = _bras_sim.STATE.robot
    if not robot:
        return
    stamp = msg.header.stamp.sec * NS + msg.header.stamp.nanosec
    positions = dict(zip(msg.name, msg.position))
    for joint in robot:
        origin = (tuple(joint['xyz']), from_rpy(*joint['rpy']))
        if joint['type'] == 'fixed':
            if not STORE.robot_fed:
                STORE.set(joint['parent'], joint['child'], 0, origin, True)
            continue
        if joint['name'] not in positions:
            continue
        q = float(positions[joint['name']])
        axis = joint['axis']
        if joint['type'] == 'prismatic':
            motion = ((axis[0] * q, axis[1] * q, axis[2] * q), (0.0, 0.0, 0.0, 1.0))
        else:
            motion = ((0.0, 0.0, 0.0), about_axis(axis, q))
        STORE.set(joint['parent'], joint['child'], stamp, compose(origin, motion), False)
    STORE.robot_fed = True
