"""A Python launch file read statically (never run): the ``Node(...)`` calls it makes and the
files of share/ it builds paths to. The launch as ``ros2 launch`` evaluates it is
:mod:`bras_kit.ros.launching`'s."""

from __future__ import annotations

import ast
from dataclasses import dataclass
from typing import Any

from .staticpy import Evaluator, ShareFile, call_name, calls, keyword


@dataclass(frozen=True)
class NodeCall:
    """A ``Node(package=..., executable=...)`` of a launch file."""

    package: Any
    executable: Any
    arguments: Any
    line: int
    parameters: Any = None  # the parameters= list as far as it can be read (None: not given)
    has_parameters: bool = False


@dataclass(frozen=True)
class LaunchFile:
    """A Python launch file read statically: its Node(...) calls and the share files it names."""

    path: str  # relative to the package folder
    nodes: list[NodeCall]
    share_files: list[tuple[ShareFile, int]]  # files of share/ the launch file builds a path to
    includes: bool = False  # includes other launch files or publishes frames itself (tf2_ros)


def read_launch_file(tree: ast.Module, rel: str, root: str) -> LaunchFile:
    evaluator = Evaluator(tree, root)
    scope = dict(evaluator.names)
    for function in evaluator.functions.values():
        scope.update(evaluator.scope_of(function))
    nodes = []
    share_files = []
    includes = False
    for call in calls(tree):
        name = call_name(call.func)
        if name.rsplit(".", 1)[-1] == "Node":
            arguments = keyword(call, "arguments")
            parameters = keyword(call, "parameters")
            nodes.append(NodeCall(evaluator.value(keyword(call, "package"), scope),
                                  evaluator.value(keyword(call, "executable"), scope),
                                  [] if arguments is None else evaluator.value(arguments, scope), call.lineno,
                                  _parameter_keys(parameters), parameters is not None))
            includes = includes or nodes[-1].package == "tf2_ros"
        elif name.rsplit(".", 1)[-1] in ("IncludeLaunchDescription", "ExecuteProcess", "OpaqueFunction"):
            includes = True
        elif name in ("os.path.join", "path.join", "join", "PathJoinSubstitution"):
            value = evaluator.value(call, scope)
            if isinstance(value, ShareFile) and value.relative:
                share_files.append((value, call.lineno))
    return LaunchFile(rel, nodes, share_files, includes)


def _parameter_keys(node: ast.expr | None) -> Any:
    """The parameter names a ``parameters=[{...}, ...]`` list gives, as a set; None when a part of
    it cannot be read without running the file (a YAML path, a variable, a substitution)."""
    if node is None:
        return set()
    if not isinstance(node, (ast.List, ast.Tuple)):
        return None
    keys: set[str] = set()
    for item in node.elts:
        if not isinstance(item, ast.Dict) or any(k is None or not isinstance(k, ast.Constant) for k in item.keys):
            return None
        keys |= {str(k.value) for k in item.keys if isinstance(k, ast.Constant)}
    return keys
