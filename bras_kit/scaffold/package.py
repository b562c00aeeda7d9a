"""The ROS 2 package of the tutorial, generated from jinja2 templates (``bras-kit new``).

The package is the one the tutorial builds by hand (steps 2 to 7): ``package.xml``,
``setup.py`` installing ``urdf/``, ``launch/`` and ``rviz/`` (so the "file not found" pitfall
cannot happen), the launch file, an RViz configuration that shows the arm at once, and an
animation node whose motion is computed here from the model's own joint limits.
"""

from __future__ import annotations

import getpass
import keyword
import math
import os
import re
import unicodedata
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from .. import __version__
from ..core.errors import BrasKitError, ModelError, OutputExistsError, ParameterError
from ..core.message import M
from ..core.resources import robot_template, templates_dir
from ..model.robot import Robot
from ..motion.sources import TUTORIAL_WAVES  # the one definition of the tutorial's motion

DEFAULT_PACKAGE = "bras_description"
PACKAGE_NAME_PATTERN = re.compile(r"[a-z][a-z0-9_]*")
# a <depend>: a package name, or a rosdep key such as python3-numpy
DEPENDENCY_PATTERN = re.compile(r"[a-z][a-z0-9_+.-]*")

OTHER_JOINT_WAVE = (0.5, 0.5, 0.0)
# Fraction of each half-range (and of each velocity limit) the motion leaves unused.
LIMIT_MARGIN = 0.1

# template (under bras_kit/templates/package/) -> file made, relative to the package folder
_FILES: tuple[tuple[str, str], ...] = (
    ("package.xml.j2", "package.xml"),
    ("setup.py.j2", "setup.py"),
    ("setup.cfg.j2", "setup.cfg"),
    ("README.md.j2", "README.md"),
    ("resource/marker.j2", "resource/{name}"),
    ("pkg/__init__.py.j2", "{name}/__init__.py"),
    ("pkg/motion.py.j2", "{name}/motion.py"),
    ("pkg/animation.py.j2", "{name}/animation.py"),
    ("launch/affichage.launch.py.j2", "launch/affichage.launch.py"),
    ("rviz/package.rviz.j2", "rviz/{name}.rviz"),
    ("test/test_motion.py.j2", "test/test_motion.py"),
)
URDF_FILE = "urdf/bras.urdf"
XACRO_FILE = "urdf/bras.urdf.xacro"


@dataclass(frozen=True)
class Wave:
    """One joint's motion: ``centre + amplitude * sin(frequency * t + phase)``."""

    joint: str
    centre: float
    amplitude: float
    frequency: float
    phase: float
    lower: float
    upper: float
    velocity: float | None

    def position(self, t: float) -> float:
        return self.centre + self.amplitude * math.sin(self.frequency * t + self.phase)


def check_package_name(name: str) -> None:
    """Raise :class:`ParameterError` unless ``name`` is a valid ROS package (and Python package) name."""
    if not PACKAGE_NAME_PATTERN.fullmatch(name or ""):
        raise ParameterError(
            M("'{name}' is not a valid ROS package name", name=name),
            hint=M("use lowercase letters, digits and underscores, starting with a letter (e.g. bras_description)"),
        )
    if keyword.iskeyword(name):
        raise ParameterError(M("'{name}' is a Python keyword and cannot name an ament_python package", name=name),
                             hint=M("choose another name, e.g. bras_description"))


# catkin_pkg's test of a maintainer's email: colcon ignores a package.xml that fails it
EMAIL_PATTERN = re.compile(r"^[-a-zA-Z0-9_%+]+(\.[-a-zA-Z0-9_%+]+)*@[-a-zA-Z0-9%]+(\.[-a-zA-Z0-9%]+)*\.[a-zA-Z]{2,}$")


def default_email(maintainer: str) -> str:
    """A placeholder address catkin_pkg accepts: ``Jean Dupont`` -> ``jean.dupont@todo.todo``."""
    ascii_name = unicodedata.normalize("NFKD", maintainer).encode("ascii", "ignore").decode().lower()
    local = ".".join(re.findall(r"[a-z0-9_+-]+", ascii_name)) or "maintainer"
    return f"{local}@todo.todo"


def check_maintainer(name: str) -> None:
    """Raise :class:`ParameterError` for a name that would break setup.py or package.xml as written."""
    bad = sorted({c for c in name if c in "'\"\\<>&" or not c.isprintable()})
    if bad or not name.strip():
        shown = " ".join(repr(c) for c in bad) if bad else M("an empty name")
        raise ParameterError(M("maintainer '{name}': {shown} cannot be written into setup.py and package.xml",
                               name=name, shown=shown),
                             hint=M("give --maintainer a plain name (letters, digits, spaces, . and -)"))


def check_email(email: str) -> None:
    """Raise :class:`ParameterError` unless catkin_pkg (hence colcon) accepts ``email``."""
    if not EMAIL_PATTERN.match(email):
        raise ParameterError(M("'{email}' is not an email address colcon accepts", email=email),
                             hint=M("give --email name@domain.tld (colcon would treat the package as plain Python)"))


def _floor(value: float, digits: int = 6) -> float:
    scale = 10.0**digits
    return math.floor(value * scale + 1e-6) / scale  # 1e-6: 0.29 * 1e6 may be 289999.99999999994


def plan_motion(robot: Robot) -> list[Wave]:
    """A sine wave per movable joint that stays inside its position and velocity limits.

    The tutorial's waves are kept as they are when they fit with a margin of
    :data:`LIMIT_MARGIN`; otherwise the wave is centred between the limits and its
    amplitude shrunk, so narrowed limits (``--set coude_upper=0.5``) are still respected.
    """
    waves = []
    for joint in robot.movable_joints():
        name = joint.name or ""
        amplitude, frequency, phase = TUTORIAL_WAVES.get(name, OTHER_JOINT_WAVE)
        lower, upper = joint.bounds()
        if lower > upper:
            raise ModelError(M("joint '{name}': lower limit {lower:g} is above upper limit {upper:g}", name=name,
                               lower=lower, upper=upper), line=joint.line, element="joint",
                             hint=M("swap the values of {name}_lower and {name}_upper", name=name))
        centre = 0.0
        if math.isfinite(lower) and math.isfinite(upper):
            half = (upper - lower) / 2.0
            keep_out = LIMIT_MARGIN * half
            if not (lower + keep_out <= -amplitude and amplitude <= upper - keep_out):
                centre = round((lower + upper) / 2.0, 6)
                amplitude = min(amplitude, half - keep_out)
        velocity = joint.limit.velocity if joint.limit is not None else None
        if velocity is not None and velocity > 0 and frequency > 0:
            amplitude = min(amplitude, (1.0 - LIMIT_MARGIN) * velocity / frequency)
        amplitude = max(0.0, _floor(amplitude))
        if math.isfinite(lower) and math.isfinite(upper):  # rounding must not cross a limit
            amplitude = max(0.0, min(amplitude, _floor(centre - lower), _floor(upper - centre)))
        waves.append(Wave(name, centre, amplitude, frequency, round(phase, 6), lower, upper, velocity))
    return waves


def tutorial_waves_text(wrist: bool) -> str:
    """The tutorial's waves as the generated comments quote them: ``epaule 0.8 sin t, coude 1.2 sin 0.7t``."""
    parts = []
    for joint, (amplitude, frequency, phase) in TUTORIAL_WAVES.items():
        if joint == "poignet" and not wrist:
            continue
        inner = "t" if frequency == 1.0 else f"{frequency!r}t"
        parts.append(f"{joint} {amplitude!r} sin {inner}" + (f" + {phase!r}" if phase else ""))
    return ", ".join(parts)


def _number(value: float | None) -> str:
    """A float as Python source: the shortest exact form, ``math.inf`` for infinities."""
    if value is None:
        return "None"
    if math.isinf(value):
        return "math.inf" if value > 0 else "-math.inf"
    return repr(float(value))


def _xacro_with_defaults(text: str, defaults: Mapping[str, str]) -> str:
    """The arm template with the default of each named ``<xacro:arg>`` replaced."""
    for name, value in defaults.items():
        pattern = re.compile(r'(<xacro:arg\s+name="' + re.escape(name) + r'"\s+default=")[^"]*(")')
        text, count = pattern.subn(r"\g<1>" + value.replace("\\", "\\\\") + r"\g<2>", text)
        if count != 1:
            raise BrasKitError(M("the arm template has {count} <xacro:arg name=\"{name}\">, expected 1", count=count,
                                 name=name))
    return text


def _view(robot: Robot) -> tuple[float, float]:
    """Height of the orbit camera's focal point and its distance, from the arm's size at rest."""
    from ..kinematics.frames import fk, tf_tree

    poses = fk(tf_tree(robot), {})
    top = 0.0
    for link in robot.links:
        frame = poses.get(link.name or "")
        if frame is None:
            continue
        for visual in link.visuals:
            geometry = visual.geometry
            half = 0.0
            if geometry is not None and geometry.kind == "box" and geometry.size:
                half = geometry.size[2] / 2.0
            elif geometry is not None and geometry.kind == "cylinder" and geometry.length:
                half = geometry.length / 2.0
            elif geometry is not None and geometry.radius:
                half = geometry.radius
            top = max(top, float(frame[2, 3]) + visual.origin.xyz[2] + half)
    top = top or 1.0
    return round(top / 2.0, 3), round(max(1.5, 2.2 * top), 2)


def _command_line(name: str, wrist: bool, inertials: bool, params: Mapping[str, str], lang: str = "en",
                  xacro: bool = False) -> str:
    words = ["bras-kit", "new"] + (["--lang", lang] if lang != "en" else [])
    if name != DEFAULT_PACKAGE:
        words += ["--name", name]
    words += [flag for flag, on in (("--wrist", wrist), ("--inertials", inertials), ("--xacro", xacro)) if on]
    for key, value in params.items():
        item = f"{key}={value}"
        words += ["--param", f'"{item}"' if " " in item else item]
    return " ".join(words)


def render_package(
    name: str = DEFAULT_PACKAGE,
    *,
    wrist: bool = False,
    inertials: bool = False,
    params: Mapping[str, object] | None = None,
    maintainer: str | None = None,
    email: str | None = None,
    lang: str = "en",
    xacro: bool = False,
) -> dict[str, str]:
    """Every file of the package as ``{relative path: text}``; nothing is written.

    The robot is the tutorial's hand-written ``urdf/bras.urdf``, the learner's to edit; with
    ``xacro`` it is ``urdf/bras.urdf.xacro`` instead, which the launch file expands with xacro
    as real packages do (one source, never a second hand-kept copy).
    Raises :class:`ParameterError` for a bad package name or template parameter.
    """
    from ..core.i18n import LANGUAGES, say
    from ..kinematics.frames import tf_tree
    from ..model.authoring import arm_urdf, localise_comments, normalise_parameters
    from ..model.robot import robot_from_xml
    from ..model.xmlio import parse_xml

    check_package_name(name)
    if lang not in LANGUAGES:
        raise ParameterError(M("unknown language '{lang}'", lang=lang), hint=M("use --lang en or --lang fr"))
    settings = normalise_parameters(params or {})
    # With inertials the arm is made for Gazebo too: a root link without <inertial> is dropped there
    # with everything below it, and KDL (robot_state_publisher) warns about an inertia on the root.
    # Both are met as real packages meet them: a bare 'world' link is the root, the base (with its
    # inertial) is fixed to it, so Gazebo also holds the arm in place. Without inertials: the tutorial's tree.
    note = say(M("Made by bras-kit {version} for the package {name}: the tutorial's arm, yours to edit",
                 version=__version__, name=name), lang)
    urdf_text = arm_urdf(wrist=wrist, inertials=inertials, params=params, root_inertial=inertials, lang=lang,
                         header=note, world_anchor=inertials)
    robot = robot_from_xml(parse_xml(urdf_text, URDF_FILE), URDF_FILE, urdf_text)
    waves = plan_motion(robot)
    tree_links = tf_tree(robot).links
    root_link = tree_links[1] if inertials else tree_links[0]  # the base: 'world' is a bare anchor
    focal_z, distance = _view(robot)
    maintainer = _default_maintainer() if maintainer is None else maintainer
    check_maintainer(maintainer)
    email = default_email(maintainer) if email is None else email
    check_email(email)

    context = {
        "name": name,
        "robot_name": robot.name,
        "root_link": root_link,
        "links": [link for link in robot.link_names if not (inertials and link == "world")],
        "waves": waves,
        "number": _number,
        "wrist": wrist,
        "inertials": inertials,
        "settings": settings,
        "maintainer": maintainer,
        "email": email,
        "focal_z": focal_z,
        "distance": distance,
        "version": __version__,
        "command": _command_line(name, wrist, inertials, settings, lang, xacro),
        "xacro": xacro,
        "margin_percent": round(LIMIT_MARGIN * 100),
        "tutorial_waves": tutorial_waves_text(wrist),
        "fr": lang == "fr",
    }
    environment = template_environment(lang)
    files: dict[str, str] = {}
    for template, target in _FILES:
        files[target.format(name=name)] = environment.get_template(template).render(context)
    if xacro:
        defaults = {"wrist": str(wrist).lower(), "inertials": str(inertials).lower(),
                    "base_inertial": str(inertials).lower(), "world_anchor": str(inertials).lower(), **settings}
        template_text = robot_template().read_text(encoding="utf-8")
        files[XACRO_FILE] = localise_comments(_xacro_with_defaults(template_text, defaults), lang)
    else:
        files[URDF_FILE] = urdf_text
    return files


def template_environment(lang: str):
    """The package templates' Jinja environment, their prose (``{% trans %}`` blocks) worded in
    ``lang`` from the ``package`` catalog (Jinja's i18n extension over gettext)."""
    import jinja2

    from ..core.i18n import catalog

    environment = jinja2.Environment(
        loader=jinja2.FileSystemLoader(str(templates_dir() / "package")),
        undefined=jinja2.StrictUndefined,
        keep_trailing_newline=True,
        trim_blocks=True,
        lstrip_blocks=True,
        autoescape=False,
        extensions=["jinja2.ext.i18n"],
    )
    environment.install_gettext_translations(catalog(lang, "package"), newstyle=False)  # type: ignore[attr-defined]
    return environment


# ros2 pkg create --build-type ament_python (ros2cli 0.32.2, Jazzy): ros2pkg/api/create.py,
# create_package_environment and populate_ament_python; template (under bras_kit/templates/empty/) -> file
_EMPTY_FILES: tuple[tuple[str, str], ...] = (
    ("package.xml.j2", "package.xml"),
    ("setup.py.j2", "setup.py"),
    ("setup.cfg.j2", "setup.cfg"),
    ("resource/marker.j2", "resource/{name}"),
    ("pkg/__init__.py.j2", "{name}/__init__.py"),
    ("test/test_copyright.py.j2", "test/test_copyright.py"),
    ("test/test_flake8.py.j2", "test/test_flake8.py"),
    ("test/test_pep257.py.j2", "test/test_pep257.py"),
)
# ros2pkg/verb/create.py: the defaults of --description and --license
EMPTY_DESCRIPTION = "TODO: Package description"
DEFAULT_LICENSE = "TODO: License declaration"


def check_description(description: str) -> None:
    """Raise :class:`ParameterError` for a description that would break setup.py or package.xml as
    ros2 pkg create writes it (its templates insert the text as it is)."""
    bad = sorted({c for c in description if c in "'\"\\<>&" or not c.isprintable()})
    if bad:
        raise ParameterError(M("description '{text}': {shown} cannot be written into setup.py and package.xml",
                               text=description, shown=" ".join(repr(c) for c in bad)),
                             hint=M("write the description in words, without quotes, <, > or &"))


def check_dependency(name: str) -> None:
    """Raise :class:`ParameterError` for a ``<depend>`` that names no package rosdep or colcon could know."""
    if not DEPENDENCY_PATTERN.fullmatch(name):
        raise ParameterError(M("'{name}' is not a package name for <depend>", name=name),
                             hint=M("give package names separated by spaces, e.g. --dependencies rclpy sensor_msgs"))


def check_license(license_name: str) -> None:
    """Raise :class:`ParameterError` for a license that would break setup.py or package.xml as written."""
    bad = sorted({c for c in license_name if c in "'\"\\<>&" or not c.isprintable()})
    if bad or not license_name.strip():
        shown = " ".join(repr(c) for c in bad) if bad else M("an empty name")
        raise ParameterError(M("license '{name}': {shown} cannot be written into setup.py and package.xml",
                               name=license_name, shown=shown),
                             hint=M("give --license an SPDX identifier, e.g. Apache-2.0"))


def render_empty_package(name: str = DEFAULT_PACKAGE, *, maintainer: str | None = None, email: str | None = None,
                         license_name: str = DEFAULT_LICENSE, description: str = EMPTY_DESCRIPTION,
                         dependencies: Sequence[str] = (), node_name: str | None = None,
                         library_name: str | None = None, package_format: int = 3) -> dict[str, str]:
    """What ``ros2 pkg create --build-type ament_python NAME`` writes, as ``{relative path: text}``.

    The same bytes in every language: ros2 pkg create writes English whatever the locale. With
    ``license_name`` Apache-2.0 the ``LICENSE`` file is written too, as ros2 pkg create copies
    ament_copyright's text for a license it knows (``ros2pkg/verb/create.py``, end of ``main``).
    ``description``, ``dependencies`` (``<depend>``), ``node_name`` (``NAME/NODE.py`` and its
    console_scripts entry), ``library_name`` (``NAME/LIBRARY/__init__.py``) and
    ``package_format`` are ros2 pkg create's options of the same names (``populate_ament_python``,
    ``populate_python_node``, ``populate_python_libary`` of ``ros2pkg/api/create.py``).
    """
    import jinja2

    check_package_name(name)
    if name == "test":  # ros2pkg/verb/create.py: the module folder would be the tests' folder
        raise ParameterError(M("an ament_python package cannot be named 'test'"),
                             hint=M("choose another name, e.g. bras_description"))
    maintainer = _default_maintainer() if maintainer is None else maintainer
    check_maintainer(maintainer)
    email = default_email(maintainer) if email is None else email
    check_email(email)
    check_license(license_name)
    check_description(description)
    if package_format not in (2, 3):
        raise ParameterError(M("package format {format} does not exist: 2 or 3", format=package_format),
                             hint=M("leave --package-format out for format 3, as ros2 pkg create does"))
    for dependency in dependencies:
        check_dependency(dependency)
    for option, module in (("--node-name", node_name), ("--library-name", library_name)):
        if module is not None and (not (module.isidentifier() and module.isascii()) or keyword.iskeyword(module)):
            raise ParameterError(M("{option} '{name}' cannot be a Python module's name", option=option, name=module),
                                 hint=M("use lowercase letters, digits and underscores, e.g. animation"))
    if node_name is not None and node_name == library_name:  # ros2pkg/verb/create.py renames it, with a warning
        node_name += "_node"
    environment = jinja2.Environment(loader=jinja2.FileSystemLoader(str(templates_dir() / "empty")),
                                     undefined=jinja2.StrictUndefined, keep_trailing_newline=True,
                                     autoescape=False, trim_blocks=True, lstrip_blocks=True)
    context = {"name": name, "maintainer": maintainer, "email": email, "license": license_name,
               "description": description, "dependencies": list(dict.fromkeys(dependencies)),
               "node_name": node_name, "package_format": package_format}
    files = {target.format(name=name): environment.get_template(template).render(context)
             for template, target in _EMPTY_FILES}
    if node_name is not None:
        files[f"{name}/{node_name}.py"] = environment.get_template("pkg/node.py.j2").render(context)
    if library_name is not None:
        files[f"{name}/{library_name}/__init__.py"] = ""
    licence_text = templates_dir() / "empty" / "licenses" / f"{license_name}.txt"
    if "/" not in license_name and licence_text.is_file():
        files["LICENSE"] = licence_text.read_text(encoding="utf-8")
    return files


def scaffold_empty_package(dest: str | os.PathLike[str], name: str = DEFAULT_PACKAGE, force: bool = False, *,
                           maintainer: str | None = None, email: str | None = None,
                           license_name: str = DEFAULT_LICENSE, **options: Any) -> list[Path]:
    """Write what ``ros2 pkg create --build-type ament_python`` writes into ``dest``; return the files made
    (``options``: :func:`render_empty_package`'s)."""
    dest = Path(dest)
    _check_destination(dest, force)
    files = render_empty_package(name, maintainer=maintainer, email=email, license_name=license_name, **options)
    return _write(dest, files)


def _default_maintainer() -> str:
    try:
        return getpass.getuser()
    except (KeyError, OSError):
        return "maintainer"


def _check_destination(dest: Path, force: bool) -> None:
    if dest.exists() and not dest.is_dir():
        raise OutputExistsError(M("{path} exists and is not a folder", path=str(dest)),
                                hint=M("choose another DIR for the package"))
    if dest.is_dir() and any(dest.iterdir()) and not force:
        raise OutputExistsError(
            M("{path} already exists and is not empty", path=str(dest)),
            hint=M("pass --force to overwrite the package's files there (other files are left alone), "
                   "or choose another DIR"),
        )


def scaffold_package(
    dest: str | os.PathLike[str],
    name: str = DEFAULT_PACKAGE,
    wrist: bool = False,
    inertials: bool = False,
    params: Mapping[str, object] | None = None,
    force: bool = False,
    *,
    maintainer: str | None = None,
    email: str | None = None,
    lang: str = "en",
    xacro: bool = False,
) -> list[Path]:
    """Write the ament_python package ``name`` into ``dest``; return the files made.

    An existing non-empty ``dest`` is refused (:class:`OutputExistsError`) unless ``force``;
    every file is rendered before the first is written, so a bad parameter writes nothing.
    """
    dest = Path(dest)
    _check_destination(dest, force)
    files = render_package(name, wrist=wrist, inertials=inertials, params=params,
                           maintainer=maintainer, email=email, lang=lang, xacro=xacro)
    return _write(dest, files)


def _write(dest: Path, files: Mapping[str, str]) -> list[Path]:
    for relative in files:
        if (dest / relative).is_symlink():  # never write through a link planted in the folder
            raise OutputExistsError(M("{path} is a symbolic link: refused", path=str(dest / relative)),
                                    hint=M("remove the link, or choose another DIR"))
    made = []
    for relative, text in files.items():
        path = dest / relative
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text, encoding="utf-8")
        made.append(path)
    return made
