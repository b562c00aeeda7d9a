"""A node file in the wrong place (issue 52, item 1): the console_scripts entry names
``bras_description.animation`` and ``bras_description/animation.py`` is missing, but a file of that
name sits elsewhere in the package (beside setup.py, in launch/, in a subfolder, in a folder of
another name, in another case, without ``.py``). colcon builds, ``ros2 run`` fails with
ModuleNotFoundError: BK622 says it as an error, naming where the file is and where it must go,
never BK608's "not written yet".

The oracle is setuptools itself: each placement is built with ``setup.py build_py`` (what colcon's
ament_python build runs) and the entry's module looked up by Python's import machinery in what it
installed."""

from __future__ import annotations

import shutil
import subprocess
import sys
from pathlib import Path

import pytest
from paths import TESTS

from bras_kit.scaffold.package import scaffold_package
from bras_kit.validate.package import validate_package

DATA = TESTS / "data"
TUTORIAL = DATA / "package_tutorial"
PKG = "bras_description"
NODE = f"{PKG}/animation.py"
ENTRY = "animation = bras_description.animation:main"

# where a learner leaves the node, and the folders that must be packages for the case to hold
PLACES = {
    "root": ("animation.py", ()),
    "launch_folder": ("launch/animation.py", ()),
    "scripts_without_suffix": ("scripts/animation", ()),
    "subfolder": (f"{PKG}/nodes/animation.py", ()),
    "subpackage": (f"{PKG}/nodes/animation.py", (f"{PKG}/nodes",)),
    "misnamed_package": ("bras_descripton/animation.py", ("bras_descripton",)),
    "src_layout": (f"src/{PKG}/animation.py", ()),
    "capitalised_file": (f"{PKG}/Animation.py", ()),
    "capitalised_folder": ("Bras_description/animation.py", ("Bras_description",)),
    "without_suffix": (f"{PKG}/animation", ()),
}
# kept aside while the rule was written, run at the end
UNSEEN = {
    "config_folder": ("config/animation.py", ()),
    "doubled_package": (f"{PKG}/{PKG}/animation.py", (f"{PKG}/{PKG}",)),
    "upper_case_suffix": (f"{PKG}/ANIMATION.PY", ()),
    "test_folder": ("test/animation.py", ()),
}


def _package(tmp_path: Path, base: str, label: str = "pkg") -> Path:
    root = tmp_path / label / PKG
    if base == "scaffold":
        scaffold_package(root)
    else:
        shutil.copytree(TUTORIAL, root)
        if base == "tutorial_packages_list":  # the tutorial's own setup.py: packages=[package_name]
            setup = root / "setup.py"
            text = setup.read_text(encoding="utf-8")
            assert text.count("find_packages(exclude=['test'])") == 1
            setup.write_text(text.replace("find_packages(exclude=['test'])", "[package_name]"), encoding="utf-8")
    return root


def _place(root: Path, where: str, packages: tuple[str, ...]) -> None:
    target = root / where
    target.parent.mkdir(parents=True, exist_ok=True)
    (root / NODE).rename(target)
    for folder in packages:
        (root / folder / "__init__.py").touch()


def _importable_once_built(root: Path, tmp_path: Path) -> bool:
    """setuptools' build_py into a folder of its own, then Python's import machinery on the result."""
    lib = tmp_path / "lib"
    subprocess.run([sys.executable, "setup.py", "-q", "build_py", "--build-lib", str(lib)], cwd=root, check=True,
                   capture_output=True, timeout=120)
    probe = "import importlib.util, sys; sys.path[:0] = [sys.argv[1]]; " \
            "print(importlib.util.find_spec('bras_description.animation') is not None)"
    out = subprocess.run([sys.executable, "-I", "-c", probe, str(lib)], capture_output=True, text=True, check=True,
                         cwd=tmp_path, timeout=60)
    return out.stdout.strip() == "True"


def _findings(root: Path, codes=("BK608", "BK622")) -> list:
    return [f for r in validate_package(str(root)) for f in r.findings if f.code in codes]


def _line_of(root: Path, text: str) -> int:
    return next(k for k, line in enumerate((root / "setup.py").read_text(encoding="utf-8").splitlines(), 1)
                if text in line)


def _check_misplaced(tmp_path: Path, base: str, where: str, packages: tuple[str, ...]) -> None:
    root = _package(tmp_path, base)
    _place(root, where, packages)
    assert not _importable_once_built(root, tmp_path), "setuptools installs this placement: not a case"
    (finding,) = _findings(root)
    assert (finding.code, finding.severity, finding.line) == ("BK622", "error", _line_of(root, ENTRY))
    assert finding.data["found"] == [where] and finding.data["node_file"] == NODE
    english, french = finding.text("en"), finding.text("fr")
    assert where in english and NODE in english and "ModuleNotFoundError" in english
    assert where in french and NODE in french and "trouvé ailleurs" in french
    assert finding.hint_text("en").startswith(f"move {where} to {NODE}")
    assert finding.hint_text("fr").startswith(f"déplacez {where} vers {NODE}")


@pytest.mark.parametrize("base", ["tutorial_packages_list", "scaffold"])
@pytest.mark.parametrize("case", sorted(PLACES))
def test_node_in_the_wrong_place_is_an_error_naming_both_places(tmp_path, base, case):
    where, packages = PLACES[case]
    _check_misplaced(tmp_path, base, where, packages)


@pytest.mark.parametrize("case", sorted(UNSEEN))
def test_node_in_the_wrong_place_unseen_cases(tmp_path, case):
    where, packages = UNSEEN[case]
    _check_misplaced(tmp_path, "tutorial_packages_list", where, packages)


def test_the_misplaced_node_is_said_once(tmp_path):
    """The node of a misnamed package folder publishes JointState with a main(): the entry's BK622
    names it, and no second BK622 asks for an entry that would run the misnamed folder's module."""
    root = _package(tmp_path, "tutorial")
    before = validate_package(str(root))
    _place(root, "bras_descripton/animation.py", ("bras_descripton",))
    after = validate_package(str(root))

    def codes(results):
        return sorted((f.code, f.line) for r in results for f in r.findings)

    added = sorted(set(codes(after)) - set(codes(before)))
    assert added == [("BK622", _line_of(root, ENTRY))]
    assert not set(codes(before)) - set(codes(after))


def test_two_copies_are_both_named(tmp_path):
    root = _package(tmp_path, "scaffold")
    shutil.copy(root / NODE, root / "animation.py")
    _place(root, "launch/animation.py", ())
    (finding,) = _findings(root)
    assert finding.data["found"] == ["animation.py", "launch/animation.py"]


@pytest.mark.parametrize("where", ["build/lib/bras_description/animation.py", ".git/animation.py",
                                   "bras_description/__pycache__/animation.py", "install/animation.py"])
def test_a_copy_no_learner_wrote_leaves_the_node_not_written(tmp_path, where):
    """colcon's build/install folders (a build run in the package folder), caches and hidden folders hold
    copies, not the learner's source: the node is still the next step (BK608, info)."""
    root = _package(tmp_path, "tutorial")
    _place(root, where, ())
    (finding,) = _findings(root)
    assert (finding.code, finding.severity) == ("BK608", "info")


def test_the_node_in_its_place_gets_neither(tmp_path):
    root = _package(tmp_path, "tutorial")
    assert _importable_once_built(root, tmp_path)
    assert _findings(root) == []


def test_validate_exits_non_zero_and_names_the_places(tmp_path):
    root = _package(tmp_path, "scaffold")
    _place(root, "animation.py", ())
    for lang, words in (("en", "move animation.py to bras_description/animation.py"),
                        ("fr", "déplacez animation.py vers bras_description/animation.py")):
        done = subprocess.run([sys.executable, "-m", "bras_kit", "validate", "--lang", lang, str(root)],
                              capture_output=True, text=True, encoding="utf-8", timeout=120)
        assert done.returncode == 1 and "Traceback" not in done.stderr
        assert "BK622" in done.stdout and "BK608" not in done.stdout and words in done.stdout


def test_bras_kit_run_says_where_the_node_must_go(tmp_path):
    """bras-kit run PKG, the counterpart of ros2 run: the same mistake, the same two places."""
    root = _package(tmp_path, "scaffold")
    _place(root, "launch/animation.py", ())
    for lang, words in (("en", "move launch/animation.py to bras_description/animation.py"),
                        ("fr", "déplacez launch/animation.py vers bras_description/animation.py")):
        done = subprocess.run([sys.executable, "-m", "bras_kit", "run", "--lang", lang, str(root)],
                              capture_output=True, text=True, encoding="utf-8", timeout=120)
        assert done.returncode == 2 and "Traceback" not in done.stderr
        assert words in done.stderr


def test_bras_kit_run_refuses_a_module_file_in_another_case(tmp_path):
    """Python's import compares the name exactly: bras_description/Animation.py is not the module
    bras_description.animation, whatever the file system (macOS and Windows would open it)."""
    root = _package(tmp_path, "scaffold")
    _place(root, f"{PKG}/Animation.py", ())
    done = subprocess.run([sys.executable, "-m", "bras_kit", "run", "--lang", "en", str(root)],
                          capture_output=True, text=True, encoding="utf-8", timeout=120)
    assert done.returncode == 2 and f"move {PKG}/Animation.py to {NODE}" in done.stderr
