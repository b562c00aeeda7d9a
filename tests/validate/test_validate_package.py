"""bras-kit validate PKGDIR: the package rules (BK6xx) on packages made by `bras-kit new`, on the
tutorial's package as a learner writes it, and on one broken copy per defect
(tests/data/package_defects/NAME.yaml, checked by test_NAME)."""

from __future__ import annotations

import json
import math
import shutil
import subprocess
import sys
from collections import Counter
from pathlib import Path

import pytest
import yaml
from paths import TESTS

from bras_kit.scaffold.package import scaffold_package
from bras_kit.validate import RULES
from bras_kit.validate.package import find_packages, validate_package

DATA = TESTS / "data"
DEFECTS = DATA / "package_defects"
TUTORIAL = DATA / "package_tutorial"
PKG = "bras_description"

VARIANTS = {
    "default": {},
    "wrist": {"wrist": True},
    "inertials": {"inertials": True},
    "wrist_inertials": {"wrist": True, "inertials": True},
    "named": {"name": "mon_bras", "maintainer": "eleve", "email": "eleve@exemple.fr"},
    "narrow_limits": {"wrist": True, "params": {"epaule_lower": -0.3, "coude_upper": 0.5, "coude_velocity": 0.5,
                                                "poignet_lower": 0.2, "poignet_upper": 0.6}},
    "full_name": {"maintainer": "Élodie Le Gall"},
    "other_lengths": {"params": {"bras_length": 0.8, "avant_bras_length": 0.3, "bras_width": 0.1}},
}


def bk6(results) -> list[tuple[str, str, int | None]]:
    """(code, file relative to the package, line) of every package finding."""
    out = []
    for result in results:
        for finding in result.findings:
            out.append((finding.code, result.path, finding.line))
    return out


def relative_findings(results, root: Path) -> Counter:
    return Counter((code, Path(path).relative_to(root).as_posix(), line) for code, path, line in bk6(results))


def run_cli(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "bras_kit", *args], capture_output=True, text=True,
                          encoding="utf-8", timeout=120)


# ---------------------------------------------------------------- clean packages


@pytest.mark.parametrize("variant", sorted(VARIANTS))
def test_every_scaffolded_variant_is_clean(tmp_path, variant):
    options = dict(VARIANTS[variant])
    name = options.pop("name", PKG)
    dest = tmp_path / name
    scaffold_package(dest, name=name, **options)
    results = validate_package(str(dest))
    assert bk6(results) == []
    read = {Path(r.path).relative_to(dest).as_posix() for r in results}
    assert {"package.xml", "setup.py", "launch/affichage.launch.py", f"rviz/{name}.rviz",
            f"{name}/animation.py", f"{name}/motion.py"} <= read


def test_scaffolded_package_passes_the_whole_validator_from_the_command_line(tmp_path):
    dest = tmp_path / PKG
    scaffold_package(dest, wrist=True, inertials=True)
    done = run_cli("validate", str(dest), "--format", "json")
    assert done.returncode == 0, done.stdout + done.stderr
    files = {Path(f["path"]).relative_to(dest).as_posix(): f for f in json.loads(done.stdout)["files"]}
    assert {"setup.py", "package.xml", "urdf/bras.urdf"} <= set(files)
    # nothing above info: the base carries its <inertial> and is fixed to a bare 'world' root (no
    # inertia on the root for robot_state_publisher's KDL, no root dropped by Gazebo, no arm falling over)
    others = [(path, x["code"]) for path, f in files.items() for x in f["findings"] if x["severity"] != "info"]
    assert others == []


def test_scaffolded_package_passes_catkin_pkg(tmp_path):
    """catkin_pkg (what colcon reads package.xml with) accepts what the scaffold writes."""
    from catkin_pkg.package import parse_package

    for variant in ("default", "named", "full_name"):
        options = dict(VARIANTS[variant])
        name = options.pop("name", PKG)
        scaffold_package(tmp_path / variant / name, name=name, **options)
        assert parse_package(str(tmp_path / variant / name)).name == name


def test_scaffold_default_email_is_made_from_the_name(tmp_path):
    scaffold_package(tmp_path / PKG, maintainer="Élodie Le Gall")
    assert 'email="elodie.le.gall@todo.todo"' in (tmp_path / PKG / "package.xml").read_text(encoding="utf-8")


@pytest.mark.parametrize("options", [{"email": "TODO"}, {"maintainer": "Jean O'Brien"}, {"maintainer": "A & B"}])
def test_scaffold_refuses_what_would_make_a_broken_package(tmp_path, options):
    """An email catkin_pkg refuses (BK606), a name that breaks setup.py or package.xml (BK600)."""
    from bras_kit.core.errors import ParameterError

    with pytest.raises(ParameterError):
        scaffold_package(tmp_path / PKG, **options)
    assert not (tmp_path / PKG).exists()


# ---------------------------------------------------------------- the tutorial's own package


def test_tutorial_package_as_written(tmp_path):
    """The tutorial's package: RViz started without -d, and nodes started without <exec_depend>."""
    results = validate_package(str(TUTORIAL))
    found = relative_findings(results, TUTORIAL)
    launch = (TUTORIAL / "launch/affichage.launch.py").read_text(encoding="utf-8").splitlines()
    rviz_line = next(k for k, text in enumerate(launch, 1) if "package='rviz2'" in text)
    xml = (TUTORIAL / "package.xml").read_text(encoding="utf-8").splitlines()
    last_depend = max(k for k, text in enumerate(xml, 1) if "<depend>" in text)
    assert found == Counter({("BK613", "launch/affichage.launch.py", rviz_line): 1,
                             ("BK605", "package.xml", last_depend): 3})
    messages = [f.text("en") for r in results for f in r.findings if f.code == "BK605"]
    assert sorted(m.split("'")[1] for m in messages) == ["joint_state_publisher_gui", "robot_state_publisher", "rviz2"]


def test_tutorial_node_formulas_are_within_the_limits():
    """0.8 sin t and 1.2 sin 0.7t stay inside ±1.57 and ±2.0: no BK623."""
    results = validate_package(str(TUTORIAL), select=["BK623"])
    assert bk6(results) == []


# ---------------------------------------------------------------- one broken copy per defect


def build_defect(name: str, tmp_path: Path) -> tuple[Path, Path, dict]:
    """The unedited base and its broken copy, as described by package_defects/NAME.yaml."""
    spec = yaml.safe_load((DEFECTS / f"{name}.yaml").read_text(encoding="utf-8"))
    copies = []
    for label in ("base", "broken"):
        dest = tmp_path / label / PKG
        if spec["base"] == "tutorial":
            shutil.copytree(TUTORIAL, dest)
        else:
            scaffold_package(dest, **spec.get("options", {}))
        copies.append(dest)
    base, broken = copies
    for edit in spec["edits"]:
        if "delete" in edit:
            (broken / edit["delete"]).unlink()
            continue
        path = broken / edit["file"]
        text = path.read_text(encoding="utf-8")
        assert text.count(edit["replace"]) == 1, f"{name}: the text to replace is not in {edit['file']} once"
        path.write_text(text.replace(edit["replace"], edit["with"]), encoding="utf-8")
    return base, broken, spec


def expected_line(root: Path, item: dict) -> int | None:
    if "line" in item:
        return item["line"]
    lines = (root / item["file"]).read_text(encoding="utf-8").splitlines()
    if "line_is" in item:
        return next(k for k, text in enumerate(lines, 1) if text == item["line_is"])
    return next(k for k, text in enumerate(lines, 1) if item["line_with"] in text)


def check_defect(name: str, tmp_path: Path) -> list:
    """Build the copy, check it in English and French; the new findings are exactly the expected ones."""
    base, broken, spec = build_defect(name, tmp_path)
    before = relative_findings(validate_package(str(base)), base)
    english = validate_package(str(broken))
    after = relative_findings(english, broken)
    expected = Counter((item["code"], item["file"], expected_line(broken, item)) for item in spec["expect"])
    assert after - before == expected
    assert not before - after, "the edit made a finding of the base disappear"
    new = [f for r in english for f in r.findings if f.code in {c for c, _, _ in expected}]
    for finding in new:  # the same finding, worded in each language where it is shown
        assert finding.text("en") and finding.text("fr") and finding.text("en") != finding.text("fr")
        assert finding.hint_text("en") and finding.hint_text("fr") and finding.hint_text("en") != finding.hint_text("fr")
    return new


def test_urdf_folder_not_installed(tmp_path):
    (finding,) = check_defect("urdf_folder_not_installed", tmp_path)
    assert "urdf/" in finding.text("en") and "('urdf/bras.urdf')" in finding.text("en")
    assert "(os.path.join('share', package_name, 'urdf'), glob('urdf/*.urdf'))" in finding.hint_text("en")


def test_launch_folder_not_installed(tmp_path):
    (finding,) = check_defect("launch_folder_not_installed", tmp_path)
    assert "'launch/affichage.launch.py'" in finding.text("en")
    assert "glob('launch/*.launch.py')" in finding.hint_text("en")


def test_rviz_config_not_installed(tmp_path):
    (finding,) = check_defect("rviz_config_not_installed", tmp_path)
    assert finding.severity == "info"
    assert "rviz/bras_description.rviz, which setup.py does not install" in finding.text("en")


def test_launch_opens_misspelled_urdf(tmp_path):
    (finding,) = check_defect("launch_opens_misspelled_urdf", tmp_path)
    assert "share/bras_description/urdf/robot.urdf" in finding.text("en")
    assert "'urdf/bras.urdf'" in finding.text("en")


def test_ament_marker_file_missing(tmp_path):
    (finding,) = check_defect("ament_marker_file_missing", tmp_path)
    assert finding.hint_text("en") == "create the empty file resource/bras_description"


def test_ament_index_entry_missing(tmp_path):
    (finding,) = check_defect("ament_index_entry_missing", tmp_path)
    assert "share/ament_index/resource_index/packages" in finding.text("en")


def test_package_xml_name_differs(tmp_path):
    (finding,) = check_defect("package_xml_name_differs", tmp_path)
    assert "'bras_desc'" in finding.text("en") and "'bras_description'" in finding.text("en")


def test_launch_dependency_not_declared(tmp_path):
    (finding,) = check_defect("launch_dependency_not_declared", tmp_path)
    assert finding.hint_text("en") == "add <exec_depend>rviz2</exec_depend> to package.xml"


def test_maintainer_email_invalid(tmp_path):
    from catkin_pkg.package import InvalidPackage, parse_package

    (finding,) = check_defect("maintainer_email_invalid", tmp_path)
    assert "'TODO'" in finding.text("en")
    # the oracle: catkin_pkg, which colcon uses, accepts the base and refuses the broken copy
    assert parse_package(str(tmp_path / "base" / PKG)).name == PKG
    with pytest.raises(InvalidPackage, match="Invalid email"):
        parse_package(str(tmp_path / "broken" / PKG))


def test_fixed_frame_not_a_link(tmp_path):
    (finding,) = check_defect("fixed_frame_not_a_link", tmp_path)
    assert "'map'" in finding.text("en") and finding.hint_text("en").startswith("set Fixed Frame to 'base'")


def test_no_robot_model_display(tmp_path):
    (finding,) = check_defect("no_robot_model_display", tmp_path)
    assert "no RobotModel display" in finding.text("en")


def test_description_topic_wrong(tmp_path):
    (finding,) = check_defect("description_topic_wrong", tmp_path)
    assert "'/robot_desc'" in finding.text("en") and finding.severity == "error"


def test_no_tf_display(tmp_path):
    (finding,) = check_defect("no_tf_display", tmp_path)
    assert finding.severity == "info"


def test_rviz_started_without_config(tmp_path):
    (finding,) = check_defect("rviz_started_without_config", tmp_path)
    assert "rviz/bras_description.rviz is not used" in finding.text("en")
    assert finding.severity == "info"


def test_nothing_publishes_joint_states(tmp_path):
    (finding,) = check_defect("nothing_publishes_joint_states", tmp_path)
    assert "bras_description.animation does, but is not started" in finding.text("en")
    assert "'epaule', 'coude'" in finding.text("en")


def test_wrist_missing_from_joint_state_names(tmp_path):
    (finding,) = check_defect("wrist_missing_from_joint_state_names", tmp_path)
    assert finding.text("en").startswith("JointState never names 'poignet'")


def test_unknown_joint_state_name(tmp_path):
    findings = check_defect("unknown_joint_state_name", tmp_path)
    assert sorted(f.data["names"][0] for f in findings) == ["epaule", "shoulder"]


def test_launched_node_has_no_entry_point(tmp_path):
    findings = check_defect("launched_node_has_no_entry_point", tmp_path)
    assert {f.hint_text("en") for f in findings} == {"add 'animation = bras_description.animation:main' to "
                                          "entry_points['console_scripts'] in setup.py"}


def test_entry_point_module_misspelled(tmp_path):
    findings = check_defect("entry_point_module_misspelled", tmp_path)
    assert any("points to bras_description.animaton, which does not exist" in f.text("en") for f in findings)


def test_node_not_written_yet(tmp_path):
    """Step 5 of the tutorial with step 7's entry typed ahead: the next step (info), no BK622 error."""
    (finding,) = check_defect("node_not_written_yet", tmp_path)
    assert finding.severity == "info"
    assert "bras_description/animation.py, not written yet" in finding.text("en")
    assert "pas encore écrit" in finding.text("fr")


def _elbow_peaks(findings) -> dict[str, tuple[float, float]]:
    return {"upper" if f.data["bound"] > 0 else "lower": (f.data["value"], f.data["time"]) for f in findings}


# 2.5 sin(0.7 t) first passes +2.0 when sin(0.7 t) = 0.8, i.e. t = asin(0.8) / 0.7 = 1.3247 s, and -2.0
# at t = (pi + asin(0.8)) / 0.7 = 5.8127 s; at 20 Hz the first sample past is at most 0.05 s later.
FIRST_ABOVE = math.asin(0.8) / 0.7
FIRST_BELOW = (math.pi + math.asin(0.8)) / 0.7


def test_node_motion_beyond_limits(tmp_path):
    findings = check_defect("node_motion_beyond_limits", tmp_path)
    peaks = _elbow_peaks(findings)
    assert peaks["upper"][0] == pytest.approx(2.5, abs=2e-3)
    assert 0 <= peaks["upper"][1] - FIRST_ABOVE <= 0.05 + 1e-9
    assert peaks["lower"][0] == pytest.approx(-2.5, abs=2e-3)
    assert 0 <= peaks["lower"][1] - FIRST_BELOW <= 0.05 + 1e-9
    assert all(f.data["joint"] == "coude" for f in findings)


def test_tutorial_node_motion_beyond_limits(tmp_path):
    findings = check_defect("tutorial_node_motion_beyond_limits", tmp_path)
    peaks = _elbow_peaks(findings)
    assert peaks["upper"][0] == pytest.approx(2.5, abs=2e-3)
    assert 0 <= peaks["upper"][1] - FIRST_ABOVE <= 0.05 + 1e-9
    assert "2.5 * sin(0.7 * t)" in findings[0].text("en")


def test_timer_period_in_hertz(tmp_path):
    (finding,) = check_defect("timer_period_in_hertz", tmp_path)
    assert finding.text("en") == "create_timer(20, ...) fires every 20 s, not 20 times a second"
    assert "create_timer(1 / 20, ...) = 0.05 s for 20 Hz" in finding.hint_text("en")


def test_setup_py_syntax_error(tmp_path):
    (finding,) = check_defect("setup_py_syntax_error", tmp_path)
    source = (tmp_path / "broken" / PKG / "setup.py").read_text(encoding="utf-8")
    with pytest.raises(SyntaxError) as python_says:
        compile(source, "setup.py", "exec")
    assert finding.line == python_says.value.lineno


def test_package_xml_not_well_formed(tmp_path):
    (finding,) = check_defect("package_xml_not_well_formed", tmp_path)
    assert finding.text("en").startswith("package.xml cannot be read")


def test_every_defect_file_has_its_test():
    names = {path.stem for path in DEFECTS.glob("*.yaml")}
    tests = {name.removeprefix("test_") for name in globals() if name.startswith("test_")}
    assert names <= tests


def test_every_package_rule_is_triggered_by_a_defect():
    expected = {item["code"] for path in DEFECTS.glob("*.yaml")
                for item in yaml.safe_load(path.read_text(encoding="utf-8"))["expect"]}
    expected |= {"BK605", "BK613"}  # also by the tutorial's own package
    expected |= {"BK615"}  # evaluated launches only: tests/ros/test_rviz_one_story.py
    expected |= {"BK607", "BK614", "BK624", "BK625", "BK626"}  # tests/validate/test_validate_tutorial.py, on the tutorial's files
    expected |= {"BK630", "BK631", "BK632", "BK633"}  # tests/ros/test_ros_launch.py, on tests/data/launch/<case>/
    expected |= {"BK639"}  # tests/trust/test_trust_hostile_packages.py, on tests/data/hostile_packages/<case>/
    expected |= {"BK634", "BK635"}  # tests/ros/test_launch_fidelity.py, on tests/data/launch/fidelity/
    expected |= {"BK628", "BK629"}  # tests/validate/test_validate_setup_cfg.py, against the system setuptools
    # BK640-BK659 read a run of the node: tests/run/test_run.py triggers each one
    assert {code for code in RULES if code.startswith("BK6") and code < "BK64"} == expected


# ---------------------------------------------------------------- command line


@pytest.fixture()
def broken_package(tmp_path) -> Path:
    _, broken, _ = build_defect("wrist_missing_from_joint_state_names", tmp_path)
    return broken


def test_cli_reports_package_findings_with_file_and_line(broken_package):
    done = run_cli("validate", str(broken_package), "--lang", "en")
    assert done.returncode == 1
    lines = (broken_package / f"{PKG}/animation.py").read_text(encoding="utf-8").splitlines()
    line = next(k for k, text in enumerate(lines, 1) if "state.name =" in text)
    assert f"{broken_package / PKG / 'animation.py'}:{line}: BK621 error JointState never names 'poignet'" in done.stdout
    assert "Traceback" not in done.stderr


def test_cli_french_and_json(broken_package):
    done = run_cli("validate", str(broken_package), "--lang", "fr", "--format", "json", "--select", "BK6")
    assert done.returncode == 1
    document = json.loads(done.stdout)
    findings = [f for entry in document["files"] for f in entry["findings"]]
    assert [f["code"] for f in findings] == ["BK621"]
    assert findings[0]["message"].startswith("JointState ne nomme jamais 'poignet'")
    assert document["summary"]["errors"] == 1


def test_cli_ignore_drops_package_rules(broken_package):
    done = run_cli("validate", str(broken_package), "--ignore", "BK6")
    assert done.returncode == 0, done.stdout


@pytest.mark.parametrize("lang, words", [
    ("en", "folder the launch needs is not installed by setup.py.\n\ncolcon copies"),
    ("fr", "dossier dont le lancement a besoin n'est pas installé par setup.py.\n\ncolcon ne copie"),
])
def test_explain_package_rule(lang, words):
    done = run_cli("explain", "BK601", "--lang", lang)
    assert done.returncode == 0
    assert done.stdout.startswith("BK601 folder-not-installed")
    assert words in done.stdout


def test_find_packages_walks_a_workspace(tmp_path):
    scaffold_package(tmp_path / "src" / "un")
    scaffold_package(tmp_path / "src" / "deux", name="deux")
    (tmp_path / "src" / "pas_un_paquet").mkdir()
    assert find_packages([str(tmp_path)]) == [str(tmp_path / "src" / "deux"), str(tmp_path / "src" / "un")]


# ---------------------------------------------------------------- hostile or unusual packages


def test_package_files_are_read_never_run(tmp_path):
    """setup.py, the launch file, the node and the .rviz file each try to leave a mark; none may."""
    dest = tmp_path / PKG
    scaffold_package(dest)
    mark = tmp_path / "ran"
    code = f"\nopen({str(mark)!r}, 'w').write('ran')\n"
    for relative in ("setup.py", "launch/affichage.launch.py", f"{PKG}/animation.py", f"{PKG}/motion.py"):
        with open(dest / relative, "a", encoding="utf-8") as handle:
            handle.write(code)
    rviz = dest / f"rviz/{PKG}.rviz"
    rviz.write_text(f"!!python/object/apply:os.system ['touch {mark}']\n", encoding="utf-8")
    results = validate_package(str(dest))
    assert not mark.exists()
    assert ("BK600", f"rviz/{PKG}.rviz") in {(c, Path(p).relative_to(dest).as_posix()) for c, p, _ in bk6(results)}


def test_unsafe_package_xml_is_refused(tmp_path):
    dest = tmp_path / PKG
    scaffold_package(dest)
    xml = dest / "package.xml"
    text = xml.read_text(encoding="utf-8").replace(
        '<package format="3">', '<!DOCTYPE p [<!ENTITY e SYSTEM "file:///etc/passwd">]>\n<package format="3">')
    xml.write_text(text.replace("<license>Apache-2.0</license>", "<license>&e;</license>"), encoding="utf-8")
    (finding,) = [f for r in validate_package(str(dest)) for f in r.findings]
    assert finding.code == "BK600" and "DTD" in finding.text("en")


def test_runaway_setup_py_stays_unknown_and_quiet(tmp_path):
    """A string doubled 200 times, then expressions nested 200,000 deep: no crash, no false finding."""
    dest = tmp_path / PKG
    scaffold_package(dest)
    setup = dest / "setup.py"
    doubling = "s = 'x'\n" + "s = s + s\n" * 200
    text = setup.read_text(encoding="utf-8").replace("package_name = ", doubling + "package_name = ")
    setup.write_text(text, encoding="utf-8")
    assert bk6(validate_package(str(dest))) == []
    setup.write_text("x = " + "(" * 200_000 + ")" * 200_000 + "\n", encoding="utf-8")  # Python: SyntaxError
    assert relative_findings(validate_package(str(dest)), dest) == Counter({("BK600", "setup.py", 1): 1})
    setup.write_text("x = " + "-" * 200_000 + "1\n", encoding="utf-8")  # Python: MemoryError
    (finding,) = [f for r in validate_package(str(dest)) for f in r.findings]
    assert finding.code == "BK600" and finding.text("en") == "setup.py cannot be read: too deeply nested to read"


def test_rviz_config_that_cannot_be_followed_is_not_reported_missing(tmp_path):
    """arguments=['-d' + path] is not understood: no claim that RViz starts without a configuration."""
    dest = tmp_path / PKG
    scaffold_package(dest)
    launch = dest / "launch/affichage.launch.py"
    text = launch.read_text(encoding="utf-8")
    launch.write_text(text.replace("arguments=['-d', rviz_config]", "arguments=['-d' + rviz_config]"), encoding="utf-8")
    assert bk6(validate_package(str(dest))) == []


def test_included_launch_file_may_publish_joint_states(tmp_path):
    """A launch file that includes another one may get /joint_states from it: BK620 stays quiet."""
    _, broken, _ = build_defect("nothing_publishes_joint_states", tmp_path)
    launch = broken / "launch/affichage.launch.py"
    text = launch.read_text(encoding="utf-8")
    text = text.replace("    return LaunchDescription([", "    other = IncludeLaunchDescription(PythonLaunchDescriptionSource('x'))\n"
                        "    return LaunchDescription([other,")
    launch.write_text(text, encoding="utf-8")
    assert "BK620" not in {c for c, _, _ in bk6(validate_package(str(broken)))}


def test_cli_on_a_package_with_an_unreadable_setup_py_prints_no_traceback(tmp_path):
    dest = tmp_path / PKG
    scaffold_package(dest)
    (dest / "setup.py").write_bytes(b"\xff\xfe\x00 not python")
    done = run_cli("validate", str(dest))
    assert done.returncode == 1
    assert "BK600" in done.stdout and "Traceback" not in done.stderr


@pytest.mark.slow
@pytest.mark.parametrize("relative", ["setup.py", "package.xml", "launch/affichage.launch.py", f"rviz/{PKG}.rviz",
                                      f"{PKG}/animation.py", f"{PKG}/motion.py"])
def test_deleting_any_one_line_never_raises(tmp_path, relative):
    """Every copy of the package with one line of one file deleted is checked without an exception,
    and every finding names a file and, when it has one, a line inside that file."""
    dest = tmp_path / PKG
    scaffold_package(dest, wrist=True)
    path = dest / relative
    original = path.read_text(encoding="utf-8").splitlines(keepends=True)
    for k in range(len(original)):
        path.write_text("".join(original[:k] + original[k + 1:]), encoding="utf-8")
        for result in validate_package(str(dest)):
            shown = Path(result.path)
            for finding in result.findings:
                if finding.line is not None:
                    assert 1 <= finding.line <= len(shown.read_text(encoding="utf-8").splitlines()), (k, finding)


def test_joint_state_built_with_keywords_is_read(tmp_path):
    """JointState(name=[...], position=[...]) is read like msg.name = ...; other .name attributes are not."""
    dest = tmp_path / PKG
    shutil.copytree(TUTORIAL, dest)
    node = dest / PKG / "animation.py"
    text = node.read_text(encoding="utf-8")
    text = text.replace("        msg = JointState()\n", "        self.name = 'animation'\n        msg = JointState(\n"
                        "            name=['epaule', 'coude', 'poignet'],\n"
                        "            position=[0.8 * math.sin(self.t), 3 * math.sin(self.t), 0.0])\n")
    text = text.replace("        msg.name = ['epaule', 'coude']\n", "")
    text = text.replace("        msg.position = [0.8 * math.sin(self.t), 1.2 * math.sin(0.7 * self.t)]\n", "")
    node.write_text(text, encoding="utf-8")
    lines = text.splitlines()
    keywords_line = next(k for k, t in enumerate(lines, 1) if "name=['epaule'" in t)
    position_line = next(k for k, t in enumerate(lines, 1) if "position=[" in t)
    found = relative_findings(validate_package(str(dest), select=["BK621", "BK623"]), dest)
    assert found == Counter({("BK621", f"{PKG}/animation.py", keywords_line): 1,
                             ("BK623", f"{PKG}/animation.py", position_line): 2})


def test_data_files_completed_by_a_loop_are_not_reported(tmp_path):
    """data_files that a loop completes cannot be followed without running setup.py: no BK601."""
    dest = tmp_path / PKG
    scaffold_package(dest)
    setup = dest / "setup.py"
    text = setup.read_text(encoding="utf-8")
    text = text.replace("        installed('urdf', '*.urdf', '*.xacro'),\n", "")
    text = text.replace("setup(\n", "files = [\n        ('share/ament_index/resource_index/packages', ['resource/' + package_name]),\n"
                        "        ('share/' + package_name, ['package.xml']),\n"
                        "        installed('launch', '*.launch.py'),\n        installed('rviz', '*.rviz'),\n]\n"
                        "for folder in ('urdf',):\n    files.append(installed(folder, '*.urdf', '*.xacro'))\n\nsetup(\n")
    start = text.index("    data_files=[")
    end = text.index("    ],\n", start) + len("    ],\n")
    setup.write_text(text[:start] + "    data_files=files,\n" + text[end:], encoding="utf-8")
    compile(setup.read_text(encoding="utf-8"), "setup.py", "exec")
    assert bk6(validate_package(str(dest))) == []
    # the same list without the loop: now urdf/ is really missing
    setup.write_text(setup.read_text(encoding="utf-8").replace(
        "for folder in ('urdf',):\n    files.append(installed(folder, '*.urdf', '*.xacro'))\n", ""), encoding="utf-8")
    assert [code for code, _, _ in bk6(validate_package(str(dest)))] == ["BK601"]


@pytest.mark.parametrize(("written", "lang", "said"), [
    ("Node(package='robot_state_publiser'", "en", "did you mean 'robot_state_publisher'?"),
    ("Node(package='robot_state_publiser'", "fr", "vouliez-vous dire 'robot_state_publisher' ?"),
    ("Node(package='joint_state_publisher_gu'", "en", "did you mean 'joint_state_publisher_gui'?"),
    ("PACKAGE = 'bras_descripton'", "en", "use the name in package.xml ('bras_description')"),
    ("PACKAGE = 'bras_descripton'", "fr", "utilisez le nom de package.xml ('bras_description')"),
])
def test_a_package_launch_cannot_find_is_named_with_the_one_meant(tmp_path, written, lang, said):
    """ROS's "package 'X' not found" (BK631): a ROS package misspelled is named as the one the tutorial
    starts; the learner's own package misspelled sends to package.xml's name."""
    from bras_kit.core.i18n import say
    from bras_kit.validate.package import Package

    root = tmp_path / PKG
    scaffold_package(str(root))
    launch = root / "launch" / "affichage.launch.py"
    original = {"Node(package='robot_state_publiser'": "Node(package='robot_state_publisher'",
                "Node(package='joint_state_publisher_gu'": "Node(package='joint_state_publisher_gui'",
                "PACKAGE = 'bras_descripton'": "PACKAGE = 'bras_description'"}[written]
    text = launch.read_text()
    assert text.count(original) == 1
    launch.write_text(text.replace(original, written))
    found = [f for r in validate_package(str(root), package=Package(str(root)), launch=True) for f in r.findings
             if f.code == "BK631"]
    assert len(found) == 1, found
    assert said in say(found[0].hint, lang), say(found[0].hint, lang)
