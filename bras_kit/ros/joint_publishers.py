"""The package's nodes that publish sensor_msgs/JointState, read statically: the joint names and
the formulas of ``msg.position``, the topic, whether a timer or a loop ever runs the callback,
and angles written in degrees. A formula may come from a sibling module or a function of the
package (:class:`PackageCode` gives this module what it reads of the package)."""

from __future__ import annotations

import ast
from dataclasses import dataclass, field
from typing import Any, Protocol

from ..model.robot import Robot
from .staticpy import Evaluator, call_name, calls, keyword


class PackageCode(Protocol):
    """What the reading of a node needs of its package (:class:`bras_kit.ros.package.Package`)."""

    root: str

    @property
    def robot(self) -> Robot | None: ...

    def module_tree(self, module: str) -> ast.Module | None: ...


@dataclass(frozen=True)
class Publisher:
    """A Python module of the package that publishes sensor_msgs/JointState."""

    path: str  # relative to the package folder
    module: str  # dotted name, e.g. bras_description.animation
    line: int  # the create_publisher call
    names: list[str] | None  # joint names when written literally (or as a constant)
    names_line: int | None
    formulas: dict[str, str] = field(default_factory=dict)  # joint -> formula in t
    formulas_line: int | None = None
    has_main: bool = False
    topic: Any = None  # the topic name when written literally (or as a module constant)
    topic_line: int | None = None
    scheduled: bool = True  # a timer or a loop calls something: False when nothing ever runs the callback
    publishes: bool = True  # some .publish(...) call exists
    degrees: list[tuple[int, str]] = field(default_factory=list)  # (line, what) of angles written in degrees


def read_publisher(package: PackageCode, tree: ast.Module, rel: str) -> Publisher | None:
    create = next((c for c in calls(tree) if call_name(c.func).endswith("create_publisher") and c.args
                   and call_name(c.args[0]).rsplit(".", 1)[-1] == "JointState"), None)
    if create is None:
        return None
    evaluator = Evaluator(tree, package.root, _imported_names(package, tree, rel))
    # the JointState messages: variables assigned JointState(), and JointState(name=..., position=...)
    messages = {ast.unparse(n.targets[0]) for n in ast.walk(tree) if isinstance(n, ast.Assign)
                and len(n.targets) == 1 and isinstance(n.value, ast.Call)
                and call_name(n.value.func).rsplit(".", 1)[-1] == "JointState"}
    name_nodes: list[ast.expr] = []
    position_nodes: list[ast.expr] = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Assign) and len(node.targets) == 1 and isinstance(node.targets[0], ast.Attribute) \
                and ast.unparse(node.targets[0].value) in messages:
            if node.targets[0].attr == "name":
                name_nodes.append(node.value)
            elif node.targets[0].attr == "position":
                position_nodes.append(node.value)
        elif isinstance(node, ast.Call) and call_name(node.func).rsplit(".", 1)[-1] == "JointState":
            name_nodes += [k.value for k in node.keywords if k.arg == "name"]
            position_nodes += [k.value for k in node.keywords if k.arg == "position"]
    names: list[str] | None = None
    names_line = formulas_line = None
    if len(name_nodes) == 1:  # several assignments: which one is sent is not known statically
        value = evaluator.value(name_nodes[0])
        names_line = name_nodes[0].lineno
        if isinstance(value, (list, tuple)) and all(isinstance(v, str) for v in value):
            names = list(value)
    positions: list[ast.expr] | None = None
    time_scope: dict[str, Any] = {}
    if len(position_nodes) == 1:
        formulas_line = position_nodes[0].lineno
        positions, time_scope = _position_expressions(package, evaluator, position_nodes[0], rel)
    formulas: dict[str, str] = {}
    if names is not None and positions is not None and len(positions) == len(names):
        from .formulas import formula

        for joint, expression in zip(names, positions):
            text = formula(expression, time_scope)
            if text is not None:
                formulas[joint] = text
    has_main = any(isinstance(n, ast.FunctionDef) and n.name == "main" for n in tree.body)
    module = rel[:-3].replace("/", ".")
    topic_node = create.args[1] if len(create.args) > 1 else keyword(create, "topic")
    topic = evaluator.value(topic_node) if topic_node is not None else None
    scheduled = any(call_name(c.func).rsplit(".", 1)[-1] in ("create_timer", "Timer", "create_rate")
                    for c in calls(tree)) or any(isinstance(n, (ast.While, ast.For)) and any(
                        isinstance(m, ast.Call) for m in ast.walk(n)) for n in ast.walk(tree))
    publishes = any(call_name(c.func).rsplit(".", 1)[-1] == "publish" for c in calls(tree))
    degrees = [found for node in position_nodes for found in _in_degrees(node)]
    if positions is not None and names is not None and package.robot is not None:
        for joint, expression in zip(names, positions):
            robot_joint = package.robot.joint(joint) if hasattr(package.robot, "joint") else None
            if robot_joint is not None and robot_joint.type == "revolute":
                degrees += _large_amplitudes(expression)
    return Publisher(rel, module, create.lineno, names, names_line, formulas, formulas_line, has_main,
                     topic, getattr(topic_node, "lineno", create.lineno), scheduled, publishes,
                     _one_per_line(degrees))


def _one_per_line(found: list[tuple[int, str]]) -> list[tuple[int, str]]:
    """The first way of writing degrees seen on each line (a conversion before the 180 inside it)."""
    out: dict[int, str] = {}
    for line, what in found:
        out.setdefault(line, what)
    return sorted(out.items())


def _in_degrees(node: ast.expr) -> list[tuple[int, str]]:
    """``math.degrees(...)``, ``np.rad2deg(...)``, ``* 180 / math.pi``: angles turned into degrees."""
    out = []
    for inner in ast.walk(node):
        if isinstance(inner, ast.Call) and call_name(inner.func).rsplit(".", 1)[-1] in ("degrees", "rad2deg"):
            out.append((inner.lineno, ast.unparse(inner.func) + "(...)"))
        elif isinstance(inner, ast.BinOp) and isinstance(inner.op, (ast.Mult, ast.Div)):
            text = ast.unparse(inner)
            if "180" in text and "pi" in text and isinstance(inner.op, ast.Div) \
                    and ast.unparse(inner.right).endswith("pi"):
                out.append((inner.lineno, text))
    return out


def _large_amplitudes(node: ast.expr) -> list[tuple[int, str]]:
    """Numbers beyond 2 pi multiplying or added to an angle of a revolute joint: degrees, not radians."""
    import math

    out = []
    for inner in ast.walk(node):
        if isinstance(inner, ast.BinOp) and isinstance(inner.op, (ast.Mult, ast.Add, ast.Sub)):
            for side in (inner.left, inner.right):
                if isinstance(side, ast.Constant) and isinstance(side.value, (int, float)) \
                        and not isinstance(side.value, bool) and abs(side.value) > 2 * math.pi \
                        and not (isinstance(inner.op, ast.Mult) and _is_time_factor(inner)):
                    out.append((inner.lineno, ast.unparse(inner)))
        elif isinstance(inner, ast.Constant) and inner is node and isinstance(inner.value, (int, float)) \
                and not isinstance(inner.value, bool) and abs(inner.value) > 2 * math.pi:
            out.append((inner.lineno, ast.unparse(inner)))
    return out


def _is_time_factor(node: ast.BinOp) -> bool:
    """``2 * pi * f * t`` inside sin(): a frequency, not an amplitude (the product sits in a call's argument)."""
    return any(isinstance(n, ast.Name) and n.id in ("t", "time") or isinstance(n, ast.Attribute) and n.attr in ("t", "time")
               for n in (node.left, node.right))


def _imported_names(package: PackageCode, tree: ast.Module, rel: str) -> dict[str, Any]:
    """Constants imported from sibling modules (``from PKG.motion import JOINT_NAMES``)."""
    out: dict[str, Any] = {}
    here = rel.split("/")[0]
    for node in tree.body:
        if not isinstance(node, ast.ImportFrom) or node.module is None:
            continue
        module = f"{here}.{node.module}" if node.level == 1 else node.module
        if not module.startswith(here + "."):
            continue
        other = package.module_tree(module)
        if other is None:
            continue
        names = Evaluator(other, package.root).names
        for alias in node.names:
            if alias.name in names:
                out[alias.asname or alias.name] = names[alias.name]
            elif any(isinstance(n, ast.FunctionDef) and n.name == alias.name for n in other.body):
                out[alias.asname or alias.name] = ("function", module, alias.name)
    return out


def _position_expressions(package: PackageCode, evaluator: Evaluator, node: ast.expr,
                          rel: str) -> tuple[list[ast.expr] | None, dict[str, Any]]:
    """The per-joint expressions of ``msg.position = ...`` and the constants they may use.

    Either a literal list (``[0.8 * math.sin(self.t), ...]``), or a call to a function of the
    package whose body returns such a list or a comprehension over a constant table.
    """
    if isinstance(node, ast.List):
        return list(node.elts), dict(evaluator.names)
    if isinstance(node, ast.Call) and isinstance(node.func, ast.Name):
        target = evaluator.names.get(node.func.id)
        if isinstance(target, tuple) and len(target) == 3 and target[0] == "function":
            tree = package.module_tree(target[1])
            if tree is None:
                return None, {}
            return _returned_expressions(Evaluator(tree, package.root), tree, target[2])
        if node.func.id in evaluator.functions:
            return _returned_expressions(evaluator, None, node.func.id)
    return None, {}


def _returned_expressions(evaluator: Evaluator, tree: ast.Module | None,
                          function_name: str) -> tuple[list[ast.expr] | None, dict[str, Any]]:
    function = evaluator.functions.get(function_name)
    if function is None:
        return None, {}
    returned = next((s.value for s in function.body if isinstance(s, ast.Return)), None)
    time = [a.arg for a in function.args.args]
    scope = dict(evaluator.names)
    if isinstance(returned, ast.List):
        return list(returned.elts), {**scope, "__time__": time}
    if isinstance(returned, ast.ListComp) and len(returned.generators) == 1 and not returned.generators[0].ifs:
        generator = returned.generators[0]
        rows = evaluator.value(generator.iter)
        if not isinstance(rows, (list, tuple)):
            return None, {}
        expressions: list[ast.expr] = []
        from .formulas import substitute

        for row in rows:
            bound: dict[str, Any] = {}
            evaluator._bind(generator.target, row, bound)
            if not all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in bound.values()):
                return None, {}
            expressions.append(substitute(returned.elt, bound))
        return expressions, {**scope, "__time__": time}
    return None, {}
