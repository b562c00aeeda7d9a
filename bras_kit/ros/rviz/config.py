"""What RViz is set to show: a ``.rviz`` read as RViz 14 (jazzy) reads it, RViz's own defaults, Save
Config, and what RViz then shows for a robot and the transforms robot_state_publisher sends.

Every rule cites the RViz source it follows (github.com/ros2/rviz, branch jazzy, commit 591594e):

* RViz reads a ``.rviz`` with yaml-cpp, and every scalar becomes a *string* (rviz_common
  yaml_config_reader.cpp:126-137); a null (``~``, an empty value) is no value at all (:139). Typed
  values are made from those strings by each property, so ``Enabled: false`` is the string "false"
  turned into a bool by Qt (config.cpp:263-271). :func:`read_config` keeps that: strings, lists, maps.
* A file that yaml-cpp cannot parse is not loaded at all (visualization_frame.cpp:703-712): RViz keeps
  what its constructor built, Fixed Frame ``base_link`` (visualization_manager.cpp:184-188) and no
  display. The same holds for a file with no ``Visualization Manager`` or no ``Fixed Frame``.
* Without ``-d``, RViz loads ``~/.rviz2/default.rviz`` (visualization_frame.cpp:345-349, 380-382) and,
  when that does not exist, its own ``rviz_common/default.rviz`` (visualization_frame.cpp:675-676):
  Fixed Frame ``/map`` (default.rviz:54) and a Grid (default.rviz:33-50). A ``-d`` naming a file that
  does not exist loads the same default (visualization_frame.cpp:674-676).
* The Fixed Frame loses one leading ``/`` (tf_frame_property.cpp setValue, :70-73), so ``/map`` is ``map``.
"""

from __future__ import annotations

import re
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field, replace
from typing import Any

import yaml

from ...core.message import M, Message

GRID = "rviz_default_plugins/Grid"
ROBOT_MODEL = "rviz_default_plugins/RobotModel"
TF = "rviz_default_plugins/TF"
KINDS = (GRID, ROBOT_MODEL, TF)  # what the page's Add offers, as RViz names the classes

CONSTRUCTED_FRAME = "base_link"  # visualization_manager.cpp:185, before any configuration is loaded
DEFAULT_FRAME = "map"  # default.rviz:54 "/map", less the slash (tf_frame_property.cpp:70-73)
FIXED_FRAME_STRING = "<Fixed Frame>"  # tf_frame_property.cpp:47
SOURCES = ("Topic", "File")  # robot_model_display.cpp:123-127, Topic first (index 0)

# Status levels, as rviz_common StatusProperty names them
OK, WARN, ERROR = "Ok", "Warn", "Error"


@dataclass(frozen=True)
class Display:
    """One display of the Displays panel. ``kind`` is RViz's class name (``Class:``); ``options`` are
    the display's other keys as read (strings, lists and maps, as RViz holds them)."""

    kind: str
    name: str
    enabled: bool = True
    options: Mapping[str, Any] = field(default_factory=dict)

    @property
    def description_source(self) -> str:
        # EnumProperty::getOptionInt gives 0 (Topic) for an unknown word (enum_property.cpp:65-73)
        value = _value(self.options.get("Description Source"))
        return "File" if value == "File" else "Topic"

    @property
    def description_topic(self) -> str:
        # a topic property with QoS children saves its own value under "Value" (property.cpp:467-475)
        value = _value(self.options.get("Description Topic"))
        return value if isinstance(value, str) else ""

    @property
    def description_file(self) -> str:
        value = _value(self.options.get("Description File"))
        return value if isinstance(value, str) else ""


@dataclass(frozen=True)
class RvizConfig:
    """What RViz is set to show: the Fixed Frame (Global Options) and the displays, in order.
    ``problem`` says why a file could not be read (then the rest is RViz's constructed state)."""

    fixed_frame: str
    displays: tuple[Display, ...] = ()
    problem: Message | None = None
    line: int | None = None


# ---------------------------------------------------------------------------- reading


class _Strings(yaml.SafeLoader):
    """yaml-cpp's view: every scalar a string, a null no value (yaml_config_reader.cpp:126-139)."""


_NULL = re.compile(r"^(?:~|null|Null|NULL|)$")
_Strings.yaml_implicit_resolvers = {}
for _first in ["~", "n", "N", ""]:
    _Strings.add_implicit_resolver("tag:yaml.org,2002:null", _NULL, [_first] if _first else None)


def _value(node: Any) -> Any:
    """The value of a property as Property::load takes it: a map's own value is its "Value" child
    (property.cpp:430-438)."""
    if isinstance(node, Mapping):
        return node.get("Value")
    return node


def _qt_bool(text: str) -> bool:
    # QVariant(QString).toBool(): false for "", "0" and "false" (any case), true otherwise
    return text.strip().lower() not in ("", "0", "false")


def constructed() -> RvizConfig:
    """RViz before any configuration: Fixed Frame base_link, no display (visualization_manager.cpp:185)."""
    return RvizConfig(CONSTRUCTED_FRAME)


def read_config(text: str | bytes) -> RvizConfig:
    """A ``.rviz`` as RViz 14 reads it (``rviz2 -d FILE``)."""
    from ...trust import yaml_gate

    try:
        data = yaml_gate.load(text, loader=_Strings)
    except yaml_gate.YamlRefused as exc:
        return replace(constructed(), problem=exc.message, line=exc.line)
    except yaml.YAMLError as exc:
        mark = getattr(exc, "problem_mark", None)
        return replace(constructed(), problem=M("RViz cannot read this file: {problem}",
                                                problem=str(getattr(exc, "problem", "") or exc)),
                       line=mark.line + 1 if mark is not None else None)
    manager = data.get("Visualization Manager") if isinstance(data, Mapping) else None
    if not isinstance(manager, Mapping):
        # visualization_frame.cpp:815 loads the "Visualization Manager" child; none, nothing loaded
        return constructed()
    fixed, _set = fixed_frame_of(data)
    displays = manager.get("Displays")
    return RvizConfig(fixed, tuple(_display(d) for d in displays) if isinstance(displays, list) else ())


def fixed_frame_of(data: Any) -> tuple[str, bool]:
    """(the Fixed Frame RViz uses with this parsed .rviz, whether the file sets one): a file that
    sets none leaves the constructor's ``base_link`` (visualization_manager.cpp:185)."""
    manager = data.get("Visualization Manager") if isinstance(data, Mapping) else None
    options = manager.get("Global Options") if isinstance(manager, Mapping) else None
    frame = _value(options.get("Fixed Frame")) if isinstance(options, Mapping) else None
    if isinstance(frame, str):
        return _strip_slash(frame), True
    return CONSTRUCTED_FRAME, False


def _strip_slash(frame: str) -> str:
    return frame[1:] if frame.startswith("/") else frame  # tf_frame_property.cpp:70-73, one slash


def _display(node: Any) -> Display:
    """One entry of Displays, as DisplayGroup::load makes it (display_group.cpp:95-116)."""
    node = node if isinstance(node, Mapping) else {}
    kind = node.get("Class")
    name = node.get("Name")
    # unchecked by default (display.cpp:72-73); then "Value", then "Enabled" (display.cpp:277-291)
    enabled = False
    for key in ("Value", "Enabled"):
        if isinstance(node.get(key), str):
            enabled = _qt_bool(node[key])
    options = {k: v for k, v in node.items() if k not in ("Class", "Name", "Enabled", "Value")}
    return Display(kind if isinstance(kind, str) else "(no class name found)",  # display_group.cpp:97
                   name if isinstance(name, str) else "", enabled, options)


def default_config() -> RvizConfig:
    """What ``rviz2`` with no ``-d`` shows when the learner has no ``~/.rviz2/default.rviz``:
    rviz_common/default.rviz (Fixed Frame map, one Grid)."""
    return RvizConfig(DEFAULT_FRAME, (new_display(GRID),))


# ---------------------------------------------------------------------------- the learner's actions


def new_display(kind: str, name: str | None = None) -> Display:
    """A display as Add makes it: enabled, named after its class, with the class's own defaults
    (Grid: default.rviz:33-50; RobotModel: robot_model_display.cpp:81-140, an empty Description
    Topic; TF: tf_display.cpp:98-160)."""
    return Display(kind, name or kind.rsplit("/", 1)[-1], True, dict(_DEFAULTS.get(kind, {})))


def with_fixed_frame(config: RvizConfig, frame: str) -> RvizConfig:
    return replace(config, fixed_frame=_strip_slash(frame.strip()))


def with_display(config: RvizConfig, display: Display) -> RvizConfig:
    return replace(config, displays=(*config.displays, display))


def without_display(config: RvizConfig, index: int) -> RvizConfig:
    return replace(config, displays=tuple(d for k, d in enumerate(config.displays) if k != index))


def with_option(config: RvizConfig, index: int, key: str, value: str | bool) -> RvizConfig:
    """One display's property set, as its row in the Displays panel sets it. ``Enabled`` is the
    display's check box; ``Description Topic`` keeps its QoS children."""
    displays = list(config.displays)
    display = displays[index]
    if key == "Enabled":
        displays[index] = replace(display, enabled=bool(value) if isinstance(value, bool) else _qt_bool(value))
    else:
        options = dict(display.options)
        old = options.get(key)
        options[key] = {**old, "Value": value} if isinstance(old, Mapping) else value
        displays[index] = replace(display, options=options)
    return replace(config, displays=tuple(displays))


# ---------------------------------------------------------------------------- Save Config

_DEFAULTS: dict[str, dict[str, Any]] = {
    GRID: {  # default.rviz:33-50
        "Alpha": "0.5", "Cell Size": "1", "Color": "160; 160; 164",
        "Line Style": {"Line Width": "0.03", "Value": "Lines"}, "Normal Cell Count": "0",
        "Offset": {"X": "0", "Y": "0", "Z": "0"}, "Plane": "XY", "Plane Cell Count": "10",
        "Reference Frame": FIXED_FRAME_STRING,
    },
    ROBOT_MODEL: {  # robot_model_display.cpp:81-140; the topic's QoS as ros_topic_display.hpp keeps it
        "Alpha": "1", "Collision Enabled": "false", "Description File": "", "Description Source": "Topic",
        "Description Topic": {"Depth": "5", "Durability Policy": "Volatile", "History Policy": "Keep Last",
                              "Reliability Policy": "Reliable", "Value": ""},
        "Mass Properties": {"Inertia": "false", "Mass": "false"}, "TF Prefix": "", "Update Interval": "0",
        "Visual Enabled": "true",
    },
    TF: {  # tf_display.cpp:98-160
        "Filter (blacklist)": "", "Filter (whitelist)": "", "Frame Timeout": "15",
        "Frames": {"All Enabled": "true"}, "Marker Scale": "1", "Show Arrows": "true", "Show Axes": "true",
        "Show Names": "false", "Update Interval": "0",
    },
}


class _StringDumper(yaml.SafeDumper):
    """Writes strings plain where yaml-cpp reads them back as the same string."""


_StringDumper.yaml_implicit_resolvers = dict(_Strings.yaml_implicit_resolvers)


def _texts(node: Any) -> Any:
    if isinstance(node, Mapping):
        return {str(k): _texts(v) for k, v in node.items()}
    if isinstance(node, list | tuple):
        return [_texts(v) for v in node]
    if isinstance(node, bool):
        return "true" if node else "false"
    return None if node is None else str(node)


def write_config(config: RvizConfig) -> str:
    """Save Config: a ``.rviz`` in the shape RViz 14 writes (rviz_common/default.rviz's sections;
    each display with Class, Name, Enabled and Value as Display::save writes them, display.cpp:293-301)."""
    displays = []
    for display in config.displays:
        entry = dict(display.options)
        entry.update({"Class": display.kind, "Name": display.name, "Enabled": display.enabled,
                      "Value": display.enabled})
        displays.append(entry)
    document = {
        "Panels": [
            {"Class": "rviz_common/Displays", "Help Height": "78", "Name": "Displays",
             "Property Tree Widget": {"Expanded": ["/Global Options1", "/Status1"], "Splitter Ratio": "0.5"},
             "Tree Height": "464"},
            {"Class": "rviz_common/Selection", "Name": "Selection"},
            {"Class": "rviz_common/Views", "Expanded": ["/Current View1"], "Name": "Views",
             "Splitter Ratio": "0.5"},
        ],
        "Visualization Manager": {
            "Class": "",
            "Displays": displays,
            "Enabled": True,
            "Global Options": {"Background Color": "48; 48; 48", "Fixed Frame": config.fixed_frame,
                               "Frame Rate": "30"},
            "Name": "root",
            "Tools": [{"Class": "rviz_default_plugins/Interact", "Hide Inactive Objects": True},
                      {"Class": "rviz_default_plugins/MoveCamera"}, {"Class": "rviz_default_plugins/Select"},
                      {"Class": "rviz_default_plugins/FocusCamera"}, {"Class": "rviz_default_plugins/Measure"}],
            "Transformation": {"Current": {"Class": "rviz_default_plugins/TF"}},
            "Value": True,
            "Views": {
                "Current": {"Class": "rviz_default_plugins/Orbit", "Distance": "2", "Focal Point":
                            {"X": "0", "Y": "0", "Z": "0.3"}, "Name": "Current View", "Near Clip Distance": "0.01",
                            "Pitch": "0.5", "Target Frame": FIXED_FRAME_STRING, "Value": "Orbit (rviz)",
                            "Yaw": "0.785398"},
                "Saved": None,
            },
        },
        "Window Geometry": {"Displays": {"collapsed": False}, "Height": "846", "Hide Left Dock": False,
                            "Hide Right Dock": True, "Width": "1200", "X": "60", "Y": "60"},
    }
    return str(yaml.dump(_texts(document), Dumper=_StringDumper, default_flow_style=False, sort_keys=True,
                         allow_unicode=True, width=100))


# ---------------------------------------------------------------------------- what RViz shows


@dataclass(frozen=True)
class Status:
    """One row of a status list, in RViz's words (they stay English: RViz has no translation)."""

    level: str
    name: str
    text: str


@dataclass(frozen=True)
class DisplayShown:
    display: Display
    statuses: tuple[Status, ...] = ()
    drawn: tuple[str, ...] = ()  # links (RobotModel), frames (TF), or the Grid's own name

    @property
    def level(self) -> str:
        levels = [s.level for s in self.statuses]
        return ERROR if ERROR in levels else WARN if WARN in levels else OK


@dataclass(frozen=True)
class Shown:
    """What RViz shows: its Global Status, each display's status, and the links of the arm drawn."""

    config: RvizConfig
    global_status: Status
    displays: tuple[DisplayShown, ...]
    links: tuple[str, ...]  # the robot's links some RobotModel draws, in the robot's order

    @property
    def arm_drawn(self) -> bool:
        return bool(self.links)


def shown(config: RvizConfig, robot: Any, transforms: Iterable[Any], description_topics: Iterable[str],
          files: Mapping[str, str] | None = None) -> Shown:
    """What RViz shows with ``config`` while ``transforms`` (frames.Tf) are on tf and the robot's
    description is published on ``description_topics`` (``files``: the description files a
    RobotModel with Description Source File can read, path -> text)."""
    from .frames import placed_links

    tfs = list(transforms)
    kept = [t for t in tfs if not getattr(t, "nan", False)]  # tf2 refuses NaN: no frame made of it
    frames = {t.parent for t in kept} | {t.child for t in kept}
    topics = set(description_topics)
    fixed = config.fixed_frame
    # visualization_manager.cpp:431-451, the "Fixed Frame" row of the Global Status; a frame exists
    # once a transform names it (tf_frame_transformer.cpp:213-219)
    if fixed in frames:
        status = Status(OK, "Fixed Frame", "OK")
    elif not kept:
        status = Status(WARN, "Fixed Frame", f"No tf data.  Actual error: Frame [{fixed}] does not exist")
    else:
        status = Status(ERROR, "Fixed Frame", f"Frame [{fixed}] does not exist")
    placed = placed_links(robot, fixed, tfs) if robot is not None else {}
    out = []
    drawn_links: set[str] = set()
    for display in config.displays:
        one = _shown_display(display, robot, placed, frames, topics, files or {}, fixed)
        if display.kind == ROBOT_MODEL:
            drawn_links.update(one.drawn)
        out.append(one)
    order = [link.name for link in robot.links] if robot is not None else []
    return Shown(config, status, tuple(out), tuple(n for n in order if n in drawn_links))


def _shown_display(display: Display, robot: Any, placed: Mapping[str, Any], frames: set[str], topics: set[str],
                   files: Mapping[str, str], fixed: str) -> DisplayShown:
    if not display.enabled:
        return DisplayShown(display)  # onDisable: unsubscribed, nothing drawn (robot_model_display.cpp:313-318)
    if display.kind == GRID:
        return DisplayShown(display, (), (display.name,))
    if display.kind == TF:
        return _shown_tf(display, placed, frames, fixed)
    if display.kind == ROBOT_MODEL:
        return _shown_robot_model(display, robot, placed, topics, files, fixed)
    # display_group.cpp:123-132: a class RViz has no plugin for becomes a FailedDisplay
    return DisplayShown(display, (Status(ERROR, "Class", f"The class required for this display, '{display.kind}', "
                                                         "could not be loaded."),))


def _shown_tf(display: Display, placed: Mapping[str, Any], frames: set[str], fixed: str) -> DisplayShown:
    # tf_display.cpp:470-481: each frame on tf, placed or not
    statuses, drawn = [], []
    for frame in sorted(frames):
        if frame == fixed or (frame in placed and placed[frame] is None):
            statuses.append(Status(OK, frame, "Transform OK"))
            drawn.append(frame)
        else:
            statuses.append(Status(WARN, frame, f"No transform from [{frame}] to [{fixed}]"))
    return DisplayShown(display, tuple(statuses), tuple(drawn))


def _shown_robot_model(display: Display, robot: Any, placed: Mapping[str, Any], topics: set[str],
                       files: Mapping[str, str], fixed: str) -> DisplayShown:
    statuses: list[Status] = []
    if display.description_source == "Topic":
        topic = display.description_topic
        if not topic:  # ros_topic_display.hpp:197-202
            return DisplayShown(display, (Status(ERROR, "Topic", "Error subscribing: Empty topic name"),))
        if topic not in topics:
            # subscribed (ros_topic_display.hpp:226), but nothing comes: no URDF, nothing drawn
            return DisplayShown(display, (Status(OK, "Topic", "OK"),))
        statuses.append(Status(OK, "Topic", "1 messages received"))  # ros_topic_display.hpp:262-280
    else:
        path = display.description_file
        if not path:
            return DisplayShown(display)  # robot_model_display.cpp:229-237: an empty path clears
        if not files.get(path):  # robot_model_display.cpp:241-256
            return DisplayShown(display, (Status(ERROR, "URDF", "URDF is empty"),))
    if robot is None or not robot.links:  # robot_model_display.cpp:274-279
        return DisplayShown(display, (*statuses, Status(ERROR, "URDF", "URDF failed Model parse")))
    statuses.append(Status(OK, "URDF", "URDF parsed OK"))  # robot_model_display.cpp:282
    drawn = []
    for link in robot.links:  # tf_link_updater.cpp:68-78
        reason = placed.get(link.name)
        if link.name in placed and reason is None:
            statuses.append(Status(OK, link.name, "Transform OK"))
            drawn.append(link.name)
        else:
            text = str(reason) if reason is not None else f"No transform from [{link.name}] to [{fixed}]"
            statuses.append(Status(ERROR, link.name, text))
    return DisplayShown(display, tuple(statuses), tuple(drawn))


# ---------------------------------------------------------------------------- why, in the learner's words


def why_not_drawn(seen: Shown, robot: Any, published: Iterable[str] = ()) -> Message | None:
    """Why RViz draws no arm (or only part of it) in ``seen``, with what to do; None when the whole
    arm is drawn. RViz's own words are quoted; the rest is ours (translated)."""
    links = [link.name for link in robot.links if link.name] if robot is not None else []
    if robot is None or (links and set(seen.links) == set(links)):
        return None
    root = _root(robot) or (links[0] if links else "base")
    models = [d for d in seen.displays if d.display.kind == ROBOT_MODEL]
    topics = sorted(published)
    topic = topics[0] if topics else "/robot_description"
    status = seen.global_status
    fixed = seen.config.fixed_frame
    if status.level != OK and fixed not in links:
        return M("Fixed Frame [{frame}] does not exist: RViz's Global Status says \"{status}\". Set Fixed Frame "
                 "to {root}, the robot's root link (its frames: {links}).", frame=fixed, status=status.text,
                 root=root, links=", ".join(links))
    if not models:
        return M("No RobotModel display: click Add, choose RobotModel, then set its Description Topic to {topic}.",
                 topic=topic)
    enabled = [d for d in models if d.display.enabled]
    if not enabled:
        return M("The RobotModel display is unchecked: tick it to draw the robot.")
    model = enabled[0]
    if seen.links:
        missing = [s for s in model.statuses if s.level == ERROR and s.name in links]
        if missing:
            return M("RViz draws only {drawn}: the RobotModel says \"{status}\". robot_state_publisher publishes "
                     "the moving links once something publishes /joint_states.",
                     drawn=", ".join(seen.links), status=missing[0].text)
        return None
    display = model.display
    if display.description_source == "File":
        if not display.description_file:
            return M("The RobotModel reads its description from a file and none is given: set Description "
                     "Source to Topic and Description Topic to {topic}.", topic=topic)
        return M("The RobotModel says \"URDF is empty\": RViz cannot read {file}.", file=display.description_file)
    if not display.description_topic:
        return M("The RobotModel says \"Error subscribing: Empty topic name\": set its Description Topic to "
                 "{topic}.", topic=topic)
    if display.description_topic not in set(topics):
        return M("Nothing publishes {topic}: robot_state_publisher publishes the robot on {published}. Set the "
                 "RobotModel's Description Topic to it.", topic=display.description_topic,
                 published=", ".join(topics) or "-")
    errors = [s for s in model.statuses if s.level == ERROR]
    if errors:
        return M("The RobotModel says \"{status}\".", status=errors[0].text)
    return None


def _root(robot: Any) -> str | None:
    children = {j.child for j in robot.joints}
    return next((link.name for link in robot.links if link.name and link.name not in children), None)
