"""bras_kit.diagrams: the TF tree as text, the frame tree (DOT, layout, drawing), tip path and motion plot."""

from __future__ import annotations

import math
import re
from types import SimpleNamespace

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from bras_kit import diagrams
from bras_kit.core.errors import ModelError, ParameterError
from bras_kit.diagrams import (
    frame_diagram,
    frames_dot,
    motion_plane,
    plot_motion,
    tidy_layout,
    tip_path,
    tip_point,
    tree_text,
)
from bras_kit.kinematics.frames import tf_tree
from bras_kit.model.authoring import load
from bras_kit.model.robot import Joint, Limit, Link, Mimic, Origin, Robot

# ---------------------------------------------------------------- fixtures

BRANCHING_URDF = """<?xml version="1.0"?>
<robot name="fourche">
  <link name="base"/>
  <link name="gauche">
    <visual><origin xyz="0 0 0.2"/><geometry><cylinder radius="0.02" length="0.4"/></geometry></visual>
  </link>
  <link name="droite"/>
  <link name="outil"/>
  <joint name="j_gauche" type="revolute">
    <parent link="base"/><child link="gauche"/>
    <origin xyz="0.1 0 0" rpy="0 0 1.5708"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/>
  </joint>
  <joint name="j_droite" type="prismatic">
    <parent link="base"/><child link="droite"/>
    <origin xyz="-0.1 0 0"/><axis xyz="1 0 0"/>
    <limit lower="0" upper="0.2" effort="1" velocity="1"/>
  </joint>
  <joint name="fixation_outil" type="fixed">
    <parent link="gauche"/><child link="outil"/><origin xyz="0 0 0.4"/>
  </joint>
</robot>
"""

TWO_PARENTS_URDF = """<?xml version="1.0"?>
<robot name="boucle">
  <link name="a"/><link name="b"/><link name="c"/>
  <joint name="ab" type="fixed"><parent link="a"/><child link="b"/></joint>
  <joint name="cb" type="fixed"><parent link="c"/><child link="b"/></joint>
</robot>
"""


@pytest.fixture
def branching_robot(tmp_path):
    path = tmp_path / "fourche.urdf"
    path.write_text(BRANCHING_URDF, encoding="utf-8")
    return load(str(path))


def _revolute(name: str, parent: str, child: str, z: float = 0.1, axis=(0.0, 1.0, 0.0)) -> Joint:
    return Joint(name, "revolute", parent, child, Origin((0.0, 0.0, z), (0.0, 0.0, 0.0)), axis,
                 Limit(-1.0, 1.0, 1.0, 1.0))


def _random_robot(count: int, seed: int = 7, fan: int = 8) -> Robot:
    """A tree of ``count`` links; each link hangs from one of the ``fan`` links before it."""
    rng = np.random.default_rng(seed)
    links = [Link(f"l{i}") for i in range(count)]
    joints = [_revolute(f"j{i}", f"l{int(rng.integers(max(0, i - fan), i))}", f"l{i}") for i in range(1, count)]
    return Robot("grand", links, joints)


def _states(names, positions, times=None):
    positions = np.atleast_2d(np.asarray(positions, dtype=float))
    times = np.arange(len(positions)) * 0.05 if times is None else np.asarray(times, dtype=float)
    return SimpleNamespace(times=times, names=list(names), positions=positions,
                           velocities=np.zeros_like(positions))


# ---------------------------------------------------------------- tree as text


def test_tree_text_of_tutorial_arm_nests_coude_under_epaule(tutorial_robot):
    assert tree_text(tutorial_robot) == (
        "base\n"
        "└─ epaule (revolute, axis 0 1 0, -1.57..1.57) → bras\n"
        "   └─ coude (revolute, axis 0 1 0, -2..2) → avant_bras\n"
    )


def test_tree_text_indents_each_joint_by_three_columns_per_depth(wrist_robot):
    text = tree_text(wrist_robot)
    tree = tf_tree(wrist_robot)
    lines = text.splitlines()
    assert lines[0] == "base"
    assert len(lines) == len(tree.links) == 4
    for link in tree.links[1:]:
        joint = wrist_robot.child_joint(link)
        line = next(line for line in lines if line.endswith(f"→ {link}"))
        assert line.index(f"{joint.name} (") == 3 * tree.depth(link)
    assert lines[3] == "      └─ poignet (revolute, axis 0 1 0, -1.57..1.57) → main"


def test_tree_text_draws_branches_and_fixed_tool_frame(branching_robot):
    assert tree_text(branching_robot) == (
        "base\n"
        "├─ j_gauche (revolute, axis 0 0 1, -1..1) → gauche\n"
        "│  └─ fixation_outil (fixed) → outil\n"
        "└─ j_droite (prismatic, axis 1 0 0, 0..0.2) → droite\n"
    )


def test_tree_text_ascii_uses_only_ascii(branching_robot):
    text = tree_text(branching_robot, ascii=True)
    assert text == (
        "base\n"
        "|- j_gauche (revolute, axis 0 0 1, -1..1) -> gauche\n"
        "|  `- fixation_outil (fixed) -> outil\n"
        "`- j_droite (prismatic, axis 1 0 0, 0..0.2) -> droite\n"
    )
    text.encode("ascii")


def test_tree_text_shows_values_and_flags_out_of_limits(tutorial_robot):
    lines = tree_text(tutorial_robot, {"epaule": 0.5, "coude": 2.5}).splitlines()
    assert lines[1] == "└─ epaule (revolute, axis 0 1 0, -1.57..1.57) = 0.5 → bras"
    assert lines[2] == "   └─ coude (revolute, axis 0 1 0, -2..2) = 2.5 (out of limits) → avant_bras"


def test_tree_text_marks_default_axis_continuous_and_mimic():
    robot = Robot("r", [Link("a"), Link("b"), Link("c")], [
        Joint("roue", "continuous", "a", "b"),
        Joint("suiveur", "revolute", "b", "c", axis=(0.0, 0.0, 1.0), limit=Limit(-1.0, 1.0, 1.0, 1.0),
              mimic=Mimic("roue", 2.0, 0.1)),
    ])
    lines = tree_text(robot, {"roue": 0.25}).splitlines()
    assert lines[1] == "└─ roue (continuous, axis 1 0 0 (default)) = 0.25 → b"
    assert lines[2] == "   └─ suiveur (revolute, axis 0 0 1, -1..1, mimics roue) = 0.6 → c"


def test_tree_text_refuses_a_link_with_two_parents(tmp_path):
    path = tmp_path / "boucle.urdf"
    path.write_text(TWO_PARENTS_URDF, encoding="utf-8")
    with pytest.raises(ModelError, match="two parents"):
        tree_text(load(str(path)))


def test_tree_text_unknown_joint_value_is_an_error(tutorial_robot):
    with pytest.raises(ParameterError, match="unknown joint 'genou'"):
        tree_text(tutorial_robot, {"genou": 1.0})


def test_tree_text_handles_a_chain_deeper_than_the_recursion_limit():
    from bras_kit.diagrams.text import MAX_INDENT

    count = 3000
    links = [Link(f"l{i}") for i in range(count)]
    joints = [Joint(f"j{i}", "fixed", f"l{i - 1}", f"l{i}") for i in range(1, count)]
    lines = tree_text(Robot("chaine", links, joints)).splitlines()
    assert len(lines) == count
    # indentation stops growing after MAX_INDENT levels; deeper lines say their depth instead
    assert lines[MAX_INDENT] == " " * (3 * (MAX_INDENT - 1)) + f"└─ j{MAX_INDENT} (fixed) → l{MAX_INDENT}"
    assert lines[-1] == " " * (3 * (MAX_INDENT - 1)) + f"[depth {count - 1}] └─ j{count - 1} (fixed) → l{count - 1}"
    assert max(len(line) for line in lines) < 3 * MAX_INDENT + 40  # linear output, not quadratic


# ---------------------------------------------------------------- DOT

_TOKEN = re.compile(r'\s*(?:(//[^\n]*)|("(?:[^"\\]|\\.)*")|(->)|([{}\[\];=,])|([A-Za-z_][A-Za-z0-9_]*|-?[0-9.]+))',
                    re.S)


def _tokens(text: str) -> list[str]:
    out, position = [], 0
    text = text.rstrip()
    while position < len(text):
        match = _TOKEN.match(text, position)
        assert match and match.end() > position, f"cannot read DOT at: {text[position:position + 30]!r}"
        position = match.end()
        if not match.group(1):
            out.append(match.group(0).strip())
    return out


def _unquote(token: str) -> str:
    if token.startswith('"'):
        return re.sub(r"\\(.)", lambda m: "\n" if m.group(1) == "n" else m.group(1), token[1:-1])
    return token


def parse_dot(text: str) -> tuple[dict[str, dict[str, str]], list[tuple[str, str, dict[str, str]]]]:
    """A strict reader for the DOT subset bras-kit writes: nodes and edges with their attributes.

    Fails on unbalanced braces or brackets, unknown statements, anything after the closing brace,
    and edges that name undeclared nodes.
    """
    tokens = _tokens(text)
    assert tokens[0] == "digraph" and tokens[2] == "{", tokens[:3]
    assert tokens[-1] == "}" and tokens.count("{") == tokens.count("}") == 1
    assert tokens.count("[") == tokens.count("]")
    i, nodes, edges = 3, {}, []

    def attributes(i: int) -> tuple[dict[str, str], int]:
        attrs: dict[str, str] = {}
        if tokens[i] != "[":
            return attrs, i
        i += 1
        while tokens[i] != "]":
            key, equals, value = tokens[i:i + 3]
            assert equals == "=" and re.fullmatch(r"[A-Za-z_]+", key), tokens[i:i + 3]
            attrs[key] = _unquote(value)
            i += 3
            if tokens[i] == ",":
                i += 1
        return attrs, i + 1

    while i < len(tokens) - 1:
        first = tokens[i]
        if first in ("graph", "node", "edge"):
            _, i = attributes(i + 1)
        elif tokens[i + 1] == "->":
            source, target = _unquote(first), _unquote(tokens[i + 2])
            attrs, i = attributes(i + 3)
            edges.append((source, target, attrs))
        else:
            attrs, i = attributes(i + 1)
            nodes[_unquote(first)] = attrs
        assert tokens[i] == ";", f"statement not ended by ';' at token {i}: {tokens[i]!r}"
        i += 1
    for source, target, _ in edges:
        assert source in nodes and target in nodes, f"edge {source} -> {target} names an undeclared node"
    return nodes, edges


def test_dot_parser_rejects_broken_dot():
    with pytest.raises(AssertionError):
        parse_dot('digraph "x" { "a" -> "b"; "a"; }')  # b never declared
    with pytest.raises(AssertionError):
        parse_dot('digraph "x" { "a" [label="a"; }')  # unbalanced bracket
    with pytest.raises(AssertionError):
        parse_dot('digraph "x" { "a" }')  # missing ';'


def test_frames_dot_declares_every_link_and_labels_every_joint(wrist_robot):
    nodes, edges = parse_dot(frames_dot(wrist_robot))
    assert set(nodes) == {"base", "bras", "avant_bras", "main"}
    assert [(s, t) for s, t, _ in edges] == [("base", "bras"), ("bras", "avant_bras"), ("avant_bras", "main")]
    labels = {attrs["label"].split("\n")[0]: attrs["label"] for _, _, attrs in edges}
    assert set(labels) == {"epaule", "coude", "poignet"}
    assert labels["epaule"].split("\n") == [
        "epaule", "revolute", "xyz 0 0 0.05", "rpy 0 0 0", "axis 0 1 0",
        "limits -1.57 .. 1.57 rad", "effort 10, velocity 1",
    ]
    assert "xyz 0 0 0.6" in labels["coude"] and "limits -2 .. 2 rad" in labels["coude"]
    assert not any("value" in label for label in labels.values())


def test_frames_dot_with_pose_shows_values_and_link_positions(tutorial_robot):
    nodes, edges = parse_dot(frames_dot(tutorial_robot, {"epaule": 0.5, "coude": 2.5}))
    labels = {attrs["label"].split("\n")[0]: attrs for _, _, attrs in edges}
    assert "value 0.5 rad (28.65 deg)" in labels["epaule"]["label"].split("\n")
    assert labels["coude"]["label"].split("\n")[-1] == "value 2.5 rad (143.2 deg) OUT OF LIMITS"
    assert labels["coude"]["color"] == "#c0392b" and "color" not in labels["epaule"]
    x = 0.6 * math.sin(0.5)
    z = 0.05 + 0.6 * math.cos(0.5)
    assert nodes["avant_bras"]["label"] == f"avant_bras\nat {x:.4g} 0 {z:.4g}"


def test_frames_dot_fixed_and_prismatic_joints(branching_robot):
    nodes, edges = parse_dot(frames_dot(branching_robot))
    labels = {attrs["label"].split("\n")[0]: attrs for _, _, attrs in edges}
    assert labels["fixation_outil"]["label"].split("\n") == ["fixation_outil", "fixed", "xyz 0 0 0.4", "rpy 0 0 0"]
    assert labels["fixation_outil"]["style"] == "dashed"
    assert "limits 0 .. 0.2 m" in labels["j_droite"]["label"].split("\n")
    assert "rpy 0 0 1.571" in labels["j_gauche"]["label"].split("\n")


def test_frames_dot_escapes_quotes_and_backslashes():
    robot = Robot('dr"ole', [Link('a"b'), Link("c\\d")], [Joint('j"1', "fixed", 'a"b', "c\\d")])
    nodes, edges = parse_dot(frames_dot(robot))
    assert set(nodes) == {'a"b', "c\\d"}
    assert edges[0][:2] == ('a"b', "c\\d")
    assert edges[0][2]["label"].split("\n")[0] == 'j"1'


# ---------------------------------------------------------------- layout


def test_layout_centres_parents_and_spaces_leaves_exactly():
    layout = tidy_layout([-1, 0, 0, 1, 1, 2], gap=1.0)
    assert layout.x == (3.0, 1.5, 4.5, 0.5, 2.5, 4.5)
    assert layout.depth == (0, 1, 1, 2, 2, 2)
    assert layout.width == 5.0


def test_layout_packs_row_by_row_not_by_bounding_box():
    # node 2 sits next to node 1 although node 1's child (3) is wide: they are on different rows
    layout = tidy_layout([-1, 0, 0, 1], widths=[1, 1, 1, 5], gap=1.0)
    assert layout.x[2] - layout.x[1] == pytest.approx(2.0)
    assert layout.x[3] == layout.x[1]


def _check_layout(parent, widths, gap):
    layout = tidy_layout(parent, widths, gap)
    children: dict[int, list[int]] = {}
    for i, p in enumerate(parent):
        if p >= 0:
            children.setdefault(p, []).append(i)
    for p, kids in children.items():
        assert layout.x[p] == pytest.approx((layout.x[kids[0]] + layout.x[kids[-1]]) / 2, abs=1e-9)
        assert all(layout.x[a] < layout.x[b] for a, b in zip(kids, kids[1:]))
    rows: dict[int, list[int]] = {}
    for i, d in enumerate(layout.depth):
        rows.setdefault(d, []).append(i)
    for row in rows.values():
        row.sort(key=lambda i: layout.x[i])
        for a, b in zip(row, row[1:]):
            assert layout.x[b] - layout.x[a] >= (widths[a] + widths[b]) / 2 + gap - 1e-9
    assert min(x - w / 2 for x, w in zip(layout.x, widths)) == pytest.approx(0.0, abs=1e-9)
    assert max(x + w / 2 for x, w in zip(layout.x, widths)) == pytest.approx(layout.width)


@settings(max_examples=150, deadline=None)
@given(st.lists(st.tuples(st.integers(0, 10**6), st.floats(0.1, 8.0)), min_size=0, max_size=60),
       st.floats(0.0, 3.0))
def test_layout_never_overlaps_a_row_and_centres_every_parent(nodes, gap):
    parent = [-1] + [choice % i for i, (choice, _) in enumerate(nodes, start=1)]
    widths = [2.0] + [w for _, w in nodes]
    _check_layout(parent, widths, gap)


def test_layout_of_random_200_node_trees():
    rng = np.random.default_rng(3)
    for _ in range(20):
        parent = [-1] + [int(rng.integers(max(0, i - 6), i)) for i in range(1, 200)]
        _check_layout(parent, list(rng.uniform(0.5, 6.0, 200)), 0.7)


def test_layout_of_a_long_chain_needs_no_recursion():
    layout = tidy_layout([-1] + list(range(9999)))
    assert set(layout.x) == {0.5}
    assert layout.depth[-1] == 9999


def test_layout_rejects_children_listed_before_parents():
    with pytest.raises(ValueError, match="topological"):
        tidy_layout([-1, 2, 0])


# ---------------------------------------------------------------- drawn frame diagram

_LINK_FILL = (0xDB / 255, 0xE8 / 255, 0xFB / 255)


def test_frame_diagram_png_is_written_with_link_boxes(tmp_path, wrist_robot):
    import matplotlib.image

    path = tmp_path / "frames.png"
    frame_diagram(wrist_robot, {"epaule": 0.5}, path=str(path))
    image = matplotlib.image.imread(str(path))
    assert image.shape[0] > 300 and image.shape[1] > 150
    box_pixels = np.all(np.abs(image[..., :3] - _LINK_FILL) < 2 / 255, axis=-1).sum()
    assert box_pixels > 4 * 500  # four link boxes, each well over 500 pixels


def test_frame_diagram_svg_keeps_every_name_as_text(tmp_path, branching_robot):
    path = tmp_path / "frames.svg"
    frame_diagram(branching_robot, path=str(path))
    svg = path.read_text(encoding="utf-8")
    texts = re.findall(r"<text[^>]*>([^<]*)</text>", svg)
    for name in ("base", "gauche", "droite", "outil", "j_gauche", "j_droite", "fixation_outil"):
        assert name in texts


def test_frame_diagram_pdf_and_dot(tmp_path, tutorial_robot):
    pdf, dot = tmp_path / "frames.pdf", tmp_path / "frames.dot"
    frame_diagram(tutorial_robot, path=str(pdf))
    frame_diagram(tutorial_robot, path=str(dot))
    assert pdf.read_bytes().startswith(b"%PDF")
    assert dot.read_text(encoding="utf-8") == frames_dot(tutorial_robot)


def test_frame_diagram_refuses_unknown_format(tmp_path, tutorial_robot):
    with pytest.raises(ParameterError, match="unknown format '.jpg'"):
        frame_diagram(tutorial_robot, path=str(tmp_path / "frames.jpg"))
    assert not (tmp_path / "frames.jpg").exists()


def _link_boxes(figure):
    from matplotlib.patches import FancyBboxPatch

    ax = figure.axes[0]
    boxes = [p for p in ax.patches if isinstance(p, FancyBboxPatch)
             and np.allclose(p.get_facecolor()[:3], _LINK_FILL, atol=1e-3)]
    return [(p.get_x(), p.get_y(), p.get_x() + p.get_width(), p.get_y() + p.get_height()) for p in boxes]


def test_frame_diagram_of_200_links_is_scaled_and_boxes_never_overlap(tmp_path):
    robot = _random_robot(200)
    figure = frame_diagram(robot, path=str(tmp_path / "big.svg"))
    small = frame_diagram(_random_robot(3))
    assert figure.get_size_inches()[0] > 4 * small.get_size_inches()[0]
    assert figure.get_size_inches()[1] > 4 * small.get_size_inches()[1]
    texts = set(re.findall(r"<text[^>]*>([^<]*)</text>", (tmp_path / "big.svg").read_text(encoding="utf-8")))
    assert {f"l{i}" for i in range(200)} <= texts and {f"j{i}" for i in range(1, 200)} <= texts
    boxes = np.array(_link_boxes(figure))
    assert len(boxes) == 200
    x0, y0, x1, y1 = boxes.T
    overlap = ((x0[:, None] < x1[None, :]) & (x0[None, :] < x1[:, None])
               & (y0[:, None] < y1[None, :]) & (y0[None, :] < y1[:, None]))
    np.fill_diagonal(overlap, False)
    assert not overlap.any()


def test_png_of_a_big_figure_is_capped_by_lowering_its_resolution(tmp_path, monkeypatch, wrist_robot):
    import matplotlib.image

    figure = frame_diagram(wrist_robot)
    width, height = figure.get_size_inches()
    diagrams.save_figure(figure, str(tmp_path / "full.png"))
    full = matplotlib.image.imread(str(tmp_path / "full.png"))
    assert full.shape[:2] == (round(height * 100), round(width * 100))
    monkeypatch.setattr(diagrams.output, "MAX_RASTER_SIDE", 300)
    diagrams.save_figure(figure, str(tmp_path / "side.png"))
    side = matplotlib.image.imread(str(tmp_path / "side.png"))
    assert max(side.shape[:2]) == 300
    monkeypatch.setattr(diagrams.output, "MAX_RASTER_PIXELS", 20_000)
    diagrams.save_figure(figure, str(tmp_path / "area.png"))
    area = matplotlib.image.imread(str(tmp_path / "area.png"))
    assert 19_000 < area.shape[0] * area.shape[1] <= 20_000 + sum(area.shape[:2])


# ---------------------------------------------------------------- tip point and path


def test_tip_of_tutorial_arm_is_the_far_end_of_the_forearm(tutorial_robot, wrist_robot):
    link, offset = tip_point(tutorial_robot)
    assert link == "avant_bras"
    np.testing.assert_allclose(offset, [0.0, 0.0, 0.5], atol=1e-15)
    link, offset = tip_point(wrist_robot)
    assert link == "main"
    np.testing.assert_allclose(offset, [0.0, 0.0, 0.15], atol=1e-15)


def test_tip_of_a_tool_frame_without_visual_is_its_origin(branching_robot):
    link, offset = tip_point(branching_robot)
    assert link == "outil"
    np.testing.assert_array_equal(offset, [0.0, 0.0, 0.0])


def test_tip_follows_the_chain_direction_through_sphere_and_rotated_cylinder():
    from bras_kit.model.robot import Geometry, Visual

    sphere = Visual(Origin((0.0, 0.0, 0.0)), Geometry("sphere", radius=0.1))
    cylinder = Visual(Origin((0.2, 0.0, 0.0), (0.0, math.pi / 2, 0.0)), Geometry("cylinder", radius=0.03, length=0.4))
    robot = Robot("r", [Link("a"), Link("b", visuals=[sphere, cylinder])],
                  [Joint("j", "revolute", "a", "b", Origin((0.5, 0.0, 0.0)), (0.0, 0.0, 1.0), Limit(-1, 1, 1, 1))])
    link, offset = tip_point(robot)  # chain runs along +x: the cylinder's far end (0.4) beats the sphere (0.1)
    assert link == "b"
    np.testing.assert_allclose(offset, [0.4, 0.0, 0.0], atol=1e-12)
    robot.links[1].visuals = [sphere]
    np.testing.assert_allclose(tip_point(robot)[1], [0.1, 0.0, 0.0], atol=1e-15)


def test_tip_path_of_tutorial_arm_matches_hand_computation(tutorial_robot):
    states = _states(["epaule", "coude"], [[0.0, 0.0], [0.5, -0.7]])
    path = tip_path(tutorial_robot, states)
    assert path.shape == (2, 3)
    np.testing.assert_allclose(path[0], [0.0, 0.0, 0.05 + 0.6 + 0.5], atol=1e-12)
    x = 0.6 * math.sin(0.5) + 0.5 * math.sin(0.5 - 0.7)
    z = 0.05 + 0.6 * math.cos(0.5) + 0.5 * math.cos(-0.2)
    np.testing.assert_allclose(path[1], [x, 0.0, z], atol=1e-12)


def test_tip_path_reads_columns_by_name(tutorial_robot):
    reordered = _states(["coude", "epaule"], [[-0.7, 0.5]])
    direct = tip_path(tutorial_robot, np.array([[0.5, -0.7]]))
    np.testing.assert_allclose(tip_path(tutorial_robot, reordered), direct, atol=1e-15)
    with pytest.raises(ParameterError, match="'genou'"):
        tip_path(tutorial_robot, _states(["genou"], [[0.1]]))


def test_motion_plane_is_normal_to_the_common_axis(tutorial_robot, branching_robot):
    plane = motion_plane(tutorial_robot)
    assert plane.common_axis
    np.testing.assert_allclose(plane.normal, [0.0, 1.0, 0.0])
    assert (plane.u_label, plane.v_label) == ("x (m)", "z (m)")
    plane = motion_plane(branching_robot)  # one revolute joint, about z
    assert (plane.u_label, plane.v_label) == ("x (m)", "y (m)")
    mixed = Robot("m", [Link("a"), Link("b"), Link("c")],
                  [_revolute("j1", "a", "b", axis=(0.0, 0.0, 1.0)), _revolute("j2", "b", "c")])
    plane = motion_plane(mixed)
    assert not plane.common_axis and (plane.u_label, plane.v_label) == ("x (m)", "z (m)")


# ---------------------------------------------------------------- motion plot


def _pixel(figure, ax, x, y, image):
    """RGB of the saved image at data point (x, y) of ``ax``."""
    px, py = ax.transData.transform((x, y))
    return image[int(round(image.shape[0] - py)), int(round(px)), :3]


def test_plot_motion_draws_limit_bands_and_marks_violations(tmp_path, tutorial_robot):
    import matplotlib.image

    from bras_kit.motion import formula_motion, sample

    states = sample(formula_motion(tutorial_robot, ["epaule=0.8*sin(t)", "coude=2.5*sin(t)"]), 4.0, 20.0)
    path = tmp_path / "plot.png"
    figure = plot_motion(tutorial_robot, states, path=str(path))
    image = matplotlib.image.imread(str(path))
    assert image.shape[0] > 400 and image.shape[1] > 800
    coude = next(ax for ax in figure.axes if ax.get_ylabel() == "coude (rad)")
    epaule = next(ax for ax in figure.axes if ax.get_ylabel() == "epaule (rad)")
    band = np.array([0xF6, 0xCC, 0xCC]) / 255
    white = np.ones(3)
    for ax, upper, lower in ((coude, 2.0, -2.0), (epaule, 1.57, -1.57)):
        gids = {p.get_gid() for p in ax.patches}
        name = ax.get_ylabel().split()[0]
        assert {f"band:{name}:upper", f"band:{name}:lower"} <= gids
        top, bottom = ax.get_ylim()[1], ax.get_ylim()[0]
        t = 3.9  # both curves are inside their limits here
        np.testing.assert_allclose(_pixel(figure, ax, t, (upper + top) / 2, image), band, atol=2 / 255)
        np.testing.assert_allclose(_pixel(figure, ax, t, (lower + bottom) / 2, image), band, atol=2 / 255)
        assert np.allclose(_pixel(figure, ax, t, (upper + lower) / 2 + 0.3, image), white, atol=2 / 255)
        dashed = [line for line in ax.lines if line.get_linestyle() == "--"]
        assert sorted(line.get_ydata()[0] for line in dashed) == [lower, upper]
    marks = [line for line in coude.lines if line.get_gid() == "violations:coude"]
    assert len(marks) == 1
    expected = np.abs(2.5 * np.sin(states.times)) > 2.0
    np.testing.assert_allclose(marks[0].get_xdata(), states.times[expected])
    assert not [line for line in epaule.lines if str(line.get_gid()).startswith("violations")]


def test_plot_motion_path_in_plane_is_the_tip_path(tutorial_robot):
    from matplotlib.collections import LineCollection

    states = _states(["epaule", "coude"], [[0.0, 0.0], [0.5, -0.7], [0.2, 0.3]])
    figure = plot_motion(tutorial_robot, states)
    flat = next(ax for ax in figure.axes if ax.get_xlabel() == "x (m)" and ax.get_ylabel() == "z (m)")
    segments = next(c for c in flat.collections if isinstance(c, LineCollection)).get_segments()
    expected = tip_path(tutorial_robot, states)[:, [0, 2]]
    np.testing.assert_allclose(np.array([s[0] for s in segments]), expected[:-1], atol=1e-12)
    np.testing.assert_allclose(segments[-1][1], expected[-1], atol=1e-12)


def test_plot_motion_saves_svg_and_refuses_unknown_format(tmp_path, tutorial_robot):
    states = _states(["epaule", "coude"], [[0.0, 0.0], [0.1, 0.2]])
    plot_motion(tutorial_robot, states, path=str(tmp_path / "p.svg"))
    assert (tmp_path / "p.svg").read_text(encoding="utf-8").lstrip().startswith("<?xml")
    with pytest.raises(ParameterError, match="unknown format"):
        plot_motion(tutorial_robot, states, path=str(tmp_path / "p.gif"))
