"""rclpy.executors, simulated: one thread, the virtual clock, callbacks in time order.

``spin_once`` runs one ready callback: first a message waiting for a subscription, then the
timer due soonest (the clock jumps to it). With nothing left to wait for, the clock runs to
the end of the run, which stops the node like Ctrl-C stops ``ros2 run``.
"""

import _bras_sim

from .context import get_default_context
from .exceptions import InvalidHandle

_SPINNING = [0]
POLL_NS = 100_000  # 0.1 ms


def spinning():
    return _SPINNING[0] > 0


class ExternalShutdownException(Exception):
    """Context has been shutdown."""


class ShutdownException(Exception):
    """Signal that executor was shut down."""


def _all_nodes():
    return [node for node in _bras_sim.STATE.nodes if not node._destroyed]


def subscriptions_on(topic):
    return [s for node in _all_nodes() for s in node._subscriptions_list if s.topic == topic and not s._destroyed]


def deliver(topic, msg_type, msg):
    for subscription in subscriptions_on(topic):
        if subscription.msg_type is msg_type:
            depth = getattr(subscription.qos_profile, 'depth', 0) or 0
            subscription.queue.append(msg)
            if depth and len(subscription.queue) > depth:
                del subscription.queue[0]


class Executor:
    def __init__(self, *, context=None):
        self._context = get_default_context() if context is None else context
        self._nodes = []
        self._is_shutdown = False

    @property
    def context(self):
        return self._context

    def add_node(self, node):
        if node not in self._nodes:
            self._nodes.append(node)
            node.executor = self
            return True
        return False

    def remove_node(self, node):
        if node in self._nodes:
            self._nodes.remove(node)

    def get_nodes(self):
        return list(self._nodes)

    def shutdown(self, timeout_sec=None):
        self._is_shutdown = True
        self._nodes = []
        return True

    def _check(self):
        if not self._context.ok():
            raise ExternalShutdownException()
        for node in self._nodes:
            if node._destroyed:
                # rclpy/src/rclpy/destroyable.cpp
                raise InvalidHandle('cannot use Destroyable because destruction was requested')

    def spin_once(self, timeout_sec=None):
        self._check()
        _SPINNING[0] += 1
        try:
            self._spin_once(timeout_sec)
        finally:
            _SPINNING[0] -= 1

    def _spin_once(self, timeout_sec):
        for node in list(self._nodes):
            for subscription in node._subscriptions_list:
                if subscription.queue and not subscription._destroyed:
                    msg = subscription.queue.pop(0)
                    subscription.callback(msg)
                    return
        timers = [t for node in self._nodes for t in node._timers_list if not t._canceled and not t._destroyed]
        now = _bras_sim.now_ns()
        limit = None if timeout_sec is None or timeout_sec < 0 else now + int(timeout_sec * 1e9)
        if timers:
            timer = min(timers, key=lambda t: t._next_call)
            if limit is None or timer._next_call <= limit:
                _bras_sim.advance_to(timer._next_call)
                timer._called()
                timer.callback()
                return
        if limit is None:
            _bras_sim.idle()
        # a poll that finds nothing still takes a little real time; without it a loop of
        # spin_once(timeout_sec=0) would never see its timers come due
        _bras_sim.advance_to(max(limit, now + POLL_NS))

    def _run_due(self, until_ns):
        """One callback due by ``until_ns`` (a message waiting, else the soonest timer), run as the
        spinning thread would; False when none is due."""
        if self._is_shutdown or not self._context.ok():
            return False
        for node in list(self._nodes):
            for subscription in node._subscriptions_list:
                if subscription.queue and not subscription._destroyed:
                    subscription.callback(subscription.queue.pop(0))
                    return True
        timers = [t for node in self._nodes if not node._destroyed
                  for t in node._timers_list if not t._canceled and not t._destroyed and t.callback is not None]
        if not timers:
            return False
        timer = min(timers, key=lambda t: t._next_call)
        if timer._next_call > until_ns:
            return False
        _bras_sim.set_now(timer._next_call)
        timer._called()
        timer.callback()
        return True

    def spin(self):
        while self._context.ok() and not self._is_shutdown:
            self.spin_once()

    def spin_until_future_complete(self, future, timeout_sec=None):
        end = None if timeout_sec is None or timeout_sec < 0 else _bras_sim.now_ns() + int(timeout_sec * 1e9)
        while self._context.ok() and not future.done():
            if end is not None and _bras_sim.now_ns() >= end:
                return
            left = None if end is None else (end - _bras_sim.now_ns()) / 1e9
            self.spin_once(timeout_sec=left)

    def spin_once_until_future_complete(self, future, timeout_sec=None):
        self.spin_once(timeout_sec)


class SingleThreadedExecutor(Executor):
    pass


def __getattr__(name):
    raise _bras_sim.not_simulated('rclpy.executors', name)
