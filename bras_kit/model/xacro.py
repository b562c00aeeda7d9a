"""Run the real ``xacro`` package without ROS, on files from strangers.

xacro itself is kept (its parser, macros, properties, includes, output), with walls around it:

* every ``${...}`` and ``$(eval ...)`` expression is interpreted by the allow-list evaluator
  of :mod:`bras_kit.model.xacro_eval`, never by Python's ``eval``;
* every file xacro opens (the main file, includes, ``load_yaml``) must be a regular file of at
  most :data:`MAX_FILE_BYTES`, inside the file's own folder or a package folder given by the
  caller, and is first read by :mod:`bras_kit.model.xmlio`, so a DTD or an entity is refused before
  minidom could expand it;
* macro nesting, include nesting, the number of elements processed, the time spent and the
  output size are bounded;
* a file that is not the built-in template is expanded in a child process with CPU, memory
  and wall-clock limits (:mod:`bras_kit.trust.sandbox`), the second wall;
* ``$(find pkg)`` is resolved from package folders given by the caller or the
  ``BRAS_KIT_PACKAGE_PATH`` environment variable (a folder holding packages, a package
  itself, or an install ``share/`` tree), then ``AMENT_PREFIX_PATH`` when ROS is there.
"""

from __future__ import annotations

import builtins
import contextlib
import io
import os
import re
import stat
import threading
import time
from collections.abc import Callable, Iterable, Mapping
from typing import Any

from ..core.errors import BrasKitError, XacroError
from ..core.message import M, Message
from .xacro_eval import BUILTINS
from .xmlio import check_xml_safe

PACKAGE_PATH_ENV = "BRAS_KIT_PACKAGE_PATH"
MAX_FILE_BYTES = 8 << 20  # any one file xacro reads
MAX_OUTPUT_CHARS = 64 << 20
MAX_MACRO_DEPTH = 100
MAX_INCLUDE_DEPTH = 50
MAX_ELEMENTS = 500_000  # elements processed (macro bodies count each time they are expanded)
MAX_CHILDREN = 20_000  # children of one element (minidom inserts in quadratic time)
SANDBOX_CPU_SECONDS = 20
SANDBOX_WALL_SECONDS = 30.0
SANDBOX_MEMORY_BYTES = 1536 << 20

_lock = threading.Lock()
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


def package_roots(extra: Iterable[str] = ()) -> list[str]:
    """Folders to search for packages: the given ones, then BRAS_KIT_PACKAGE_PATH, then AMENT_PREFIX_PATH/share."""
    roots = [os.path.abspath(p) for p in extra]
    for var, suffix in ((PACKAGE_PATH_ENV, ""), ("AMENT_PREFIX_PATH", "share"), ("ROS_PACKAGE_PATH", "")):
        for entry in os.environ.get(var, "").split(os.pathsep):
            if entry:
                roots.append(os.path.join(entry, suffix) if suffix else entry)
    return roots


def find_package(name: str, roots: Iterable[str]) -> str:
    """The folder of package ``name`` under one of ``roots``.

    A folder ``name`` with a ``package.xml`` (or in an install ``share/`` tree) wins; failing
    that, a plain folder named ``name`` is taken, as ``xacro`` does with a package path whose
    packages were copied without their manifest. :func:`packages_used` says which was used.
    """
    searched: list[str] = []
    fallback = None
    for root in roots:
        candidates = [os.path.join(root, name), os.path.join(root, "share", name)]
        if os.path.basename(os.path.normpath(root)) == name:
            candidates.insert(0, root)
        for candidate in candidates:
            searched.append(candidate)
            if not os.path.isdir(candidate):
                continue
            if os.path.isfile(os.path.join(candidate, "package.xml")) \
                    or os.path.basename(os.path.dirname(candidate)) == "share":
                return _remember(name, os.path.abspath(candidate))
            fallback = fallback or os.path.abspath(candidate)
    if fallback is not None:
        return _remember(name, fallback)
    raise XacroError(
        M("$(find {name}): package '{name}' not found", name=name),
        hint=M("pass --package-path DIR (a folder holding {name}/ or an install share/ tree) or set {variable}; "
               "searched: {folders}", name=name, variable=PACKAGE_PATH_ENV, folders=searched) if searched else
        M("pass --package-path DIR (a folder holding {name}/ or an install share/ tree) or set {variable}",
          name=name, variable=PACKAGE_PATH_ENV),
    )


_FOUND: dict[str, str] = {}


def _remember(name: str, folder: str) -> str:
    _FOUND[name] = folder
    return folder


def packages_used() -> dict[str, str]:
    """Every package found so far, name -> folder (``$(find)`` and ``package://``)."""
    return dict(sorted(_FOUND.items()))


def describe_package_folder(name: str, folder: str) -> Message:
    """``name -> folder``, saying when the folder was taken by its name alone (no package.xml)."""
    if os.path.isfile(os.path.join(folder, "package.xml")) or os.path.basename(os.path.dirname(folder)) == "share":
        return M("package '{name}': {folder}", name=name, folder=folder)
    return M("package '{name}': {folder} (no package.xml: found by its folder name)", name=name, folder=folder)


def _locate(path: str, message: str, extra: Iterable[str] = ()) -> int | None:
    """Best guess at the line of ``path`` an xacro error is about, from the names it quotes."""
    tokens = list(extra) + re.findall(r"['\"]([^'\"]{1,80})['\"]", message)
    tokens += re.findall(r"\$\{[^}]*\}|\$\([^)]*\)", message)
    tokens += [f"$(arg {name})" for name in re.findall(r"Undefined substitution argument (\S+)", message)]
    tokens += re.findall(r"[\w./-]+\.(?:xacro|urdf|yaml)\b", message)
    paths = [os.path.normpath(t) for t in tokens if "/" in t or t.startswith(".")]
    # an included file is quoted with its full path; the including file holds a relative one
    tokens += paths + [p.split(os.sep, k)[-1] for p in paths for k in range(1, p.count(os.sep) + 1)]
    try:
        lines = _read_limited(path).decode("utf-8", errors="replace").splitlines()
    except (OSError, BrasKitError):
        return None
    for token in tokens:
        for number, text in enumerate(lines, 1):
            if token and token in text:
                return number
    return None


def _inner_error(exc: BaseException) -> BrasKitError | None:
    """The BrasKitError (from our guards) that xacro wrapped in its own exception, if any."""
    seen: set[int] = set()
    current: BaseException | None = exc
    while current is not None and id(current) not in seen:
        seen.add(id(current))
        if isinstance(current, BrasKitError):
            return current
        inner = getattr(current, "exc", None)
        current = inner if isinstance(inner, BaseException) else (current.__cause__ or current.__context__)
    return None


_MISSING_FILE = re.compile(r"No such file or directory: (\S+)")


def expand_xacro(
    path: str | os.PathLike[str],
    mappings: Mapping[str, str] | None = None,
    package_paths: Iterable[str] = (),
    *,
    sandbox: bool | None = None,
) -> str:
    """Expand a xacro file to URDF text with the real xacro package, behind the walls above.

    ``mappings`` are xacro args (``name:=value`` on xacro's command line). Errors become a
    :class:`XacroError` naming the file, the best-guess line and what to do. ``sandbox``
    (default: every file but the built-in template) runs the expansion in a limited child.
    """
    path = os.fspath(path)
    if not os.path.exists(path):
        raise BrasKitError(M("no such file: {path}", path=path), hint=M("check the path and spelling"))
    check_readable_file(path)
    if sandbox is None:
        sandbox = not _is_builtin_template(path)
    if sandbox:
        from ..trust.sandbox import run_limited

        text, found = run_limited(_expand_and_report, path, dict(mappings or {}), tuple(package_paths),
                                  cpu_seconds=SANDBOX_CPU_SECONDS, memory_bytes=SANDBOX_MEMORY_BYTES,
                                  wall_seconds=SANDBOX_WALL_SECONDS, what=f"expanding {path}")
        _FOUND.update(found)  # the child found the packages: remember them here, for --verbose
        return text
    return _expand(path, dict(mappings or {}), tuple(package_paths))


def _expand_and_report(path: str, mappings: Mapping[str, str],
                       package_paths: tuple[str, ...]) -> tuple[str, dict[str, str]]:
    return _expand(path, mappings, package_paths), dict(_FOUND)


def _is_builtin_template(path: str) -> bool:
    from ..core.resources import robot_template

    try:
        return os.path.samefile(path, robot_template())
    except OSError:
        return False


_FORBIDDEN_TREES = ("/proc", "/sys", "/dev")
# the folder in memory where bras-kit builds a package to evaluate it (scratch.IN_MEMORY): its
# regular files are files like any other (a device there is refused below, as anywhere)
_SHARED_MEMORY = "/dev/shm"


def check_readable_file(path: str) -> None:
    """Raise unless ``path`` is a regular file of at most :data:`MAX_FILE_BYTES` outside /proc, /sys,
    /dev (its /dev/shm folder in memory excepted)."""
    real = os.path.realpath(path)
    system = any(real == tree or real.startswith(tree + os.sep) for tree in _FORBIDDEN_TREES)
    if system and not real.startswith(_SHARED_MEMORY + os.sep):
        raise XacroError(M("refused to read {path}: it is a system file, not a robot description", path=path),
                         hint=M("include only files of your robot's packages"))
    try:
        info = os.stat(path)
    except OSError as exc:
        raise BrasKitError(M("cannot read {path}: {reason}", path=path, reason=exc.strerror)) from None
    if stat.S_ISDIR(info.st_mode):
        raise BrasKitError(M("{path} is a folder, not a file", path=path))
    if not stat.S_ISREG(info.st_mode):
        raise XacroError(M("refused to read {path}: it is not a regular file (a device, pipe or socket)", path=path),
                         hint=M("give the path of a .xacro, .urdf or .yaml file"))
    if info.st_size > MAX_FILE_BYTES:
        raise XacroError(M("refused to read {path}: {size} bytes is more than the {limit} MiB a robot "
                           "description file may have", path=path, size=info.st_size, limit=MAX_FILE_BYTES >> 20))


def _read_limited(path: str) -> bytes:
    """The bytes of a checked regular file, never blocking on a pipe swapped in meanwhile."""
    check_readable_file(path)
    fd = os.open(path, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0))
    try:
        if not stat.S_ISREG(os.fstat(fd).st_mode):
            raise XacroError(M("refused to read {path}: it is not a regular file", path=path))
        data = b""
        while len(data) <= MAX_FILE_BYTES:
            chunk = os.read(fd, 1 << 20)
            if not chunk:
                return data
            data += chunk
        raise XacroError(M("refused to read {path}: more than {limit} MiB", path=path, limit=MAX_FILE_BYTES >> 20))
    finally:
        os.close(fd)


def _inside(path: str, folders: Iterable[str]) -> bool:
    real = os.path.realpath(path)
    return any(real == f or real.startswith(f.rstrip(os.sep) + os.sep) for f in folders)


class _Hooks:
    """The replacements put into xacro for one expansion, and what they share."""

    def __init__(self, xacro: Any, subst: Any, path: str, roots: list[str]) -> None:
        from .xacro_eval import BUILTINS, MATH, Budget

        self.xacro, self.subst, self.roots = xacro, subst, roots
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
            if not os.path.exists(full):
                return self.original[0](inp, filename)  # xacro's own "No such file" error
            data = _read_limited(full)
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

        text = _read_limited(full)
        try:
            yaml_gate.check(text)  # xacro's own loader then reads it: bounded first (aliases, depth, size)
        except yaml_gate.YamlRefused as exc:
            raise XacroError(M("{path}: {reason}", path=filename, reason=exc.message),
                             hint=M("load_yaml reads a plain YAML file: no alias repeated thousands of times, "
                                    "no nesting past {most} levels", most=yaml_gate.MAX_DEPTH)) from None
        return self.original_load_yaml(filename)

    @property
    def original_load_yaml(self) -> Callable[[str], Any]:
        return self.xacro.load_yaml

    def resolve(self, name: str) -> str:
        return find_package(name, self.roots)

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


def _expand(path: str, mappings: Mapping[str, str], package_paths: tuple[str, ...]) -> str:
    import xacro
    import xacro.substitution_args as subst

    hooks = _Hooks(xacro, subst, path, package_roots(package_paths))
    stderr = io.StringIO()
    arguments = _Arguments(mappings)
    with _lock:
        hooks.install()
        try:
            with contextlib.redirect_stderr(stderr):
                doc = xacro.process_file(path, mappings=arguments, verbosity=0)
                arguments.check(path)
                text = doc.toprettyxml(indent="  ")
            if len(text) > MAX_OUTPUT_CHARS:
                raise XacroError(M("the expanded URDF has {count} characters, more than {limit} Mi allowed",
                                   count=len(text), limit=MAX_OUTPUT_CHARS >> 20), path=path)
            return str(text)
        except BrasKitError:
            raise
        except Exception as exc:  # xacro raises many kinds; all become one clean error
            raise _clean_error(xacro, path, exc, hooks.files) from None
        finally:
            hooks.uninstall()
            xacro.init_stacks(None)


class _Arguments(dict[str, str]):
    """The ``name:=value`` arguments as xacro reads them, remembering which names the files ask
    about: ``<xacro:arg name=...>`` tests ``name in args`` and ``$(arg name)`` reads
    ``args[name]`` (xacro/__init__.py, ``eval_all`` and ``substitution_args_context``). A name
    given on the command line that no file asks about is a typo: xacro ignores it without a word,
    and the learner wonders why the arm did not change."""

    def __init__(self, given: Mapping[str, str]) -> None:
        super().__init__(given)
        self.given = tuple(given)
        self.asked: set[str] = set()

    def __contains__(self, name: object) -> bool:
        if isinstance(name, str):
            self.asked.add(name)
        return super().__contains__(name)

    def __getitem__(self, name: str) -> str:
        self.asked.add(name)
        return super().__getitem__(name)

    def check(self, path: str) -> None:
        import difflib

        from ..core.errors import ParameterError

        for name in self.given:
            if name in self.asked:
                continue
            declared = sorted(n for n in self.asked if n not in self.given or n == name)
            close = difflib.get_close_matches(name, declared, n=1, cutoff=0.6)
            valid = (M("the arguments it declares: {names}", names=", ".join(declared)) if declared
                     else M("this file declares no <xacro:arg>"))
            raise ParameterError(
                M("unknown xacro argument '{name}': {path} declares no <xacro:arg name=\"{name}\">", name=name,
                  path=path),
                hint=M("did you mean {close}? {valid}", close=close[0], valid=valid) if close else valid)


_EVALUATING = re.compile(r"when evaluating expression '(.*)'\s*$", re.S)
_ESCAPES = (("&", "&amp;"), ("<", "&lt;"), (">", "&gt;"), ('"', "&quot;"), ("'", "&apos;"))


def _chain(xacro: Any, exc: BaseException) -> tuple[BaseException, list[str]]:
    """The root cause of a chain of xacro exceptions and the expressions it went through, innermost first."""
    expressions: list[str] = []
    current: BaseException = exc
    seen: set[int] = set()
    while id(current) not in seen:
        seen.add(id(current))
        suffix = getattr(current, "suffix", None)
        if isinstance(suffix, str):
            found = _EVALUATING.search(suffix.strip())
            if found:
                expressions.append(found.group(1))
        inner = getattr(current, "exc", None)
        if not isinstance(inner, BaseException):
            break
        current = inner
    return current, expressions[::-1]


def _escaped(text: str) -> list[str]:
    forms = [text]
    for plain, escape in _ESCAPES:
        forms += [form.replace(plain, escape) for form in forms if plain in form]
    return forms


def find_expression(expression: str, files: Iterable[str]) -> tuple[str, int] | None:
    """The first file and line (in ``files`` order) where ``${expression}`` or ``$(eval expression)`` is written."""
    expression = expression.strip()
    tokens = [wrap.format(form) for form in _escaped(expression) for wrap in ("${{{}}}", "$(eval {})")]
    for path in dict.fromkeys(files):
        try:
            text = _read_limited(path).decode("utf-8", errors="replace")
        except (OSError, BrasKitError):
            continue
        for token in tokens:
            at = text.find(token)
            if at >= 0:
                return path, text.count("\n", 0, at) + 1
    return None


def _clean_error(xacro: Any, path: str, exc: BaseException, files: Iterable[str] = ()) -> BrasKitError:
    where = _current_file(xacro, path)
    files = [where, *files, path]
    inner = _inner_error(exc)
    if inner is not None:  # one of our walls, possibly wrapped by xacro: report it alone
        expression = getattr(inner, "expression", "")
        if inner.path is None:
            found = find_expression(expression, files) if expression else None
            inner.path, inner.line = found or (where, inner.line or _locate(where, str(inner.message)))
        return inner
    root, expressions = _chain(xacro, exc)
    if isinstance(root, RecursionError):
        return XacroError(M("the file nests too deeply (macros, properties or elements)"), path=where,
                          hint=M("a macro or property probably refers to itself"))
    if isinstance(root, MemoryError):
        return XacroError(M("the expansion ran out of memory"), path=where, hint=M("simplify the file"))
    close = getattr(root, "close", None)  # safe_eval's guess at a misspelt name
    if expressions:  # root cause first, where its expression is written; then what used it
        cause = _one_line(str(root) or type(root).__name__)
        if not isinstance(root, xacro.XacroException) and type(root).__name__ not in cause:
            cause = f"{type(root).__name__}: {cause}"
        found = find_expression(expressions[0], files)
        message = M("{cause} in the expression '{expression}'", cause=cause, expression=expressions[0])
        if len(expressions) > 1:
            message = M("{message} (used by {expressions})", message=message, expressions=expressions[1:])
        at, line = found or (where, None)
        hint = _hint_for(cause)
        if close:
            hint = M("did you mean '{close}'? Otherwise, {hint}", close=close, hint=hint)
        error = XacroError(message, path=at, line=line, hint=hint)
        error.close = close  # type: ignore[attr-defined]  # validate's BK102 names it too
        return error
    text = _one_line(str(exc) or type(exc).__name__)
    missing = _MISSING_FILE.search(text)
    if missing:
        return XacroError(M("cannot include {path}: no such file", path=missing.group(1).rstrip(":")), path=where,
                          line=_locate(where, text), hint=_hint_for("no such file"))
    line = getattr(exc, "lineno", None) or _locate(where, text)
    return XacroError(M("xacro failed: {error}", error=text), path=where, line=line, hint=_hint_for(text))


def _one_line(text: str) -> str:
    text = " ".join(text.split())
    return text if len(text) <= 500 else text[:500] + "..."


def _current_file(xacro_module, default: str) -> str:
    stack = [f for f in (xacro_module.filestack or []) if f]
    return os.path.normpath(stack[-1]) if stack else default


_NOT_DEFINED = re.compile(r"name '([^']*)' is not defined")


def _names_in(table: Any) -> list[str]:
    """Every name an expression can read in ``table``: its properties, its parents' (macro
    parameters over the file's properties), then xacro's globals (math, the namespaces)."""
    names: list[str] = []
    seen: set[int] = set()
    while isinstance(table, dict) and id(table) not in seen:
        seen.add(id(table))
        names += [n for n in dict.keys(table) if isinstance(n, str) and not n.startswith("_")]
        table = getattr(table, "parent", None)
    return names


def _closest(name: str, names: Iterable[str]) -> str | None:
    import difflib

    close = difflib.get_close_matches(name, list(dict.fromkeys(names)), n=1, cutoff=0.6) if name else []
    return close[0] if close else None


def _hint_for(message: str) -> Message:
    if "Undefined substitution argument" in message or "arg" in message.lower() and "undefined" in message.lower():
        return M("pass the argument as name:=value, or give it a default with <xacro:arg name=... default=...>")
    if "Undefined property" in message or "name '" in message and "is not defined" in message:
        return M("define the property with <xacro:property name=... value=...> before using it")
    if "no such file" in message.lower():
        return M("check the path of the included file (relative paths start from the including file)")
    if "not well-formed" in message or "mismatched tag" in message:
        return M("check the XML on this line is closed and quoted properly")
    return M("check the xacro syntax on this line")
