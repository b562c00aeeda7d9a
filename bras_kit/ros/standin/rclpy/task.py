"""rclpy.task, simulated: a Future the simulated executor completes."""


class Future:
    def __init__(self, *, executor=None):
        self._done = False
        self._cancelled = False
        self._result = None
        self._exception = None
        self._callbacks = []

    def done(self):
        return self._done or self._cancelled

    def cancelled(self):
        return self._cancelled

    def cancel(self):
        if not self._done:
            self._cancelled = True
        self._run_callbacks()

    def result(self):
        if self._exception:
            raise self._exception
        return self._result

    def exception(self):
        return self._exception

    def set_result(self, result):
        self._result = result
        self._done = True
        self._run_callbacks()

    def set_exception(self, exception):
        self._exception = exception
        self._done = True
        self._run_callbacks()

    def add_done_callback(self, callback):
        if self.done():
            callback(self)
        else:
            self._callbacks.append(callback)

    def _run_callbacks(self):
        callbacks, self._callbacks = self._callbacks, []
        for callback in callbacks:
            callback(self)
