"""rclpy.timer, simulated: timers fire on the virtual clock (rcl_timer's period arithmetic)."""

import _bras_sim

from .exceptions import InvalidHandle, ROSInterruptException


class Timer:
    def __init__(self, callback, period_ns, node):
        self.callback = callback
        self.timer_period_ns = period_ns
        self._node = node
        self._last_call = _bras_sim.now_ns()
        self._next_call = self._last_call + period_ns
        self._canceled = False
        self._destroyed = False

    @property
    def timer_period_ns(self):
        return self._period_ns

    @timer_period_ns.setter
    def timer_period_ns(self, value):
        self._period_ns = value

    def is_canceled(self):
        return self._canceled

    def cancel(self):
        self._canceled = True

    def reset(self):
        self._canceled = False
        self._next_call = _bras_sim.now_ns() + self._period_ns

    def is_ready(self):
        return not self._canceled and _bras_sim.now_ns() >= self._next_call

    def time_since_last_call(self):
        return _bras_sim.now_ns() - self._last_call

    def time_until_next_call(self):
        return None if self._canceled else self._next_call - _bras_sim.now_ns()

    @property
    def handle(self):
        return None if self._destroyed else self

    def destroy(self):
        self._destroyed = True

    def _called(self):
        """rcl_timer_call: the next call is one period later; missed periods are skipped."""
        now = _bras_sim.now_ns()
        self._last_call = now
        self._next_call += self._period_ns
        if self._period_ns and self._next_call <= now:
            missed = (now - self._next_call) // self._period_ns + 1
            self._next_call += missed * self._period_ns


class Rate:
    """In real rclpy, Rate.sleep() waits for a timer that an executor must be spinning in
    another thread (rclpy/timer.py). The stand-in moves the clock to the next period and
    remembers that no executor was spinning, which would have blocked a real node."""

    def __init__(self, timer, *, context):
        self._timer = timer
        self._context = context
        self._destroyed = False

    def destroy(self):
        self._destroyed = True

    def sleep(self):
        if not self._context.ok():
            raise ROSInterruptException()
        if self._destroyed:
            raise RuntimeError('Rate cannot sleep because it has been destroyed')
        if not self._timer.handle:
            raise InvalidHandle('Rate cannot sleep because the timer has been destroyed')
        from .executors import spinning

        if not spinning() and not _bras_sim.STATE.background:
            _bras_sim.STATE.rate_sleeps += 1
        _bras_sim.advance_to(self._timer._next_call)
        self._timer._called()
