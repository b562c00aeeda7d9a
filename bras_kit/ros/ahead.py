"""A package's build and launch evaluation begun in a worker of bras-kit's own, before the caller
imports what it needs meanwhile (``validate PKG_DIR``: its rules, numpy among them).

The caller imports what both sides need first (the evaluation, :mod:`bras_kit.ros.launched`, with
which it reads the worker's answer; PyYAML), so the worker starts with it. The worker then loads
what only it needs (libseccomp, the launch children's installer) on the other core, while the
caller imports its rules. Each learner file still runs in its own contained child, forked by the
worker; the worker itself runs bras-kit's code only, and sends back data
(:class:`~bras_kit.ros.launched.Launched`).
"""

from __future__ import annotations

import os
from collections.abc import Callable, Iterable
from typing import Any

from .workspace import find_packages


def evaluate_ahead(paths: Iterable[str]) -> Callable[[str], Any]:
    """The packages among ``paths`` (and below them) built and evaluated by
    :func:`bras_kit.ros.launched.evaluate_package` in a worker begun now, while the caller goes on.
    The function returned gives a package folder's :class:`~bras_kit.ros.launched.Launched`,
    waiting for the worker the first time; None where the worker has none (no worker, not one of
    its packages, or the worker in trouble): the caller then evaluates the package itself."""
    import threading

    from ..core.errors import BrasKitError
    from ..core.message import M
    from ..trust.sandbox import start_limited
    from . import launched  # noqa: F401 - read by the caller too: imported once, before the fork

    roots = [os.path.abspath(root) for root in find_packages(paths)]
    if not roots or threading.active_count() > 1:  # a fork beside another thread may wait forever for an
        return lambda root: None  # import lock that thread holds (docs/design/ros-layer.md): not ahead, then
    import yaml  # noqa: F401 - both sides read YAML (the rules .rviz files, launch_ros parameters): once, here

    pending = start_limited(_evaluate_all, roots, cpu_seconds=3600, wall_seconds=3600, memory_bytes=1 << 40,
                            what=M("the build and launch evaluation"))
    answers: list[dict[str, Any]] = []

    def answer(root: str) -> Any:
        if not answers:
            try:
                answers.append(pending.result())
            except BrasKitError:  # the worker's own trouble: evaluated by the caller instead, as without it
                answers.append({})
        return answers[0].get(os.path.abspath(root))

    return answer


def _evaluate_all(roots: list[str]) -> dict[str, Any]:
    """In the worker: each package evaluated, in order, up to the first that raises (the caller
    meets that error again, in its place). What each launch file's child needs is imported while
    another child runs: the containment's trial, or, where this boot's record of a passed trial
    spares it, setup.py's (:func:`.launched.launch_package`)."""
    from ..core.errors import BrasKitError
    from ..trust.contain import available, begin_trial
    from . import launched
    from .launching import preload_planning

    if begin_trial():
        preload_planning()
    available()
    out: dict[str, Any] = {}
    for root in roots:
        try:
            out[root] = launched.evaluate_package(root)
        except BrasKitError:
            break
    return out
