"""rclpy.clock, simulated: every clock reads the run's virtual clock."""

from _bras_sim import START_NS, now_ns, sleep

from .clock_type import ClockType
from .time import Time


class Clock:
    def __init__(self, *, clock_type=ClockType.SYSTEM_TIME):
        if not isinstance(clock_type, ClockType):
            raise TypeError('Clock type must be a ClockType enum')
        self._clock_type = clock_type

    @property
    def clock_type(self):
        return self._clock_type

    def now(self):
        return Time(nanoseconds=START_NS + now_ns(), clock_type=self._clock_type)

    def sleep_for(self, rel_time):
        sleep(rel_time.nanoseconds / 1e9)
        return True

    def sleep_until(self, until):
        left = until.nanoseconds - (START_NS + now_ns())
        if left > 0:
            sleep(left / 1e9)
        return True

    def __repr__(self):
        return f'Clock(clock_type={self._clock_type.name})'


class ROSClock(Clock):
    def __init__(self):
        super().__init__(clock_type=ClockType.ROS_TIME)

    @property
    def ros_time_is_active(self):
        return False
