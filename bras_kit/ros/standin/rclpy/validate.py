"""Name rules of rcl/rmw (rmw/src/validate_node_name.c, rcl/src/rcl/validate_topic_name.c),
checked the way rclpy.validate_node_name / validate_topic_name report them."""

import re

from .exceptions import InvalidNodeNameException, InvalidTopicNameException

NODE_NAME_MAX = 255


def validate_node_name(name):
    if not isinstance(name, str):
        raise TypeError(f"node name must be a str, not {type(name).__name__}")
    if name == '':
        raise InvalidNodeNameException(name, 'node name must not be empty', 0)
    for index, char in enumerate(name):
        if not (char.isascii() and (char.isalnum() or char == '_')):
            raise InvalidNodeNameException(
                name, "node name must not contain characters other than alphanumerics or '_'", index)
    if name[0].isdigit():
        raise InvalidNodeNameException(name, 'node name must not start with a number', 0)
    if len(name) > NODE_NAME_MAX:
        raise InvalidNodeNameException(name, 'node name length should not exceed 255', NODE_NAME_MAX - 1)
    return True


def validate_topic_name(name):
    if not isinstance(name, str):
        raise TypeError(f"topic name must be a str, not {type(name).__name__}")
    if name == '':
        raise InvalidTopicNameException(name, 'topic name must not be empty string', 0)
    if name.endswith('/'):
        raise InvalidTopicNameException(name, 'topic name must not end with a forward slash', len(name) - 1)
    depth = 0
    for index, char in enumerate(name):
        if char == '{':
            depth += 1
        elif char == '}':
            depth -= 1
            if depth < 0:
                raise InvalidTopicNameException(
                    name, "topic name must not have unmatched (unbalanced) curly braces '{}'", index)
        elif not (char.isascii() and (char.isalnum() or char in '_/~')):
            raise InvalidTopicNameException(
                name, "topic name must not contain characters other than alphanumerics, '_', '~', '{', or '}'",
                index)
        elif char == '~' and index != 0:
            raise InvalidTopicNameException(
                name, "topic name must not have tilde '~' unless it is the first character", index)
    if depth:
        raise InvalidTopicNameException(
            name, "topic name must not have unmatched (unbalanced) curly braces '{}'", len(name) - 1)
    if name.startswith('~') and len(name) > 1 and name[1] != '/':
        raise InvalidTopicNameException(
            name, "topic name must not have a tilde '~' that is not followed by a forward slash", 1)
    for match in re.finditer(r'(?:^|/)(\d)', name):
        raise InvalidTopicNameException(name, 'topic name token must not start with a number', match.start(1))
    if '//' in name:
        raise InvalidTopicNameException(name, "topic name must not contain repeated '/'", name.index('//') + 1)
    return True


def expand_topic_name(name, node_name, namespace):
    """rcl_expand_topic_name: '~' is the node's private namespace; relative names join the namespace."""
    if name.startswith('~'):
        base = namespace.rstrip('/') + '/' + node_name
        return base + name[1:]
    if name.startswith('/'):
        return name
    return namespace.rstrip('/') + '/' + name


def validate_parameter_name(name):
    """rclpy/validate_parameter_name.py: only an empty name is refused."""
    if not name:
        from .exceptions import InvalidParameterException

        raise InvalidParameterException(name)
    return True
