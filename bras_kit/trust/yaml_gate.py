"""The one way bras-kit reads YAML it did not write (an ``.rviz``, an exercise set's manifests, a
grade rubric, a bag's ``metadata.yaml``, a launch file's parameters and YAML launch files, a
xacro's ``load_yaml``, ``-p`` values): PyYAML's safe loader, behind bounds it checks first.

PyYAML composes an alias as a second reference to the node it names, so a "billion laughs"
(nine anchors, each a list of ten aliases of the one before) costs nothing to load but a
billion values to any code that walks the result, copies it (merge keys ``<<`` copy their
pairs) or prints it. Before anything is composed, the parser's events are read once (no tree
is built, no recursion) and the document is refused when:

- the text is longer than ``limit`` characters (:data:`MAX_CHARS`);
- its values, counted as if every alias were expanded, are more than :data:`MAX_NODES`
  (a long text counts once per 256 characters: text expanded through aliases is bounded too);
- it nests deeper than :data:`MAX_DEPTH` (PyYAML's composer and constructor recurse per level:
  a few thousand ``[`` would be a RecursionError);
- an alias names the node it is inside of (a structure that contains itself, which a walk
  never finishes).

A value the constructor cannot make (an integer of more than 4,300 digits, a 13th month) is a
:class:`yaml.YAMLError` too, as are the refusals above (:class:`YamlRefused`), so a caller's
``except yaml.YAMLError`` covers them::

    from bras_kit.trust import yaml_gate
    data = yaml_gate.load(text)                  # as yaml.safe_load(text), bounded
    data = yaml_gate.load(text, loader=MyLoader)  # a SafeLoader subclass of the caller's

``tests/trust/test_yaml_gate.py`` fails when any other module of bras_kit calls PyYAML's loaders.
"""

from __future__ import annotations

from typing import Any

import yaml

from ..core.message import M, Message

MAX_CHARS = 8 << 20  # as the one reader's MAX_BYTES: a file bras-kit reads for the learner
MAX_NODES = 100_000  # as xacro_eval's collections, counted through shared anchors
MAX_DEPTH = 100
TEXT_UNIT = 256  # characters of a scalar counted as one more value

# the C parser when PyYAML was built with libyaml (10x faster), its pure-Python twin otherwise
_FAST = getattr(yaml, "CSafeLoader", yaml.SafeLoader)


class YamlRefused(yaml.YAMLError):
    """A YAML text bras-kit does not load: ``kind`` is "size", "nodes", "depth", "recursive" or
    "value"; ``line`` (1-based) where the parser was when it refused, when known; ``message`` the
    words for the learner (``str()`` gives them in English)."""

    def __init__(self, kind: str, message: Message, line: int | None = None) -> None:
        super().__init__(str(message))
        self.kind, self.message, self.line = kind, message, line
        self.problem = str(self)  # as PyYAML's MarkedYAMLError, which callers read for the words
        self.problem_mark = _Mark(line - 1) if line is not None else None


class _Mark:
    def __init__(self, line: int) -> None:
        self.line = line


def check(text: str | bytes, *, limit: int = MAX_CHARS, nodes: int = MAX_NODES, depth: int = MAX_DEPTH,
          loader: Any = None) -> None:
    """Raise :class:`YamlRefused` when ``text`` passes one of the bounds (see the module's
    words), a :class:`yaml.YAMLError` when it is not YAML (in the words of ``loader``'s parser,
    libyaml's by default); nothing is built."""
    if len(text) > limit:
        raise YamlRefused("size", M("the YAML text is longer than {most} MiB", most=limit >> 20) if limit >= 1 << 20
                          else M("the YAML text is longer than {most} characters", most=limit))
    try:
        _count(text, nodes, depth, loader or _FAST)
    except yaml.MarkedYAMLError as exc:
        if "maximum nesting depth" not in str(exc.problem):  # libyaml's own bound (1,000), met scanning ahead
            raise
        raise YamlRefused("depth", M("the YAML nests more than {most} levels deep", most=depth),
                          exc.problem_mark.line + 1 if exc.problem_mark is not None else None) from None


def _count(text: str | bytes, nodes: int, depth: int, loader: Any) -> None:
    sizes: dict[str, int] = {}  # anchor -> its node's size, every alias in it expanded
    open_anchors: set[str] = set()
    stack: list[list[Any]] = [[0, None]]  # [size so far, anchor] of each collection being read
    for event in yaml.parse(text, Loader=loader):  # the parser alone: events, no tree, no recursion
        if isinstance(event, (yaml.MappingStartEvent, yaml.SequenceStartEvent)):
            if len(stack) > depth:
                raise YamlRefused("depth", M("the YAML nests more than {most} levels deep", most=depth),
                                  _line(event))
            stack.append([1, event.anchor])
            if event.anchor is not None:
                open_anchors.add(event.anchor)
            continue
        if isinstance(event, (yaml.MappingEndEvent, yaml.SequenceEndEvent)):
            size, anchor = stack.pop()
            if anchor is not None:
                sizes[anchor] = size
                open_anchors.discard(anchor)
        elif isinstance(event, yaml.ScalarEvent):
            size = 1 + len(event.value) // TEXT_UNIT
            if event.anchor is not None:
                sizes[event.anchor] = size
        elif isinstance(event, yaml.AliasEvent):
            if event.anchor in open_anchors:
                raise YamlRefused("recursive", M("the YAML alias *{anchor} is inside the value it names",
                                                 anchor=str(event.anchor)[:80]), _line(event))
            size = sizes.get(event.anchor, 1)  # an unknown anchor: the loader's own error, later
        else:
            continue
        stack[-1][0] += size
        if stack[-1][0] > nodes:
            raise YamlRefused("nodes", M("the YAML holds more than {most} values once its aliases are expanded",
                                         most=nodes), _line(event))


def load(text: str | bytes, *, loader: Any = None, limit: int = MAX_CHARS, nodes: int = MAX_NODES,
         depth: int = MAX_DEPTH) -> Any:
    """``yaml.load(text, loader)`` (``loader``: a SafeLoader or a subclass; libyaml's when built)
    once :func:`check` has passed it; every failure a :class:`yaml.YAMLError`. Give
    ``loader=yaml.SafeLoader`` where the words of a syntax error must be ``yaml.safe_load``'s
    (the stand-ins: PyYAML's Python parser and libyaml word them differently)."""
    check(text, limit=limit, nodes=nodes, depth=depth, loader=loader)
    try:
        return yaml.load(text, Loader=loader or _FAST)  # noqa: S506 - a SafeLoader, or the caller's subclass of it
    except (ValueError, OverflowError, RecursionError, MemoryError) as exc:
        raise YamlRefused("value", M("a YAML value cannot be read: {reason}", reason=str(exc)[:200])) from None


def compose(text: str | bytes, *, limit: int = MAX_CHARS) -> Any:
    """``yaml.compose`` (the node tree, with each node's place) once :func:`check` has passed it."""
    check(text, limit=limit, loader=yaml.SafeLoader)
    return yaml.compose(text, Loader=yaml.SafeLoader)


def _line(event: Any) -> int | None:
    mark = getattr(event, "start_mark", None)
    return mark.line + 1 if mark is not None else None
