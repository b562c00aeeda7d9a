"""A launch's findings: the package rules (BK6xx) on the build ``bras-kit launch`` made, and the
URDF rules on the robot robot_state_publisher loads from it (:mod:`bras_kit.ros.evaluation` reads
the launch; this module judges it)."""

from __future__ import annotations

import os
from typing import Any

from ...findings.data import FileResult, merge_results
from ...ros.evaluation import LaunchEvaluation


def check_launch(evaluation: LaunchEvaluation, package: Any, package_paths: tuple[str, ...] = ()) -> None:
    """The evaluation's findings: the package rules (BK6xx) on this build, and the URDF rules on
    the robot robot_state_publisher loads, at the lines of the package file it comes from (the
    installed copy is that file as built). The package's own nodes are added by their runner."""
    from .. import validate
    from . import validate_package

    results = validate_package(evaluation.root, select=["BK6"], package=package, launch=True)
    if evaluation.robot is not None and evaluation.robot_file is not None:
        path = os.path.join(evaluation.root, evaluation.robot_file)
        found = validate(evaluation.robot, package_paths=package_paths)
        results = sorted(merge_results(results, [FileResult(path, found)]), key=lambda r: r.path)
    evaluation.results = results
