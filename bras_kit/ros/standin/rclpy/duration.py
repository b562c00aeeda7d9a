"""rclpy.duration, simulated (the arithmetic of rclpy/duration.py)."""

from builtin_interfaces.msg import Duration as DurationMsg

S_TO_NS = 10**9


class Duration:
    def __init__(self, *, seconds=0, nanoseconds=0):
        total = int(seconds * S_TO_NS) + int(nanoseconds)
        if not -(2**63) <= total < 2**63:
            raise OverflowError('Total nanoseconds value is too large to store in C duration.')
        self._nanoseconds = total

    @property
    def nanoseconds(self):
        return self._nanoseconds

    def to_msg(self):
        return DurationMsg(sec=self._nanoseconds // S_TO_NS, nanosec=self._nanoseconds % S_TO_NS)

    @classmethod
    def from_msg(cls, msg):
        if not isinstance(msg, DurationMsg):
            raise TypeError('Must pass a builtin_interfaces.msg.Duration object')
        return cls(seconds=msg.sec, nanoseconds=msg.nanosec)

    def __repr__(self):
        return f'Duration(nanoseconds={self._nanoseconds})'

    def __eq__(self, other):
        if isinstance(other, Duration):
            return self._nanoseconds == other._nanoseconds
        return NotImplemented

    def __lt__(self, other):
        if isinstance(other, Duration):
            return self._nanoseconds < other._nanoseconds
        return NotImplemented

    def __le__(self, other):
        return self == other or self < other

    def __gt__(self, other):
        if isinstance(other, Duration):
            return self._nanoseconds > other._nanoseconds
        return NotImplemented

    def __ge__(self, other):
        return self == other or self > other

    def __hash__(self):
        return hash(self._nanoseconds)
