"""BK1xx: is this a readable robot, and do its links form one tree?"""

from __future__ import annotations

import difflib
import re
from collections.abc import Iterable, Iterator

from ..findings.registry import ERROR, INFO, WARNING, Hit, hit, loader_rule, rule
from ..model.robot import JOINT_TYPES, Joint, parse_numbers
from .context import Context, find_loops

# Reported by the loader when a file cannot be read at all (bras-kit validate then exits 2),
# or when a .xacro holds only macros.
loader_rule("BK100", "xml-not-well-formed")
loader_rule("BK101", "xml-unsafe")
loader_rule("BK102", "xacro-failed")
loader_rule("BK103", "file-unreadable")
loader_rule("BK124", "xacro-macro-library", INFO)
loader_rule("BK126", "urdf-generated-from-xacro", INFO)
loader_rule("BK127", "generated-urdf-out-of-date", WARNING)

MAX_SUGGESTIONS = 20  # close-name searches per rule and file (each is linear in the names)

# Attribute examples for hints: (tag, attribute) -> a correct way to write it.
EXAMPLES = {
    ("link", "name"): 'name="bras"',
    ("joint", "name"): 'name="coude"',
    ("joint", "type"): 'type="revolute"',
    ("joint", "parent"): '<parent link="bras"/>',
    ("joint", "child"): '<child link="avant_bras"/>',
    ("parent", "link"): 'link="bras"',
    ("child", "link"): 'link="avant_bras"',
    ("mimic", "joint"): 'joint="coude"',
    ("box", "size"): 'size="0.08 0.08 0.6"',
    ("cylinder", "radius"): 'radius="0.15"',
    ("cylinder", "length"): 'length="0.1"',
    ("sphere", "radius"): 'radius="0.05"',
    ("mesh", "filename"): 'filename="package://bras_description/meshes/bras.stl"',
    ("mesh", "scale"): 'scale="1 1 1"',
    ("origin", "xyz"): 'xyz="0 0 0.6"',
    ("origin", "rpy"): 'rpy="0 0 1.5708"',
    ("color", "rgba"): 'rgba="0.2 0.4 0.9 1"',
    ("mass", "value"): 'value="1.0"',
    ("inertial", "mass"): '<mass value="1.0"/>',
    ("inertial", "inertia"): '<inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" izz="0.01"/>',
}
for _key in ("ixx", "ixy", "ixz", "iyy", "iyz", "izz"):
    EXAMPLES[("inertia", _key)] = f'{_key}="0"' if _key[1] != _key[2] else f'{_key}="0.01"'
# attributes that are child elements in the file (the parser names them as attributes)
MISSING_ELEMENTS = {("joint", "parent"), ("joint", "child"), ("inertial", "mass"), ("inertial", "inertia")}
VECTOR_SIZES = {"xyz": 3, "rpy": 3, "size": 3, "scale": 3, "rgba": 4}


def closest(name: str | None, choices: Iterable[str], cutoff: float = 0.6) -> str | None:
    if not name:
        return None
    match = difflib.get_close_matches(name, list(choices), n=1, cutoff=cutoff)
    return match[0] if match else None


@rule("BK104", "root-not-robot", ERROR)
def root_not_robot(ctx: Context) -> Iterator[Hit]:
    for issue in ctx.issues("root_not_robot"):
        yield hit(issue.value or issue.element, None, issue.line, tag=issue.value)


@rule("BK105", "robot-name-missing", ERROR)
def robot_name_missing(ctx: Context) -> Iterator[Hit]:
    if ctx.is_robot and not (ctx.robot.name or "").strip():
        yield hit("robot", None, ctx.robot.line)


@rule("BK125", "xml-declaration-not-first", WARNING)
def xml_declaration_not_first(ctx: Context) -> Iterator[Hit]:
    for issue in ctx.issues("late_xml_declaration"):  # a tab is named: it is invisible in most editors
        yield hit("file", None, issue.line, "tab" if issue.value == "tab" else "", at=issue.line)


@rule("BK106", "no-links", ERROR)
def no_links(ctx: Context) -> Iterator[Hit]:
    if ctx.is_robot and not ctx.robot.links:
        yield hit("robot", ctx.robot.name, ctx.robot.line)


@rule("BK107", "duplicate-link-name", ERROR)
def duplicate_link_name(ctx: Context) -> Iterator[Hit]:
    for link in ctx.robot.links:
        first = ctx.links.get(link.name) if link.name is not None else None
        if first is not None and first is not link:
            yield hit("link", link.name, link.line, link=link.name, first_line=first.line)


@rule("BK108", "duplicate-joint-name", ERROR)
def duplicate_joint_name(ctx: Context) -> Iterator[Hit]:
    for joint in ctx.robot.joints:
        first = ctx.joints.get(joint.name) if joint.name is not None else None
        if first is not None and first is not joint:
            yield hit("joint", joint.name, joint.line, joint=joint.name, first_line=first.line)


@rule("BK109", "duplicate-material", ERROR)
def duplicate_material(ctx: Context) -> Iterator[Hit]:
    first_line: dict[str, int | None] = {}
    for material in ctx.robot.materials:
        if not material.name:
            continue
        if material.name in first_line:
            yield hit("material", material.name, material.line, material=material.name,
                      first_line=first_line[material.name])
        else:
            first_line[material.name] = material.line


@rule("BK110", "material-redefined", WARNING)
def material_redefined(ctx: Context) -> Iterator[Hit]:
    for link in ctx.robot.links:
        for visual in link.visuals:
            m = visual.material
            if m is None or not m.name or (m.rgba is None and not m.texture):
                continue
            winner = ctx.materials.get(m.name)
            if winner is None or winner is m or (winner.rgba, winner.texture) == (m.rgba, m.texture):
                continue
            yield hit("material", m.name, m.line, material=m.name, link=link.name,
                      colour=_colour(m.rgba, m.texture), first_colour=_colour(winner.rgba, winner.texture),
                      first_line=winner.line)


def _colour(rgba: tuple[float, ...] | None, texture: str | None) -> object:
    return rgba if rgba is not None else (texture or "?")


def _unknown_link(ctx: Context, role: str) -> Iterator[Hit]:
    suggestions, names = 0, list(ctx.links)
    for joint in ctx.robot.joints:
        name = joint.parent if role == "parent" else joint.child
        if name is None or name in ctx.links:
            continue
        close = None
        if suggestions < MAX_SUGGESTIONS:
            suggestions += 1
            close = closest(name, ctx.links)
        yield hit("joint", joint.name, joint.line, "close" if close else "",
                  joint=joint.name, link=name, close=close, links=names)


@rule("BK111", "joint-parent-unknown", ERROR)
def joint_parent_unknown(ctx: Context) -> Iterator[Hit]:
    return _unknown_link(ctx, "parent")


@rule("BK112", "joint-child-unknown", ERROR)
def joint_child_unknown(ctx: Context) -> Iterator[Hit]:
    return _unknown_link(ctx, "child")


@rule("BK113", "joint-parent-is-child", ERROR)
def joint_parent_is_child(ctx: Context) -> Iterator[Hit]:
    for joint in ctx.robot.joints:
        if joint.parent is not None and joint.parent == joint.child:
            yield hit("joint", joint.name, joint.line, joint=joint.name, link=joint.child)


@rule("BK114", "link-two-parents", ERROR)
def link_two_parents(ctx: Context) -> Iterator[Hit]:
    graph = ctx.graph
    for joint in graph.extra_parents:
        first = graph.parent_joint[joint.child]  # type: ignore[index]
        yield hit("joint", joint.name, joint.line, joint=joint.name, link=joint.child,
                  first_joint=first.name, first_line=first.line)


def loop_text(joints: list[Joint]) -> str:
    """``bras -> avant_bras -> bras``: the links of a loop, in joint order."""
    names = [joints[0].parent or "?"] + [j.child or "?" for j in joints]
    return " -> ".join(names)


@rule("BK115", "joint-cycle", ERROR)
def joint_cycle(ctx: Context) -> Iterator[Hit]:
    for loop in ctx.graph.cycles:
        closing = max(loop, key=lambda j: j.line or 0)  # the joint written last closes the loop
        yield hit("joint", closing.name, closing.line, joint=closing.name, loop=loop_text(loop),
                  joints=[j.name or "?" for j in loop])


@rule("BK116", "several-roots", ERROR)
def several_roots(ctx: Context) -> Iterator[Hit]:
    graph = ctx.graph
    isolated = set(graph.isolated)
    roots = [name for name in graph.roots if name not in isolated]
    if len(roots) > 1:
        extra = ctx.links[roots[1]]
        yield hit("link", extra.name, extra.line, roots=roots, root=roots[0], extra=roots[1])


@rule("BK117", "link-disconnected", ERROR)
def link_disconnected(ctx: Context) -> Iterator[Hit]:
    graph = ctx.graph
    if not graph.isolated:
        return
    isolated = set(graph.isolated)
    # the root links hang from; with no joint at all, the first link is taken as the root
    root = next((name for name in graph.roots if name not in isolated), None) or next(iter(ctx.links))
    for name in graph.isolated:
        if name != root:
            yield hit("link", name, ctx.links[name].line, link=name, root=root)


@rule("BK118", "joint-type-unknown", ERROR)
def joint_type_unknown(ctx: Context) -> Iterator[Hit]:
    for joint in ctx.robot.joints:
        if joint.type is not None and joint.type not in JOINT_TYPES:
            close = closest(joint.type.lower(), JOINT_TYPES)
            yield hit("joint", joint.name, joint.line, "close" if close else "",
                      joint=joint.name, type=joint.type, close=close, types=list(JOINT_TYPES))


@rule("BK119", "xacro-not-expanded", ERROR)
def xacro_not_expanded(ctx: Context) -> Iterator[Hit]:
    issues = ctx.issues("unexpanded_xacro")
    if issues:
        first = issues[0]
        lines = {issue.line for issue in issues}
        tag = first.value or first.element
        yield hit(tag, first.name, first.line, "more" if len(lines) > 1 else "",
                  tag=tag, more=len(lines) - 1, path=ctx.robot.path or "FILE")


@rule("BK120", "mimic-joint-unknown", ERROR)
def mimic_joint_unknown(ctx: Context) -> Iterator[Hit]:
    suggestions, names = 0, list(ctx.joints)
    for joint in ctx.robot.joints:
        mimic = joint.mimic
        if mimic is None or mimic.joint is None or mimic.joint in ctx.joints:
            continue
        close = None
        if suggestions < MAX_SUGGESTIONS:
            suggestions += 1
            close = closest(mimic.joint, ctx.joints)
        yield hit("joint", joint.name, mimic.line or joint.line, "close" if close else "",
                  joint=joint.name, leader=mimic.joint, close=close, joints=names)


@rule("BK121", "mimic-cycle", ERROR)
def mimic_cycle(ctx: Context) -> Iterator[Hit]:
    leader = {name: joint.mimic.joint for name, joint in ctx.joints.items()
              if joint.mimic is not None and joint.mimic.joint is not None and joint.mimic.joint in ctx.joints}
    for loop in find_loops(ctx.joints, leader):
        joint = ctx.joints[loop[-1]]
        line = (joint.mimic.line if joint.mimic is not None else None) or joint.line
        yield hit("joint", joint.name, line, joint=joint.name, chain=" -> ".join(loop + [loop[0]]))


@rule("BK122", "attribute-missing", ERROR)
def attribute_missing(ctx: Context) -> Iterator[Hit]:
    for issue in ctx.issues("missing_attribute"):
        if issue.element == "axis":
            continue  # BK206 says it better
        element, name = ctx.owner(issue)
        key = (issue.element, issue.attribute or "")
        yield hit(element, name, issue.line, "element" if key in MISSING_ELEMENTS else "",
                  tag=issue.element, attribute=issue.attribute, owner=name,
                  example=EXAMPLES.get(key, f'{issue.attribute}="..."'), part=issue.part)


@rule("BK123", "number-unreadable", ERROR)
def number_unreadable(ctx: Context) -> Iterator[Hit]:
    for issue in ctx.issues("bad_number"):
        if issue.element == "axis":
            continue  # BK206
        element, name = ctx.owner(issue)
        count = VECTOR_SIZES.get(issue.attribute or "", 1)
        variant, fixed, comma = comma_fix(issue.value or "", count)
        yield hit(element, name, issue.line, variant or ("one" if count == 1 else ""),
                  tag=issue.element, attribute=issue.attribute, value=issue.value, count=count,
                  example=EXAMPLES.get((issue.element, issue.attribute or ""))
                  or f'{issue.attribute}="{" ".join(["0"] * count)}"', fixed=fixed, comma=comma, part=issue.part)


_DECIMAL_COMMA = re.compile(r"(?<=[0-9]),(?=[0-9])")


def comma_fix(value: str, count: int) -> tuple[str, str, str]:
    """("comma", the value with decimal points, the first number written with a comma) for
    ``0 0 0,6``; ("commas", the value with spaces, "") for ``0,0,0.6``; ("", "", "") otherwise."""
    if "," not in value:
        return "", "", ""
    decimal = _DECIMAL_COMMA.sub(".", value)
    numbers = parse_numbers(decimal)
    if numbers is not None and len(numbers) == count:
        comma = next((part for part in value.split() if _DECIMAL_COMMA.search(part)), value)
        return "comma", " ".join(decimal.split()), comma
    tokens = value.split()
    if not (len(tokens) == 1 or all(token.endswith(",") for token in tokens[:-1])):
        return "", "", ""  # commas and spaces mixed ("0 0,6"): no guess at what was meant
    spaced = " ".join(value.replace(",", " ").split())
    numbers = parse_numbers(spaced)
    if numbers is not None and len(numbers) == count:
        return "commas", spaced, ""
    return "", "", ""
