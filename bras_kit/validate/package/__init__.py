"""Package rules (BK6xx): a whole ROS 2 ament_python package, like the one ``bras-kit new`` makes.

::

    from bras_kit.validate.package import validate_package
    results = validate_package("bras_description")   # list of FileResult, one per file

Nothing in the package is run: ``setup.py``, launch files and nodes are read with :mod:`ast`,
``.rviz`` files as YAML, ``package.xml`` with the safe XML reader. The robot description
itself is checked by the URDF rules (``bras-kit validate PKGDIR`` collects its ``.urdf`` and
``.xacro`` files as usual); these rules only read it to know the links, joints and limits.
"""

from __future__ import annotations

from collections.abc import Iterable

from ...findings.data import FileResult, Finding, finding, sort_key
from ...findings.registry import select_rules
from ...ros.launched import launch_package  # noqa: F401  (the package built and launched)
from ...ros.package import Package
from ...ros.workspace import find_packages, is_package  # noqa: F401  (light: the CLI finds packages before importing the rules)

# isort: split
# the rule families register on import, in this order (the order they run in): the three pitfalls
# first, as rules.py held them, then the rules of the other modules
from . import install_rules, rviz_rules, motion_rules, node_code_rules  # noqa: F401, I001  (in this order)

# isort: split
from . import (
    build_reach,  # noqa: F401  (BK639: what setup.py and launch files tried)
    node_mistakes,  # noqa: F401  (BK627, registered on import)
    run_reach,  # noqa: F401  (BK659: what the containment stopped)
    run_record,  # noqa: F401  (BK657-BK658: the run's record, bounded and checked)
    setup_cfg,  # noqa: F401  (BK628-BK629: what colcon and setuptools do with setup.cfg)
    texts,  # noqa: F401  (the rules' words)
)
from .evaluated import launched  # noqa: F401
from .launch_rules import LAUNCH_CHECKS, installed_descriptions  # noqa: F401  (BK630-BK633)
from .rules import PACKAGE_CHECKS  # importing registers the rules
from .run_rules import RUN_CHECKS  # the rules over a run of the node (BK640-BK659)

# Rules that read nothing of the build and launch evaluation and take time (BK623 follows each
# formula for a minute of motion): they run first, while ``validate PKG_DIR``'s worker is still
# evaluating (BK600, the first of the others, waits for its answer). What they read (setup.py, the
# launch files, the nodes, the URDF) BK600 reads too, so its findings do not depend on the order.
BEFORE_THE_EVALUATION = ("BK623",)

__all__ = ["Package", "find_packages", "installed_descriptions", "is_package", "launch_package", "validate_package"]


def validate_package(path: str, *, lang: str | None = None, select: Iterable[str] = (),
                     ignore: Iterable[str] = (), package: Package | None = None,
                     launch: bool = False) -> list[FileResult]:
    """The package rules' findings, one :class:`FileResult` per file read or with a finding
    (in name order; a file the rules read and found clean has an empty result).

    ``select``/``ignore`` are code prefixes as for :func:`bras_kit.validate.validate`; URDF
    rule codes among them are simply not package rules. Unknown prefixes raise ValueError.
    Findings are data, worded where shown (``lang`` is accepted for older callers, unused).
    ``launch`` also builds the package and evaluates its launch files (BK630-BK633): that runs the
    learner's setup.py and launch files in the sandbox child, as colcon and ros2 launch would.
    """
    package = Package(path) if package is None else package
    if launch:
        package.evaluate = True  # the rules over whole launches (BK611, BK620...) read the evaluation too
    by_file: dict[str, list[Finding]] = {}
    for chosen in sorted(select_rules(select, ignore), key=lambda r: r.code not in BEFORE_THE_EVALUATION):
        check = PACKAGE_CHECKS.get(chosen.code)
        if chosen.code in RUN_CHECKS:
            continue  # only with a recording: run_findings
        if chosen.code in LAUNCH_CHECKS and not launch:
            continue  # only when asked to run the learner's setup.py and launch files
        if check is None:
            continue
        for found in check(package):
            file = str(found.params.get("file", ""))
            by_file.setdefault(file, []).append(finding(chosen, found))
    for file in package.read:
        by_file.setdefault(file, [])
    return [FileResult(package.path(file), sorted(findings, key=sort_key))
            for file, findings in sorted(by_file.items())]
