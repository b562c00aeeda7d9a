"""The validator: URDF defects and the tutorial's pitfalls, as findings with codes and hints.

::

    from bras_kit.validate import validate, validate_path
    findings = validate(robot, pose={"coude": 2.5})
    print(findings[0].text("fr"))           # findings are data, worded where shown
    findings = validate_path("bras.urdf")   # .urdf or .xacro; unreadable files give BK100-BK103

Every rule lives in the registry (:data:`RULES`), one module per family: :mod:`.structure`
(BK1xx), :mod:`.joints` (BK2xx), :mod:`.pitfalls` (BK3xx), :mod:`.geometry` (BK4xx),
:mod:`.inertia` (BK5xx), :mod:`.package` (BK6xx, a whole ROS 2 package).
Each rule's English texts are registered beside the rules (modules ``texts``); the French is in
``locale/fr/LC_MESSAGES/validate.po``. Findings are data, worded where shown
(:meth:`Finding.text`, :func:`bras_kit.findings.report.format_text`).
"""

from __future__ import annotations

import contextlib
import dataclasses
import gc
import os
import re
from collections.abc import Iterable, Iterator, Mapping, Sequence
from typing import Any

from ..core.errors import BrasKitError, ParameterError, XacroError, XMLSafetyError, XMLSyntaxError
from ..core.i18n import LANGUAGES, resolve_language
from ..core.message import M, Message, Mn
from ..core.wording import quoted
from ..findings.data import UNREADABLE_CODES, FileResult, Finding, finding, sort_key
from ..findings.registry import ERROR, INFO, RULES, WARNING, Hit, Rule, run_rules, select_rules
from ..model.robot import Robot
from . import (  # noqa: F401  (importing registers the rules)
    gazebo,
    gazebo_texts,
    geometry,
    inertia,
    joints,
    live,
    live_texts,
    package,
    pitfalls,
    slips,
    slips_texts,
    structure,
    texts,
)
from .context import Context

__all__ = [
    "ERROR", "INFO", "LANGUAGES", "RULES", "UNREADABLE_CODES", "WARNING", "FileResult", "Finding",
    "Rule", "check_robot", "collect_files", "compare_generated", "default_language", "found_in", "generated_pairs",
    "validate", "validate_path",
]

SOURCE_SUFFIXES = (".urdf", ".xacro")


def default_language(environ: Mapping[str, str] | None = None) -> str:
    """``BRAS_KIT_LANG``, else ``fr`` when the locale says French, else ``en``."""
    return resolve_language(None, environ)


def validate(
    robot: Robot,
    *,
    pose: Mapping[str, float] | None = None,
    states: Any = None,
    lang: str | None = None,
    package_paths: Sequence[str] = (),
    select: Iterable[str] = (),
    ignore: Iterable[str] = (),
    target: str | None = None,
) -> list[Finding]:
    """Check a robot model; return its findings sorted by line.

    ``pose`` (joint -> value) is checked against the limits (BK303); ``states`` (a
    :class:`bras_kit.motion.JointStates`) against limits and velocities (BK304, BK305).
    A pose or states naming a joint the robot cannot move is a :class:`ParameterError`.
    ``select``/``ignore`` are code prefixes (``BK3``, ``BK301``). ``target="gazebo"`` says the robot
    is heading for Gazebo: the BK7xx rules take their severities from
    :data:`bras_kit.validate.gazebo.TARGET_SEVERITY` (refusals and lost parts become errors).
    Findings hold no words: show
    them with :meth:`Finding.text` / :meth:`Finding.hint_text` in the language of the place
    (``lang`` is accepted for older callers and has no effect).
    """
    context = Context(robot, pose=pose, states=states, package_paths=tuple(package_paths), target=target)
    _check_joint_names(context, pose, "--pose")
    if states is not None:
        _check_joint_names(context, dict.fromkeys(states.names, 0.0), "the motion")
    rules = _rules(select, ignore)
    findings = [finding(r, found) for r, found in run_rules(rules, context)]
    if target is not None:
        findings = _for_target(findings, target)
    return sorted(findings, key=sort_key)


def _for_target(findings: list[Finding], target: str) -> list[Finding]:
    if target not in gazebo.TARGET_SEVERITY:
        raise ParameterError(M("unknown target '{target}'", target=target),
                             hint=M("the targets are: {targets}", targets=", ".join(gazebo.TARGETS)))
    severities = gazebo.TARGET_SEVERITY[target]
    return [dataclasses.replace(f, severity=severities.get(f.code, f.severity)) for f in findings]


def validate_path(
    path: str | os.PathLike[str],
    *,
    pose: Mapping[str, float] | None = None,
    motion: Sequence[str] | None = None,
    duration: float | None = None,
    lang: str | None = None,
    package_paths: Sequence[str] = (),
    mappings: Mapping[str, str] | None = None,
    select: Iterable[str] = (),
    ignore: Iterable[str] = (),
    target: str | None = None,
    roots: Sequence[str] | None = None,
) -> list[Finding]:
    """Load a ``.urdf`` or ``.xacro`` file and check it (``target``: see :func:`validate`).
    ``roots``: the folders a file found in a folder (a submission, ``validate DIR``) is read
    beneath, with its includes and meshes (:func:`found_in`); None for a file named itself.

    A file that cannot be read at all (missing, not well-formed, unsafe XML, xacro failure)
    gives a single finding BK100-BK103 instead of raising; ``bras-kit validate`` exits 2 on
    those. ``motion`` specs (``"tutorial"``, ``"coude=1.2*sin(0.7*t)"``, a waypoint file) are
    sampled at 20 Hz for ``duration`` seconds and checked like ``states``. Only a bad ``pose``
    or ``motion`` raises (:class:`~bras_kit.core.errors.ParameterError`).
    """
    path = os.fspath(path)
    with _collector_paused():
        robot_or_failure = load_for_validation(path, mappings=mappings, package_paths=package_paths, roots=roots)
        if isinstance(robot_or_failure, Finding):
            return [robot_or_failure]
        robot = robot_or_failure
        if path.endswith(".xacro") and not robot.links and robot.root_tag == "robot" \
                and _defines_macros(path):
            chosen = any(r.code == "BK124" for r in _rules(select, ignore))
            return [_loader_finding("BK124", Hit("robot", robot.name, None))] if chosen else []
        states = motion_states(robot, motion, duration) if motion else None
        findings = validate(robot, pose=pose, states=states, package_paths=package_paths,
                            select=select, ignore=ignore, target=target)
    if path.endswith(".xacro"):
        findings = _lines_in_xacro_source(path, findings)
    return findings


def check_robot(robot: Robot, *, motion: Sequence[str] | None = None, duration: float | None = None,
                **options: Any) -> FileResult:
    """An already loaded robot (the built-in arm) checked like a file, as a :class:`FileResult`."""
    states = motion_states(robot, motion, duration) if motion else None
    return FileResult(robot.path or "<robot>", validate(robot, states=states, **options))


@contextlib.contextmanager
def _collector_paused() -> Iterator[None]:
    """Pause Python's cyclic garbage collector while a file is read and checked.

    A 10,000-link URDF makes some 200,000 small objects and no reference cycles; the collector
    would scan them again and again for nothing (about half the load time).
    """
    enabled = gc.isenabled()
    gc.disable()
    try:
        yield
    finally:
        if enabled:
            gc.enable()


# ---------------------------------------------------------------- files


def collect_files(paths: Iterable[str]) -> list[str]:
    """The files to check: files as given, folders searched recursively for *.urdf and *.xacro
    (hidden folders skipped, sorted). A path that does not exist is kept: it becomes BK103."""
    out: list[str] = []
    for path in paths:
        if not os.path.isdir(path):
            out.append(path)
            continue
        from ..trust.learner_files import walk

        # through the one reader (links to folders never walked into), as every folder walk is
        for folder, dirs, files in walk(path, (path,)):
            dirs[:] = sorted(d for d in dirs if not d.startswith("."))
            out.extend(os.path.join(folder, f) for f in sorted(files) if f.endswith(SOURCE_SUFFIXES))
    return out


def found_in(path: str, given: Iterable[str]) -> tuple[str, ...] | None:
    """The folder of ``given`` that ``path`` was found in by :func:`collect_files` (its files,
    includes and meshes are then read beneath it, never through a link out), or None for a path
    given itself."""
    full = os.path.abspath(path)
    for folder in given:
        top = os.path.abspath(folder)
        if full != top and os.path.isdir(top) and full.startswith(top.rstrip(os.sep) + os.sep):
            return (top,)
    return None


def generated_pairs(paths: Sequence[str], given: Iterable[str]) -> dict[str, str]:
    """``{urdf: xacro}`` for each ``X.urdf`` found in a folder beside ``X.urdf.xacro`` (or ``X.xacro``).

    Files named explicitly in ``given`` are always checked themselves.
    """
    named = {os.path.abspath(p) for p in given if not os.path.isdir(p)}
    present = {os.path.abspath(p) for p in paths}
    pairs = {}
    for path in paths:
        full = os.path.abspath(path)
        if not path.endswith(".urdf") or full in named:
            continue
        for candidate in (full + ".xacro", full[: -len(".urdf")] + ".xacro"):
            if candidate in present:
                pairs[path] = next(p for p in paths if os.path.abspath(p) == candidate)
                break
    return pairs


def compare_generated(urdf: str, xacro: str, *, mappings: Mapping[str, str] | None = None,
                      package_paths: Sequence[str] = (), lang: str | None = None,
                      select: Iterable[str] = (), ignore: Iterable[str] = ()) -> list[Finding]:
    """BK126 (the URDF matches a fresh expansion of its xacro) or BK127 (it does not)."""
    chosen = {rule.code for rule in _rules(select, ignore)}
    if not chosen & {"BK126", "BK127"}:
        return []
    from ..model.xacro import expand_xacro
    from ..model.xmlio import parse_xml, read_bytes

    try:
        expected = parse_xml(expand_xacro(xacro, mappings, package_paths), xacro)
        actual = parse_xml(read_bytes(urdf), urdf)
    except BrasKitError:
        return []  # the xacro's own check (or the URDF's) reports why it cannot be read
    difference = _tree_difference(actual, expected)
    params = {"xacro": xacro, "urdf": urdf, "difference": difference or ""}
    code = "BK126" if difference is None else "BK127"
    return [finding(RULES[code], Hit("file", None, None, params))] if code in chosen else []


def _tree_difference(a: Any, b: Any, where: str = "") -> Message | None:
    """The first difference between two XML trees (tags, attributes, numbers to 1e-9), or None."""
    here = f"{where}/{a.tag}" + (f"[@name='{a.get('name')}']" if a.get("name") else "")
    if a.tag != b.tag:
        return M("{where}: <{tag}> where the xacro file gives <{expected}>", where=here, tag=a.tag, expected=b.tag)
    if set(a.attrib) != set(b.attrib):
        return M("{where}: attributes {names} where the xacro file gives {expected}", where=here,
                 names=" ".join(sorted(a.attrib)) or "-", expected=" ".join(sorted(b.attrib)) or "-")
    for key, value in a.attrib.items():
        if not _same_value(value, b.attrib[key]):
            return M("{where} {key}=\"{value}\" where the xacro file gives \"{expected}\"", where=here, key=key,
                     value=value, expected=b.attrib[key])
    if len(a.children) != len(b.children):
        return Mn("{where}: {n} child element where the xacro file gives {expected}",
                  "{where}: {n} child elements where the xacro file gives {expected}", len(a.children),
                  where=here, expected=len(b.children))
    for x, y in zip(a.children, b.children):
        found = _tree_difference(x, y, here)
        if found:
            return found
    return None


def _same_value(x: str, y: str) -> bool:
    if x == y:
        return True
    try:
        xs, ys = [float(v) for v in x.split()], [float(v) for v in y.split()]
    except ValueError:
        return " ".join(x.split()) == " ".join(y.split())
    return len(xs) == len(ys) and all(abs(u - v) <= 1e-9 * max(1.0, abs(u), abs(v)) for u, v in zip(xs, ys))


def load_for_validation(path: str, *, mappings: Mapping[str, str] | None = None,
                        package_paths: Sequence[str] = (), lang: str | None = None,
                        roots: Sequence[str] | None = None) -> Robot | Finding:
    """The robot in ``path``, or the finding (BK100-BK103) saying why it cannot be read."""
    from ..model.authoring import load

    if path == "-":  # standard input: bras-kit urdf | bras-kit validate -
        pass
    elif os.path.isdir(path):
        return _loader_finding("BK103", Hit("file", None, None, {"path": path}, "folder"))
    elif not os.path.exists(path):
        return _loader_finding("BK103", _missing_file(path))
    try:
        return load(path, mappings=mappings, package_paths=package_paths, roots=roots)
    except BrasKitError as exc:
        return _unreadable(path, exc)


def _missing_file(path: str) -> Hit:
    """BK103 for a path that does not exist: a Windows-style path, or a near name in the same folder."""
    if "\\" in path:
        fixed = path.replace("\\", "/")
        return Hit("file", None, None, {"path": path, "suggestion": fixed}, "windows")
    import difflib

    folder = os.path.dirname(path) or "."
    from ..trust.learner_files import list_folder

    try:
        names = [n for n, _kind in list_folder(folder, (folder,)) if n.endswith(SOURCE_SUFFIXES)]
    except OSError:
        names = []
    close = difflib.get_close_matches(os.path.basename(path), names, n=1, cutoff=0.6)
    if close:
        return Hit("file", None, None, {"path": path, "suggestion": os.path.join(os.path.dirname(path), close[0])},
                   "near")
    return Hit("file", None, None, {"path": path}, "missing")


def _unreadable(path: str, exc: BrasKitError) -> Finding:
    other = exc.path if exc.path and os.path.abspath(exc.path) != os.path.abspath(path) else None
    where = f"{other}:{exc.line}: " if other and exc.line else (f"{other}: " if other else "")
    line = None if other else exc.line
    if isinstance(exc, XMLSafetyError):
        variant = {"attlist": "dtd"}.get(exc.kind, exc.kind)
        hit = Hit("file", None, line, {"where": f" ({where.rstrip(': ')})" if where else ""}, variant)
        return _loader_finding("BK101", hit)
    if isinstance(exc, XMLSyntaxError):
        encoding = _encoding_problem(exc.path or path)
        if encoding is not None:
            at, byte, guess = encoding
            return _loader_finding("BK100", Hit("file", None, at, {"at": at, "byte": byte, "guess": guess},
                                                "encoding"))
        swallowed = _swallowing_comment(exc.path or path, exc.line)
        if swallowed is not None:
            variant = "comment" if swallowed["end_line"] else "comment_unclosed"  # no '-->' after it
            return _loader_finding("BK100", Hit("file", None, int(swallowed["line"]), swallowed, variant))
        detail: Any = exc.detail if exc.detail is not None else exc.message
        if where:
            detail = M("{where}{detail}", where=where, detail=detail)
        if exc.fix is not None:  # a character pasted from elsewhere: named, with its own fix
            return _loader_finding("BK100", Hit("file", None, line, {"detail": detail, "fix": exc.fix}, "pasted"))
        return _loader_finding("BK100", Hit("file", None, line, {"detail": detail}))
    if isinstance(exc, XacroError):
        english = str(exc.message).removeprefix("xacro failed: ")
        # the words stay a message (worded in the finding's language); xacro's own English, when
        # that is all there is, is quoted after the rule's sentence
        said: Any = exc.message
        if isinstance(said, Message) and said.id == "xacro failed: {error}":
            said = quoted(str(said.params.get("error", english)))
        if where:
            said = M("{where}{detail}", where=where, detail=said)
        kind, params = _xacro_kind(english), {"detail": said}
        close = getattr(exc, "close", None)  # the name in scope closest to a misspelt property
        if kind == "property" and close:
            kind, params = "property_close", {"detail": said, "close": close}
        return _loader_finding("BK102", Hit("file", None, line, params, kind))
    return _loader_finding("BK103", Hit("file", None, line, {"path": path, "detail": exc.message}))


def _read_own_bytes(path: str, limit: int | None = None) -> bytes | None:
    """The file's bytes through the one reader (beneath its own folder: never a link out of it,
    a pipe or a device), or None when it cannot be read (the validator says why elsewhere)."""
    from ..trust.learner_files import MAX_BYTES, read_bytes

    folder = os.path.dirname(os.path.abspath(path))
    try:
        return read_bytes(path, (folder,), limit=limit or MAX_BYTES)
    except OSError:  # Unreadable is an OSError too
        return None


def _read_own(path: str, limit: int | None = None) -> str | None:
    data = _read_own_bytes(path, limit)
    return None if data is None else data.decode("utf-8", errors="replace")


def _swallowing_comment(path: str, error_line: int | None) -> dict[str, Any] | None:
    """A comment closed with '->' that runs on past the line where the XML reader gave up."""
    from .slips import swallowing_comment

    text = _read_own(path, 64 << 20)
    if text is None:
        return None
    found = swallowing_comment(text)
    if found is None or error_line is None:
        return None
    end = int(found["end_line"]) or error_line
    return found if int(found["line"]) <= error_line <= end else None


def _encoding_problem(path: str) -> tuple[int, str, str] | None:
    """(line, byte, the byte read as Latin-1) when ``path`` is not UTF-8 and declares no other encoding: the usual cause of an
    XML error on a line with accents (a file saved as Latin-1 or Windows-1252)."""
    data = _read_own_bytes(path, 64 << 20)
    if data is None:
        return None
    head = data[:200].lower()
    if b"encoding=" in head and b"utf-8" not in head:
        return None
    try:
        data.decode("utf-8")
    except UnicodeDecodeError as exc:
        line = data[:exc.start].count(b"\n") + 1
        guess = data[exc.start:exc.start + 1].decode("latin-1")
        return line, f"0x{data[exc.start]:02x}", guess
    return None


def _xacro_kind(message: str) -> str:
    lowered = message.lower()
    if lowered.startswith("refused the expression") or "cannot read the expression" in lowered:
        return "unsafe"
    if "$(find" in message:
        return "package"
    if "substitution arg" in lowered or ("arg" in lowered and "undefined" in lowered):
        return "arg"
    if "undefined property" in lowered or "is not defined" in lowered:
        return "property"
    if "no such file" in lowered:
        return "include"
    if "not well-formed" in lowered or "mismatched tag" in lowered:
        return "xml"
    return ""


def _loader_finding(code: str, found: Hit) -> Finding:
    return finding(RULES[code], found)


def _defines_macros(path: str) -> bool:
    text = _read_own(path)
    return text is not None and "<xacro:macro" in text


_NAME = re.compile(r"""<(link|joint|material|robot)\b[^>]*?\bname\s*=\s*["']([^"']*)["']""")


def _lines_in_xacro_source(path: str, findings: list[Finding]) -> list[Finding]:
    """Point findings at the xacro source rather than the expanded text: the line of the
    element with that name when the name is written literally once; otherwise no line."""
    text = _read_own(path)
    if text is None:
        return [dataclasses.replace(f, line=None) for f in findings]
    lines: dict[tuple[str, str], int | None] = {}
    for match in _NAME.finditer(text):
        key = (match.group(1), match.group(2))
        lines[key] = None if key in lines else text.count("\n", 0, match.start()) + 1
    return [dataclasses.replace(f, line=lines.get((f.element, f.name or ""))) for f in findings]


# ---------------------------------------------------------------- pose and motion


def _check_joint_names(context: Context, values: Mapping[str, float] | None, source: str) -> None:
    for name in values or {}:
        joint = context.joints.get(name)
        movable = [j.name for j in context.robot.movable_joints() if j.name]
        hint = M("movable joints: {names}", names=", ".join(movable)) if movable else M("this robot has no movable joint")
        where = context.robot.path
        if joint is None:
            raise ParameterError(M("{source} names joint '{name}', which this robot does not have",
                                   source=source, name=name), path=where, hint=hint)
        if not joint.movable:
            if joint.mimic is not None:
                raise ParameterError(M("{source} sets joint '{name}', which follows '{leader}' and cannot be set",
                                       source=source, name=name, leader=joint.mimic.joint), path=where, hint=hint)
            raise ParameterError(M("{source} sets joint '{name}', which is {type} and cannot be set",
                                   source=source, name=name, type=joint.type), path=where, hint=hint)


def motion_states(robot: Robot, specs: Sequence[str] | None, duration: float | None = None) -> Any:
    """Sample the motion given by ``specs`` (see :func:`bras_kit.motion.motion_from_specs`).

    Returns None when the robot's links do not form a tree (the structure rules say why).
    """
    from ..core.errors import ModelError
    from ..motion import motion_from_specs, sample

    try:
        return sample(motion_from_specs(robot, list(specs or [])), duration=duration)
    except ModelError:
        return None
    except ParameterError as exc:
        exc.path = exc.path or robot.path
        raise


def _rules(select: Iterable[str], ignore: Iterable[str]) -> list[Rule]:
    try:
        return select_rules(select, ignore)
    except ValueError as exc:
        raise ParameterError(M("no rule code starts with '{prefix}'", prefix=str(exc)),
                             hint=M("codes look like BK301; families are BK1 to BK7 (bras-kit explain lists them)")) from None
