"""Launch files answered as ROS 2 Jazzy answers them (issue 44, the Launch categories).

Every file is tests/data/launch/fidelity/bras_description/launch/<case>. The expected nodes,
command lines and error words were obtained by running the real Jazzy sources on each file —
launch 3.4.3 / launch_xml / launch_yaml (ros2/launch, branch jazzy) and launch_ros 0.26.6
(ros2/launch_ros, branch jazzy), wrapped in IncludeLaunchDescription as ros2launch/api/api.py:168
does, with no process started — and are kept in tests/data/launch/fidelity/JAZZY.md. ROS argument
parsing follows rcl 9.2.0 (rcl/src/rcl/arguments.c), the words of UnknownROSArgsError rclpy's
utils.cpp:277 and rclcpp's exceptions.hpp:199.
"""

from __future__ import annotations

import os
import shutil

import pytest
from paths import DATA as DATA_DIR

from bras_kit.ros.build import build_package
from bras_kit.ros.launching import ros_arguments_start
from bras_kit.ros.names import (
    InvalidROSArgs,
    expand_topic_name,
    parse_ros_arguments,
    resolve_topic_name,
    unknown_ros_args_error,
)
from bras_kit.validate.package import validate_package

DATA = os.path.join(DATA_DIR, "launch", "fidelity", "bras_description")
# the same package with a node publishing JointState on 'etats' (bras_description/etats.py)
TOPICS = os.path.join(DATA_DIR, "launch", "fidelity_topics", "bras_description")


@pytest.fixture(scope="module")
def installed(tmp_path_factory):
    """The fidelity package built once; plan(FILE) evaluates one of its launch files."""
    from bras_kit.ros.launching import plan_launch

    record = build_package(DATA, str(tmp_path_factory.mktemp("fidelity") / "install"))
    assert record.failure is None
    share = os.path.join(record.prefix, "share", "bras_description")

    def plan(name: str):
        return plan_launch(os.path.join(share, "launch", name), [record.prefix], learner_roots=(DATA,))

    plan.share = share  # type: ignore[attr-defined]
    return plan


def started(plan) -> list[tuple[str, list[str]]]:
    """(full node name, command line after the program) of each node, in start order."""
    return [(n.full_name, n.argv) for n in plan.nodes]


def package_with(tmp_path, *launch_files: str, data: str = DATA) -> str:
    """A copy of the fidelity package (or ``data``) holding only ``launch_files`` in launch/."""
    dest = tmp_path / "bras_description"
    shutil.copytree(data, dest, ignore=shutil.ignore_patterns("launch"))
    (dest / "launch").mkdir()
    for name in launch_files:
        shutil.copy(os.path.join(data, "launch", name), dest / "launch" / name)
    return str(dest)


def findings(root: str, *codes: str) -> list[tuple[str, str, str, int | None]]:
    return [(f.code, f.variant, os.path.relpath(r.path, root), f.line)
            for r in validate_package(root, select=list(codes), launch=True) for f in r.findings]


# ---------------------------------------------------------------- substitutions before the split


@pytest.mark.parametrize("name", ["args_substitution.launch.xml", "args_substitution.launch.yaml"])
def test_args_attribute_is_read_for_substitutions_before_it_is_split(installed, name):
    plan = installed(name)
    assert plan.failure is None
    rviz = plan.nodes[-1]
    assert rviz.arguments == ["-d", os.path.join(installed.share, "rviz", "bras.rviz")]
    assert rviz.argv == ["-d", os.path.join(installed.share, "rviz", "bras.rviz"), "--ros-args"]


def test_words_around_substitutions_become_arguments_as_parse_cmdline_splits_them(installed):
    plan = installed("args_words_around_substitutions.launch.xml")
    assert plan.failure is None
    assert plan.nodes[0].arguments == ["--fixed-frame", "base", "-d", f"{installed.share}/rviz/bras.rviz",
                                       "--splash-screen", "base.png"]
    assert [p["cmd"] for p in plan.processes] == [["cat", f"{installed.share}/urdf/bras.urdf"]]


# ---------------------------------------------------------------- names as rcl resolves them


def test_rcl_expands_relative_private_and_absolute_names():
    assert expand_topic_name("robot_description", "robot_state_publisher", "/bras") == "/bras/robot_description"
    assert expand_topic_name("robot_description", "robot_state_publisher", "/") == "/robot_description"
    assert expand_topic_name("~/description", "robot_state_publisher", "/") == "/robot_state_publisher/description"
    assert expand_topic_name("~/description", "rsp", "/bras") == "/bras/rsp/description"
    assert expand_topic_name("/joint_states", "rsp", "/bras") == "/joint_states"
    assert expand_topic_name("{node}/x", "rsp", "/bras") == "/bras/rsp/x"


def test_rcl_remaps_the_first_matching_rule_on_the_expanded_name():
    rules = parse_ros_arguments(["--ros-args", "-r", "other:=/x", "-r", "robot_description:=~/description",
                                 "-r", "/bras/robot_description:=/y"]).remaps
    assert resolve_topic_name("robot_description", "rsp", "/bras", rules) == "/bras/rsp/description"
    node_only = parse_ros_arguments(["--ros-args", "-r", "autre:robot_description:=/z"]).remaps
    assert resolve_topic_name("robot_description", "rsp", "/", node_only) == "/robot_description"
    assert resolve_topic_name("robot_description", "autre", "/", node_only) == "/z"


@pytest.mark.parametrize(("name", "namespaces"), [
    ("ns_group_rviz_root.launch.py", ["/bras/robot_state_publisher", "/bras/joint_state_publisher_gui", "/rviz2"]),
    ("ns_group_rviz_root.launch.xml", ["/bras/robot_state_publisher", "/bras/joint_state_publisher_gui", "/rviz2"]),
    ("ns_attribute_rviz_matching.launch.yaml", ["/bras/robot_state_publisher", "/bras/joint_state_publisher_gui",
                                                "/bras/rviz2"]),
])
def test_namespaces_reach_the_nodes_as_launch_ros_passes_them(installed, name, namespaces):
    plan = installed(name)
    assert plan.failure is None
    assert [n.full_name for n in plan.nodes] == namespaces
    assert plan.nodes[0].argv == ["--ros-args", "-r", "__ns:=/bras"]  # node.py:405, as Jazzy's command line
    assert plan.nodes[0].resolve("robot_description") == "/bras/robot_description"


@pytest.mark.parametrize(("name", "published"), [
    ("remap_back_to_root.launch.py", "/robot_description"),
    ("remap_private.launch.xml", "/robot_state_publisher/description"),
])
def test_remappings_change_the_topic_robot_state_publisher_publishes(installed, name, published):
    rsp = installed(name).nodes[0]
    assert rsp.resolve("robot_description") == published


@pytest.mark.parametrize(("name", "published"), [
    ("ns_group_rviz_root.launch.py", "/bras/robot_description"),
    ("ns_group_rviz_root.launch.xml", "/bras/robot_description"),
    ("ns_attribute_rviz_root.launch.py", "/bras/robot_description"),
    ("remap_private.launch.xml", "/robot_state_publisher/description"),
])
def test_rviz_reading_the_root_topic_beside_a_robot_state_publisher_elsewhere_is_named(tmp_path, name, published):
    root = package_with(tmp_path, name)
    found = [f for r in validate_package(root, select=["BK611"], launch=True) for f in r.findings]
    assert [(f.code, f.variant, f.line) for f in found] == [("BK611", "namespace", 45)]
    assert f"'/robot_description', but robot_state_publisher publishes it on {published}" in found[0].text()


@pytest.mark.parametrize("name", ["ns_attribute_rviz_matching.launch.yaml", "remap_back_to_root.launch.py"])
def test_rviz_reading_the_topic_robot_state_publisher_really_publishes_is_clean(tmp_path, name):
    assert findings(package_with(tmp_path, name), "BK61") == []


@pytest.mark.parametrize("name", ["etats_remapped.launch.py", "etats_remapped.launch.xml"])
def test_node_topic_remapped_to_joint_states_by_the_launch_is_heard(tmp_path, name):
    root = package_with(tmp_path, name, data=TOPICS)
    assert findings(root, "BK620", "BK624") == []


def test_node_topic_nothing_remaps_is_named_once_in_the_node(tmp_path):
    root = package_with(tmp_path, "etats_not_remapped.launch.yaml", data=TOPICS)
    assert findings(root, "BK620", "BK624") == [("BK624", "", "bras_description/etats.py", 9)]


@pytest.mark.parametrize(("name", "line"), [("rsp_namespaced_sliders_at_root.launch.py", 16),
                                            ("rsp_namespaced_sliders_at_root.launch.yaml", 3)])
def test_sliders_at_the_root_beside_a_namespaced_robot_state_publisher_are_not_heard(tmp_path, name, line):
    root = package_with(tmp_path, name, data=TOPICS)
    found = [f for r in validate_package(root, select=["BK620"], launch=True) for f in r.findings]
    assert [(f.variant, f.line) for f in found] == [("topic", line)]
    assert "listens on /bras/joint_states, but JointState is published elsewhere " \
           "(/joint_state_publisher_gui -> /joint_states)" in found[0].text()


# ---------------------------------------------------------------- values converted as launch converts them


@pytest.mark.parametrize(("name", "line"), [
    ("param_command_without_type.launch.xml", 3),
    ("param_command_without_type.launch.yaml", 3),
    ("parameter_value_without_type.launch.py", 15),
])
def test_urdf_without_a_string_type_fails_with_launchs_yaml_rules_words(installed, name, line):
    plan = installed(name)
    assert plan.failure is not None and plan.failure.type == "ValueError"
    assert plan.failure.message.startswith("Failed to convert '<?xml version=\"1.0\" ?>")
    assert "' using yaml rules: yaml.safe_load() failed\nmapping values are not allowed here" in plan.failure.message
    assert (os.path.basename(plan.failure.file), plan.failure.line) == (name, line)


@pytest.mark.parametrize("name", ["param_command_without_type_read_as_text.launch.xml",
                                  "parameter_value_str.launch.py", "param_command_type_str.launch.yaml"])
def test_urdf_that_yaml_reads_as_one_string_or_typed_str_starts(installed, name):
    plan = installed(name)
    assert plan.failure is None
    assert plan.nodes[0].parameters["robot_description"].lstrip().startswith("<?xml")


def test_yaml_rules_failure_is_named_with_the_fix_of_its_language(tmp_path):
    root = package_with(tmp_path, "param_command_without_type.launch.xml")
    found = [f for r in validate_package(root, select=["BK631"], launch=True) for f in r.findings]
    assert [(f.variant, f.line) for f in found] == [("yaml_rules", 3)]
    assert "mapping values are not allowed here" in found[0].text()
    assert 'type="str"' in found[0].hint_text()


# ---------------------------------------------------------------- ROS arguments by rcl's rules


def test_rcl_leaves_log_level_and_its_value_in_one_word_unparsed():
    assert parse_ros_arguments(["--ros-args", "--log-level warn"]).unknown == ["--log-level warn"]
    assert parse_ros_arguments(["--ros-args", "--log-level", "warn"]).unknown == []
    assert parse_ros_arguments(["-d", "x.rviz", "--ros-args", "--disable-rosout-logs"]).others == ["-d", "x.rviz"]
    with pytest.raises(InvalidROSArgs):
        parse_ros_arguments(["--ros-args", "--log-level"])
    assert unknown_ros_args_error(["--log-level warn"], cpp=False) == "['--log-level warn']"
    assert unknown_ros_args_error(["--log-level warn"], cpp=True) == "found unknown ROS arguments: '--log-level warn'"


@pytest.mark.parametrize(("name", "dies"), [
    ("ros_arguments_one_string.launch.py", ["joint_state_publisher_gui"]),
    ("arguments_ros_args_one_string.launch.py", ["rviz2"]),
    ("ros_args_split.launch.xml", ["rviz2"]),
    ("ros_args_one_word.launch.yaml", ["joint_state_publisher_gui"]),
])
def test_a_ros_argument_given_as_one_word_kills_the_node_it_is_given_to(installed, name, dies):
    plan = installed(name)
    assert plan.failure is None
    assert [n.executable for n in plan.nodes if ros_arguments_start(n)] == dies
    problem = next(p for n in plan.nodes for p in ros_arguments_start(n))
    assert problem.kind == "unknown_ros_args" and problem.detail == "--log-level warn"


def test_node_killed_by_its_ros_arguments_is_named_with_the_words_it_dies_with(tmp_path):
    root = package_with(tmp_path, "ros_arguments_one_string.launch.py")
    found = [f for r in validate_package(root, select=["BK634"], launch=True) for f in r.findings]
    assert [(f.variant, f.line) for f in found] == [("unknown_ros_args", 8)]
    assert "UnknownROSArgsError: ['--log-level warn']" in found[0].text()
    assert "'--log-level', 'warn'" in found[0].hint_text()


# ---------------------------------------------------------------- event handlers


def test_on_process_start_of_a_node_never_started_never_fires(installed):
    plan = installed("on_start_of_node_never_started.launch.py")
    assert plan.failure is None
    assert [n.executable for n in plan.nodes] == ["joint_state_publisher_gui"]  # no robot_state_publisher, no RViz


def test_on_process_start_of_a_node_whose_condition_is_false_never_fires(installed):
    assert installed("on_start_of_node_whose_condition_fails.launch.py").nodes == []


@pytest.mark.parametrize(("name", "line", "target"), [
    ("on_start_of_node_never_started.launch.py", 19, "robot_state_publisher"),
    ("on_start_of_node_whose_condition_fails.launch.py", 16, "joint_state_publisher_gui"),
])
def test_handler_waiting_for_a_process_that_never_starts_is_named(tmp_path, name, line, target):
    root = package_with(tmp_path, name)
    found = [f for r in validate_package(root, select=["BK635"], launch=True) for f in r.findings]
    assert [(f.code, f.line) for f in found] == [("BK635", line)]
    assert f"waits for {target}, which this launch never starts: 'rviz2' never starts" in found[0].text()


def test_handler_whose_target_started_is_not_named(tmp_path):
    assert findings(package_with(tmp_path, "on_start_fires_after_target.launch.py"), "BK635") == []


def test_on_process_start_registered_after_its_target_fires_once_it_started(installed):
    plan = installed("on_start_fires_after_target.launch.py")
    assert [n.executable for n in plan.nodes] == ["robot_state_publisher", "joint_state_publisher_gui", "rviz2"]


# ---------------------------------------------------------------- front-end schema errors


@pytest.mark.parametrize(("name", "words", "line"), [
    ("executable_instead_of_exec.launch.yaml",
     "Caught multiple exceptions when trying to load file of format [yaml]:\n"
     " - AttributeError: Can not find attribute 'exec' in Entity 'node'\n"
     " - SyntaxError: invalid syntax (executable_instead_of_exec.launch.yaml, line 2)", 3),
    ("executable_instead_of_exec.launch.xml",
     "Caught multiple exceptions when trying to load file of format [xml]:\n"
     " - AttributeError: Attribute 'exec' of type '<class 'str'>' not found in Entity 'node'\n"
     " - SyntaxError: invalid syntax (executable_instead_of_exec.launch.xml, line 1)", 3),
    ("unknown_attribute.launch.xml",
     "Caught multiple exceptions when trying to load file of format [xml]:\n"
     " - ValueError: Unexpected attribute(s) found in `node`: {'package'}\n"
     " - SyntaxError: invalid syntax (unknown_attribute.launch.xml, line 1)", 3),
    ("unknown_key.launch.yaml",
     "Caught multiple exceptions when trying to load file of format [yaml]:\n"
     " - ValueError: Unexpected key(s) found in `node`: {'arguments'}\n"
     " - SyntaxError: invalid syntax (unknown_key.launch.yaml, line 2)", 3),
    ("unknown_tag.launch.xml",
     "Caught multiple exceptions when trying to load file of format [xml]:\n"
     " - RuntimeError: Unrecognized entity of the type: Node\n"
     " - SyntaxError: invalid syntax (unknown_tag.launch.xml, line 1)", 3),
])
def test_front_end_schema_errors_stop_the_launch_in_launchs_words(installed, name, words, line):
    plan = installed(name)
    assert plan.failure is not None
    assert (plan.failure.type, plan.failure.message) == ("InvalidLaunchFileError", words)
    assert (os.path.basename(plan.failure.file), plan.failure.line) == (name, line)


@pytest.mark.parametrize(("name", "variant", "fix"), [
    ("executable_instead_of_exec.launch.yaml", "attribute_missing", "exec:"),
    ("executable_instead_of_exec.launch.xml", "attribute_missing", "exec="),
    ("unknown_attribute.launch.xml", "attribute_renamed", "pkg="),
    ("unknown_key.launch.yaml", "attribute_renamed", "args:"),
])
def test_python_names_in_a_front_end_file_are_named_with_the_front_end_name(tmp_path, name, variant, fix):
    root = package_with(tmp_path, name)
    found = [f for r in validate_package(root, select=["BK631"], launch=True) for f in r.findings]
    assert [(f.variant, f.line) for f in found] == [(variant, 3)]
    assert fix in found[0].hint_text()


# ---------------------------------------------------------------- Python API misuse


def test_launch_arguments_given_as_a_dict_fail_with_too_many_values_to_unpack(installed):
    plan = installed("include_arguments_dict.launch.py")
    assert (plan.failure.type, plan.failure.message) == ("ValueError", "too many values to unpack (expected 2)")
    assert (os.path.basename(plan.failure.file), plan.failure.line) == ("include_arguments_dict.launch.py", 13)
    assert [n.executable for n in installed("include_arguments_items.launch.py").nodes] == [
        "robot_state_publisher", "joint_state_publisher_gui"]


@pytest.mark.parametrize(("name", "returned", "line"), [
    ("returns_nothing.launch.py", "NoneType", 4), ("returns_a_list.launch.py", "list", 3)])
def test_file_that_returns_no_launch_description_is_named_as_such(tmp_path, installed, name, returned, line):
    plan = installed(name)
    assert (plan.failure.type, plan.failure.message) == (
        "AttributeError",
        f"'{returned}' object has no attribute 'get_launch_arguments_with_include_launch_description_actions'")
    root = package_with(tmp_path, name)
    assert findings(root, "BK631") == [("BK631", "no_description", f"launch/{name}", line)]


@pytest.mark.parametrize(("name", "words", "variant", "line"), [
    ("parameters_dict.launch.py", "TypeError: 'Node' expected 'parameters' to be one of [<class 'list'>], but got "
                                  "'{'robot_description': '<?xml", "parameters_not_list", 13),
    ("description_of_one_node.launch.py", "TypeError: 'Node' object is not iterable", "not_a_list", 7),
    ("no_generate_function.launch.py", "InvalidPythonLaunchFileError: launch file at '{share}/launch/"
                                       "no_generate_function.launch.py' does not contain the required function "
                                       "'generate_launch_description()'", "no_generate", None),
    ("default_value_bool.launch.py", "TypeError: 'bool' object is not iterable", "not_text", 8),
])
def test_python_api_misuse_fails_with_jazzys_words_at_the_learners_line(tmp_path, installed, name, words, variant,
                                                                        line):
    plan = installed(name)
    assert plan.failure is not None and plan.failure.type == "InvalidLaunchFileError"
    assert plan.failure.message.startswith("Caught multiple exceptions when trying to load file of format [py]:\n - "
                                           + words.replace("{share}", installed.share))
    assert findings(package_with(tmp_path, name), "BK631") == [("BK631", variant, f"launch/{name}", line)]


def test_failure_while_loading_a_python_file_lists_every_loaders_words_as_ros2_launch_does(tmp_path):
    # any_launch_file_utilities.py:30: the Python loader, then the front end, both failures kept
    bad = os.path.join(DATA_DIR, "launch", "wrong_package", "bras_description")
    found = [f for r in validate_package(bad, select=["BK631"], launch=True) for f in r.findings]
    assert "Caught multiple exceptions when trying to load file of format [py]:\n" \
           " - PackageNotFoundError: \"package 'bras_descripton' not found" in found[0].text()
    assert " - InvalidFrontendLaunchFileError: The launch file may have a syntax error, or its format is unknown" \
        in found[0].text()


# ---------------------------------------------------------------- an included file, judged with its includer


@pytest.mark.parametrize("includer", ["includes_rsp_with_slider.launch.yaml", "includes_rsp_with_slider.launch.xml"])
def test_file_starting_the_sliders_and_including_robot_state_publisher_is_complete(tmp_path, includer):
    root = package_with(tmp_path, includer, "rsp_only.launch.py")
    assert findings(root, "BK620", "BK631") == []


def test_included_robot_state_publisher_without_sliders_anywhere_is_still_named(tmp_path):
    root = package_with(tmp_path, "includes_rsp_without_slider.launch.yaml", "rsp_only.launch.py")
    assert findings(root, "BK620") == [("BK620", "nodes", "launch/rsp_only.launch.py", 15)]


# ---------------------------------------------------------------- not errors


@pytest.mark.parametrize("name", ["rviz_config_missing.launch.py", "rviz_config_missing.launch.xml",
                                  "double_slash.launch.py", "double_slash.launch.xml"])
def test_missing_rviz_configuration_and_doubled_slash_are_not_errors(tmp_path, name):
    root = package_with(tmp_path, name)
    errors = [(f.code, f.variant) for r in validate_package(root, select=["BK6"], launch=True) for f in r.findings
              if f.severity == "error"]
    assert errors == []


@pytest.mark.parametrize(("name", "line"), [("rviz_config_missing.launch.py", 17),
                                            ("rviz_config_missing.launch.xml", 7)])
def test_missing_rviz_configuration_says_rviz_opens_its_default(tmp_path, name, line):
    root = package_with(tmp_path, name)
    assert findings(root, "BK613") == [("BK613", "missing", f"launch/{name}", line)]


def test_doubled_slash_reaches_the_same_rviz_configuration(tmp_path):
    # double_slash.launch.xml gives '-d SHARE//rviz/bras.rviz': the RViz rules read rviz/bras.rviz
    from bras_kit.validate.package import Package
    from bras_kit.validate.package.rules import _rviz_files

    root = package_with(tmp_path, "double_slash.launch.xml")
    package = Package(root)
    validate_package(root, select=["BK61"], package=package, launch=True)
    assert [source for source, _, _ in _rviz_files(package)] == ["rviz/bras.rviz"]


@pytest.mark.parametrize(("name", "nodes"), [
    ("tags_learners_copy.launch.xml", [
        ("/rsp", ["--ros-args", "-r", "__node:=rsp", "-r", "/joint_states:=/etats"]),
        ("/joint_state_publisher_gui", ["--ros-args", "-r", "joint_states:=/etats"]),
        ("/rviz", ["-d", "{share}/rviz/bras.rviz", "--ros-args", "-r", "__node:=rviz",
                   "-r", "robot_description:=/description"]),
        ("/robot_state_publisher", ["--ros-args", "-r", "robot_description:=/description"])]),
    ("keys_learners_copy.launch.yaml", [
        ("/bras/rsp", ["--ros-args", "-r", "__node:=rsp", "-r", "__ns:=/bras", "-r", "joint_states:=/joint_states"]),
        ("/joint_state_publisher", ["--ros-args"]),
        ("/outils/rviz2", ["-d", "{share}/rviz/bras_ns.rviz", "--ros-args", "-r", "__ns:=/outils"])]),
])
def test_tags_and_keys_learners_copy_reach_the_nodes_as_jazzy_passes_them(installed, name, nodes):
    # JAZZY.md: the same names, namespaces and -r rules (launch_ros adds -p/--params-file, not recorded here)
    plan = installed(name)
    assert plan.failure is None
    assert started(plan) == [(n, [a.format(share=installed.share) for a in argv]) for n, argv in nodes]
    if name.endswith(".xml"):
        assert [p["cmd"] for p in plan.processes] == [["echo", "base"]]
        assert plan.processes[0]["delay"] == 2.0
