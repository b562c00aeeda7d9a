"""ROS names as rcl (Jazzy, 9.2) makes them: ``--ros-args`` parsed, topic names expanded and remapped.

Pure functions, no import beyond the standard library: the parent (the launch rules) and the
child's stand-in (rclpy, launch_ros) use the same ones.

* :func:`parse_ros_arguments` — rcl/src/rcl/arguments.c ``rcl_parse_arguments`` (lines 320-640):
  the flags it knows, what it keeps (remap rules, ``-p`` overrides, the log level) and what it
  leaves unparsed, which rclpy (utils.cpp:277) and rclcpp (exceptions.hpp:199) raise as
  ``UnknownROSArgsError``.
* :func:`expand_topic_name` — rcl/src/rcl/expand_topic_name.c: ``~`` (line 99), ``{node}``,
  ``{ns}``/``{namespace}`` (lines 39-41), a relative name under the namespace (line 198).
* :func:`remap_topic_name` — rcl/src/rcl/remap.c ``rcl_remap_name`` (line 167): the node's own
  rules first, then the global ones; the first rule whose expanded match equals the expanded name
  wins (``rcl_remap_first_match``, line 104), a ``node:`` prefix limits a rule to that node (line 121).
"""

from __future__ import annotations

from dataclasses import dataclass, field

ROS_ARGS = "--ros-args"  # rcl/include/rcl/arguments.h:42
END = "--"  # arguments.h:45
# the flags that take the next argument as their value (arguments.h:48-75)
VALUE_FLAGS = {
    "--param": "param", "-p": "param", "--remap": "remap", "-r": "remap", "--params-file": "params_file",
    "--enclave": "enclave", "-e": "enclave", "--log-level": "log_level", "--log-file-name": "log_file_name",
    "--log-config-file": "log_config_file",
}
# --enable-X / --disable-X, without a value (arguments.h:79-87, _rcl_parse_disabling_flag)
SWITCHES = tuple(f"--{way}-{what}" for way in ("enable", "disable")
                 for what in ("stdout-logs", "rosout-logs", "external-lib-logs"))
LOG_LEVELS = ("unset", "debug", "info", "warn", "error", "fatal")  # rcutils_logging_severity_level_from_string


class InvalidROSArgs(ValueError):
    """rcl_parse_arguments returned RCL_RET_INVALID_ROS_ARGS (a flag whose value is wrong or missing)."""


@dataclass(frozen=True)
class RemapRule:
    """One ``--remap``/``-r`` rule (rcl_remap_t): ``match:=replacement``, for one node or all."""

    match: str
    replacement: str
    node: str | None = None  # "node:from:=to" applies to that node only

    @property
    def kind(self) -> str:
        """rcl's rule types: __node, __ns, or a topic/service name."""
        return {"__node": "node", "__name": "node", "__ns": "namespace"}.get(self.match, "topic")


@dataclass
class ROSArguments:
    """A command line's ROS arguments, parsed as rcl parses them (rcl_arguments_t)."""

    remaps: list[RemapRule] = field(default_factory=list)
    parameters: list[tuple[str, str]] = field(default_factory=list)  # -p NAME:=VALUE, in order
    params_files: list[str] = field(default_factory=list)
    log_levels: list[str] = field(default_factory=list)
    unknown: list[str] = field(default_factory=list)  # unparsed ROS arguments: UnknownROSArgsError
    others: list[str] = field(default_factory=list)  # arguments outside --ros-args, the program's own


def parse_remap_rule(text: str) -> RemapRule | None:
    """_rcl_parse_remap_rule (arguments.c:48): ``[node:]from:=to``, both sides non-empty."""
    if ":=" not in text:
        return None
    left, _, right = text.partition(":=")
    node = None
    if ":" in left:
        node, _, left = left.partition(":")
        if not node:
            return None
    if not left or not right:
        return None
    return RemapRule(left, right, node)


def _log_level_ok(text: str) -> bool:
    name, sep, level = text.rpartition(":=")
    return (level if sep else text).lower() in LOG_LEVELS and (not sep or bool(name))


def parse_ros_arguments(argv: list[str]) -> ROSArguments:
    """What rcl keeps of ``argv`` (without the program's name), as rcl_parse_arguments reads it."""
    out = ROSArguments()
    ros = False
    k = 0
    while k < len(argv):
        word = argv[k]
        if not ros:
            if word == ROS_ARGS:
                ros = True
            else:
                rule = parse_remap_rule(word)  # the deprecated form, outside --ros-args (arguments.c:621)
                (out.remaps.append(rule) if rule is not None else out.others.append(word))
            k += 1
            continue
        if word == ROS_ARGS:
            k += 1
            continue
        if word == END:
            ros = False
            k += 1
            continue
        kind = VALUE_FLAGS.get(word)
        if kind is not None:
            if k + 1 >= len(argv):
                raise InvalidROSArgs(f"Couldn't parse trailing {word} flag. No {kind.replace('_', ' ')} provided.")
            value = argv[k + 1]
            if kind == "remap":
                rule = parse_remap_rule(value)
                if rule is None:
                    raise InvalidROSArgs(f"Couldn't parse remap rule: '{word} {value}'.")
                out.remaps.append(rule)
            elif kind == "param":
                if ":=" not in value or value.startswith(":="):
                    raise InvalidROSArgs(f"Couldn't parse parameter override rule: '{word} {value}'.")
                name, _, text = value.partition(":=")
                out.parameters.append((name, text))
            elif kind == "params_file":
                out.params_files.append(value)
            elif kind == "log_level":
                if not _log_level_ok(value):
                    raise InvalidROSArgs(f"Couldn't parse log level rule: '{word} {value}'.")
                out.log_levels.append(value)
            k += 2
            continue
        if word not in SWITCHES:
            out.unknown.append(word)  # arguments.c:608: "an unknown ROS specific argument"
        k += 1
    return out


def unknown_ros_args_error(unknown: list[str], *, cpp: bool) -> str:
    """The words each client library dies with: rclcpp exceptions.hpp:199-201, rclpy utils.cpp:277."""
    if cpp:
        return "found unknown ROS arguments: '" + "', '".join(unknown) + "'"
    return repr(unknown)


def expand_topic_name(name: str, node_name: str, namespace: str) -> str:
    """rcl_expand_topic_name for a valid name: the fully qualified name."""
    namespace = namespace or "/"
    base = namespace.rstrip("/")
    for token, value in (("{node}", node_name), ("{ns}", namespace), ("{namespace}", namespace)):
        name = name.replace(token, value)
    if name.startswith("~"):
        name = base + "/" + node_name + name[1:]
    if not name.startswith("/"):
        name = base + "/" + name
    return name


def resolve_topic_name(name: str, node_name: str, namespace: str, local: list[RemapRule],
                       global_rules: list[RemapRule] = ()) -> str:  # type: ignore[assignment]
    """rcl_node_resolve_name: expanded, then the first matching remap rule's replacement, expanded."""
    expanded = expand_topic_name(name, node_name, namespace)
    for rules in (local, global_rules):
        for rule in rules:
            if rule.kind != "topic" or (rule.node is not None and rule.node != node_name):
                continue
            if expand_topic_name(rule.match, node_name, namespace) == expanded:
                return expand_topic_name(rule.replacement, node_name, namespace)
    return expanded


def node_identity(name: str, namespace: str, local: list[RemapRule],
                  global_rules: list[RemapRule] = ()) -> tuple[str, str]:  # type: ignore[assignment]
    """The node's name and namespace after ``__node:=`` / ``__ns:=`` (rcl_remap_node_name, remap.c:294;
    rcl_remap_node_namespace, remap.c:314): local rules first, the first that applies wins."""
    found: dict[str, str] = {}
    for rules in (local, global_rules):
        for rule in rules:
            if rule.kind in found or rule.kind == "topic" or (rule.node is not None and rule.node != name):
                continue
            found[rule.kind] = rule.replacement
    return found.get("node", name), found.get("namespace", namespace or "/")


NODE_NAME_MAX = 255  # rmw/include/rmw/validate_node_name.h: RMW_NODE_NAME_MAX_NAME_LENGTH
TOPIC_NAME_MAX = 255 - 8  # rmw/include/rmw/validate_full_topic_name.h: RMW_TOPIC_MAX_NAME_LENGTH


def is_node_name(text: object) -> bool:
    """rmw_validate_node_name: ASCII letters, digits and '_', not starting with a digit, 1 to 255 long."""
    return (isinstance(text, str) and 0 < len(text) <= NODE_NAME_MAX and text.isascii() and not text[0].isdigit()
            and all(c.isalnum() or c == "_" for c in text))


def is_full_topic_name(text: object) -> bool:
    """rmw_validate_full_topic_name: absolute ('/' first), not ending in '/', no '//', every token
    ASCII letters, digits and '_' not starting with a digit, at most 247 characters."""
    if not (isinstance(text, str) and 1 < len(text) <= TOPIC_NAME_MAX and text.startswith("/")):
        return False
    return all(token and is_node_name(token) for token in text[1:].split("/"))


def is_interface_type(text: object) -> bool:
    """A message type as rosidl names it: ``package/msg/Name`` (package: lower case, digits, '_')."""
    if not isinstance(text, str) or len(text) > NODE_NAME_MAX or text.count("/") != 2:
        return False
    package, kind, name = text.split("/")
    return (kind in ("msg", "srv", "action") and is_node_name(package) and package == package.lower()
            and is_node_name(name) and name[0].isupper())
