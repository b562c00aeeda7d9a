"""rclpy.executors, simulated on the virtual clock (rclpy/executors.py, jazzy).

An executor waits (the running thread parks on the simulated clock) until a timer of its
nodes is due or a message reaches one of their subscriptions, then hands out the callbacks
ready at that moment in rclpy's order: node by node, timers then subscriptions
(executors.py:714-728). SingleThreadedExecutor runs each in the spinning thread
(executors.py:805-824); MultiThreadedExecutor gives it to a pool of simulated threads and lets
the callback groups decide what may overlap (executors.py:868-892), so a callback that sleeps
lets the others run, the same way on every run.
"""

import os
import types

import _bras_sim

from .callback_groups import MutuallyExclusiveCallbackGroup
from .context import get_default_context

POLL_NS = 100_000  # a wait of timeout 0 that finds nothing still takes a little time (0.1 ms)


class ExternalShutdownException(Exception):
    """Context has been shutdown."""


class ShutdownException(Exception):
    """Signal that executor was shut down."""


class TimeoutException(Exception):
    """Signal that a timeout occurred."""


class ConditionReachedException(Exception):
    """Future has been completed."""


def _all_nodes():
    return [node for node in _bras_sim.STATE.nodes if not node._destroyed]


def subscriptions_on(topic):
    return [s for node in _all_nodes() for s in node._subscriptions_list if s.topic == topic and not s._destroyed]


def deliver(topic, msg_type, msg):
    """A published message reaches every subscription on the topic (same type), as DDS would on
    one machine; the executors spinning those nodes wake."""
    for subscription in subscriptions_on(topic):
        if subscription.msg_type is msg_type:
            depth = getattr(subscription.qos_profile, 'depth', 0) or 0
            subscription.queue.append(msg)
            if depth and len(subscription.queue) > depth:
                del subscription.queue[0]
            executor = subscription._node.executor
            if executor is not None:
                executor.wake()


def spinning(node):
    """Whether an executor is spinning ``node`` (so a Rate of the node gets its timer)."""
    return any(executor._spinning and node in executor._nodes for executor in _EXECUTORS)


_EXECUTORS: list = []


class _Handler:
    """One callback taken from its timer or subscription, ready to run."""

    def __init__(self, entity, node, call):
        self.entity = entity
        self.node = node
        self.call = call
        self.exception = None
        self.done = False

    def run(self):
        group = self.entity.callback_group
        try:
            self.call()
        except (_bras_sim.DurationReached, _bras_sim.RunStopped, _bras_sim.PublishStorm,
                _bras_sim.NotSimulated, _bras_sim.Aborted):
            raise
        except Exception as exc:  # noqa: BLE001 - the learner's, re-raised by spin (executors.py:820-824)
            _mark(exc, self.entity)
            self.exception = exc
        finally:
            group.ending_execution(self.entity)
            self.done = True


def _mark(exc, entity):
    """Remember which callback raised, where it was made and where its def is (for the finding)."""
    callback = getattr(entity, 'callback', None)
    code = getattr(getattr(callback, '__func__', callback), '__code__', None)
    exc._bras_callback = {
        'kind': type(entity).__name__.lower(),
        'name': getattr(callback, '__qualname__', repr(callback)),
        'def_path': code.co_filename if code else '', 'def_line': code.co_firstlineno if code else 0,
        'made_path': entity._made_at[0], 'made_line': entity._made_at[1],
        'bound': isinstance(callback, types.MethodType),
    }


class Executor:
    def __init__(self, *, context=None):
        self._context = get_default_context() if context is None else context
        self._nodes = []
        self._is_shutdown = False
        self._ready = []  # callbacks ready at the last wait, handed out one per spin_once (_cb_iter)
        self._waiters = []
        self._spinning = False
        self._context.on_shutdown(self.wake)
        _EXECUTORS.append(self)

    @property
    def context(self):
        return self._context

    def add_node(self, node):
        if node not in self._nodes:
            self._nodes.append(node)
            node.executor = self
            self.wake()
            return True
        return False

    def remove_node(self, node):
        if node in self._nodes:
            self._nodes.remove(node)
            self.wake()

    def get_nodes(self):
        return list(self._nodes)

    def wake(self):
        for thread in self._waiters:
            _bras_sim.notify(thread)

    def shutdown(self, timeout_sec=None):
        if not self._is_shutdown:
            self._is_shutdown = True
            self.wake()
        self._nodes = []
        return True

    def create_task(self, callback, *args, **kwargs):
        raise _bras_sim.NotSimulated('rclpy.executors.Executor.create_task')

    # ---------------------------------------------------------------- waiting

    def _collect(self):
        """The callbacks ready now, in rclpy's order (executors.py:714-728)."""
        now = _bras_sim.now_ns()
        ready = []
        for node in list(self._nodes):
            if node._destroyed:
                # rclpy 7.1.6 executors.py:600-606: a destroyed node has no entities left to wait
                # on (destroy_node emptied them), so spin waits for nothing until Ctrl-C (the real
                # rclpy, tests/ros/test_rclpy_oracle.py: run/nodes/spin_destroyed.py)
                continue
            for timer in node._timers_list:
                if (not getattr(timer, '_rate', False) and not timer._canceled and not timer._destroyed
                        and timer._next_call <= now and timer.callback_group.can_execute(timer)):
                    ready.append((timer, node))
            for subscription in node._subscriptions_list:
                if (subscription.queue and not subscription._destroyed
                        and subscription.callback_group.can_execute(subscription)):
                    ready.append((subscription, node))
        return ready

    def _next_due(self):
        calls = [t._next_call for node in self._nodes if not node._destroyed for t in node._timers_list
                 if not getattr(t, '_rate', False) and not t._canceled and not t._destroyed]
        return min(calls) if calls else None

    def _take(self, entity, node):
        """Take the callback (the timer is called, the message taken) if its group lets it begin."""
        if not entity.callback_group.beginning_execution(entity):
            return None
        if hasattr(entity, 'queue'):
            if not entity.queue:
                entity.callback_group.ending_execution(entity)
                return None
            msg = entity.queue.pop(0)
            return _Handler(entity, node, lambda: entity.callback(msg))
        if entity._next_call > _bras_sim.now_ns() or entity._canceled:
            entity.callback_group.ending_execution(entity)
            return None
        entity._called()  # executors.py:369 call_timer(): the next call is one period later
        return _Handler(entity, node, entity.callback)

    def wait_for_ready_callbacks(self, timeout_sec=None, nodes=None, condition=lambda: False):
        """The next callback to run, waiting on the simulated clock for one to be ready."""
        start = _bras_sim.now_ns()
        deadline = None if timeout_sec is None or timeout_sec < 0 else start + int(timeout_sec * 1e9)
        while True:
            if self._is_shutdown:
                raise ShutdownException()
            if not self._context.ok():
                raise ExternalShutdownException()  # executors.py:685-689
            if condition():
                raise ConditionReachedException()
            while self._ready:
                entity, node = self._ready.pop(0)
                handler = self._take(entity, node)
                if handler is not None:
                    return handler, entity, node
            self._ready = self._collect()
            if self._ready:
                continue
            if deadline is not None and _bras_sim.now_ns() >= deadline:
                if timeout_sec == 0 and _bras_sim.now_ns() == start:
                    # a poll takes a little time, so a loop of spin_once(timeout_sec=0) sees its timers come due
                    _bras_sim.advance_to(start + POLL_NS)
                raise TimeoutException()
            due = self._next_due()
            wake_at = min(t for t in (due, deadline) if t is not None) if (due, deadline) != (None, None) else None
            me = _bras_sim.current()
            self._waiters.append(me)
            self._spinning = True
            try:
                _bras_sim.wait_until(wake_at)
            finally:
                self._waiters.remove(me)
                self._spinning = bool(self._waiters)

    # ---------------------------------------------------------------- spinning

    def spin(self):
        """executors.py:305-308."""
        while self._context.ok() and not self._is_shutdown:
            self.spin_once()

    def spin_until_future_complete(self, future, timeout_sec=None):
        future.add_done_callback(lambda x: self.wake())
        if timeout_sec is None or timeout_sec < 0:
            while self._context.ok() and not future.done() and not self._is_shutdown:
                self.spin_once_until_future_complete(future, timeout_sec)
            return
        end = _bras_sim.now_ns() + int(timeout_sec * 1e9)
        while self._context.ok() and not future.done() and not self._is_shutdown:
            left = (end - _bras_sim.now_ns()) / 1e9
            if left <= 0:
                return
            self.spin_once_until_future_complete(future, left)

    def spin_once(self, timeout_sec=None):
        self._spin_once_impl(timeout_sec)

    def spin_once_until_future_complete(self, future, timeout_sec=None):
        future.add_done_callback(lambda x: self.wake())
        self._spin_once_impl(timeout_sec, future.done)

    def __enter__(self):
        return self  # executors.py:786-788

    def __exit__(self, exc_type, exc_val, exc_tb):
        self.shutdown()  # executors.py:790-797


class SingleThreadedExecutor(Executor):
    """executors.py:799-824: the callback runs in the thread that spins; an exception in it
    leaves spin (an ExternalShutdownException from the wait is not caught here)."""

    def _spin_once_impl(self, timeout_sec=None, wait_condition=lambda: False):
        try:
            handler, entity, node = self.wait_for_ready_callbacks(timeout_sec, None, wait_condition)
        except (ShutdownException, TimeoutException, ConditionReachedException):
            pass
        else:
            handler.run()
            if handler.exception is not None:
                raise handler.exception


class MultiThreadedExecutor(Executor):
    """executors.py:838-892: callbacks go to a pool of ``num_threads`` threads; an exception in
    one is raised by a later spin_once (executors.py:891-896)."""

    def __init__(self, num_threads=None, *, context=None):
        super().__init__(context=context)
        if num_threads is None:
            num_threads = len(os.sched_getaffinity(0)) if hasattr(os, 'sched_getaffinity') else os.cpu_count()
            num_threads = num_threads or 2
        if num_threads == 1:
            import warnings

            warnings.warn('MultiThreadedExecutor is used with a single thread.\n'
                          'Use the SingleThreadedExecutor instead.', stacklevel=2)
        self._num_threads = num_threads
        self._queue = []
        self._workers = []
        self._idle = []
        self._futures = []

    def _spin_once_impl(self, timeout_sec=None, wait_condition=lambda: False):
        try:
            handler, entity, node = self.wait_for_ready_callbacks(timeout_sec, None, wait_condition)
        except (ExternalShutdownException, ShutdownException, TimeoutException, ConditionReachedException):
            pass
        else:
            self._submit(handler)
        for future in self._futures[:]:
            if future.done:
                self._futures.remove(future)
                if future.exception is not None:
                    raise future.exception

    def _submit(self, handler):
        self._queue.append(handler)
        self._futures.append(handler)
        if self._idle:
            _bras_sim.notify(self._idle[0])
        elif len(self._workers) < self._num_threads:
            self._workers.append(_bras_sim.start_worker(f'ThreadPoolExecutor-{id(self) % 100}_{len(self._workers)}',
                                                        self._work))

    def _work(self):
        me = _bras_sim.current()
        while True:
            if not self._queue:
                self._idle.append(me)
                try:
                    _bras_sim.wait_until(None)
                finally:
                    self._idle.remove(me)
                continue
            handler = self._queue.pop(0)
            handler.run()
            self.wake()  # the group is free again: the executor may hand out what it held back


def __getattr__(name):
    raise _bras_sim.not_simulated('rclpy.executors', name)


__all__ = ['Executor', 'SingleThreadedExecutor', 'MultiThreadedExecutor', 'ExternalShutdownException',
           'ShutdownException', 'TimeoutException', 'MutuallyExclusiveCallbackGroup']
