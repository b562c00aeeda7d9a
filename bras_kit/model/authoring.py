"""The tutorial arm and its variants, made from the shipped xacro template.

The template's ``<xacro:arg>`` elements are the single list of parameters: their names, defaults
and kinds (number, colour, flag) are read from it, so a parameter added there is at once
settable with ``--set`` and listed in errors.
"""

from __future__ import annotations

import math
import os
import re
from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from typing import Any

from ..core.errors import ParameterError
from ..core.message import M, Message
from ..core.resources import robot_template
from ..core.wording import either
from .robot import Robot, robot_from_xml
from .xacro import expand_xacro
from .xmlio import parse_xml, read_bytes, read_xml

VARIANT_FLAGS = ("wrist", "inertials", "collisions")


@dataclass(frozen=True)
class Parameter:
    """One parameter of the arm template: its name, default value (as written) and kind."""

    name: str
    default: str
    kind: str  # "number", "colour" or "flag"


def template_parameters() -> dict[str, Parameter]:
    """Every parameter of the arm template, in the template's order."""
    root = read_xml(robot_template())
    params = {}
    for node in root.children:
        if node.tag != "xacro:arg":
            continue
        name, default = node.get("name") or "", node.get("default") or ""
        if default in ("true", "false"):
            kind = "flag"
        elif len(default.split()) == 4:
            kind = "colour"
        else:
            kind = "number"
        params[name] = Parameter(name, default, kind)
    return params


def parse_assignments(items: Iterable[str], what: Message | None = None) -> dict[str, str]:
    """``["a=1", "b=2"]`` -> ``{"a": "1", "b": "2"}``; a missing '=' is a :class:`ParameterError`
    (``what`` names the value in the hint: "parameter" unless told)."""
    out: dict[str, str] = {}
    for item in items:
        name, sep, value = item.partition("=")
        name = name.strip()
        if not sep or not name:
            raise ParameterError(M("'{item}' is not NAME=VALUE", item=item),
                                 hint=M("write the {what} as NAME=VALUE, e.g. bras_length=0.8",
                                        what=what or M("parameter")))
        out[name] = value.strip()
    return out


def _number(text: str) -> float | None:
    if _COMMA_NUMBER.match(text.strip()):  # the French decimal comma: 0,8
        text = text.replace(",", ".")
    try:
        value = float(text)
    except ValueError:
        return None
    return value if math.isfinite(value) else None


def normalise_parameters(values: Mapping[str, object]) -> dict[str, str]:
    """Check names and values against the template; return xacro mappings (strings).

    Numbers are written back with ``repr(float)``; colours must be four numbers in 0..1.
    """
    params = template_parameters()
    settable = {name: p for name, p in params.items() if p.kind != "flag"}
    out = {}
    for name, raw in values.items():
        if name not in settable:
            close = [n for n in settable if n.split("_")[0] == name.split("_")[0]]
            valid = M("valid names: {names}", names=", ".join(settable))
            raise ParameterError(
                M("unknown parameter '{name}'", name=name),
                hint=M("did you mean {close}? {valid}", close=either(close), valid=valid) if close else valid,
            )
        text = " ".join(str(v) for v in raw) if isinstance(raw, (list, tuple)) else str(raw)
        if settable[name].kind == "colour":
            parts = [_number(p) for p in text.replace(",", " ").split()]
            if len(parts) != 4 or any(p is None or not 0.0 <= p <= 1.0 for p in parts):
                raise ParameterError(M("{name}={text!r} is not a colour", name=name, text=text),
                                     hint=M("give four numbers between 0 and 1 (r g b a), e.g. {name}=\"0.2 0.4 0.9 1\"",
                                            name=name))
            out[name] = " ".join(repr(p) for p in parts)
        else:
            value = _limit_value(text) if name.endswith(("_lower", "_upper")) else _number(text)
            if value is None:
                raise ParameterError(M("{name}={text!r} is not a number", name=name, text=text),
                                     hint=M("give a finite number, e.g. {name}={default}", name=name,
                                            default=settable[name].default))
            _check_range(name, text, value, settable[name].default)
            out[name] = repr(value)
    _check_limit_order(out, settable)
    return out


@dataclass(frozen=True)
class Range:
    """The values a kind of template parameter may take, bounds included.

    Chosen so that every combination gives a URDF the validator accepts: sizes of 1 mm to
    10 m keep each box's smallest principal moment of inertia far above the validator's
    1e-12 relative threshold (a 1 mm x 1 mm x 10 m box: 2e-8) and every number finite; joint
    limits stay within one turn each way (a larger number is most often degrees).
    """

    lowest: float
    highest: float
    message: Message  # filled in with {name}, {value}, {lowest}, {highest}
    hint: Message  # filled in with {name}, {default}


_TURN = round(2 * math.pi, 4)
_SIZE_HINT = M("sizes are in metres (0.6 is 60 cm): give e.g. {name}={default}")
RANGES: dict[str, Range] = {  # by the parameter name's last word
    "length": Range(0.001, 10.0, M("{name}={value}: a length must be between {lowest} and {highest} m"), _SIZE_HINT),
    "width": Range(0.001, 10.0, M("{name}={value}: a width must be between {lowest} and {highest} m"), _SIZE_HINT),
    "radius": Range(0.001, 10.0, M("{name}={value}: a radius must be between {lowest} and {highest} m"), _SIZE_HINT),
    "mass": Range(0.001, 1000.0, M("{name}={value}: a mass must be between {lowest} and {highest} kg"),
                  M("masses are in kilograms: give e.g. {name}={default}")),
    "effort": Range(0.001, 10000.0,
                    M("{name}={value}: an effort limit must be between {lowest} and {highest} N.m"),
                    M("give the largest torque of the joint's motor, e.g. {name}={default}")),
    "velocity": Range(0.001, 100.0,
                      M("{name}={value}: a velocity limit must be between {lowest} and {highest} rad/s"),
                      M("give the largest speed of the joint, e.g. {name}={default}")),
    "lower": Range(-_TURN, _TURN, M("{name}={value}: a joint limit must be between {lowest} and {highest} rad"),
                   M("limits are in radians: give e.g. {name}={default}, pi/2 or 90deg")),
    "upper": Range(-_TURN, _TURN, M("{name}={value}: a joint limit must be between {lowest} and {highest} rad"),
                   M("limits are in radians: give e.g. {name}={default}, pi/2 or 90deg")),
}


def parameter_range(name: str) -> Range | None:
    """The allowed values of a number parameter of the arm template (``None``: any finite number)."""
    return RANGES.get(name.rsplit("_", 1)[-1])


def _check_range(name: str, text: str, value: float, default: str) -> None:
    allowed = parameter_range(name)
    if allowed is None or allowed.lowest <= value <= allowed.highest:
        return
    message = allowed.message.with_params(name=name, value=text, lowest=allowed.lowest, highest=allowed.highest)
    hint = allowed.hint.with_params(name=name, default=default)
    in_degrees = math.radians(value)
    if name.endswith(("_lower", "_upper")) and allowed.lowest <= in_degrees <= allowed.highest:
        hint = M("{value} looks like degrees: write {name}={value}deg ({radians} rad)",
                 name=name, value=text, radians=f"{in_degrees:.4f}")
    raise ParameterError(message, hint=hint)


_COMMA_NUMBER = re.compile(r"^[-+]?\d*,\d+$")


def _limit_value(text: str) -> float | None:
    """A joint limit as learners type joint values: ``1.2``, ``1,2``, ``pi/2``, ``90deg``."""
    from .expr import parse_joint_value

    try:
        return parse_joint_value(text)
    except ParameterError:
        return None


def _check_limit_order(values: Mapping[str, str], settable: Mapping[str, Any]) -> None:
    """lower <= upper for every joint, whichever of the two was changed (equal: a still joint)."""
    for joint in sorted({name.rsplit("_", 1)[0] for name in values if name.endswith(("_lower", "_upper"))}):
        lower = float(values.get(f"{joint}_lower", settable[f"{joint}_lower"].default))
        upper = float(values.get(f"{joint}_upper", settable[f"{joint}_upper"].default))
        if not lower <= upper:
            raise ParameterError(
                M("{joint}_lower={lower:g} is above {joint}_upper={upper:g}", joint=joint, lower=lower, upper=upper),
                hint=M("the lower limit of a joint must not be above its upper limit: "
                       "swap the values, or change {joint}_lower and {joint}_upper together", joint=joint))


_BANNER = re.compile(r"<!-- =+ -->\s*<!-- \|.*?\| -->\s*<!-- \|.*?\| -->\s*<!-- =+ -->\s*", re.S)


def arm_urdf(*, wrist: bool = False, inertials: bool = False, params: Mapping[str, object] | None = None,
             collisions: bool = False, root_inertial: bool = True, lang: str | None = None,
             header: str | None = None, world_anchor: bool = False) -> str:
    """URDF text of the tutorial arm, optionally with the wrist, inertials, collision shapes and changed parameters.

    ``inertials`` brings the collision shapes too (physics needs both); ``root_inertial=False``
    leaves the base without one, as robot_state_publisher's KDL parser prefers for the root;
    ``world_anchor`` makes a ``world`` link the root, with the base fixed to it. The
    comments are in ``lang`` (default: the current language); ``header``, if given, replaces
    the first one, which otherwise names the options that made the file.
    """
    from ..core.i18n import current_language, translator

    lang = lang or current_language()
    mappings = normalise_parameters(params or {})
    mappings.update(wrist=str(wrist).lower(), inertials=str(inertials).lower(), collisions=str(collisions).lower(),
                    base_inertial=str(root_inertial).lower(), world_anchor=str(world_anchor).lower())
    text = localise_comments(_expand_template(mappings), lang)
    if header is None:
        options = [f for f, on in (("wrist", wrist), ("inertials", inertials),
                                   ("collisions", collisions and not inertials)) if on]
        options += [f"param {k}={v}" for k, v in (params or {}).items()]
        header = header_comment(options, translator(lang, "package"))
    return _BANNER.sub(lambda _match: f"<!-- {_comment_safe(header)} -->\n", text, count=1)


def header_comment(options: list[str], say: Any) -> str:
    """The first comment of ``bras-kit urdf``'s output: the options that made it.

    An XML comment may not hold two dashes in a row (XML 1.0, section 2.5: xmllint, Python's
    parsers and lxml reject the file), so the options are named without theirs and the comment
    says so, rather than showing a command whose dashes were changed.
    """
    none, some = HEADER_TEXTS
    if not options:
        return str(say(none))
    return str(say(some)).format(options=", ".join(options))


# The two wordings of that first comment, ids of the ``package`` catalog (the catalogs' extractor
# reads them here, with the template's own comments: bras_kit.cli.catalogs.extract_arm_comments).
HEADER_TEXTS = ("Generated by bras-kit urdf (no option)",
                "Generated by bras-kit urdf with the options {options} (on the command line, each starts "
                "with two dashes, which an XML comment cannot hold)")


def _comment_safe(text: str) -> str:
    """``text`` as the body of an XML comment: no two dashes in a row, no dash at the end."""
    while "--" in text:
        text = text.replace("--", "- -")
    return text + " " if text.endswith("-") else text


_COMMENT = re.compile(r"<!--(.*?)-->", re.S)


def localise_comments(text: str, lang: str) -> str:
    """The comments of the arm template (kept in its expansion) in ``lang``.

    Each comment's lines, stripped, are an English id of the ``package`` catalog; a comment the
    catalog does not know is left as it is.
    """
    from ..core.i18n import DEFAULT_LANGUAGE, translator

    if lang == DEFAULT_LANGUAGE:
        return text
    say = translator(lang, "package")

    def swap(found: re.Match[str]) -> str:
        body = found.group(1)
        english = comment_id(body)
        words = say(english)
        if words == english:
            return found.group(0)
        if "\n" in body.strip() or body.startswith("\n"):  # a block: one line each, indented like the original
            indent = re.match(r"\n([ \t]*)", body)
            pad = indent.group(1) if indent else "  "
            tail = body[body.rstrip(" \t").rfind("\n"):] if body.rstrip(" \t").endswith("\n") else "\n"
            return "<!--\n" + "\n".join(pad + _comment_safe(line) for line in words.split("\n")) + tail + "-->"
        return f"<!-- {_comment_safe(words)} -->"

    return _COMMENT.sub(swap, text)


def comment_id(body: str) -> str:
    """The catalog id of a comment: its lines stripped, blank ones dropped."""
    return "\n".join(line.strip() for line in body.strip().splitlines() if line.strip())


def _expand_template(mappings: Mapping[str, str]) -> str:
    """The built-in template expanded by the real xacro, kept in the user's cache folder
    (``$XDG_CACHE_HOME/bras-kit``, else ``~/.cache/bras-kit``) under a hash of the template, the
    arguments and bras-kit's version: most commands draw the default arm, and loading xacro to
    expand it again costs more than the rest of a small command. A cache that cannot be read or
    written is simply not used."""
    import hashlib
    import json

    from .. import __version__

    template = robot_template()
    source = template.read_bytes()
    key = hashlib.sha256(json.dumps([__version__, sorted(mappings.items())]).encode() + source).hexdigest()[:32]
    from ..core.cachedir import cache_home

    folder = cache_home()
    cached = os.path.join(folder, f"arm-{key}.urdf")
    try:
        if os.path.isfile(cached) and not os.path.islink(cached):
            with open(cached, encoding="utf-8") as handle:
                text = handle.read()
            if text.startswith("<?xml") and text.rstrip().endswith("</robot>"):
                return text
    except (OSError, UnicodeDecodeError):
        pass
    text = expand_xacro(template, dict(mappings))
    try:
        os.makedirs(folder, mode=0o700, exist_ok=True)
        temporary = f"{cached}.{os.getpid()}.tmp"
        with open(temporary, "x", encoding="utf-8") as handle:
            handle.write(text)
        os.replace(temporary, cached)
    except OSError:
        pass
    return text


def arm(*, wrist: bool = False, inertials: bool = False, params: Mapping[str, object] | None = None,
        collisions: bool = False, world_anchor: bool = False) -> Robot:
    """The tutorial arm as a :class:`Robot` (the default input of every command); ``world_anchor``
    as :func:`arm_urdf`'s."""
    text = arm_urdf(wrist=wrist, inertials=inertials, params=params, collisions=collisions, world_anchor=world_anchor)
    return robot_from_xml(parse_xml(text, "<bras-kit tutorial arm>"), "<bras-kit tutorial arm>", text)


def load(path: str | os.PathLike[str] | None = None, *, mappings: Mapping[str, str] | None = None,
         package_paths: Iterable[str] = (), roots: Iterable[str] | None = None) -> Robot:
    """Load a robot: a ``.urdf`` file, a ``.xacro`` file (expanded first) or, with no path, the tutorial arm.

    XML is read safely; parse problems inside the file are recorded on ``robot.issues``. With
    ``roots`` (the folders a learner's robot lives in: its package, a submission), the file, the
    files it includes and later its meshes are read through the one reader beneath them (and
    beneath the packages ``$(find)`` names), never through a link out of them.
    """
    if path is None:
        return arm()
    path = os.fspath(path)
    within = tuple(os.path.abspath(r) for r in roots) if roots is not None else None
    if path.endswith(".xacro"):
        text = expand_xacro(path, mappings, package_paths, roots=within)
        robot = robot_from_xml(parse_xml(text, path), path, text)
    else:
        data = read_bytes(path, within)
        robot = robot_from_xml(parse_xml(data, path), path, data.decode("utf-8", errors="replace"))
    robot.roots = within
    return robot
