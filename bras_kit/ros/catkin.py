"""package.xml as catkin_pkg reads it for colcon-ros: accepted or not, and what colcon takes from it.

colcon-ros identifies a ROS package only when catkin_pkg parses its package.xml
(colcon_ros/package_identification/ros.py, _get_package, lines 172-201 of colcon-ros 0.5.0): a
manifest catkin_pkg refuses (``InvalidPackage``) is passed over without a word on the terminal,
and colcon-python-setup-py then builds the folder as a plain Python package, named by setup.py.
The conditions of format 3 (``condition="$ROS_VERSION == 2"``) are evaluated against the
environment colcon runs in (ros.py, lines 196-200), and a dependency whose condition is false is
left out of the run dependencies (_enumerate_dependency_descriptors, lines 216-222).

What is checked here is catkin_pkg 1.1.1's (catkin_pkg/package.py: parse_package_string, lines
597-786, and Package.validate, lines 229-330); :func:`refusal` gives its first words.
"""

from __future__ import annotations

import operator
import os
import re
from collections.abc import Mapping
from dataclasses import dataclass

from ..model.xmlio import Node

__all__ = ["Manifest", "evaluate_condition", "read_manifest"]

_EMAIL = re.compile(r"^[-a-zA-Z0-9_%+]+(\.[-a-zA-Z0-9_%+]+)*@[-a-zA-Z0-9%]+(\.[-a-zA-Z0-9%]+)*\.[a-zA-Z]{2,}$")
_NAME = re.compile(r"^[a-zA-Z0-9][a-zA-Z0-9_-]*$")
_VERSION = re.compile(r"^[0-9]+\.[0-9]+\.[0-9]+$")
_DEPENDS = ("build_depend", "buildtool_depend", "test_depend", "conflict", "replace")
_LATER_DEPENDS = ("build_export_depend", "buildtool_export_depend", "depend", "exec_depend", "doc_depend")


@dataclass(frozen=True)
class Manifest:
    """What colcon-ros takes from a package.xml catkin_pkg accepted (``problem`` empty), or why not."""

    name: str
    build_type: str  # "" when catkin_pkg finds none ("catkin" by its default), or more than one
    run_depends: tuple[str, ...]  # colcon-core's share/colcon-core/packages/PKG, sorted
    problem: str = ""  # catkin_pkg's InvalidPackage words: colcon builds a plain Python package instead
    build_types: int = 0


def read_manifest(xml: Node, environ: Mapping[str, str] | None = None) -> Manifest:
    """catkin_pkg's reading of the parsed package.xml ``xml``, conditions against ``environ``."""
    environ = os.environ if environ is None else environ
    problem = _problem(xml)
    name = _text(xml.find("name")) if len(xml.findall("name")) == 1 else ""
    if problem:
        return Manifest(name, "", (), problem)
    context = {**environ, "DISABLE_GROUPS_WORKAROUND": "1"}
    form = _format(xml)

    def kept(tags: tuple[str, ...]) -> set[str]:
        out = set()
        for tag in tags:
            for node in xml.findall(tag):
                if _holds(node, context):
                    out.add(_text(node))
        return out

    run_tags = ("run_depend",) if form == 1 else ("build_export_depend", "buildtool_export_depend", "exec_depend",
                                                  "depend")
    export = xml.find("export")
    types = [_text(n) for n in (export.findall("build_type") if export is not None else []) if _holds(n, context)]
    # catkin_pkg/package.py, get_build_type (lines 160-168): catkin by default, more than one refused,
    # and colcon-ros then passes the package over (ros.py, _get_build_type, lines 204-213)
    build_type = types[0] if len(types) == 1 else ("catkin" if not types else "")
    return Manifest(name, build_type, tuple(sorted(kept(run_tags))), "", len(types))


def _holds(node: Node, context: Mapping[str, str]) -> bool:
    condition = node.get("condition")
    try:
        return evaluate_condition(condition, context)
    except ValueError:
        return False


def _text(node: Node | None) -> str:
    return (node.text or "").strip() if node is not None else ""


def _format(xml: Node) -> int:
    value = xml.get("format") or "1"
    return int(value) if value.isdigit() else 0


def _problem(xml: Node) -> str:
    """catkin_pkg's first refusal of the manifest, in its words; "" when it accepts it."""
    if xml.tag != "package":
        return 'The manifest must contain a single "package" root tag'
    form = _format(xml)
    if form not in (1, 2, 3):
        return f"Unable to handle package.xml format version '{xml.get('format')}'"
    for tag in ("name", "version", "description"):
        if len(xml.findall(tag)) != 1:
            return f'The manifest must contain exactly one "{tag}" tag'
    if any(person.get("email") is None for person in xml.findall("maintainer")):  # _get_node_attr, no default
        return 'The "maintainer" tag must have the attribute "email"'
    errors = _redundant(xml, form)
    known = {"name": [], "version": ["compatibility"], "description": [], "maintainer": ["email"], "license": [],
             "url": ["type"], "author": ["email"], "export": []}
    attributes = ["version_lt", "version_lte", "version_eq", "version_gte", "version_gt"]
    if form > 2:
        attributes.append("condition")
    for tag in _DEPENDS:
        known[tag] = attributes
    if form == 1:
        known["run_depend"] = attributes
    else:
        for tag in _LATER_DEPENDS:
            known[tag] = attributes
    if form > 2:
        known.update({"group_depend": ["condition"], "member_of_group": ["condition"], "license": ["file"]})
    errors += [f'The "package" tag must not have the following attributes: {a}' for a in xml.attrib
               if a not in ("format",) and not a.startswith("{")]
    unknown = sorted({child.tag for child in xml.children if child.tag not in known})
    if unknown:
        name = _text(xml.find("name"))
        errors.append(f'The manifest of package "{name}" (with format version {form}) must not contain the following '
                      f"tags: {', '.join(unknown)}")
    for child in xml.children:
        if child.tag in known:
            extra = [a for a in child.attrib if a not in known[child.tag] and not a.startswith("{")]
            if extra:
                errors.append(f'The "{child.tag}" tag must not have the following attributes: {", ".join(extra)}')
            if child.tag not in ("description", "export") and child.children:
                errors.append(f'The "{child.tag}" tag must not contain the following children: '
                              + ", ".join(c.tag for c in child.children))
    if errors:
        return "Error(s):" + "".join(f"\n- {e}" for e in errors)
    return _invalid(xml, form)


def _redundant(xml: Node, form: int) -> list[str]:
    """parse_package_string's refusals of a dependency given twice (lines 683-716): a ``<depend>``
    beside the same build, build_export or exec dependency; in format 1 a test dependency beside
    the same build or run one. Two dependencies are the same when their name and attributes are."""
    def same(a: Node, b: Node) -> bool:
        return _text(a) == _text(b) and a.attrib == b.attrib

    errors = []
    if form != 1:
        for depend in xml.findall("depend"):
            tags = [tag for tag in ("build_depend", "build_export_depend", "exec_depend")
                    for node in xml.findall(tag) if same(node, depend)]
            if tags:
                errors.append(f"The generic dependency on '{_text(depend)}' is redundant with: {', '.join(tags)}")
    else:
        for test in xml.findall("test_depend"):
            tags = [tag for tag in ("build_depend", "run_depend") for node in xml.findall(tag) if same(node, test)]
            if tags:
                errors.append(f'The test dependency on "{_text(test)}" is redundant with: {", ".join(tags)}')
    return errors


def _invalid(xml: Node, form: int) -> str:
    """Package.validate's errors (catkin_pkg/package.py, lines 229-330), joined as it joins them."""
    errors = []
    name = _text(xml.find("name"))
    if not name:
        errors.append("Package name must not be empty")
    if not _NAME.match(name):
        errors.append(f'Package name "{name}" does not follow naming conventions')
    version = _text(xml.find("version"))
    if not version:
        errors.append("Package version must not be empty")
    elif not _VERSION.match(version):
        errors.append(f'Package version "{version}" does not follow version conventions')
    if not _text(xml.find("description")) and not xml.find("description").children:  # type: ignore[union-attr]
        errors.append("Package description must not be empty")
    maintainers = xml.findall("maintainer")
    if not maintainers:
        errors.append(f"Package '{name}' must declare at least one maintainer")
    for person in maintainers:
        email = person.get("email")
        if email is not None and not _EMAIL.match(email):
            return f'Invalid email "{email}" for person "{_text(person)}"'  # Person.validate raises at once
        if not email:
            errors.append("Maintainers must have an email address")
    licenses = xml.findall("license")
    if not licenses:
        errors.append('The package node must contain at least one "license" tag')
    if any(not _text(n) for n in licenses):
        errors.append("The license tag must neither be empty nor only contain whitespaces")
    for person in xml.findall("author"):
        email = person.get("email")
        if email is not None and not _EMAIL.match(email):
            errors.append(f'Invalid email "{email}" for person "{_text(person)}"')
    tags = ("build_depend", "buildtool_depend", "test_depend") + (("run_depend",) if form == 1 else
                                                                  ("build_export_depend", "buildtool_export_depend",
                                                                   "exec_depend", "depend", "doc_depend"))
    for tag in tags:
        for node in xml.findall(tag):
            if _text(node) == name:
                kind = tag[:-len("_depend")] if tag.endswith("_depend") else tag
                errors.append(f'The package "{name}" must not "{kind}_depend" on a package with the same name as '
                              "this package")
    return "\n".join(errors)


# ------------------------------------------------------------------ conditions
# catkin_pkg/condition.py: ``$VAR`` (its value in the context, "" when unset), a word of letters,
# digits, '_' and '-', or a quoted string; compared with == != >= > <= < as strings; joined by
# ``and`` (tighter) and ``or``, with parentheses

_TOKEN = re.compile(r"\s*(?:(==|!=|>=|<=|>|<)|(\()|(\))|(\$[A-Za-z0-9_]+)|\"([^\"]*)\"|'([^']*)'|([A-Za-z0-9_-]+))")
_COMPARE = {"==": operator.eq, "!=": operator.ne, ">=": operator.ge, ">": operator.gt, "<=": operator.le,
            "<": operator.lt}


def evaluate_condition(condition: str | None, context: Mapping[str, str]) -> bool:
    """catkin_pkg's evaluate_condition: True for no condition; ValueError when it does not parse."""
    if condition is None:
        return True
    tokens: list[tuple[str, str]] = []
    position = 0
    text = condition.rstrip()
    while position < len(text):
        match = _TOKEN.match(text, position)
        if match is None or match.end() == position:
            raise ValueError(f"condition '{condition}' failed to parse")
        position = match.end()
        op, opening, closing, variable, double, single, word = match.groups()
        if op:
            tokens.append(("op", op))
        elif opening:
            tokens.append(("(", "("))
        elif closing:
            tokens.append((")", ")"))
        elif variable:
            tokens.append(("term", str(context.get(variable[1:], ""))))
        elif double is not None or single is not None:
            tokens.append(("term", double if double is not None else single))
        elif word in ("and", "or"):
            tokens.append((word, word))
        else:
            tokens.append(("term", word))
    value, rest = _either(tokens, condition)
    if rest:
        raise ValueError(f"condition '{condition}' failed to parse")
    return value


def _either(tokens: list[tuple[str, str]], condition: str) -> tuple[bool, list[tuple[str, str]]]:
    value, tokens = _both(tokens, condition)
    while tokens and tokens[0][0] == "or":
        other, tokens = _both(tokens[1:], condition)
        value = value or other
    return value, tokens


def _both(tokens: list[tuple[str, str]], condition: str) -> tuple[bool, list[tuple[str, str]]]:
    value, tokens = _one(tokens, condition)
    while tokens and tokens[0][0] == "and":
        other, tokens = _one(tokens[1:], condition)
        value = value and other
    return value, tokens


def _one(tokens: list[tuple[str, str]], condition: str) -> tuple[bool, list[tuple[str, str]]]:
    if tokens and tokens[0][0] == "(":
        value, rest = _either(tokens[1:], condition)
        if not rest or rest[0][0] != ")":
            raise ValueError(f"condition '{condition}' failed to parse")
        return value, rest[1:]
    if len(tokens) >= 3 and tokens[0][0] == "term" and tokens[1][0] == "op" and tokens[2][0] == "term":
        return _COMPARE[tokens[1][1]](tokens[0][1], tokens[2][1]), tokens[3:]
    raise ValueError(f"condition '{condition}' failed to parse")
