"""rclpy.timer, simulated: timers fire on the virtual clock (rcl_timer's period arithmetic)."""

import _bras_sim

from .exceptions import InvalidHandle, ROSInterruptException


class Timer:
    def __init__(self, callback, period_ns, node, callback_group=None, clock=None, autostart=True):
        self.callback = callback
        self._period_ns = period_ns
        self._node = node
        self._clock = clock if clock is not None else node.get_clock()
        self._last_call = _bras_sim.now_ns()
        self._next_call = self._last_call + period_ns
        self._canceled = not autostart
        self._destroyed = False
        self.callback_group = callback_group
        self._made_at = _bras_sim.caller()

    @property
    def clock(self):
        return self._clock

    @property
    def timer_period_ns(self):
        return self._period_ns

    @timer_period_ns.setter
    def timer_period_ns(self, value):
        self._period_ns = value
        self.reset()

    def is_canceled(self):
        return self._canceled

    def cancel(self):
        self._canceled = True

    def reset(self):
        self._canceled = False
        self._next_call = _bras_sim.now_ns() + self._period_ns
        if self._node.executor is not None:
            self._node.executor.wake()

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
    """rclpy/timer.py:117-177: ``sleep()`` waits for the rate's timer, which only fires while an
    executor spins the node (in another thread). Without one a real node blocks for ever; the
    stand-in lets the clock move to the next period and counts the sleep (rule BK643)."""

    def __init__(self, timer, *, context):
        self._timer = timer
        self._context = context
        self._is_shutdown = False
        self._is_destroyed = False
        context.on_shutdown(self._on_shutdown)  # timer.py:136

    def _on_shutdown(self):
        self._is_shutdown = True
        self.destroy()

    def destroy(self):
        self._is_destroyed = True
        self._timer.destroy()

    def _presleep(self):
        if self._is_shutdown:
            raise ROSInterruptException()  # timer.py:147-148
        if self._is_destroyed:
            raise RuntimeError('Rate cannot sleep because it has been destroyed')
        if not self._timer.handle:
            self.destroy()
            raise InvalidHandle('Rate cannot sleep because the timer has been destroyed')

    def sleep(self):
        self._presleep()
        from .executors import spinning

        node = self._timer._node
        _bras_sim.wait_until(_bras_sim.now_ns())  # threads started just now get going first
        if not spinning(node):
            _bras_sim.STATE.rate_sleeps += 1
        if not self._context.ok():
            # after Ctrl-C (the context shut down by rclpy's SIGINT handler, which tells no Rate),
            # no executor spins any more: the timer's event is never set (timer.py:175)
            _bras_sim.wait_until(None)
        _bras_sim.advance_to(self._timer._next_call)
        self._timer._called()
        if self._is_shutdown:  # timer.py:162-164
            self.destroy()
            raise ROSInterruptException()
