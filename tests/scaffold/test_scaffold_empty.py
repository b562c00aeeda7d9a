"""bras-kit new --empty: what `ros2 pkg create --build-type ament_python` writes (the tutorial's
step 2), and a package made that way, by hand, step by step, as bras-kit then finds and checks it.

The oracle is tests/data/ros2_pkg_create/: ros2cli's own Jazzy templates expanded by empy (its
README says how), never bras-kit's templates."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest
from paths import TESTS

from bras_kit.scaffold.package import render_empty_package
from bras_kit.validate.package import find_packages, validate_package

DATA = TESTS / "data"
CREATED = DATA / "ros2_pkg_create"
TUTORIAL = DATA / "package_tutorial"  # the tutorial's files as a learner types them
PKG = "bras_description"
OWNER = ("--maintainer", "eleve", "--email", "eleve@todo.todo")


def files_below(root: Path) -> dict[str, bytes]:
    return {str(p.relative_to(root)): p.read_bytes() for p in sorted(root.rglob("*")) if p.is_file()}


@pytest.mark.parametrize("lang", ["en", "fr"])
@pytest.mark.parametrize(("options", "oracle"), [((), "license_default"),
                                                 (("--license", "Apache-2.0"), "license_apache")])
def test_empty_package_is_byte_for_byte_what_ros2_pkg_create_writes(run_cli, tmp_path, lang, options, oracle):
    code, out, err = run_cli("--lang", lang, "new", "--empty", str(tmp_path / PKG), *OWNER, *options)
    assert (code, err) == (0, "")
    assert files_below(tmp_path / PKG) == files_below(CREATED / oracle / PKG)


@pytest.mark.parametrize(("lang", "made", "step"), [
    ("en", "as ros2 pkg create does:", "next (the tutorial's step 3): describe the arm in"),
    ("fr", "comme le fait ros2 pkg create :", "ensuite (étape 3 du tutoriel) : décrivez le bras dans"),
])
def test_empty_package_lists_its_files_and_names_the_next_step(run_cli, tmp_path, lang, made, step):
    code, out, _ = run_cli("--lang", lang, "new", "--empty", str(tmp_path / PKG), *OWNER)
    assert code == 0
    lines = out.splitlines()
    assert made in lines[0]
    assert [line.strip() for line in lines[1:9]] == [
        "package.xml", "setup.py", "setup.cfg", f"resource/{PKG}", f"{PKG}/__init__.py",
        "test/test_copyright.py", "test/test_flake8.py", "test/test_pep257.py"]
    assert step in out and f"bras-kit validate {tmp_path / PKG}" in out


@pytest.mark.parametrize(("argv", "english", "french"), [
    (("--wrist",), "--wrist: not with --empty", "--wrist : pas avec --empty"),
    (("--xacro", "--param", "bras_length=0.5"), "--xacro, --param: not with --empty", "--xacro, --param : pas avec"),
])
def test_empty_refuses_the_robot_options_and_writes_nothing(run_cli, tmp_path, argv, english, french):
    for lang, words in (("en", english), ("fr", french)):
        code, out, err = run_cli("--lang", lang, "new", "--empty", str(tmp_path / PKG), *argv)
        assert code == 2 and words in err and "Traceback" not in err
    assert not (tmp_path / PKG).exists()


def test_license_without_empty_is_refused(run_cli, tmp_path):
    code, _, err = run_cli("new", str(tmp_path / PKG), "--license", "MIT")
    assert code == 2 and "--license applies to --empty only" in err
    code, _, err = run_cli("--lang", "fr", "new", str(tmp_path / PKG), "--license", "MIT")
    assert code == 2 and "--license ne s'emploie qu'avec --empty" in err
    assert not (tmp_path / PKG).exists()


@pytest.mark.parametrize("license_name", ["it's mine", "A<B", ""])
def test_a_license_that_would_break_setup_py_is_refused(run_cli, tmp_path, license_name):
    code, _, err = run_cli("new", "--empty", str(tmp_path / PKG), "--license", license_name)
    assert code == 2 and "cannot be written into setup.py and package.xml" in err
    assert not (tmp_path / PKG).exists()


def test_a_package_named_test_is_refused_as_ros2_pkg_create_refuses_it(run_cli, tmp_path):
    # ros2pkg/verb/create.py: "ament_python packages can't be named 'test'"
    code, _, err = run_cli("new", "--empty", str(tmp_path / "test"), "--name", "test")
    assert code == 2 and "cannot be named 'test'" in err


def test_empty_keeps_a_non_empty_folder_without_force(run_cli, tmp_path):
    mine = tmp_path / PKG / "notes.txt"
    mine.parent.mkdir()
    mine.write_text("mine", encoding="utf-8")
    code, _, err = run_cli("new", "--empty", str(tmp_path / PKG))
    assert code != 0 and "not empty" in err
    assert sorted(p.name for p in (tmp_path / PKG).iterdir()) == ["notes.txt"]


def test_empty_renders_the_same_bytes_in_every_language():
    """ros2 pkg create writes English whatever the locale: so does bras-kit new --empty."""
    assert render_empty_package(maintainer="eleve", email="eleve@todo.todo") == \
        {k: v.decode() for k, v in files_below(CREATED / "license_default" / PKG).items()}


@pytest.fixture()
def hand_made(tmp_path) -> Path:
    """The workspace of the tutorial's step 2: ros2 pkg create's files in src/, nothing of bras-kit."""
    package = tmp_path / "ros2_cellule_ws" / "src" / PKG
    shutil.copytree(CREATED / "license_apache" / PKG, package)
    return package


def test_a_package_made_by_hand_is_found_as_a_package(hand_made, run_cli):
    workspace = hand_made.parents[1]
    assert find_packages([str(workspace)]) == [str(hand_made)]
    code, out, _ = run_cli("build", str(workspace))
    assert code == 0 and f"Finished <<< {PKG}" in out
    assert (workspace / "install" / PKG / "share" / "ament_index" / "resource_index" / "packages" / PKG).is_file()


def _next_steps(package: Path) -> list[tuple[str, str, str]]:
    results = validate_package(str(package))
    return [(f.code, f.severity, Path(r.path).name) for r in results for f in r.findings
            if f.code in ("BK608", "BK622")] + \
        [("error", f.code, Path(r.path).name) for r in results for f in r.findings if f.severity == "error"]


def test_validate_names_the_next_step_at_each_step_of_the_tutorial(hand_made):
    """Step by step as the tutorial types it: what is not written yet is the next step (info),
    never an error; the errors are the tutorial's own pitfall (step 4: data_files not written)."""
    assert _next_steps(hand_made) == [("BK608", "info", "setup.py")]  # step 2: the urdf comes next
    (hand_made / "urdf").mkdir()
    (hand_made / "launch").mkdir()
    shutil.copy(TUTORIAL / "urdf" / "bras.urdf", hand_made / "urdf")  # step 3
    found = validate_package(str(hand_made))
    (nxt,) = [f for r in found for f in r.findings if f.code == "BK608"]
    assert nxt.hint_text("en") == "next step: write launch/affichage.launch.py (the tutorial's step 4)"
    assert nxt.hint_text("fr") == "étape suivante : écrivez launch/affichage.launch.py (étape 4 du tutoriel)"
    shutil.copy(TUTORIAL / "launch" / "affichage.launch.py", hand_made / "launch")  # step 4
    assert {code for kind, code, _ in _next_steps(hand_made) if kind == "error"} == {"BK601"}
    shutil.copy(CREATED / "steps" / "setup_step5.py", hand_made / "setup.py")  # step 5
    assert _next_steps(hand_made) == []
    # step 7 typed in setup.py before the node: the node is the next step, colcon build still works
    text = (hand_made / "setup.py").read_text(encoding="utf-8")
    (hand_made / "setup.py").write_text(text.replace(
        "'console_scripts': []", "'console_scripts': ['animation = bras_description.animation:main']"), encoding="utf-8")
    assert _next_steps(hand_made) == [("BK608", "info", "setup.py")]
    shutil.copy(TUTORIAL / PKG / "animation.py", hand_made / PKG)
    assert _next_steps(hand_made) == []


@pytest.mark.parametrize(("lang", "words"), [
    ("en", "no robot description yet: urdf/ holds no .urdf or .xacro file"),
    ("fr", "pas encore de description du robot : urdf/ ne contient aucun fichier .urdf ou .xacro"),
])
def test_validate_on_what_ros2_pkg_create_writes_exits_0_with_the_next_step(hand_made, run_cli, lang, words):
    code, out, err = run_cli("--lang", lang, "validate", str(hand_made))
    assert (code, err) == (0, "") and "BK608" in out and words in out


@pytest.mark.parametrize(("lang", "success"), [("en", "install tree:"), ("fr", "arborescence d’installation :")])
def test_a_failed_build_claims_no_install_tree(hand_made, run_cli, lang, success):
    """bras-kit build printed its install-tree line after failing: nothing claims success after a failure."""
    setup = hand_made / "setup.py"
    setup.write_text(setup.read_text(encoding="utf-8").replace("package_name = ", "package_name = undefined_name  # "),
                     encoding="utf-8")
    code, out, _ = run_cli("--lang", lang, "build", str(hand_made.parents[1]))
    assert code == 1 and f"1 package failed: {PKG}" in out
    assert success not in out
    setup.write_text((CREATED / "license_apache" / PKG / "setup.py").read_text(encoding="utf-8"), encoding="utf-8")
    code, out, _ = run_cli("--lang", lang, "build", str(hand_made.parents[1]))
    assert code == 0 and success in out
