"""The terminal's BK611 and the page's RViz read a .rviz one way (issue 55): the package rule and
``shown()`` both start from ``bras_kit.ros.rviz.config.read_config``, so for each way a RobotModel
can be set, BK611 fires exactly when the page (RViz) draws no arm.

Oracle: RViz jazzy's reading rules, one case per rule (display.cpp:72-73 a display unchecked by
default, 277-291 Value then Enabled; config.cpp:263-271 and Qt's string-to-bool; enum_property.cpp:
65-73 an unknown Description Source is Topic; ros_topic_display.hpp:197-202 an empty topic)."""

from __future__ import annotations

import pytest

from bras_kit.ros.rviz.config import read_config, shown
from bras_kit.ros.rviz.started import launch_transforms

ENABLED = "      Enabled: true\n"
VALUE = "      Value: true\n"

# (how the RobotModel's lines are changed, whether RViz draws the arm)
CASES = {
    "as_scaffolded": ({}, True),
    "value_false_enabled_true": ({VALUE: "      Value: false\n"}, True),  # Enabled is read last
    "enabled_false_value_true": ({ENABLED: "      Enabled: false\n"}, False),
    "enabled_capital_false": ({ENABLED: "      Enabled: False\n", VALUE: ""}, False),  # Qt: any case
    "enabled_zero": ({ENABLED: "      Enabled: 0\n", VALUE: ""}, False),
    "enabled_no": ({ENABLED: "      Enabled: no\n", VALUE: ""}, True),  # Qt knows only 0 and false
    "neither_enabled_nor_value": ({ENABLED: "", VALUE: ""}, False),  # unchecked by default
    "source_lowercase_file": ({"Description Source: Topic": "Description Source: file"}, True),
    "topic_empty": ({"        Value: /robot_description\n": "        Value: \"\"\n"}, False),
    "topic_misspelt": ({"        Value: /robot_description\n": "        Value: /robot_descripton\n"}, False),
}


def _robot_model_block(text: str) -> tuple[int, int]:
    start = text.index("    - Alpha: 1\n      Class: rviz_default_plugins/RobotModel")
    end = text.index("    - Class: rviz_default_plugins/TF", start)
    return start, end


@pytest.fixture(scope="module")
def scaffolded(tmp_path_factory):
    from bras_kit.scaffold.package import scaffold_package

    root = tmp_path_factory.mktemp("pkg") / "bras_description"
    scaffold_package(root)
    return root


@pytest.mark.parametrize("case", list(CASES))
def test_bk611_fires_exactly_when_the_page_draws_no_arm(scaffolded, tutorial_robot, tmp_path, case):
    import shutil

    from bras_kit.validate.package import validate_package

    changes, drawn = CASES[case]
    root = tmp_path / "bras_description"
    shutil.copytree(scaffolded, root)
    rviz = root / "rviz" / "bras_description.rviz"
    text = rviz.read_text(encoding="utf-8")
    start, end = _robot_model_block(text)
    block = text[start:end]
    for old, new in changes.items():
        assert old in block, (case, old)
        block = block.replace(old, new, 1)
    text = text[:start] + block + text[end:]
    rviz.write_text(text, encoding="utf-8")
    seen = shown(read_config(text), tutorial_robot, launch_transforms(tutorial_robot, True), {"/robot_description"})
    assert seen.arm_drawn is drawn  # RViz's rules, as the page applies them
    found = [f.code for r in validate_package(str(root), select=["BK611"]) for f in r.findings]
    assert (found == []) is drawn, (case, found)
