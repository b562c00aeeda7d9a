from .._actions import *  # noqa: F403
from .._actions import __all__  # noqa: F401
