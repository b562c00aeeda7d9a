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


# How the launch starts rviz2, and what RViz then does (rviz_common, jazzy 591594e): its options
# as Qt's QCommandLineParser reads them (visualizer_app.cpp:84-103; -dFILE and --opt=FILE are Qt's
# forms, a value given twice is the last); no -d, or a file it cannot load, opens the default
# configuration (visualization_frame.cpp:345-349, 674-676); -f is set after the file
# (visualizer_app.cpp:165-168). (arguments, setup.py keeps rviz/, RViz reads the file, Fixed
# Frame RViz uses, BK613 variant or None, BK610 variant or None)
STARTS = {
    "d_file": ("['-d', rviz_config]", True, True, "base", None, None),
    "long_option": ("['--display-config', rviz_config]", True, True, "base", None, None),
    "long_option_equals": ("['--display-config=' + rviz_config]", True, True, "base", None, None),
    "short_option_glued": ("['-d' + rviz_config]", True, True, "base", None, None),
    "no_d": ("[]", True, False, "map", "unused", None),
    "d_to_a_file_the_package_lacks": ("['-d', os.path.join(share, 'rviz', 'autre.rviz')]", True, False, "map",
                                      "missing", None),
    "d_not_installed": ("['-d', rviz_config]", False, False, "map", "not_installed", None),
    "last_d_wins": ("['-d', os.path.join(share, 'rviz', 'autre.rviz'), '-d', rviz_config]", True, True, "base",
                    None, None),
    "f_alone": ("['-f', 'base']", True, False, "base", "unused", None),
    "f_over_the_file": ("['-d', rviz_config, '-f', 'monde']", True, True, "monde", None, "argument"),
    "f_long_over_the_file": ("['-d', rviz_config, '--fixed-frame=/base']", True, True, "base", None, None),
    # a file RViz never loads says nothing of its own Fixed Frame: RViz shows map (BK613 says why)
    "not_installed_with_a_wrong_frame": ("['-d', rviz_config]", False, False, "map", "not_installed", None,
                                         "monde"),
    "installed_with_a_wrong_frame": ("['-d', rviz_config]", True, True, "monde", None, "", "monde"),
}


@pytest.mark.parametrize("case", list(STARTS))
def test_the_terminal_says_rviz_opens_its_default_exactly_when_the_page_opens_it(scaffolded, tmp_path, case):
    """The terminal's BK613 and BK610 and the page's RViz come from one evaluation of the launch
    (bras-kit launch's: ros.evaluation, then the package rules), for each way rviz2 can be started."""
    import shutil

    from bras_kit.ros.evaluation import evaluate_launch
    from bras_kit.ros.rviz.config import default_config
    from bras_kit.validate.package import Package
    from bras_kit.validate.package.launch_check import check_launch

    arguments, installed, read, frame, bk613, bk610, *in_file = STARTS[case]
    root = tmp_path / "bras_description"
    shutil.copytree(scaffolded, root)
    if in_file:  # the .rviz's own Fixed Frame
        rviz = root / "rviz" / "bras_description.rviz"
        rviz.write_text(rviz.read_text(encoding="utf-8").replace("Fixed Frame: base", f"Fixed Frame: {in_file[0]}"),
                        encoding="utf-8")
    launch = root / "launch" / "affichage.launch.py"
    text = launch.read_text(encoding="utf-8")
    assert "arguments=['-d', rviz_config]" in text
    launch.write_text(text.replace("arguments=['-d', rviz_config]", f"arguments={arguments}"), encoding="utf-8")
    if not installed:
        setup = root / "setup.py"
        setup.write_text(setup.read_text(encoding="utf-8").replace("        installed('rviz', '*.rviz'),\n", ""),
                         encoding="utf-8")
    package = Package(str(root))
    evaluation = evaluate_launch(str(root), str(tmp_path / "install"), "affichage.launch.py", {}, package)
    check_launch(evaluation, package)
    found = {f.code: f.variant for r in evaluation.results for f in r.findings if f.code in ("BK610", "BK613")}
    page = evaluation.rviz  # what the page's RViz opens with
    assert (evaluation.rviz_file is not None) is read
    assert page.fixed_frame == frame
    if not read:
        assert page.displays == default_config().displays
    assert found.get("BK613") == bk613, found
    assert found.get("BK610") == bk610, found


@pytest.mark.parametrize(("removed", "bk615"), [("package='rviz2'", True), ("package=PACKAGE, executable='animation'", False)])
def test_a_launch_without_rviz2_opens_no_rviz_in_the_page_nor_the_terminal(scaffolded, tmp_path, removed, bk615):
    """No rviz2 in the launch: the page has no RViz (evaluation.rviz None, its blank says so) and
    the terminal's BK615 says the same, at the robot_state_publisher line; with rviz2, neither."""
    import shutil

    from bras_kit.ros.evaluation import NO_RVIZ, evaluate_launch
    from bras_kit.validate.package import Package
    from bras_kit.validate.package.launch_check import check_launch

    root = tmp_path / "bras_description"
    shutil.copytree(scaffolded, root)
    launch = root / "launch" / "affichage.launch.py"
    lines = launch.read_text(encoding="utf-8").splitlines(keepends=True)
    kept = [line for line in lines if removed not in line]
    assert len(kept) == len(lines) - 1
    launch.write_text("".join(kept), encoding="utf-8")
    package = Package(str(root))
    evaluation = evaluate_launch(str(root), str(tmp_path / "install"), "affichage.launch.py", {}, package)
    check_launch(evaluation, package)
    found = [(f.code, r.path, f.line) for r in evaluation.results for f in r.findings if f.code == "BK615"]
    rsp = next(k for k, line in enumerate(kept, 1) if "robot_state_publisher'" in line)
    assert found == ([("BK615", str(root / "launch" / "affichage.launch.py"), rsp)] if bk615 else [])
    assert (evaluation.rviz is None) is bk615
    assert (evaluation.blank() is NO_RVIZ) is bk615


def test_the_pages_header_counts_the_warnings_as_the_terminals_summary_does():
    """The header's counts are the terminal's summary's (N files checked: E errors, W warnings, I
    info): a warning explains what the learner sees as often as an error does."""
    import re
    from types import SimpleNamespace

    from bras_kit.findings.data import FileResult
    from bras_kit.findings.report import summary_text
    from bras_kit.view.panel import banner

    for severities in (["error", "warning", "warning", "info"], ["warning"], ["info", "info"], ["error"]):
        found = [SimpleNamespace(severity=s, code="BK600", file="x", line=None) for s in severities]
        header = re.sub(r"<[^>]+>", "", banner(None, found, "en"))
        terminal = summary_text([FileResult("x.urdf", found)], "en")
        for word in ("error", "warning"):
            said = re.search(rf"(\d+) {word}s?", terminal)
            count = int(said.group(1)) if said else 0
            shown = re.search(rf"(\d+) {word}s?", header)
            assert (int(shown.group(1)) if shown else 0) == count, (severities, header, terminal)
