"""BK627: the beginner's mistakes rclpy (Jazzy) stops on, seen in a node's source without running it.

The same mistakes as the run rule BK652 explains after ``bras-kit run``, where the source alone
shows them: ``create_timer(20, ...)`` meant as 20 Hz, ``self.tick()`` handed to create_timer,
``def tick():`` without ``self``, a Node subclass whose ``__init__`` never calls
``super().__init__``, ``with Node() as``, ``stamp = ...now()`` without ``.to_msg()``,
``rclpy.shutdown()`` after catching Ctrl-C, ``stamp.sec = int(time.time())``, and a timer
period that disagrees with the time step the callback adds. A name the reading cannot resolve
says nothing.
"""

from __future__ import annotations

import ast
from collections.abc import Iterator

from ...findings.registry import ERROR, Hit, hit
from ...ros.package import Package
from .rules import package_rule


def _at(file: str, line: int | None, variant: str, **params: object) -> Hit:
    return hit("file", None, line, variant, file=file, **params)


def _number(node: ast.expr | None) -> float | None:
    if isinstance(node, ast.Constant) and isinstance(node.value, (int, float)) and not isinstance(node.value, bool):
        return float(node.value)
    return None


def _is_self_attr(node: ast.expr | None) -> str | None:
    if isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name) and node.value.id == "self":
        return node.attr
    return None


def _node_classes(tree: ast.Module) -> list[ast.ClassDef]:
    """Classes deriving from Node (rclpy.node.Node, or Node imported from it)."""
    out = []
    for cls in (n for n in ast.walk(tree) if isinstance(n, ast.ClassDef)):
        for base in cls.bases:
            name = base.attr if isinstance(base, ast.Attribute) else base.id if isinstance(base, ast.Name) else ""
            if name == "Node":
                out.append(cls)
    return out


def _methods(cls: ast.ClassDef) -> dict[str, ast.FunctionDef]:
    return {f.name: f for f in cls.body if isinstance(f, ast.FunctionDef)}


def _calls_super_init(function: ast.FunctionDef) -> bool:
    for call in (n for n in ast.walk(function) if isinstance(n, ast.Call)):
        func = call.func
        if isinstance(func, ast.Attribute) and func.attr == "__init__":
            return True  # super().__init__(...), Node.__init__(self, ...)
    return False


def mistakes(tree: ast.Module) -> Iterator[tuple[str, int, dict[str, object]]]:
    """(variant, line, parameters) of each mistake the module's source shows."""
    classes = _node_classes(tree)
    for cls in classes:
        methods = _methods(cls)
        init = methods.get("__init__")
        if init is not None and not _calls_super_init(init):
            yield "super_init", init.lineno, {"cls": cls.name}
        for call in (n for n in ast.walk(cls) if isinstance(n, ast.Call)):
            if not (isinstance(call.func, ast.Attribute) and call.func.attr == "create_timer" and len(call.args) >= 2):
                continue
            period, callback = _number(call.args[0]), call.args[1]
            if period is not None and period >= 2 and period == int(period):
                yield "timer_period", call.lineno, {"period": int(period), "hz": round(1 / period, 4)}
            if isinstance(callback, ast.Call) and _is_self_attr(callback.func):
                yield "callback_called", call.lineno, {"short": _is_self_attr(callback.func)}
                continue
            name = _is_self_attr(callback)
            target = methods.get(name or "")
            if target is not None and not target.args.args and not target.args.vararg \
                    and not any(isinstance(d, ast.Name) and d.id == "staticmethod" for d in target.decorator_list):
                yield "no_self", target.lineno, {"short": name}
            elif target is not None and period is not None:
                step = _time_step(target)
                if step is not None and abs(step[0] - period) > 1e-9 * max(1.0, period):
                    yield "time_step", step[1], {"short": name, "step": step[0], "period": period,
                                                 "ratio": round(step[0] / period, 3)}
    node_names = {cls.name for cls in classes} | {"Node"}
    for node in ast.walk(tree):
        if isinstance(node, ast.With):
            for item in node.items:
                expr = item.context_expr
                if isinstance(expr, ast.Call) and isinstance(expr.func, ast.Name) and expr.func.id in node_names:
                    yield "with_node", node.lineno, {"cls": expr.func.id}
        if isinstance(node, ast.Assign) and len(node.targets) == 1:
            assigned, value = node.targets[0], node.value
            if isinstance(assigned, ast.Attribute) and assigned.attr == "stamp" and isinstance(value, ast.Call) \
                    and isinstance(value.func, ast.Attribute) and value.func.attr == "now":
                yield "now_not_msg", node.lineno, {}
            if isinstance(assigned, ast.Attribute) and assigned.attr == "sec" and isinstance(value, ast.Call) \
                    and isinstance(value.func, ast.Name) and value.func.id == "int" and value.args \
                    and "time" in ast.unparse(value.args[0]):
                yield "stamp_seconds", node.lineno, {}
        if isinstance(node, ast.FunctionDef):
            yield from _shutdown_after_ctrl_c(node)


def _time_step(function: ast.FunctionDef) -> tuple[float, int] | None:
    """``self.X += <number>`` in the callback: the time step it adds at each tick, and its line."""
    for node in ast.walk(function):
        if isinstance(node, ast.AugAssign) and isinstance(node.op, ast.Add) and _is_self_attr(node.target) \
                and _is_self_attr(node.target) in ("t", "time", "temps", "elapsed"):
            step = _number(node.value)
            if step is not None:
                return step, node.lineno
    return None


def _shutdown_after_ctrl_c(function: ast.FunctionDef) -> Iterator[tuple[str, int, dict[str, object]]]:
    """``try: rclpy.spin(...) except KeyboardInterrupt: ...`` then ``rclpy.shutdown()`` in the same
    function: after Ctrl-C the context is already shut down, and shutdown() raises on Jazzy."""
    caught = False
    for statement in ast.walk(function):
        if isinstance(statement, ast.Try) and any(
                isinstance(h.type, ast.Name) and h.type.id == "KeyboardInterrupt"
                or isinstance(h.type, ast.Tuple) and any(isinstance(e, ast.Name) and e.id == "KeyboardInterrupt"
                                                         for e in h.type.elts)
                for h in statement.handlers):
            caught = True
    if not caught:
        return
    guarded = {id(n) for branch in ast.walk(function) if isinstance(branch, ast.If) and "ok()" in ast.unparse(branch.test)
               for statement in branch.body for n in ast.walk(statement)}  # if rclpy.ok(): rclpy.shutdown()
    for call in (n for n in ast.walk(function) if isinstance(n, ast.Call) and id(n) not in guarded):
        if isinstance(call.func, ast.Attribute) and call.func.attr == "shutdown" \
                and isinstance(call.func.value, ast.Name) and call.func.value.id == "rclpy" and not call.keywords:
            yield "shutdown_twice", call.lineno, {}


@package_rule("BK627", "node-beginner-mistake-in-source", ERROR)
def node_beginner_mistake_in_source(pkg: Package) -> Iterator[Hit]:
    for module in pkg.python_modules():
        tree = pkg.module_tree(module[:-3])
        if tree is None:
            continue
        for variant, line, params in mistakes(tree):
            yield _at(module, line, variant, **params)
