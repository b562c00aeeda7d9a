"""Issue 19: the tutorial's pitfalls, caught on what learners really write.

The package in tests/data/tutorial_package/ is the tutorial's text copied as it stands
(/work/shared/tutorial/simuler-bras-ros2.fr.txt: urdf/bras.urdf, launch/affichage.launch.py,
setup.py with the step-7 console_scripts entry, bras_description/animation.py), with the
package.xml, setup.cfg and resource marker that ``ros2 pkg create --build-type ament_python
--license Apache-2.0 bras_description`` writes. Each mistake in tests/data/tutorial_mistakes/
and tests/data/urdf/pitfalls/ is one ordinary edit of those files.
"""

from __future__ import annotations

import os
import re
import runpy
import shutil
import sys
import types
from pathlib import Path

import pytest
from paths import TESTS

from bras_kit.validate import validate_path
from bras_kit.validate.package import validate_package

DATA = TESTS / "data"
TUTORIAL = DATA / "tutorial_package"
MISTAKES = DATA / "tutorial_mistakes"
PITFALLS = DATA / "urdf" / "pitfalls"


def _package_with(tmp_path: Path, **files: Path) -> Path:
    """A copy of the tutorial's package with some files replaced (``setup_py=...``, ``animation=...``)."""
    root = tmp_path / "bras_description"
    shutil.copytree(TUTORIAL, root)
    targets = {"setup_py": root / "setup.py", "animation": root / "bras_description" / "animation.py"}
    for key, source in files.items():
        shutil.copy(source, targets[key])
    return root


def _findings(root: Path) -> list:
    return [(r.path, f) for r in validate_package(str(root)) for f in r.findings]


def _run_setup(root: Path) -> dict:
    """Run setup.py as colcon does (python setup.py ...), with setuptools.setup replaced by a
    recorder: the real interpreter is the oracle for NameError."""
    recorded: dict = {}
    fake = types.ModuleType("setuptools")
    fake.setup = lambda **kwargs: recorded.update(kwargs)  # type: ignore[attr-defined]
    fake.find_packages = lambda *a, **k: ["bras_description"]  # type: ignore[attr-defined]
    saved, here = sys.modules.get("setuptools"), os.getcwd()
    sys.modules["setuptools"] = fake
    os.chdir(root)
    try:
        runpy.run_path(str(root / "setup.py"), run_name="__main__")
    finally:
        os.chdir(here)
        if saved is not None:
            sys.modules["setuptools"] = saved
        else:  # not left behind: a child forked later by this process would inherit the recorder
            del sys.modules["setuptools"]
    return recorded


# ---------------------------------------------------------------- the tutorial as written


def test_the_tutorial_package_as_written_gets_nothing_above_info():
    results = validate_package(str(TUTORIAL))
    urdf = validate_path(str(TUTORIAL / "urdf" / "bras.urdf"))
    found = [f for r in results for f in r.findings] + urdf
    assert [(f.code, f.severity) for f in found if f.severity != "info"] == []
    assert {f.code for f in found} <= {"BK505", "BK605", "BK613"}
    assert _run_setup(TUTORIAL)["entry_points"] == {"console_scripts": ["animation = bras_description.animation:main"]}


def test_the_tutorial_urdf_has_no_pitfall():
    assert [f.code for f in validate_path(str(PITFALLS / "bras_tutoriel.urdf")) if f.code.startswith("BK3")] == []


# ---------------------------------------------------------------- misplaced segments


@pytest.mark.parametrize("name, z", [("coude_z_0_76", 0.76), ("coude_z_0_8", 0.8), ("coude_z_1_2", 1.2)])
def test_elbow_past_the_upper_arm_at_any_distance(name, z):
    (f,) = [f for f in validate_path(str(PITFALLS / f"{name}.urdf")) if f.code == "BK301"]
    assert (f.name, f.variant, f.severity) == ("coude", "beyond", "warning")
    assert f.data["distance"] == pytest.approx(z - 0.6)  # the box runs z 0..0.6 (origin z=0.3, size 0.6)
    assert f.hint_text("en") == "put the joint at the end of 'bras': <origin xyz=\"0 0 0.6\"/>"
    assert f"{round(z - 0.6, 6):g} m" in f.text("en")
    assert "placez l'articulation au bout de 'bras'" in f.hint_text("fr")


def test_elbow_beside_the_upper_arm():
    (f,) = [f for f in validate_path(str(PITFALLS / "coude_a_cote.urdf")) if f.code == "BK301"]
    assert (f.name, f.variant) == ("coude", "beside")
    assert f.data["distance"] == pytest.approx((0.6 ** 2 + 0.6 ** 2) ** 0.5)  # (0.6,0,0) to (0,0,0.6)
    assert f.hint_text("en").endswith('<origin xyz="0 0 0.6"/>')
    assert "à côté du link 'bras'" in f.text("fr")


def test_upper_arm_floating_above_the_base():
    (f,) = [f for f in validate_path(str(PITFALLS / "bras_flottant.urdf")) if f.code == "BK301"]
    assert (f.name, f.variant) == ("epaule", "detached")
    assert f.data["distance"] == pytest.approx(0.3 - 0.05)  # the base cylinder's top face is z=0.05
    assert f.hint_text("en") == "put the joint on the <cylinder> of 'base': <origin xyz=\"0 0 0.05\"/>"


# ---------------------------------------------------------------- the node, read without running it


@pytest.mark.parametrize("mistake, code, line, variant", [
    ("animation_topic_joint_state.py", "BK624", 9, ""),
    ("animation_topic_constant.py", "BK624", 11, ""),
    ("animation_no_timer.py", "BK625", 9, "timer"),
    ("animation_no_publish.py", "BK625", 9, "publish"),
    ("animation_degrees.py", "BK626", 19, ""),
    ("animation_pi_over_180.py", "BK626", 19, ""),
    ("animation_amplitude_degrees.py", "BK626", 19, ""),
])
def test_node_mistakes_are_errors_with_file_line_and_fix(tmp_path, mistake, code, line, variant):
    root = _package_with(tmp_path, animation=MISTAKES / mistake)
    found = [(path, f) for path, f in _findings(root) if f.severity != "info"]
    assert [(Path(path).relative_to(root).as_posix(), f.code, f.line, f.variant) for path, f in found] == [
        ("bras_description/animation.py", code, line, variant)]
    finding = found[0][1]
    assert finding.severity == "error" and finding.hint_text("en")
    assert finding.text("fr") != finding.text("en") and finding.hint_text("fr") != finding.hint_text("en")
    source = (MISTAKES / mistake).read_text(encoding="utf-8").splitlines()
    assert source[line - 1].strip()  # the line named is a line of the learner's file


def test_wrong_topic_is_named_and_not_called_joint_states_by_bk620(tmp_path):
    root = _package_with(tmp_path, animation=MISTAKES / "animation_topic_joint_state.py")
    (f,) = [f for _, f in _findings(root) if f.code == "BK624"]
    assert "'joint_state'" in f.text("en") and "/joint_states" in f.text("en")
    assert "self.create_publisher(JointState, 'joint_states', 10)" in f.hint_text("en")


@pytest.mark.parametrize("right", ["animation_topic_absolute.py", "animation_radians_conversion.py"])
def test_node_written_right_another_way_passes(tmp_path, right):
    root = _package_with(tmp_path, animation=MISTAKES / right)
    assert [f.code for _, f in _findings(root) if f.severity != "info"] == []


# ---------------------------------------------------------------- setup.py as Python runs it


def test_tutorial_lines_pasted_into_a_pkg_create_setup_py_stop_the_build(tmp_path):
    root = _package_with(tmp_path, setup_py=MISTAKES / "setup_pkg_create_tutorial_lines.py")
    with pytest.raises(NameError):  # the oracle: Python itself
        _run_setup(root)
    found = [(f.code, f.data["undefined"], f.hint_text("en")) for _, f in _findings(root) if f.code == "BK607"]
    assert sorted(found) == [("BK607", "glob", "add this line at the top of setup.py: from glob import glob"),
                             ("BK607", "os", "add this line at the top of setup.py: import os")]
    assert all(f.severity == "error" and "NameError" in f.text("fr") for _, f in _findings(root) if f.code == "BK607")


@pytest.mark.parametrize("setup", ["setup_pkg_create.py", "tutorial"])
def test_the_data_files_entry_bk601_suggests_works_pasted_into_that_setup_py(tmp_path, setup):
    if setup == "tutorial":  # the tutorial's setup.py without its urdf line
        root = _package_with(tmp_path)
        text = (root / "setup.py").read_text(encoding="utf-8")
        (root / "setup.py").write_text(text.replace(
            "        (os.path.join('share', package_name, 'urdf'), glob('urdf/*.urdf')),\n", ""), encoding="utf-8")
    else:
        root = _package_with(tmp_path, setup_py=MISTAKES / setup)
    missing = [f for _, f in _findings(root) if f.code == "BK601"]
    assert missing
    text = (root / "setup.py").read_text(encoding="utf-8")
    for f in missing:
        entry = re.fullmatch(r"add (.*) to data_files, then run colcon build again", f.hint_text("en")).group(1)
        text = text.replace("['package.xml']),\n", f"['package.xml']),\n        {entry},\n", 1)
    (root / "setup.py").write_text(text, encoding="utf-8")
    data_files = dict(_run_setup(root)["data_files"])  # runs: no NameError
    assert data_files["share/bras_description/urdf"] == ["urdf/bras.urdf"] or \
        data_files[os.path.join("share", "bras_description", "urdf")] == ["urdf/bras.urdf"]
    assert [f.code for _, f in _findings(root) if f.code in ("BK601", "BK607")] == []


# ---------------------------------------------------------------- XML errors and paths


def test_forgotten_closing_link_is_named_with_its_opening_line():
    (f,) = validate_path(str(PITFALLS / "link_non_ferme.urdf"))
    assert (f.code, f.line) == ("BK100", 13)
    assert f.text("en") == ('not well-formed XML: the tag <link name="bras"> opened on line 13 is never closed: '
                            'the reader met </robot> on line 47 while <link name="bras"> was still open')
    assert f.text("fr").startswith('XML mal formé : la balise <link name="bras"> ouverte ligne 13 n\'est jamais fermée')


def test_expat_reasons_are_worded_never_left_as_the_whole_message(tmp_path):
    path = tmp_path / "bras.urdf"
    path.write_text('<robot name="bras">\n  <link name=bras/>\n</robot>\n', encoding="utf-8")
    (f,) = validate_path(str(path))
    assert "invalid token" not in f.text("en") and "(line 2, column" in f.text("en")
    assert f.text("fr").startswith("XML mal formé : un caractère qui ne peut") and "(ligne 2, colonne" in f.text("fr")


def test_a_misspelled_file_name_suggests_the_file_beside_it(tmp_path):
    shutil.copy(TUTORIAL / "urdf" / "bras.urdf", tmp_path / "bras.urdf")
    (f,) = validate_path(str(tmp_path / "bra.urdf"))
    assert (f.code, f.variant) == ("BK103", "near")
    assert f.hint_text("en") == f"did you mean {tmp_path / 'bras.urdf'}? It is in the same folder"


def test_a_windows_style_path_is_recognised():
    (f,) = validate_path("urdf\\bras.urdf")
    assert (f.code, f.variant) == ("BK103", "windows")
    assert f.hint_text("en") == "write the path with '/': urdf/bras.urdf"
    assert "Windows" in f.text("fr")


# ---------------------------------------------------------------- the launch file


@pytest.mark.parametrize("mistake, variant", [("launch_no_parameters.launch.py", "none"),
                                               ("launch_wrong_parameter.launch.py", "")])
def test_robot_state_publisher_without_robot_description_is_an_error(tmp_path, mistake, variant):
    root = tmp_path / "bras_description"
    shutil.copytree(TUTORIAL, root)
    shutil.copy(MISTAKES / mistake, root / "launch" / "affichage.launch.py")
    found = [(Path(path).relative_to(root).as_posix(), f) for path, f in _findings(root) if f.severity != "info"]
    assert [(path, f.code, f.line, f.variant) for path, f in found] == [
        ("launch/affichage.launch.py", "BK614", 13, variant)]
    assert "parameters=[{'robot_description': description}]" in found[0][1].hint_text("en")
    assert "RViz reste" in found[0][1].text("fr")
