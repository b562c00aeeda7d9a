"""The pitfalls a run showed, as validator findings (rules BK640-BK659 of the validator).

::

    recording = run_node("bras_description")
    for finding in run_findings(recording, robot_of("bras_description")):
        print(finding.code, finding.text())
"""

from __future__ import annotations

import os
from collections.abc import Iterable
from typing import Any

from ..ros.recording import Recording


def run_findings(recording: Recording, robot: Any, *, lang: str | None = None, select: Iterable[str] = (),
                 ignore: Iterable[str] = (), root: str | None = None) -> list[Any]:
    """The findings of the run rules (BK640-BK659) for ``recording``, worded in ``lang``.

    ``data["file"]`` of each finding is the learner's file it points at (relative to the
    package folder), its ``line`` the line there when known. ``root``, that folder: a rule may
    then read the learner's file for its line (BK649: where ``msg.position`` is set).
    """
    from ..core.i18n import current_language
    from ..findings.data import finding, sort_key
    from ..findings.registry import select_rules
    from ..validate.package.run_rules import RUN_CHECKS, run_hits

    lang = lang or current_language()
    chosen = {rule.code: rule for rule in select_rules(select, ignore) if rule.code in RUN_CHECKS}
    findings = [finding(chosen[code], found) for code, found in run_hits(recording, robot, sorted(chosen), root)]
    return sorted(findings, key=sort_key)


def node_file_results(path: str, *, lang: str | None = None, select: Iterable[str] = (),
                      ignore: Iterable[str] = (), duration: float = 10.0, **limits: Any) -> list[Any]:
    """``validate FILE.py --run``: the one node file run as ``bras-kit run FILE.py`` runs it (its
    package's robot, else the built-in tutorial arm), its run rules' findings as FileResults."""
    from ..findings.data import FileResult, sort_key
    from ..model.authoring import arm
    from .node import robot_of, run_node

    recording = run_node(path, duration=duration, **limits)
    robot = robot_of(path)
    by_file: dict[str, list[Any]] = {}
    for found in run_findings(recording, robot if robot is not None else arm(), lang=lang, select=select,
                              ignore=ignore, root=os.path.dirname(os.path.abspath(path))):
        by_file.setdefault(str(found.data.get("file") or recording.source), []).append(found)
    by_file.setdefault(recording.source, [])
    base = os.path.dirname(path)
    return [FileResult(os.path.join(base, file), sorted(findings, key=sort_key))
            for file, findings in sorted(by_file.items())]


def package_run_results(path: str, *, lang: str | None = None, select: Iterable[str] = (),
                        ignore: Iterable[str] = (), duration: float = 10.0, **limits: Any) -> list[Any]:
    """Run every executable of the package's console_scripts and return the run rules'
    findings as :class:`~bras_kit.findings.data.FileResult` objects, one per file with a
    finding (paths shown under ``path``, like :func:`~bras_kit.validate.package.validate_package`).

    A node stopped by a limit of the sandbox (CPU, memory, wall clock) is reported as BK640.
    """
    from ..core.errors import BrasKitError
    from ..findings.data import FileResult
    from ..ros.package import Package
    from ..ros.recording import NodeFailure
    from ..trust.contain import ContainmentError
    from .node import NodeRunError, locate, run_node

    package = Package(path)
    scripts = package.setup.scripts if package.setup is not None else None
    robot = package.robot
    by_file: dict[str, list[Any]] = {}
    for entry in scripts or []:
        try:
            recording = run_node(path, entry.name, duration=duration, **limits)
        except NodeRunError as exc:
            from ..core.i18n import say

            target = locate(path, entry.name)
            source = os.path.relpath(target.path, target.root).replace(os.sep, "/")
            recording = Recording(target=target.shown, source=source, function=target.function, duration=duration,
                                  end=exc.time, ended="error",
                                  failure=NodeFailure("NodeRunError", say(exc.message, lang), [], exc.time))
        except ContainmentError:  # the walls failed here: never skipped in silence
            raise
        except BrasKitError:  # an entry that cannot be started: BK622 reports it
            continue
        for finding in run_findings(recording, robot, lang=lang, select=select, ignore=ignore,
                                    root=os.path.abspath(path)):
            by_file.setdefault(str(finding.data.get("file") or recording.source), []).append(finding)
    from ..findings.data import sort_key

    return [FileResult(package.path(file), sorted(findings, key=sort_key)) for file, findings in sorted(by_file.items())]
