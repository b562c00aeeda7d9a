"""Grading one submission, in a worker process (a local pool or a Dask worker).

Reading and checking the learner's files happens in a child process under CPU, memory and
wall-time limits (:func:`bras_kit.trust.sandbox.run_limited`): a hostile or enormous submission
costs at most those limits and scores zero, and the batch goes on. The picture is drawn in
the worker itself, which keeps pyrender and its OpenGL libraries loaded from one learner to
the next (only the first submission of each worker pays for them).
"""

from __future__ import annotations

import os
import shutil
import tempfile
import time
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..core.errors import BrasKitError
from ..core.i18n import say, say_error
from ..core.message import M, Message
from .exercises import exercises_passed
from .rubric import SEVERITIES, Item, Rubric
from .submissions import MAX_SUBMISSION_BYTES, Submission, SubmissionError, content_hash, unpack

CHECK_CPU_SECONDS = 20
CHECK_WALL_SECONDS = 40.0
CHECK_MEMORY_BYTES = 1536 << 20
# a robot file of a class bras-kit parses and holds (the tutorial's arm: 5 kB, 3 links): a long
# comment is legal, so the size is generous; the links and joints are robot_state_publisher's
# bound (bras_kit.ros.launching.MAX_DESCRIPTION_ELEMENTS)
MAX_ROBOT_FILE_BYTES = 32 << 20
RUN_SECONDS = 10.0  # simulated seconds each node runs with --run-nodes
RUN_CPU_SECONDS = 10
RUN_WALL_SECONDS = 30.0
PICTURE_SIZE = (480, 360)
MAX_DRAWN_LINKS = 500
ANIMATION_SIZE = (320, 240)
ANIMATION_SECONDS = 4.0
ANIMATION_FPS = 10.0
UNREADABLE = ("BK100", "BK101", "BK102", "BK103")


@dataclass(frozen=True)
class Options:
    lang: str = "en"
    pictures: str | None = None  # folder for the PNGs, None: no pictures
    gif: bool = False
    run_nodes: bool = False  # also run each package's nodes (bras-kit run): executes the learner's code
    contain: str = "require"  # how: "require" (contained, else refused), "auto" (--unsafe-run-nodes)


# the folder a grading under way unpacks into: a worker the pool terminates removes it on its way
# out (grade.runner), since its finally block never runs
workdir_in_use: str | None = None


def grade(submission: Submission, rubric: Rubric, options: Options) -> dict[str, Any]:
    """Everything the reports need about one learner, as plain data (JSON-ready)."""
    start = time.monotonic()
    result: dict[str, Any] = {"learner": submission.learner, "path": submission.path,
                              "hash": content_hash(submission.path), "status": "graded", "findings": [],
                              "picture": None, "animation": None, "main_file": None, "package": False}
    global workdir_in_use
    robot = None
    workdir = workdir_in_use = tempfile.mkdtemp(prefix="bras-kit-grade-")
    try:
        root = _materialise(submission, workdir)
        result["exercises"] = exercises_passed(root)
        inspected = _inspect_limited(root, options.lang)
        result.update(findings=inspected["findings"], main_file=inspected["main"], package=inspected["package"])
        if options.run_nodes and inspected["package"]:
            result["findings"] = result["findings"] + _run_nodes(root, options.lang, options.contain)
        robot = inspected["robot"]
        if robot is None:
            result["status"] = "unreadable"
        elif options.pictures and _drawable(robot):  # while an archive's meshes are still unpacked
            paths = (root, os.path.dirname(root)) if os.path.isdir(root) else ()
            result["picture"] = _picture(robot, submission.learner, options, paths)
            if options.gif:
                result["animation"] = _animation(robot, submission.learner, options, paths)
    except BrasKitError as exc:
        result["status"] = "unreadable"
        result["findings"] = [_finding("BK103", "error", say_error(exc, options.lang, with_hint=False).split("\n")[0],
                                       say(exc.hint, options.lang) if exc.hint else "", submission.path)]
    finally:
        shutil.rmtree(workdir, ignore_errors=True)
        workdir_in_use = None
    result["items"] = {item.id: _score(item, robot, result) for item in rubric.items}
    result["score"] = float(sum(result["items"].values()))
    result["max"] = rubric.total
    errors = [f for f in result["findings"] if f["severity"] == "error"]
    result["first_error"] = f"{errors[0]['code']} {errors[0]['message']}" if errors else ""
    result["seconds"] = round(time.monotonic() - start, 3)
    return result


def _materialise(submission: Submission, workdir: str) -> str:
    if submission.kind == "other":
        raise SubmissionError(M("not a robot description: hand in a folder, a .urdf or .xacro file, or a .zip/.tar.gz"),
                              path=submission.path)
    size = _size(submission.path)
    if size > MAX_SUBMISSION_BYTES:
        raise SubmissionError(M("the submission holds {size} MB, more than {most} MB", size=size >> 20,
                                most=MAX_SUBMISSION_BYTES >> 20), path=submission.path, hint=M("hand in the package only"))
    if submission.kind == "archive":
        target = os.path.join(workdir, "unpacked")
        os.makedirs(target)
        unpack(submission.path, target)
        return target
    return submission.path


def _size(path: str) -> int:
    """The submission's bytes, counted through the one reader (links neither followed nor counted)."""
    from ..trust.learner_files import folder_size

    return folder_size(path, (os.path.dirname(os.path.abspath(path)),), stop_past=MAX_SUBMISSION_BYTES)


def node_containment(unsafe: bool = False) -> Message | None:
    """Before ``--run-nodes``: None when the nodes will run contained; else raises
    :class:`~bras_kit.trust.contain.ContainmentUnavailable` (what is missing, how to get it), or
    with ``unsafe`` (``--unsafe-run-nodes``) returns the warning to show."""
    from ..trust.contain import available, containment_required

    status = available()
    if status.ok:
        return None
    if not unsafe:
        try:
            containment_required()
        except BrasKitError as exc:
            exc.hint = M("{how}; or, for code you trust, --unsafe-run-nodes runs it with your rights",
                         how=exc.hint or "-")
            raise
    return M("warning: the nodes run NOT contained (this machine lacks {missing}): they have your rights",
             missing=status.missing)


def _run_nodes(root: str, lang: str, contain: str = "require") -> list[dict[str, Any]]:
    """What the package's launch files and nodes did when run (rules BK630-BK633, BK640-BK659),
    as ``bras-kit validate PKG`` and ``bras-kit run`` find it. Each node runs in its own
    child process under the sandbox's CPU, memory and wall-clock limits (bras_kit.run), contained
    (bras_kit.trust.contain); with ``contain="require"``, a machine that cannot contain them
    raises :class:`~bras_kit.trust.contain.ContainmentUnavailable` (that learner is not graded)."""
    from ..run.findings import package_run_results
    from ..trust.contain import containment_required
    from ..validate.package import find_packages

    if contain == "require":
        containment_required()
    from ..validate.package import validate_package
    from ..validate.package.launch_rules import LAUNCH_CHECKS

    findings: list[dict[str, Any]] = []
    for package in find_packages([root]):
        # built as colcon builds it and launched as ros2 launch does (BK630-BK633): the learner's
        # setup.py and launch files run too, contained as the nodes are
        for result in validate_package(package, select=LAUNCH_CHECKS, launch=True):
            findings += [_as_dict(f, _relative(result.path, root), lang) for f in result.findings]
        for result in package_run_results(package, lang=lang, duration=RUN_SECONDS, cpu_seconds=RUN_CPU_SECONDS,
                                          wall_seconds=RUN_WALL_SECONDS, contain=contain):
            findings += [_as_dict(f, _relative(result.path, root), lang) for f in result.findings]
    return findings


_fork_server: Any = None  # a local pool worker's ForkServer (see start_fork_server)


def start_fork_server() -> None:
    """In a pool worker that has drawn nothing yet: the small process its checks are forked
    from (:class:`bras_kit.trust.sandbox.ForkServer`), holding the modules they use."""
    global _fork_server
    from .. import validate  # noqa: F401  imported before the fork: the checks' children have them
    from ..trust.sandbox import ForkServer
    from ..validate import package  # noqa: F401

    if _fork_server is None:
        import multiprocessing.util

        _fork_server = ForkServer()
        # a pool worker ends through multiprocessing's exit functions, not atexit
        multiprocessing.util.Finalize(_fork_server, _fork_server.close, exitpriority=10)


def _inspect_limited(root: str, lang: str) -> dict[str, Any]:
    from .. import validate  # noqa: F401  imported here, the limited child is forked with them
    from ..trust.sandbox import run_limited
    from ..validate import package  # noqa: F401  (else every submission would pay for importing them)

    run = _fork_server.run if _fork_server is not None else run_limited
    return run(_inspect, root, lang, cpu_seconds=CHECK_CPU_SECONDS,
               memory_bytes=CHECK_MEMORY_BYTES, wall_seconds=CHECK_WALL_SECONDS,
               what=M("checking {name}", name=os.path.basename(root)))


def _inspect(root: str, lang: str) -> dict[str, Any]:
    """In the limited child: the findings of every file (and of the package), and the main robot.
    A submission that is one file is judged from a copy alone in a folder of its own: its folder
    is the class's, and what it includes beside it would be another learner's."""
    if os.path.isdir(root):
        return _inspect_within(root, lang)
    from ..trust import scratch
    from ..trust.learner_files import copy_file

    with scratch.folder("bras-kit-grade-") as alone:
        copy = os.path.join(alone, os.path.basename(root))
        try:
            copy_file(os.path.abspath(root), (os.path.dirname(os.path.abspath(root)),), copy,
                      limit=MAX_ROBOT_FILE_BYTES + 1)
        except OSError:  # a pipe, a device, a link out, too large: judged where it is, as before
            return _inspect_within(root, lang)
        result = _inspect_within(copy, lang)
    # the findings name the learner's own file, not the copy
    here, there = alone + os.sep, os.path.dirname(os.path.abspath(root)) + os.sep
    for finding in result["findings"]:
        for key in ("message", "hint"):
            if isinstance(finding.get(key), str):
                finding[key] = finding[key].replace(here, there)
    return result


def _inspect_within(root: str, lang: str) -> dict[str, Any]:
    from ..model.authoring import load
    from ..validate import collect_files, generated_pairs, validate_path
    from ..validate.package import find_packages, validate_package

    paths = collect_files([root]) if os.path.isdir(root) else [root]
    # every file of a submission is read beneath it (a folder, or the one file's own folder)
    within = (os.path.abspath(root) if os.path.isdir(root) else os.path.dirname(os.path.abspath(root)),)
    pairs = generated_pairs(paths, [root]) if os.path.isdir(root) else {}
    packages = find_packages([root]) if os.path.isdir(root) else []
    findings: list[dict[str, Any]] = []
    for package in packages:
        for result in validate_package(package):
            findings += [_as_dict(f, _relative(result.path, root), lang) for f in result.findings]
    checked = []
    for path in (p for p in paths if p not in pairs):
        size = os.path.getsize(path) if os.path.isfile(path) else 0
        if size > MAX_ROBOT_FILE_BYTES:  # its size, before any parser holds it: the learner's finding
            findings.append(_finding(
                "BK103", "error", say(M("{file} holds {size} MiB, more than the {most} MiB bras-kit reads in a robot "
                                        "file: not read", file=_relative(path, root), size=round(size / (1 << 20), 1),
                                        most=MAX_ROBOT_FILE_BYTES >> 20), lang),
                say(M("hand in the robot's own URDF or xacro file (the tutorial's arm is 5 kB)"), lang),
                _relative(path, root)))
            continue
        many = _too_many_elements(path)
        if many:
            findings.append(_finding(
                "BK103", "error", say(M("{file} declares more than {most} links and joints, more than bras-kit holds "
                                        "in a robot file: not read", file=_relative(path, root), most=many), lang),
                say(M("hand in the robot's own URDF or xacro file (the tutorial's arm has 3 links)"), lang),
                _relative(path, root)))
            continue
        checked.append(path)
    for path in checked:
        findings += [_as_dict(f, _relative(path, root), lang) for f in validate_path(path, roots=within)]
    main = _main_file(checked, root)
    robot = None
    if main is not None and not any(f["code"] in UNREADABLE and f["file"] == _relative(main, root) for f in findings):
        try:
            robot = load(main, roots=within)  # its includes and meshes too: beneath the submission
        except BrasKitError:
            robot = None
    if not paths:
        findings.append(_finding("BK103", "error", "no .urdf or .xacro file in the submission",
                                 "hand in the robot description (urdf/bras.urdf or urdf/bras.urdf.xacro)", "."))
    return {"findings": findings, "robot": robot, "main": _relative(main, root) if main else None,
            "package": bool(packages)}


def _too_many_elements(path: str) -> int:
    """The bound when the URDF at ``path`` declares more links and joints than it, else 0
    (counted on the text, before a parser holds it; a xacro is bounded by its expansion's own)."""
    from ..ros.launching import MAX_DESCRIPTION_ELEMENTS, description_too_large

    if not path.lower().endswith(".urdf"):
        return 0
    from ..trust.learner_files import read_bytes

    try:
        data = read_bytes(path, (os.path.dirname(os.path.abspath(path)),), limit=MAX_ROBOT_FILE_BYTES + 1)
    except OSError:  # Unreadable too: the validator says why (a file past the bytes' bound included)
        return 0
    text = data.decode("utf-8", errors="replace")
    problem = description_too_large(text, most_chars=MAX_ROBOT_FILE_BYTES)
    return MAX_DESCRIPTION_ELEMENTS if problem is not None and problem.kind == "too_many" else 0


def _main_file(paths: list[str], root: str) -> str | None:
    """The robot to score: a top-level xacro (xacro:include'd parts are not robots of their own)
    or a URDF, preferring those under urdf/ and the shortest names."""
    def rank(path: str) -> tuple[int, int, int, str]:
        relative = _relative(path, root)
        in_urdf = 0 if "/urdf/" in "/" + relative else 1
        kind = 0 if path.endswith(".urdf.xacro") else 1 if path.endswith(".urdf") else 2
        return in_urdf, kind, len(relative), relative
    return min(paths, key=rank) if paths else None


def _relative(path: str, root: str) -> str:
    if not os.path.isdir(root):
        return os.path.basename(path)
    return os.path.relpath(path, root).replace(os.sep, "/")


def _as_dict(finding: Any, file: str, lang: str) -> dict[str, Any]:
    return {"file": file, "line": finding.line, "code": finding.code, "severity": finding.severity,
            "message": finding.text(lang), "hint": finding.hint_text(lang)}


def _finding(code: str, severity: str, message: str, hint: str, file: str) -> dict[str, Any]:
    return {"file": os.path.basename(file), "line": None, "code": code, "severity": severity,
            "message": message, "hint": hint}


def _score(item: Item, robot: Any, result: dict[str, Any]) -> float:
    return item.points if passes(item, robot, result["findings"], result["package"]) else 0.0


def passes(item: Item, robot: Any, findings: list[dict[str, Any]], package: bool) -> bool:
    """Whether ``item`` is earned by a submission with these findings and model."""
    if robot is None or (item.needs_package and not package):
        return False
    if item.check == "loads":
        return True
    if item.check == "no_findings":
        floor = SEVERITIES[item.severity]
        return not any(SEVERITIES.get(f["severity"], 0) >= floor
                       and (not item.codes or f["code"].startswith(item.codes)) for f in findings)
    if item.check == "joints":
        return all(_moves(robot, name) for name in item.joints)
    if item.check == "joint":
        return _joint_ok(item, robot)
    if item.check == "inertials":
        return _inertials_ok(robot)
    return False


def _moves(robot: Any, name: str) -> bool:
    joint = robot.joint(name)
    return joint is not None and joint.type in ("revolute", "continuous", "prismatic")


def _joint_ok(item: Item, robot: Any) -> bool:
    from ..kinematics.frames import tf_tree
    from ..kinematics.tip import link_tip

    joint = robot.joint(item.joint)
    if joint is None or (item.parent and joint.parent != item.parent):
        return False
    if item.at_tip:
        tree = tf_tree(robot)
        if joint.parent not in tree.links:
            return False
        tip = link_tip(tree, joint.parent)
        return bool(np.linalg.norm(np.asarray(joint.origin.xyz, dtype=float) - tip) <= item.tolerance)
    return True


def _inertials_ok(robot: Any) -> bool:
    from ..kinematics.frames import tf_tree

    tree = tf_tree(robot)
    moving = set()
    for index, joint in enumerate(tree.joints):
        parent = tree.parent[index]
        if joint is not None and (joint.type != "fixed" or tree.links[parent] in moving):
            moving.add(tree.links[index])
    for name in moving:
        link = robot.link(name)
        inertial = link.inertial if link is not None else None
        if inertial is None or not inertial.mass or inertial.mass <= 0:
            return False
        try:
            eigen = np.linalg.eigvalsh(np.asarray(inertial.matrix(), dtype=float))
        except (TypeError, ValueError, np.linalg.LinAlgError):
            return False
        if not np.all(eigen > 0):
            return False
    return bool(moving)


def _drawable(robot: Any) -> bool:
    """Drawing happens in the worker, outside the limited child: not a robot of 100,000 links,
    and no mesh named by an absolute path or one climbing out of the submission (``..``),
    which would make the teacher's machine read, and picture, files of its own."""
    if len(robot.links) > MAX_DRAWN_LINKS:
        return False
    from ..validate.usable import blocking_findings

    if blocking_findings(robot, ("kinematics", "visual")):  # already in the report: never drawn from NaN
        return False
    for link in robot.links:
        for visual in link.visuals:
            name = (visual.geometry.filename or "") if visual.geometry is not None else ""
            if name.startswith(("file:", "/")) or ".." in name.replace("\\", "/").split("/"):
                return False
    return True


def _picture(robot: Any, learner: str, options: Options, package_paths: tuple[str, ...] = ()) -> str | None:
    """The learner's arm at rest with its TF frames, as pictures/<learner>.png (None if it cannot be drawn)."""
    from ..render import render_pose, save_png
    from ..trust.outputs import staged

    assert options.pictures is not None
    name = _safe_name(learner) + ".png"
    try:
        image = render_pose(robot, {}, size=PICTURE_SIZE, tf=True, package_paths=package_paths)
        with staged(os.path.join(options.pictures, name), True) as temporary:  # atomic, links not followed
            save_png(image, temporary)
    except (BrasKitError, MemoryError, OSError, RuntimeError, ValueError):
        return None
    return f"pictures/{name}"


def _animation(robot: Any, learner: str, options: Options, package_paths: tuple[str, ...] = ()) -> str | None:
    """The tutorial's motion on the learner's arm (every moving joint swinging), as pictures/<learner>.gif."""
    from ..motion import motion_from_specs, sample_loop
    from ..render import render_motion, save_gif
    from ..trust.outputs import staged

    assert options.pictures is not None
    name = _safe_name(learner) + ".gif"
    try:
        states = sample_loop(motion_from_specs(robot, []), ANIMATION_SECONDS, ANIMATION_FPS)
        with render_motion(robot, states, progress=False, size=ANIMATION_SIZE, tf=True,
                           package_paths=package_paths) as frames:
            with staged(os.path.join(options.pictures, name), True) as temporary:
                save_gif(frames, temporary, ANIMATION_FPS)
    except (BrasKitError, MemoryError, OSError, RuntimeError, ValueError):
        return None
    return f"pictures/{name}"


def _safe_name(learner: str) -> str:
    """A file name for ``learner``'s picture and page: bras_kit.trust.inert.file_stem, the one mapping
    from a user-given name to a file (two learners never share one, on any file system)."""
    from ..trust.inert import file_stem

    return file_stem(learner)
