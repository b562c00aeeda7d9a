"""bras_kit.ros.rviz.config reads a .rviz as RViz 14 (jazzy) reads it, and Save Config writes one it reads.

Oracles: RViz's own default configuration (tests/data/rviz/rviz_common_default.rviz, a copy of
ros2/rviz jazzy rviz_common/default.rviz, see tests/data/rviz/README.md) and the rules of RViz's
config-reading code, cited beside each case (yaml_config_reader.cpp, display.cpp, display_group.cpp,
tf_frame_property.cpp, visualization_manager.cpp, enum_property.cpp)."""

from __future__ import annotations

import pytest
import yaml
from paths import TESTS

from bras_kit.ros.rviz.config import (
    GRID,
    KINDS,
    ROBOT_MODEL,
    TF,
    default_config,
    new_display,
    read_config,
    with_display,
    with_fixed_frame,
    with_option,
    without_display,
    write_config,
)

DATA = TESTS / "data"
DEFAULT = (DATA / "rviz" / "rviz_common_default.rviz").read_text(encoding="utf-8")
SAVED_BY_JAZZY = (DATA / "launch" / "jazzy_starts" / "bras_description" / "rviz" / "bras.rviz").read_text("utf-8")


def _raw(text: str):
    return yaml.load(text, Loader=yaml.BaseLoader)  # every scalar a string, as yaml-cpp reads it


def _shape(node, depth: int = 0):
    """The keys of a .rviz down to ``depth``: what "the same shape" means here."""
    if isinstance(node, dict):
        return {k: _shape(v, depth - 1) if depth > 0 else None for k, v in node.items()}
    return None


def test_rvizs_default_file_is_the_default_config():
    config = read_config(DEFAULT)
    assert config.fixed_frame == "map"  # "/map" at default.rviz:54, less the slash
    assert config == default_config()
    assert [(d.kind, d.name, d.enabled) for d in config.displays] == [(GRID, "Grid", True)]


def test_grid_options_are_the_default_files_own():
    grid = _raw(DEFAULT)["Visualization Manager"]["Displays"][0]
    options = {k: v for k, v in grid.items() if k not in ("Class", "Name", "Enabled", "Value")}
    assert dict(default_config().displays[0].options) == options


def test_saved_default_has_rvizs_shape_and_reads_back():
    text = write_config(default_config())
    ours, theirs = _raw(text), _raw(DEFAULT)
    assert set(ours) == set(theirs)  # Panels, Visualization Manager, Window Geometry
    assert set(theirs["Visualization Manager"]) <= set(ours["Visualization Manager"])
    assert set(theirs["Visualization Manager"]["Global Options"]) <= set(ours["Visualization Manager"]["Global Options"])
    assert ours["Visualization Manager"]["Displays"] == theirs["Visualization Manager"]["Displays"]
    assert read_config(text) == default_config()


def test_a_config_saved_by_jazzy_reads_as_rviz_shows_it():
    config = read_config(SAVED_BY_JAZZY)
    assert config.fixed_frame == "base"
    assert [(d.kind, d.enabled) for d in config.displays] == [(GRID, True), (ROBOT_MODEL, True), (TF, True)]
    model = config.displays[1]
    assert (model.description_source, model.description_topic) == ("Topic", "/robot_description")


@pytest.mark.parametrize("kind", KINDS)
def test_each_added_display_saves_in_the_shape_jazzy_saves_it(kind):
    """The keys a display gets from Add are those RViz jazzy saved for the same class."""
    saved = {d["Class"]: d for d in _raw(SAVED_BY_JAZZY)["Visualization Manager"]["Displays"]}
    ours = _raw(write_config(with_display(default_config(), new_display(kind))))["Visualization Manager"]["Displays"]
    assert set(ours[-1]) - {"Links"} >= set(saved[kind]) - {"Links"}  # Links: RobotModel's per-link tree
    assert _shape(ours[-1].get("Description Topic"), 1) == _shape(saved[kind].get("Description Topic"), 1)


def _config(body: str) -> str:
    return "Visualization Manager:\n" + body


@pytest.mark.parametrize(("text", "frame"), [
    (_config("  Global Options:\n    Fixed Frame: base\n"), "base"),
    (_config("  Global Options:\n    Fixed Frame: /base\n"), "base"),  # tf_frame_property.cpp:70-73
    (_config("  Global Options:\n    Fixed Frame: //base\n"), "/base"),  # one slash only
    (_config("  Global Options:\n    Fixed Frame: \"\"\n"), ""),
    (_config("  Global Options:\n    Fixed Frame: 1\n"), "1"),  # a string to yaml-cpp
    (_config("  Global Options:\n    Fixed Frame: true\n"), "true"),
    (_config("  Global Options:\n    Fixed Frame:\n      Value: bras\n"), "bras"),  # property.cpp:437
    (_config("  Global Options:\n    Fixed Frame: ~\n"), "base_link"),  # a null: nothing loaded
    (_config("  Global Options:\n    Fixed Frame:\n"), "base_link"),
    (_config("  Global Options:\n    Background Color: 0; 0; 0\n"), "base_link"),  # visualization_manager.cpp:185
    (_config("  Displays: []\n"), "base_link"),
    ("Panels: []\n", "base_link"),  # no Visualization Manager
    ("- a\n- b\n", "base_link"),
    ("", "base_link"),
])
def test_fixed_frame_as_rviz_loads_it(text, frame):
    assert read_config(text).fixed_frame == frame


def test_a_file_rviz_cannot_parse_loads_nothing():
    config = read_config(DEFAULT.replace("Fixed Frame: /map", "Fixed Frame: [map"))
    assert (config.fixed_frame, config.displays) == ("base_link", ())  # visualization_frame.cpp:703-712
    assert config.problem is not None and config.line is not None


def _one(display: str):
    return read_config(_config("  Displays:\n" + display)).displays[0]


@pytest.mark.parametrize(("entry", "enabled"), [
    ("    - Class: rviz_default_plugins/TF\n", False),  # unchecked by default, display.cpp:72-73
    ("    - Class: rviz_default_plugins/TF\n      Enabled: true\n", True),
    ("    - Class: rviz_default_plugins/TF\n      Value: true\n", True),  # BoolProperty::load
    ("    - Class: rviz_default_plugins/TF\n      Value: true\n      Enabled: false\n", False),  # Enabled last
    ("    - Class: rviz_default_plugins/TF\n      Value: false\n      Enabled: true\n", True),
    ("    - Class: rviz_default_plugins/TF\n      Enabled: False\n", False),  # Qt: "false" in any case
    ("    - Class: rviz_default_plugins/TF\n      Enabled: 0\n", False),
    ("    - Class: rviz_default_plugins/TF\n      Enabled: no\n", True),  # Qt knows only 0 and false
    ("    - Class: rviz_default_plugins/TF\n      Enabled: ~\n", False),
])
def test_enabled_as_rviz_reads_it(entry, enabled):
    assert _one(entry).enabled is enabled


def test_a_display_without_class_or_name():
    display = _one("    - Enabled: true\n")
    assert (display.kind, display.name) == ("(no class name found)", "")  # display_group.cpp:97


@pytest.mark.parametrize(("entry", "source", "topic"), [
    ("Description Source: Topic\n      Description Topic:\n        Value: /robot_description\n",
     "Topic", "/robot_description"),
    ("Description Topic: /robot_description\n", "Topic", "/robot_description"),  # no QoS children
    ("Description Source: File\n", "File", ""),
    ("Description Source: file\n", "Topic", ""),  # enum_property.cpp:65-73: unknown word, option 0
    ("Description Topic:\n        Depth: 5\n", "Topic", ""),
    ("Description Topic: \"\"\n", "Topic", ""),
])
def test_robot_model_description(entry, source, topic):
    display = _one("    - Class: rviz_default_plugins/RobotModel\n      Enabled: true\n      " + entry)
    assert (display.description_source, display.description_topic) == (source, topic)


def test_step_six_by_actions_saves_and_reads_back():
    config = default_config()
    config = with_fixed_frame(config, "base")
    config = with_display(config, new_display(ROBOT_MODEL))
    assert config.displays[1].description_topic == ""  # Add gives an empty Description Topic
    config = with_option(config, 1, "Description Topic", "/robot_description")
    config = with_display(config, new_display(TF))
    config = with_option(config, 2, "Enabled", False)
    back = read_config(write_config(config))
    assert back == config
    assert back.displays[1].description_topic == "/robot_description"
    assert without_display(back, 0).displays == back.displays[1:]


@pytest.mark.parametrize("frame", ["base: x", "#base", "- base", "'base'", "base\"", "bras avant", "é"])
def test_awkward_frames_survive_save(frame):
    assert read_config(write_config(with_fixed_frame(default_config(), frame))).fixed_frame == frame


def test_save_config_names_its_file_before_writing_and_a_refused_save_keeps_the_name(tmp_path):
    """The rebuild loop ignores Save Config's own file by name (view.rviz_state.written): named
    before the file appears (the loop may look between the write and the naming), and a second
    Save that asks before replacing does not drop the name the first one put there (the loop may
    not have seen the first write yet: it would take it for the learner's save and rebuild)."""
    from types import SimpleNamespace

    from bras_kit.view.rviz_state import RvizState

    state = RvizState(SimpleNamespace(rviz=None, root=str(tmp_path), package="bras_description"))
    seen_named = []
    import bras_kit.trust.outputs as outputs

    real = outputs.write_text

    def spying(path, *args, **kwargs):
        real(path, *args, **kwargs)
        seen_named.append(path in state.written)  # what the loop sees once the file is there

    outputs.write_text = spying
    try:
        first = state.save("bras_description.rviz", False)
        second = state.save("bras_description.rviz", False)
    finally:
        outputs.write_text = real
    assert (first.state, second.state) == ("saved", "exists")
    assert seen_named == [True]
    assert str(tmp_path / "rviz" / "bras_description.rviz") in state.written
