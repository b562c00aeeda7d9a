"""A package built as colcon builds it and its launch files evaluated as ``ros2 launch`` would: the
reading under ``bras-kit launch`` and ``bras-kit validate PKG_DIR`` (whose rules, BK630-BK635,
live in :mod:`bras_kit.validate.package.launch_rules`). It imports no rule and no numpy, so that
:func:`evaluate_ahead` can begin it in a worker before the rules are imported.
"""

from __future__ import annotations

import os
import tempfile
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field
from typing import Any

from .build import BuildRecord, build_package
from .launching import (
    LaunchPlan,
    PlannedNode,
    StartProblem,
    plan_launch,
    preload_planning,
    robot_state_publisher_start,
    ros_arguments_start,
)


@dataclass
class Launched:
    build: BuildRecord
    launch_file: str = ""  # package-relative source of the launch file
    plan: LaunchPlan | None = None
    description: str | None = None  # the URDF robot_state_publisher loads
    problems: list[tuple[PlannedNode, StartProblem]] = field(default_factory=list)
    others: dict[str, Launched] = field(default_factory=dict)  # the other launch files, by source
    start_problems: list[tuple[PlannedNode, StartProblem]] = field(default_factory=list)  # BK634: rcl's arguments


def launch_sources(build: BuildRecord) -> list[str]:
    return sorted(i.source for i in build.installed
                  if i.target.startswith(f"share/{build.package}/") and
                  i.source.endswith((".launch.py", "_launch.py", ".launch.xml", ".launch.yaml", ".launch.yml")))


def share_files_named(build: BuildRecord, name: str) -> list[str]:
    """The package files installed under share/PKG/ with the name ``name``, whatever it ends with:
    ros2launch looks for the name in every folder of the share directory and takes any file
    (ros2launch/api/api.py, get_share_file_path_from_package, Jazzy lines 39-64; more than one is
    its MultipleLaunchFilesError)."""
    wanted = os.path.basename(name)
    return sorted(i.source for i in build.installed
                  if i.target.startswith(f"share/{build.package}/") and os.path.basename(i.target) == wanted)


def launch_package(root: str, install_base: str, launch_file: str | None = None,
                   arguments: dict[str, str] | None = None, *, prefixes: tuple[str, ...] = ()) -> Launched:
    """Build ``root`` into ``install_base`` and evaluate ``launch_file`` (a file's name anywhere in
    the package's share folder, default: the first installed launch file) as ``ros2 launch PKG
    FILE`` would; ``prefixes``: the other packages of the workspace, built."""
    build = build_package(root, install_base)
    result = Launched(build)
    if build.failure is not None:
        return result
    sources = launch_sources(build)
    if launch_file is not None:
        chosen = share_files_named(build, launch_file)
        result.launch_file = chosen[0] if len(chosen) == 1 else launch_file
    elif sources:
        result.launch_file = sources[0]
    if not result.launch_file:
        return result
    target = next((i.target for i in build.installed if i.source == result.launch_file), None)
    if target is None:
        return result
    plan = plan_launch(os.path.join(build.prefix, target), [build.prefix, *prefixes], arguments,
                       learner_roots=(root,))
    result.plan = plan
    for node in plan.nodes:
        result.start_problems += [(node, p) for p in ros_arguments_start(node)]
        if node.package == "robot_state_publisher":
            text, problems = robot_state_publisher_start(node, roots=(build.prefix, *prefixes, root))
            result.problems += [(node, p) for p in problems]
            if text is not None and result.description is None:
                result.description = text
    return result


def evaluate_package(root: str) -> Launched | None:
    """``root`` built in a temporary install tree, its first launch file evaluated, then each other one
    (None: no package.xml)."""
    if not os.path.isfile(os.path.join(root, "package.xml")):
        return None
    with tempfile.TemporaryDirectory(prefix="bras-kit-build-") as base:
        first = launch_package(root, os.path.join(base, "install"))
        if first.plan is not None:
            for other in launch_sources(first.build):
                if other != first.launch_file:
                    first.others[other] = launch_package(root, os.path.join(base, "install"), other)
    return first


def evaluate_ahead(paths: Iterable[str]) -> Callable[[str], Launched | None]:
    """The packages among ``paths`` (and below them) built and evaluated by :func:`evaluate_package`
    in a worker of bras-kit's own begun now, while the caller goes on (``validate PKG_DIR`` imports
    its rules and reads the package statically meanwhile: on two cores, about half its time). The
    function returned gives a package folder's answer, waiting for the worker the first time; None
    where the worker has none (no worker, not one of its packages, or the worker in trouble): the
    caller then evaluates the package itself. Each learner file still runs in its own contained
    child, forked by the worker."""
    import threading

    from ..errors import BrasKitError
    from ..message import M
    from ..sandbox import start_limited
    from .contain import available, begin_trial
    from .workspace import find_packages

    roots = [os.path.abspath(root) for root in find_packages(paths)]
    if not roots or threading.active_count() > 1:  # a fork beside another thread may wait forever for an
        return lambda root: None  # import lock that thread holds (docs/design/ros-layer.md): not ahead, then
    begin_trial()  # the containment's trial, on the other core while the line below imports
    preload_planning()  # the worker and each of its children start with them (the rules need most too)
    available()  # the trial's answer, which the worker inherits
    pending = start_limited(_evaluate_all, roots, cpu_seconds=3600, wall_seconds=3600, memory_bytes=1 << 40,
                            what=M("the build and launch evaluation"))
    answers: list[dict[str, Launched | None]] = []

    def answer(root: str) -> Launched | None:
        if not answers:
            try:
                answers.append(pending.result())
            except BrasKitError:  # the worker's own trouble: evaluated by the caller instead, as without it
                answers.append({})
        return answers[0].get(os.path.abspath(root))

    return answer


def _evaluate_all(roots: list[str]) -> dict[str, Any]:
    """In the worker: each package evaluated, in order, up to the first that raises (the caller
    meets that error again, in its place)."""
    from ..errors import BrasKitError

    out: dict[str, Any] = {}
    for root in roots:
        try:
            out[root] = evaluate_package(root)
        except BrasKitError:
            break
    return out
