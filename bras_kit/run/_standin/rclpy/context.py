"""rclpy.context, simulated (the checks of rclpy/context.py)."""


class Context:
    def __init__(self):
        self._initialized = False
        self._shutdown = False
        self._callbacks = []

    @property
    def handle(self):
        return self if self._initialized else None

    def init(self, args=None, *, initialize_logging=True, domain_id=None):
        if self._initialized:
            raise RuntimeError('Context.init() must only be called once')
        self._initialized = True
        self._shutdown = False

    def ok(self):
        return self._initialized and not self._shutdown

    def shutdown(self):
        if not self._initialized or self._shutdown:
            # rclpy/src/rclpy/context.cpp: ContextAlreadyShutdown / RuntimeError
            raise RuntimeError('Context must be initialized before it can be shutdown'
                               if not self._initialized else 'Context already shutdown.')
        self._shutdown = True
        callbacks, self._callbacks = self._callbacks, []
        for callback in callbacks:
            callback()

    def try_shutdown(self):
        if self._initialized and not self._shutdown:
            self.shutdown()

    def on_shutdown(self, callback):
        if not callable(callback):
            raise TypeError('callback should be a callable, got {}', type(callback))
        self._callbacks.append(callback)

    def get_domain_id(self):
        if not self._initialized:
            raise RuntimeError('Context must be initialized before it can have a domain id')
        return 0


_DEFAULT = Context()


def get_default_context(*, shutting_down=False):
    return _DEFAULT
