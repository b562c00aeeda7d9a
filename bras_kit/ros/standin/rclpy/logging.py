"""rclpy.logging, simulated: a logger records each line with the simulated time."""

import enum
import sys

import _bras_sim


class LoggingSeverity(enum.IntEnum):
    UNSET = 0
    DEBUG = 10
    INFO = 20
    WARN = 30
    ERROR = 40
    FATAL = 50


# rclpy/impl/rcutils_logger.py (7.1): the filters a call may ask for, in the order they are
# applied (supported_filters, lines 172-176), with their parameters and defaults (None: required)
_FILTERS = {
    'throttle': {'throttle_duration_sec': None, 'throttle_time_source_type': None},  # default: Clock()
    'skip_first': {'skip_first': None},
    'once': {'once': None},
}


def _caller():
    """The learner's call site (rcutils_logger.py CallerId, lines 54-66): function, file, line and
    instruction, so two calls on one line keep their own filters."""
    frame = sys._getframe(1)
    while frame is not None and frame.f_code.co_filename == __file__:
        frame = frame.f_back
    if frame is None:
        return ('', '', 0, 0)
    return (frame.f_code.co_name, frame.f_code.co_filename, frame.f_lineno, frame.f_lasti)


def _filters_asked(kwargs):
    """get_filters_from_kwargs (lines 179-211): a filter is on when one of its parameters is
    truthy; a required one left out and an unknown keyword are TypeErrors, in rclpy's words."""
    asked = [name for name, params in _FILTERS.items() if any(kwargs.get(p) for p in params)]
    for name in asked:
        for param in _FILTERS[name]:
            if param in kwargs:
                continue
            if param == 'throttle_time_source_type':
                from .clock import Clock

                kwargs[param] = Clock()
                continue
            raise TypeError(f'required parameter "{param}" not specified '
                            f'but is required for the the logging filter "{name}"')
    known = [p for params in _FILTERS.values() for p in params]
    for kwarg in kwargs:
        if kwarg not in known:
            raise TypeError(f'parameter "{kwarg}" is not one of the recognized logging options "{known}"')
    return asked


def _should_log(name, context):
    """Each filter's should_log (lines 97-170): whether to log, the filter's state moved on."""
    if name == 'throttle':
        now = context['throttle_time_source_type'].now().nanoseconds
        if now >= context['throttle_last_logged'] + context['throttle_duration_sec'] * 1e9:
            context['throttle_last_logged'] = now
            return True
        return False
    flag = {'skip_first': 'first_has_been_skipped', 'once': 'has_been_logged_once'}[name]
    done = context[flag]
    context[flag] = True
    return done if name == 'skip_first' else not done


class RcutilsLogger:
    def __init__(self, name=''):
        self.name = name
        self._level = LoggingSeverity.INFO
        self.contexts = {}  # call site -> its filters' state (rcutils_logger.py line 219)

    def get_child(self, name):
        return RcutilsLogger(f'{self.name}.{name}' if self.name else name)

    def set_level(self, level):
        self._level = LoggingSeverity(level)

    def get_effective_level(self):
        return self._level

    def is_enabled_for(self, severity):
        return LoggingSeverity(severity) >= self._level

    def log(self, message, severity, **kwargs):
        """RcutilsLogger.log (lines 255-335): the level first, then the call site's filters."""
        if not self.is_enabled_for(severity):
            return False
        severity = LoggingSeverity(severity)
        name = kwargs.pop('name', self.name)
        asked = _filters_asked(kwargs)
        site = _caller()
        context = self.contexts.get(site)
        if context is None:
            context = {'name': name, 'severity': severity, 'filters': asked}
            for param in (p for f in asked for p in _FILTERS[f]):
                context[param] = kwargs[param]
            context.update(throttle_last_logged=0, first_has_been_skipped=False, has_been_logged_once=False)
            if 'throttle' in asked and type(context['throttle_time_source_type']).__name__ not in (
                    'Clock', 'ROSClock'):
                raise ValueError(f'Received throttle_time_source_type of "{context["throttle_time_source_type"]}" '
                                 'is not a clock instance')
            self.contexts[site] = context
        else:
            if severity != context['severity']:
                raise ValueError('Logger severity cannot be changed between calls.')
            if name != context['name']:
                raise ValueError('Logger name cannot be changed between calls.')
            if asked != context['filters']:
                raise ValueError('Requested logging filters cannot be changed between calls.')
            if any(context[p] != kwargs.get(p) for f in asked for p in _FILTERS[f]
                   if p != 'throttle_time_source_type'):
                raise ValueError('Logging filter parameters cannot be changed between calls.')
        for logging_filter in asked:  # the first filter that says no stops the others (line 325)
            if not _should_log(logging_filter, context):
                return False
        if not isinstance(message, str):
            raise TypeError(
                'log(): incompatible function arguments. The message must be a str, not '
                f'{type(message).__name__}')
        _bras_sim.log(severity.name, name, message)
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
