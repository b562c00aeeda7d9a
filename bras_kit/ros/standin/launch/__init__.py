"""Stand-in for ros2/launch (Jazzy): the part launch files use, in its shape (see _core.py)."""

from . import (
    actions,
    conditions,
    event_handlers,
    events,
    launch_description_sources,
    substitutions,
    utilities,
)
from ._core import (
    Action,
    Condition,
    LaunchContext,
    LaunchDescription,
    LaunchDescriptionEntity,
    Substitution,
)
from ._handlers import EventHandler
from ._sources import LaunchDescriptionSource

SomeSubstitutionsType = object
SomeActionsType = object
SomeSubstitutionsType_types_tuple = (str,)
SomeActionsType_types_tuple = (LaunchDescriptionEntity,)


class LaunchService:
    """Running a launch description outside ``ros2 launch`` is not simulated."""

    def __init__(self, *args, **kwargs):
        import _bras_sim

        raise _bras_sim.NotSimulated("launch.LaunchService")


__all__ = ["Action", "Condition", "EventHandler", "LaunchContext", "LaunchDescription", "LaunchDescriptionEntity",
           "LaunchDescriptionSource", "LaunchService", "SomeActionsType", "SomeSubstitutionsType", "Substitution",
           "actions", "conditions", "event_handlers", "events", "launch_description_sources", "substitutions",
           "utilities"]
