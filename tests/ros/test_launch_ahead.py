"""validate's worker forks and walls in the launch file's child while setup.py's child runs
(bras_kit.ros.launching.begin_plan, issue 43): the evaluation is the one plan_launch makes after the
build. Oracles: the same package evaluated both ways (what the rules read of it, what the walls
stopped, the launch file's warnings and logs), the processes left and the folders left in the
scratch root after a build that fails or gives no launch file, and the kernel's answer inside the
child (a write outside its folder fails, the package's install tree reads)."""

from __future__ import annotations

import os
import shutil
import tempfile
from pathlib import Path

import pytest
from paths import TESTS

from bras_kit.ros.launched import launch_package
from bras_kit.scaffold.package import scaffold_package
from bras_kit.trust import scratch
from bras_kit.trust.contain import available

DATA = TESTS / "data"
TUTORIAL = DATA / "launch" / "tutorial" / "bras_description"
HOSTILE = DATA / "hostile_packages"
PKG = "bras_description"


def _shape(launched) -> tuple:  # type: ignore[no-untyped-def]
    plan = launched.plan
    return (launched.build.package, launched.build.failure, sorted((i.source, i.target) for i in launched.build.installed),
            launched.launch_file, launched.description, sorted((str(n), str(p)) for n, p in launched.problems),
            sorted((str(n), str(p)) for n, p in launched.start_problems),
            None if plan is None else [(n.package, n.executable, n.name, n.parameters, n.arguments, n.line)
                                       for n in plan.nodes],
            None if plan is None else plan.failure, None if plan is None else plan.warnings,
            None if plan is None else plan.logs, None if plan is None else [str(a) for a in sorted(plan.blocked, key=lambda a: (a.kind, a.path, a.line, os.path.basename(a.detail)))],
            None if plan is None else [os.path.basename(f) for f in plan.included])


def _both(root: Path, tmp_path: Path, **options) -> tuple:  # type: ignore[no-untyped-def, type-arg]
    """The package evaluated with the child begun early and after the build, each into an install
    base of its own; their shapes, with each base's path written <BASE>."""
    first = launch_package(str(root), str(tmp_path / "early" / "install"), ahead=True, **options)
    second = launch_package(str(root), str(tmp_path / "after" / "install"), ahead=False, **options)
    return first, second, *(repr(_shape(launched)).replace(str(tmp_path / where), "<BASE>")
                            for launched, where in ((first, "early"), (second, "after")))


def _package(tmp_path: Path, over: Path | None = None) -> Path:
    root = tmp_path / "src" / PKG
    shutil.copytree(TUTORIAL, root)
    if over is not None:
        shutil.copytree(over, root, dirs_exist_ok=True)
    return root


CASES = ["tutorial", "launch_reaches", "rsp_secret", "name_home", "source_dotdot", "entry_point_code"]


@pytest.mark.parametrize("case", CASES)
def test_the_launch_child_begun_before_the_build_evaluates_what_the_one_after_it_does(tmp_path, case):
    assert available().ok, available()
    root = _package(tmp_path, None if case == "tutorial" else HOSTILE / case)
    early, _, shape_early, shape_after = _both(root, tmp_path)
    assert shape_early == shape_after
    if case == "launch_reaches":
        assert early.plan is not None and early.plan.blocked  # the walls stopped it, begun early or not


def test_a_launch_file_chosen_by_name_with_arguments_is_evaluated_alike(tmp_path):
    root = tmp_path / PKG
    scaffold_package(str(root))
    early, _, shape_early, shape_after = _both(root, tmp_path, launch_file="affichage.launch.py",
                                               arguments={"gui": "false"})
    assert early.plan is not None and shape_early == shape_after


def _children() -> set[int]:
    """This process's children, reaped or not (a zombie is still one)."""
    import psutil

    return {child.pid for child in psutil.Process().children()}


def _launch_folders() -> set[str]:
    root = scratch.scratch_root() or tempfile.gettempdir()
    return {name for name in os.listdir(root) if name.startswith("bras-kit-launch-")}


@pytest.mark.parametrize("how", ["setup_raises", "no_launch_file", "other_file"])
def test_a_launch_child_with_nothing_to_evaluate_ends_and_leaves_nothing(tmp_path, how):
    """The build fails, installs no launch file, or the one asked for is not there: the child begun
    early is told nothing, ends without running any learner file, and its folder goes."""
    root = tmp_path / PKG
    scaffold_package(str(root))
    if how == "setup_raises":
        (root / "setup.py").write_text("raise SystemExit('no build today')\n", encoding="utf-8")
    elif how == "no_launch_file":
        shutil.rmtree(root / "launch")
    before, children = _launch_folders(), _children()
    launched = launch_package(str(root), str(tmp_path / "install"), "absent.launch.py" if how == "other_file" else None,
                              ahead=True)
    assert launched.plan is None
    assert _children() <= children  # the early child ended and was reaped
    assert _launch_folders() <= before


def test_the_child_begun_early_reads_the_install_tree_and_writes_nowhere_else(tmp_path):
    """A launch file that reads its installed URDF and tries to write beside it and in the
    learner's package: the read works, both writes are stopped by the walls (BK639's attempts)."""
    root = tmp_path / PKG
    scaffold_package(str(root))
    launch = root / "launch" / "affichage.launch.py"
    text = launch.read_text(encoding="utf-8")
    trick = ("\n_here = os.path.dirname(os.path.abspath(__file__))\n"
             "open(os.path.join(_here, '..', 'urdf', 'bras.urdf')).read()\n"
             "for _target in (os.path.join(_here, 'planted.txt'), " + repr(str(root / 'planted.txt')) + "):\n"
             "    try:\n        open(_target, 'w').write('x')\n    except OSError:\n        pass\n")
    head = "import os\n" if "import os" not in text else ""
    launch.write_text(head + text + trick, encoding="utf-8")
    early, _, shape_early, shape_after = _both(root, tmp_path)
    assert early.plan is not None and early.plan.failure is None, early.plan
    assert shape_early == shape_after
    assert len(early.plan.blocked) == 2, early.plan.blocked
    assert not (root / "planted.txt").exists()
