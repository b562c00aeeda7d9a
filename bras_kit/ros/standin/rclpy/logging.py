"""rclpy.logging, simulated: a logger records each line with the simulated time."""

import enum

import _bras_sim


class LoggingSeverity(enum.IntEnum):
    UNSET = 0
    DEBUG = 10
    INFO = 20
    WARN = 30
    ERROR = 40
    FATAL = 50


class RcutilsLogger:
    def __init__(self, name=''):
        self.name = name
        self._level = LoggingSeverity.INFO
        self._once = set()

    def get_child(self, name):
        return RcutilsLogger(f'{self.name}.{name}' if self.name else name)

    def set_level(self, level):
        self._level = LoggingSeverity(level)

    def get_effective_level(self):
        return self._level

    def is_enabled_for(self, severity):
        return LoggingSeverity(severity) >= self._level

    def log(self, message, severity, **kwargs):
        if not isinstance(message, str):
            raise TypeError(
                'log(): incompatible function arguments. The message must be a str, not '
                f'{type(message).__name__}')
        severity = LoggingSeverity(severity)
        if kwargs.get('once'):
            key = (message, severity)
            if key in self._once:
                return False
            self._once.add(key)
        if severity < self._level:
            return False
        _bras_sim.log(severity.name, self.name, message)
        return True

    def debug(self, message, **kwargs):
        return self.log(message, LoggingSeverity.DEBUG, **kwargs)

    def info(self, message, **kwargs):
        return self.log(message, LoggingSeverity.INFO, **kwargs)

    def warning(self, message, **kwargs):
        return self.log(message, LoggingSeverity.WARN, **kwargs)

    warn = warning

    def error(self, message, **kwargs):
        return self.log(message, LoggingSeverity.ERROR, **kwargs)

    def fatal(self, message, **kwargs):
        return self.log(message, LoggingSeverity.FATAL, **kwargs)


def get_logger(name):
    return RcutilsLogger(name)
