class Shutdown:
    def __init__(self, *, reason: str = 'reason not given') -> None:
        self.reason = reason


def matches_action(target_action):
    return target_action
