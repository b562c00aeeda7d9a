"""What every rule reads: the robot, the options, and indexes built once (so rules stay linear).

Nothing here re-reads XML: links, joints, materials and the parser's issues come from the
:class:`~bras_kit.model.robot.Robot`. The link graph (roots, loops, links with two parents) is
analysed once, in linear time, without building a kinematic tree (which would stop at the
first defect).
"""

from __future__ import annotations

import os
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from functools import cached_property
from typing import Any

from ..model.robot import Collision, Issue, Joint, Link, Material, Robot, Visual
from .solids import Bounds, shape_bounds

# tags that only occur inside a <joint>; everything else named in an issue belongs to a link
_JOINT_TAGS = frozenset({"joint", "parent", "child", "axis", "limit", "mimic", "dynamics",
                         "calibration", "safety_controller"})


@dataclass
class Graph:
    """The link graph as written, defects included."""

    parent_joint: dict[str, Joint]  # link -> the first valid joint naming it as child
    extra_parents: list[Joint]  # later joints naming an already-parented link as child
    roots: list[str]  # links with no parent, in file order
    isolated: list[str]  # links named by no joint at all (when the robot has several links)
    cycles: list[list[Joint]]  # each loop as the joints that form it, in order
    children: dict[str, list[Joint]] = field(default_factory=dict)  # link -> valid child joints


@dataclass
class Context:
    """What the URDF rules read: the robot, the pose or motion to check, and facts computed once."""

    robot: Robot
    pose: Mapping[str, float] | None = None
    states: Any = None  # bras_kit.motion.JointStates (times, names, positions, velocities)
    package_paths: Sequence[str] = ()
    target: str | None = None  # where the robot is heading ("gazebo"): notes for it are given only then
    _bounds: dict[int, Bounds | None] = field(default_factory=dict, init=False, repr=False)
    _derived: dict[str, Any] = field(default_factory=dict, init=False, repr=False)

    def derived(self, key: str, compute: Callable[[Context], Any]) -> Any:
        """A fact several rules need (e.g. every principal moment), computed once per validation."""
        if key not in self._derived:
            self._derived[key] = compute(self)
        return self._derived[key]

    # ------------------------------------------------------------ indexes

    @cached_property
    def links(self) -> dict[str, Link]:
        """Links by name (the first definition when a name repeats)."""
        out: dict[str, Link] = {}
        for link in self.robot.links:
            if link.name is not None:
                out.setdefault(link.name, link)
        return out

    @cached_property
    def joints(self) -> dict[str, Joint]:
        out: dict[str, Joint] = {}
        for joint in self.robot.joints:
            if joint.name is not None:
                out.setdefault(joint.name, joint)
        return out

    @cached_property
    def materials(self) -> dict[str, Material]:
        """Colours by material name as a URDF reader resolves them: top-level ones first,
        then the first inline definition (in a <visual>) that carries a colour or texture."""
        out: dict[str, Material] = {}
        for material in self.robot.materials:
            if material.name:
                out.setdefault(material.name, material)
        for link in self.robot.links:
            for visual in link.visuals:
                m = visual.material
                if m is not None and m.name and (m.rgba is not None or m.texture):
                    out.setdefault(m.name, m)
        return out

    @cached_property
    def issues_by_kind(self) -> dict[str, list[Issue]]:
        out: dict[str, list[Issue]] = {}
        for issue in self.robot.issues:
            out.setdefault(issue.kind, []).append(issue)
        return out

    def issues(self, kind: str) -> list[Issue]:
        return self.issues_by_kind.get(kind, [])

    @cached_property
    def unreadable(self) -> set[tuple[int, str | None]]:
        """(line, attribute) of every value the parser could not read as a number."""
        return {(issue.line, issue.attribute) for issue in self.issues("bad_number")}

    @property
    def is_robot(self) -> bool:
        return self.robot.root_tag == "robot"

    @property
    def folder(self) -> str | None:
        """The folder relative mesh paths start from (None for the built-in arm)."""
        path = self.robot.path
        if not path or path.startswith("<"):
            return None
        return os.path.dirname(os.path.abspath(path))

    # ------------------------------------------------------------ graph

    @cached_property
    def graph(self) -> Graph:
        known = self.links
        parent_joint: dict[str, Joint] = {}
        extra: list[Joint] = []
        children: dict[str, list[Joint]] = {}
        named: set[str] = set()
        for joint in self.robot.joints:
            named.update(n for n in (joint.parent, joint.child) if n)
            if joint.parent not in known or joint.child not in known or joint.parent == joint.child:
                continue
            assert joint.child is not None and joint.parent is not None
            if joint.child in parent_joint:
                extra.append(joint)
                continue
            parent_joint[joint.child] = joint
            children.setdefault(joint.parent, []).append(joint)
        roots = [name for name in known if name not in parent_joint]
        isolated = [name for name in known if name not in named] if len(known) > 1 else []
        parent_of = {child: joint.parent or "" for child, joint in parent_joint.items()}
        # a walk from child to parent meets the loop's links in reverse joint order
        cycles = [[parent_joint[name] for name in reversed(loop)] for loop in find_loops(known, parent_of)]
        return Graph(parent_joint, extra, roots, isolated, cycles, children)

    # ------------------------------------------------------------ shapes

    def shape(self, link: Link) -> tuple[Visual | Collision, Bounds] | None:
        """The link's one primitive shape and its bounds in the link frame, if it has exactly one.

        Visuals are used when there are any; otherwise collisions. Links with several shapes or
        a mesh return None: rules that reason about "the segment" skip them rather than guess.
        """
        key = id(link)
        if key not in self._bounds:
            self._bounds[key] = None
            elements: list[Visual] | list[Collision] = link.visuals or link.collisions
            if len(elements) == 1:
                bounds = shape_bounds(elements[0].origin, elements[0].geometry)
                self._bounds[key] = bounds
        bounds = self._bounds[key]
        if bounds is None:
            return None
        return (link.visuals or link.collisions)[0], bounds

    # ------------------------------------------------------------ issues -> owners

    def owner(self, issue: Issue) -> tuple[str, str | None]:
        """The named element (link, joint or material) an issue belongs to, as (tag, name).

        The parser records the owner's name; links and joints may share a name (``poignet``),
        so the owner is the one whose definition starts last at or before the issue's line.
        """
        link = self.links.get(issue.name) if issue.name is not None else None
        joint = self.joints.get(issue.name) if issue.name is not None else None
        if link is not None and joint is not None:
            before = [(line, tag) for line, tag in ((link.line or 0, "link"), (joint.line or 0, "joint"))
                      if line <= issue.line]
            if len(before) == 2 and before[0][0] != before[1][0]:
                return max(before)[1], issue.name
            if len(before) == 1:
                return before[0][1], issue.name
        elif joint is not None:
            return "joint", issue.name
        elif link is not None:
            return "link", issue.name
        if issue.element in ("material", "color", "texture") and link is None and joint is None:
            return "material", issue.name
        return ("joint" if issue.element in _JOINT_TAGS else "link"), issue.name


def find_loops(nodes: Iterable[str], step: Mapping[str, str]) -> list[list[str]]:
    """Loops in a "points to" relation (link -> parent link, joint -> mimicked joint), each once.

    Each node is walked from at most once, so the search is linear in the number of nodes.
    A loop is returned as the nodes met, in walking order, starting where it closes.
    """
    state: dict[str, int] = {}  # 1: on the current walk, 2: settled
    loops: list[list[str]] = []
    for start in nodes:
        walk: list[str] = []
        current: str | None = start
        while current is not None and current not in state:
            state[current] = 1
            walk.append(current)
            current = step.get(current)
        if current is not None and state[current] == 1:  # came back onto this walk
            loops.append(walk[walk.index(current):])
        for name in walk:
            state[name] = 2
    return loops
