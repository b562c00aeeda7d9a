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

from ._resources import robot_template
from .errors import ParameterError
from .model import Robot, robot_from_xml
from .xacrotools import expand_xacro
from .xmlio import parse_xml, read_bytes, read_xml

VARIANT_FLAGS = ("wrist", "inertials", "collisions")


@dataclass(frozen=True)
class Parameter:
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


def parse_assignments(items: Iterable[str], what: str = "parameter") -> dict[str, str]:
    """``["a=1", "b=2"]`` -> ``{"a": "1", "b": "2"}``; a missing '=' is a :class:`ParameterError`."""
    out: dict[str, str] = {}
    for item in items:
        name, sep, value = item.partition("=")
        name = name.strip()
        if not sep or not name:
            raise ParameterError(f"'{item}' is not NAME=VALUE", hint=f"write the {what} as NAME=VALUE, e.g. bras_length=0.8")
        out[name] = value.strip()
    return out


def _number(text: str) -> float | None:
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
            raise ParameterError(
                f"unknown parameter '{name}'",
                hint=("did you mean " + " or ".join(close) + "? " if close else "")
                + "valid names: " + ", ".join(settable),
            )
        text = " ".join(str(v) for v in raw) if isinstance(raw, (list, tuple)) else str(raw)
        if settable[name].kind == "colour":
            parts = [_number(p) for p in text.replace(",", " ").split()]
            if len(parts) != 4 or any(p is None or not 0.0 <= p <= 1.0 for p in parts):
                raise ParameterError(f"{name}={text!r} is not a colour",
                                     hint=f"give four numbers between 0 and 1 (r g b a), e.g. {name}=\"0.2 0.4 0.9 1\"")
            out[name] = " ".join(repr(p) for p in parts)  # type: ignore[arg-type]
        else:
            value = _number(text)
            if value is None:
                raise ParameterError(f"{name}={text!r} is not a number",
                                     hint=f"give a finite number, e.g. {name}={settable[name].default}")
            if name.endswith(_POSITIVE) and value <= 0:
                raise ParameterError(f"{name}={text}: {_POSITIVE_WHAT[name.rsplit('_', 1)[1]]} must be above 0",
                                     hint=f"give a positive number, e.g. {name}={settable[name].default}")
            out[name] = repr(value)
    _check_limit_order(out, settable)
    return out


_POSITIVE = ("_length", "_radius", "_width", "_mass", "_effort", "_velocity")
_POSITIVE_WHAT = {"length": "a length", "radius": "a radius", "width": "a width", "mass": "a mass",
                  "effort": "an effort limit", "velocity": "a velocity limit"}


def _check_limit_order(values: Mapping[str, str], settable: Mapping[str, Any]) -> None:
    """lower < upper for every joint, whichever of the two was changed."""
    for joint in {name.rsplit("_", 1)[0] for name in values if name.endswith(("_lower", "_upper"))}:
        lower = float(values.get(f"{joint}_lower", settable[f"{joint}_lower"].default))
        upper = float(values.get(f"{joint}_upper", settable[f"{joint}_upper"].default))
        if not lower <= upper:
            raise ParameterError(f"{joint}_lower={lower:g} is above {joint}_upper={upper:g}",
                                 hint="the lower limit of a joint must not be above its upper limit")


_BANNER = re.compile(r"<!-- =+ -->\s*<!-- \|.*?\| -->\s*<!-- \|.*?\| -->\s*<!-- =+ -->\s*", re.S)


def arm_urdf(*, wrist: bool = False, inertials: bool = False, params: Mapping[str, object] | None = None,
             collisions: bool = False, root_inertial: bool = True) -> str:
    """URDF text of the tutorial arm, optionally with the wrist, inertials, collision shapes and changed parameters.

    ``inertials`` brings the collision shapes too (physics needs both); ``root_inertial=False``
    leaves the root link without one, as robot_state_publisher's KDL parser prefers.
    """
    mappings = normalise_parameters(params or {})
    mappings.update(wrist=str(wrist).lower(), inertials=str(inertials).lower(), collisions=str(collisions).lower(),
                    base_inertial=str(root_inertial).lower())
    text = _expand_template(mappings)
    from .i18n import _

    # An XML comment may not hold "--": the options are named without their dashes.
    options = [f for f, on in (("wrist", wrist), ("inertials", inertials),
                               ("collisions", collisions and not inertials)) if on]
    options += [f"param {k}={v}".replace("--", "-") for k, v in (params or {}).items()]
    note = ("<!-- " + (_("Generated by bras-kit urdf with the options: {options}").format(options=", ".join(options))
                       if options else _("Generated by bras-kit urdf")) + " -->\n")
    return _BANNER.sub(note, text, count=1)


def _expand_template(mappings: Mapping[str, str]) -> str:
    """The built-in template expanded by the real xacro, kept in the user's cache folder
    (``$XDG_CACHE_HOME/bras-kit``, else ``~/.cache/bras-kit``) under a hash of the template, the
    arguments and bras-kit's version: most commands draw the default arm, and loading xacro to
    expand it again costs more than the rest of a small command. A cache that cannot be read or
    written is simply not used."""
    import hashlib
    import json

    from . import __version__

    template = robot_template()
    source = template.read_bytes()
    key = hashlib.sha256(json.dumps([__version__, sorted(mappings.items())]).encode() + source).hexdigest()[:32]
    folder = os.path.join(os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache"),
                          "bras-kit")
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
        collisions: bool = False) -> Robot:
    """The tutorial arm as a :class:`Robot` (the default input of every command)."""
    text = arm_urdf(wrist=wrist, inertials=inertials, params=params, collisions=collisions)
    return robot_from_xml(parse_xml(text, "<bras-kit tutorial arm>"), "<bras-kit tutorial arm>", text)


def load(path: str | os.PathLike[str] | None = None, *, mappings: Mapping[str, str] | None = None,
         package_paths: Iterable[str] = ()) -> Robot:
    """Load a robot: a ``.urdf`` file, a ``.xacro`` file (expanded first) or, with no path, the tutorial arm.

    XML is read safely; parse problems inside the file are recorded on ``robot.issues``.
    """
    if path is None:
        return arm()
    path = os.fspath(path)
    if path.endswith(".xacro"):
        text = expand_xacro(path, mappings, package_paths)
        return robot_from_xml(parse_xml(text, path), path, text)
    data = read_bytes(path)
    return robot_from_xml(parse_xml(data, path), path, data.decode("utf-8", errors="replace"))
