"""The walls put into the real xacro for one expansion (:class:`_Hooks`): files read through the
gate and the XML safety check, expressions through the allow-list evaluator, ``$(find)`` through
the package paths, and bounds on nesting, elements, children and time."""

from __future__ import annotations

import builtins
import os
import time
from collections.abc import Callable, Mapping
from typing import Any

from ..core.errors import XacroError
from ..core.message import M, Message
from .package_paths import find_package
from .xacro_errors import _NOT_DEFINED, _closest, _names_in
from .xacro_eval import BUILTINS
from .xacro_files import _inside, _read_limited
from .xmlio import check_xml_safe

MAX_MACRO_DEPTH = 100
MAX_INCLUDE_DEPTH = 50
MAX_ELEMENTS = 500_000  # elements processed (macro bodies count each time they are expanded)
MAX_CHILDREN = 20_000  # children of one element (minidom inserts in quadratic time)
_SELF_EXPANDING = M("a macro probably expands itself too many times")


def check_expression(expression: str) -> None:
    """Raise :class:`XacroError` unless ``expression`` only uses what the allow-list accepts.

    The expression is not evaluated: names are not looked up. Used to vet an expression
    alone; during expansion the evaluator itself refuses what it does not know.
    """
    from .xacro_eval import UnsafeXacroExpression, vet

    try:
        vet(expression)
    except SyntaxError as exc:
        raise XacroError(M("cannot read the expression '{expression}': {reason}", expression=expression,
                           reason=exc.msg), hint=M("check brackets and operators inside ${{...}}")) from None
    except UnsafeXacroExpression as exc:
        raise XacroError(_refused(expression, exc.message), hint=exc.hint) from None


def _refused(expression: str, reason: Message | str) -> Message:
    return M("refused the expression '{expression}': {reason}", expression=expression.strip(), reason=reason)


class _Hooks:
    """The replacements put into xacro for one expansion, and what they share."""

    def __init__(self, xacro: Any, subst: Any, path: str, roots: list[str],
                 read_roots: tuple[str, ...] | None = None) -> None:
        from .xacro_eval import BUILTINS, MATH, Budget

        self.xacro, self.subst, self.roots = xacro, subst, roots
        # the folders files are read beneath (None: any regular file); each package $(find) names joins them
        self.read_roots = read_roots
        self.budget = Budget()
        self.elements = 0
        self.files: list[str] = []  # every file read, for finding where an expression is written
        self.yaml_folders = [os.path.realpath(os.path.dirname(os.path.abspath(path)))]
        self.yaml_folders += [os.path.realpath(r) for r in roots if os.path.isdir(r)]
        self.original = (xacro.parse, xacro.safe_eval, xacro.eval_all, subst._eval, subst._eval_find,
                         subst._eval_dict.get("find"), xacro.replace_node)
        self.callables = self._callables(BUILTINS, MATH)

    def _callables(self, builtin_table: Mapping[str, Any], math_table: Mapping[str, Any]) -> dict[int, Any]:
        import builtins
        import math

        xacro, table = self.xacro, {}
        for name, safe in builtin_table.items():
            table[id(safe)] = safe
            real = getattr(builtins, name, None)
            if real is not None:
                table[id(real)] = safe
        for name, safe in math_table.items():
            if callable(safe):
                table[id(safe)] = safe
                table[id(getattr(math, name))] = safe
        symbols = xacro._global_symbols
        for name in ("sorted", "range"):  # deprecated direct forms of python.sorted / python.range
            if name in symbols:
                table[id(dict.__getitem__(symbols, name))] = builtin_table[name]
        namespace = dict.__getitem__(symbols, "xacro")
        for name in ("arg", "tokenize", "dotify", "abs_filename", "message", "warning", "error",
                     "print_location", "fatal"):
            if dict.__contains__(namespace, name):
                helper = dict.__getitem__(namespace, name)
                table[id(helper)] = helper
            if name in symbols:  # the deprecated direct form wraps the same helper
                table[id(dict.__getitem__(symbols, name))] = dict.__getitem__(namespace, name)
        for candidate in (dict.get(namespace, "load_yaml"), symbols.get("load_yaml"), xacro.load_yaml):
            if candidate is not None:
                table[id(candidate)] = self.load_yaml
        table[id(self.load_yaml)] = self.load_yaml
        for name in ("env", "optenv"):
            function = self.subst._eval_dict.get(name)
            if function is not None:
                table[id(function)] = function
        table[id(self.resolve)] = self.resolve
        return table

    # files
    def parse(self, inp: Any, filename: str | None = None) -> Any:
        xacro = self.xacro
        if len(xacro.filestack or []) > MAX_INCLUDE_DEPTH:
            raise XacroError(M("includes are nested more than {count} deep", count=MAX_INCLUDE_DEPTH),
                             hint=M("a file probably includes itself"))
        if inp is None and filename is not None:
            full = os.path.normpath(os.path.join(xacro.root_dir, filename))
            if self.read_roots is None and not os.path.exists(full):
                return self.original[0](inp, filename)  # xacro's own "No such file" error
            # beneath roots, a missing file is the reader's to say: xacro's own parse would open the
            # path again, through a folder swapped for a link out meanwhile
            data = _read_limited(full, self.read_roots)
            check_xml_safe(data, full)
            try:
                text = data.decode("utf-8")
            except UnicodeDecodeError as exc:
                raise XacroError(M("{path} is not UTF-8 text (byte {byte})", path=full, byte=exc.start),
                                 hint=M("save the file as UTF-8")) from None
            self.files.append(full)
            return self.original[0](text, filename)
        if isinstance(inp, (str, bytes)):
            check_xml_safe(inp, filename)
        return self.original[0](inp, filename)

    def load_yaml(self, filename: str) -> Any:
        full = self.xacro.abs_filename_spec(filename)
        if not _inside(full, self.yaml_folders):
            raise XacroError(M("refused to load {path}: only YAML files next to the robot description "
                               "or inside the given package folders may be read", path=filename),
                             hint=M("move the file next to your xacro file, or pass its package with --package-path"))
        from ..trust import yaml_gate

        text = _read_limited(full, self.read_roots)
        if self.read_roots is None:
            try:
                yaml_gate.check(text)  # xacro's own loader then reads it: bounded first (aliases, depth, size)
            except yaml_gate.YamlRefused as exc:
                raise self._yaml_refused(filename, exc) from None
            return self.original_load_yaml(filename)
        return self._load_yaml_text(filename, full, text)

    def _yaml_refused(self, filename: str, exc: Any) -> XacroError:
        from ..trust import yaml_gate

        return XacroError(M("{path}: {reason}", path=filename, reason=exc.message),
                          hint=M("load_yaml reads a plain YAML file: no alias repeated thousands of times, "
                                 "no nesting past {most} levels", most=yaml_gate.MAX_DEPTH))

    def _load_yaml_text(self, filename: str, full: str, text: bytes) -> Any:
        """xacro's load_yaml (xacro/__init__.py) on the text the one reader read: the file is never
        opened again by its path, which a folder swapped for a link out could lead elsewhere."""
        import yaml

        from ..trust import yaml_gate

        xacro = self.xacro
        for unit in xacro.ConstructUnits:  # !radians, !degrees... as xacro registers them
            yaml.SafeLoader.add_constructor(unit.value.tag, unit.constructor)
        xacro.filestack.append(full)
        try:
            return xacro.YamlListWrapper.wrap(yaml_gate.load(text, loader=yaml.SafeLoader))
        except yaml_gate.YamlRefused as exc:
            raise self._yaml_refused(filename, exc) from None
        finally:
            xacro.filestack.pop()
            xacro.all_includes.append(full)

    @property
    def original_load_yaml(self) -> Callable[[str], Any]:
        return self.xacro.load_yaml

    def resolve(self, name: str) -> str:
        folder = find_package(name, self.roots)
        if self.read_roots is not None and folder not in self.read_roots:
            self.read_roots += (folder,)  # the package the file names: its files are read beneath it
        return folder

    # expressions
    def _evaluate(self, expression: str, lookup: Callable[[str], Any],
                  inner_lookup: Callable[[str], Any] | None = None) -> Any:
        from .xacro_eval import Evaluator, UnsafeXacroExpression

        try:
            return Evaluator(lookup, self._attribute, self.callables, self.budget, inner_lookup).run(expression)
        except UnsafeXacroExpression as exc:
            error = XacroError(_refused(expression, exc.message), hint=exc.hint)
            error.expression = expression.strip()  # type: ignore[attr-defined]
            raise error from None

    def _attribute(self, value: Any, name: str) -> Any:
        from .xacro_eval import UnsafeXacroExpression

        if isinstance(value, self.xacro.NameSpace):
            try:
                return value[name]
            except KeyError:
                raise NameError(f"name '{name}' is not defined") from None
        if isinstance(value, self.xacro.YamlDictWrapper):
            return value.__getattr__(name)
        raise UnsafeXacroExpression(M("it uses the attribute '.{name}' of a {kind}", name=name,
                                      kind=type(value).__name__),
                                    hint=M("only namespaces (math., python., xacro.) and YAML data have attributes"))

    def safe_eval(self, expr: str, globals_: Any, locals_: Any = None) -> Any:
        table = locals_ if locals_ is not None else globals_
        try:
            return self._evaluate(expr, table.__getitem__)
        except NameError as exc:  # a misspelt property: the closest name in scope, as validate does for links
            missing = getattr(exc, "name", None) or _NOT_DEFINED.search(str(exc))
            name = missing if isinstance(missing, str) else missing.group(1) if missing else ""
            exc.close = _closest(name, _names_in(table))  # type: ignore[attr-defined]
            raise

    def subst_eval(self, s: str, context: dict[str, Any]) -> str:
        subst = self.subst
        if "arg" not in context:
            context["arg"] = {}
        if s.find("__") >= 0:
            raise subst.SubstitutionException("$(eval ...) may not contain double underscore expressions")
        args = context["arg"]

        def arg(name: str) -> Any:
            return subst.convert_value(subst._eval_arg(name, args=args), "auto")

        def dirname() -> str:
            return subst._eval_dirname(context["filename"])

        functions: dict[str, Any] = {k: v for k, v in subst._eval_dict.items() if k != "__builtins__"}
        functions.update(arg=arg, dirname=dirname, find=self.resolve)
        self.callables[id(arg)] = arg
        self.callables[id(dirname)] = dirname

        def builtin(name: str) -> Any:  # Python's own (the safe twin is called in its place)
            if name in BUILTINS and hasattr(builtins, name):
                return getattr(builtins, name)
            return BUILTINS[name]

        def lookup(name: str) -> Any:  # xacro: eval(s, {}, functions-then-args), then the builtins
            if name in functions:
                return functions[name]
            if name in args:
                return subst.convert_value(args[name], "auto")
            return builtin(name)

        return str(self._evaluate(s, lookup, inner_lookup=builtin))

    def eval_all(self, node: Any, macros: Any, symbols: Any) -> Any:
        self.elements += 1
        if self.elements > MAX_ELEMENTS:
            raise XacroError(M("the expansion makes more than {count} elements", count=MAX_ELEMENTS),
                             hint=_SELF_EXPANDING)
        if len(self.xacro.macrostack or []) > MAX_MACRO_DEPTH:
            raise XacroError(M("macros are nested more than {count} deep", count=MAX_MACRO_DEPTH),
                             hint=M("a macro probably calls itself without end"))
        self.budget.spend()
        if self.elements % 64 == 0 and time.monotonic() > self.budget.deadline:
            raise XacroError(M("the expansion takes too long and was stopped"), hint=_SELF_EXPANDING)
        return self.original[2](node, macros, symbols)

    def replace_node(self, node: Any, by: Any, content_only: bool = False) -> Any:
        parent = node.parentNode
        if parent is not None and by is not None:
            if isinstance(by, list):
                incoming = sum(len(b.childNodes) if content_only else 1 for b in by)
            else:
                incoming = len(by.childNodes) if content_only else 1
            if len(parent.childNodes) + incoming > MAX_CHILDREN:
                raise XacroError(M("an element gets more than {count} children", count=MAX_CHILDREN),
                                 hint=_SELF_EXPANDING)
        if time.monotonic() > self.budget.deadline:
            raise XacroError(M("the expansion takes too long and was stopped"), hint=_SELF_EXPANDING)
        return self.original[6](node, by, content_only)

    def install(self) -> None:
        xacro, subst = self.xacro, self.subst
        xacro.parse, xacro.safe_eval, xacro.eval_all = self.parse, self.safe_eval, self.eval_all
        xacro.replace_node = self.replace_node
        subst._eval, subst._eval_find = self.subst_eval, self.resolve
        subst._eval_dict["find"] = self.resolve

    def uninstall(self) -> None:
        xacro, subst = self.xacro, self.subst
        xacro.parse, xacro.safe_eval, xacro.eval_all = self.original[0], self.original[1], self.original[2]
        xacro.replace_node = self.original[6]
        subst._eval, subst._eval_find = self.original[3], self.original[4]
        subst._eval_dict["find"] = self.original[5]
