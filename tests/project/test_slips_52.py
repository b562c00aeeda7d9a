"""Slips a learner notices (issue 52, item 7), each against an oracle outside the code it tests."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import pytest
from paths import TESTS

DATA = TESTS / "data"
TUTORIAL_URDF = (DATA / "live" / "bras.urdf").read_text(encoding="utf-8")


# --- doctor --ros names the root link the learner sets Fixed Frame to --------------------------------

def _healthy_look(urdf: str):  # type: ignore[no-untyped-def]
    from bras_kit.ros.graph import snapshot_from_json

    return snapshot_from_json({"descriptions": [{"text": urdf, "received": 1.0, "length": len(urdf)}],
                               "nodes": ["/robot_state_publisher"], "started": 0.0, "ended": 3.0})


@pytest.mark.parametrize("root", ["base", "socle", "world_link"])
@pytest.mark.parametrize(("lang", "words"), [("en", "set Fixed Frame to {root} and"),
                                             ("fr", "réglez Fixed Frame sur {root} et")])
def test_doctor_ros_names_the_root_link_to_set_as_fixed_frame(root, lang, words):
    from bras_kit.cli._doctor_ros import _text

    # the oracle: the root is the link no joint has as child, renamed here by hand in the tutorial's text
    urdf = TUTORIAL_URDF.replace('"base"', f'"{root}"')
    assert f'<link name="{root}"' in urdf
    text = _text(_healthy_look(urdf), [], lang)
    assert words.format(root=root) in text
    assert "link racine" not in text and "root link" not in text


# --- French plurals: 0 and 1 take the singular, and each count agrees with its own noun -------------------

class _Counted:
    """A file's results as _text reads them: no finding shown, only the counts."""

    def __init__(self, errors: int, warnings: int) -> None:
        self.findings: list[object] = []
        self._counts = {"error": errors, "warning": warnings}

    def count(self, severity: str) -> int:
        return self._counts[severity]


# the oracle: French grammar (Grevisse § 518): the plural begins at 2, 0 and 1 take the singular
def _french_noun(n: int, singular: str, plural: str) -> str:
    return f"{n} {singular if n < 2 else plural}"


@pytest.mark.parametrize("warnings", [0, 1, 2, 7])
def test_doctor_counts_its_warnings_in_french(warnings):
    from bras_kit.cli._doctor_ros import _text

    text = _text(_healthy_look(TUTORIAL_URDF), [_Counted(1, warnings)], "fr")
    assert f"({_french_noun(warnings, 'avertissement', 'avertissements')})" in text
    text = _text(_healthy_look(TUTORIAL_URDF), [_Counted(1, warnings)], "en")
    assert f"({warnings} warning{'' if warnings == 1 else 's'})" in text


def _one_link_robot():  # type: ignore[no-untyped-def]
    from bras_kit.model.robot import robot_from_xml
    from bras_kit.model.xmlio import parse_xml

    text = '<robot name="seul"><link name="base"/></robot>'
    return robot_from_xml(parse_xml(text, "seul.urdf"), path="seul.urdf", source_text=text)


@pytest.mark.parametrize(("wrist", "links"), [(None, 1), (False, 3), (True, 4)])
def test_the_frame_tree_title_agrees_with_its_counts(wrist, links):
    from bras_kit.diagrams.dot import graph_title
    from bras_kit.kinematics.frames import tf_tree
    from bras_kit.model.authoring import arm

    robot = _one_link_robot() if wrist is None else arm(wrist=wrist)
    tree = tf_tree(robot)
    assert len(tree.links) == links  # counted by hand: base, bras, avant_bras (+ poignet's link)
    joints = movable = links - 1  # every joint of the arm is revolute
    title = graph_title(robot, tree, None, "fr")
    assert (f"{_french_noun(links, 'segment', 'segments')}, {_french_noun(joints, 'articulation', 'articulations')} "
            f"({_french_noun(movable, 'mobile', 'mobiles')})") in title


def test_frames_says_one_frame_and_zero_joint_in_french(run_cli, tmp_path):
    robot = tmp_path / "seul.urdf"
    robot.write_text('<robot name="seul"><link name="base"/></robot>')
    code, _, err = run_cli("frames", str(robot), "-o", str(tmp_path / "f.svg"), "--lang", "fr")
    assert code == 0, err
    assert "1 repère, 0 articulation" in err


@pytest.mark.parametrize(("count", "words"), [(1, "enregistré :"), (2, "enregistrés :"), (3, "enregistrés :")])
def test_files_saved_agree_with_their_number(count, words):
    from bras_kit.core.i18n import say
    from bras_kit.core.message import Mn

    names = ", ".join(["urdf/bras.urdf", "setup.py", "launch/affichage.launch.py"][:count])
    # the very message launch's live loop prints (bras_kit/launcher/relaunch.py, live)
    message = Mn("{files} saved: the package is built and launched again",
                 "{files} saved: the package is built and launched again", count, files=names)
    assert say(dataclasses.replace(message, domain="cli"), "fr").startswith(f"{names} {words}")


# --- bras-kit urdf's output is clean of bras-kit's own findings, and says the formulas BK507 points to ---

def _validate_clean(run_cli, path: Path) -> str:
    code, out, err = run_cli("validate", str(path), "--lang", "en")
    return f"exit {code}\n{out}{err}"


@pytest.mark.parametrize("wrist", [False, True])
@pytest.mark.parametrize("inertials", [False, True])
@pytest.mark.parametrize("collisions", [False, True])
@pytest.mark.parametrize("params", [(), ("bras_length=0.8",), ("avant_bras_mass=2", "coude_upper=2.5")])
def test_every_urdf_option_combination_validates_clean(run_cli, tmp_path, wrist, inertials, collisions, params):
    argv = ["urdf", "-o", str(tmp_path / "bras.urdf")]
    argv += ["--wrist"] * wrist + ["--inertials"] * inertials + ["--collisions"] * collisions
    for param in params:
        argv += ["--param", param]
    code, _, err = run_cli(*argv)
    assert code == 0, err
    report = _validate_clean(run_cli, tmp_path / "bras.urdf")
    if inertials:  # nothing at all, not even an info
        assert report.startswith("exit 0\n") and "no problems found" in report, report
    else:  # the tutorial's own arm has no inertia: the one info that points to --inertials, nothing else
        assert report.startswith("exit 0\n") and "0 errors, 0 warnings, 1 info." in report, report
        assert " BK505 info " in report and "bras-kit urdf --inertials" in report, report


def test_validate_inertials_checks_the_arm_urdf_inertials_prints(run_cli):
    code, out, _ = run_cli("validate", "--inertials", "--lang", "en")
    assert code == 0 and "no problems found" in out, out


def _random_arm_params():  # type: ignore[no-untyped-def]
    """Sizes of every segment and of the base, and masses from a density a real solid has
    (100 to 8,000 kg/m3, foam to steel): a mass no solid could have is BK509's, rightly."""
    import math

    from hypothesis import assume
    from hypothesis import strategies as st

    size = st.floats(0.03, 0.8, allow_nan=False).map(lambda v: round(v, 3))
    density = st.floats(100.0, 8000.0, allow_nan=False)

    @st.composite
    def params(draw):  # type: ignore[no-untyped-def]
        out: dict[str, float] = {}
        for segment in ("bras", "avant_bras", "poignet"):
            length, width = draw(size), draw(size)
            out.update({f"{segment}_length": length, f"{segment}_width": width,
                        f"{segment}_mass": round(draw(density) * width * width * length, 6)})
        length, radius = draw(size), draw(size)
        out.update(base_length=length, base_radius=radius,
                   base_mass=round(draw(density) * math.pi * radius * radius * length, 6))
        assume(all(0.001 <= v <= 1000 for k, v in out.items() if k.endswith("_mass")))  # the template's range
        return out

    return params()


def test_urdf_inertials_with_any_sizes_and_masses_validates_clean(tmp_path):
    from hypothesis import HealthCheck, given, settings

    from bras_kit.model.authoring import arm
    from bras_kit.validate import validate

    @settings(max_examples=25, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
    @given(params=_random_arm_params())
    def check(params):  # type: ignore[no-untyped-def]
        robot = arm(wrist=True, inertials=True, params=params, world_anchor=True)  # every link has an inertial
        found = [(f.code, f.text("en")) for f in validate(robot)]
        assert found == [], (params, found)

    check()


def _inertials_of(text: str):  # type: ignore[no-untyped-def]
    """Each link of a URDF text: (comment just above its <inertial>, mass, inertia, visual geometry)."""
    import xml.etree.ElementTree as ET

    parser = ET.XMLParser(target=ET.TreeBuilder(insert_comments=True))
    root = ET.fromstring(text, parser=parser)
    out = {}
    for link in root.iter("link"):
        children = list(link)
        for i, child in enumerate(children):
            if child.tag == "inertial":
                comment = children[i - 1].text if i and children[i - 1].tag is ET.Comment else None
                inertia = {k: float(v) for k, v in child.find("inertia").attrib.items()}
                geometry = link.find("visual/geometry")[0]
                out[link.get("name")] = (comment, float(child.find("mass").get("value")), inertia, geometry)
    return out


@pytest.mark.parametrize("lang", ["en", "fr"])
def test_urdf_inertials_writes_each_formula_it_used(run_cli, lang):
    code, out, _ = run_cli("urdf", "--inertials", "--wrist", "--lang", lang)
    assert code == 0
    links = _inertials_of(out)
    assert set(links) == {"base", "bras", "avant_bras", "main"}  # the wrist joint poignet carries the link main
    for name, (comment, m, inertia, geometry) in links.items():
        assert comment is not None, f"{name}: no formula above its <inertial>"
        # the oracle: the solid-primitive inertias (a box about its centre; a cylinder along z)
        if geometry.tag == "box":
            x, y, z = map(float, geometry.get("size").split())
            expected = {"ixx": m * (y * y + z * z) / 12, "iyy": m * (x * x + z * z) / 12, "izz": m * (x * x + y * y) / 12}
            assert "ixx = m (y² + z²) / 12, iyy = m (x² + z²) / 12, izz = m (x² + y²) / 12" in comment
        else:
            r, h = float(geometry.get("radius")), float(geometry.get("length"))
            expected = {"ixx": m * (3 * r * r + h * h) / 12, "iyy": m * (3 * r * r + h * h) / 12, "izz": m * r * r / 2}
            assert "ixx = iyy = m (3 r² + h²) / 12, izz = m r² / 2" in comment
        for key, value in expected.items():
            assert inertia[key] == pytest.approx(value, rel=1e-12), (name, key)


def test_bk507_hint_gives_the_formula_the_generated_file_holds(run_cli):
    from bras_kit.findings.data import Finding

    hint = Finding("BK507", "error", "link", "bras", 1, params={"link": "bras", "a": 1, "b": 1, "c": 5,
                                                                   "ratio": 2.5}).hint_text("en")
    _, out, _ = run_cli("urdf", "--inertials", "--lang", "en")
    box = next(c for c, *_ in _inertials_of(out).values() if c and "box" in c)
    formula = box.split(": ", 1)[1].strip()
    assert formula in hint, (formula, hint)


# --- a misspelt xacro property gets a "did you mean" ---------------------------------------------------------

_XACRO = """<?xml version="1.0"?>
<robot name="r" xmlns:xacro="http://www.ros.org/wiki/xacro">
  <xacro:property name="bras_length" value="0.6"/>
  <xacro:property name="avant_bras_width" value="0.06"/>
  <xacro:macro name="segment" params="name length width">
    <link name="${{name}}"><visual><geometry><box size="${{width}} ${{width}} {inside}"/></geometry></visual></link>
  </xacro:macro>
  <link name="base"><visual><geometry><box size="0.1 0.1 {outside}"/></geometry></visual></link>
  <xacro:segment name="bras" length="${{bras_length}}" width="0.08"/>
</robot>
"""

# (text at the top level, text inside the macro, the name meant: None when nothing is close)
_MISSPELT = [
    ("${bras_lenght}", "${length}", "bras_length"),  # two letters swapped
    ("${2 * bras_lengt}", "${length}", "bras_length"),  # in an expression, a letter missing
    ("${Bras_length}", "${length}", "bras_length"),  # the case
    ("${avant_bras_widht}", "${length}", "avant_bras_width"),
    ("${bras_length}", "${lenght}", "length"),  # a macro's own parameter, inside the macro
    ("${bras_length}", "${widht + 0.1}", "width"),
    ("${zzz_qqq}", "${length}", None),  # nothing like it: no guess
]


@pytest.mark.parametrize(("outside", "inside", "meant"), _MISSPELT)
@pytest.mark.parametrize("command", ["validate", "xacro"])
def test_a_misspelt_xacro_property_gets_did_you_mean(run_cli, tmp_path, command, outside, inside, meant):
    path = tmp_path / "r.urdf.xacro"
    path.write_text(_XACRO.format(outside=outside, inside=inside), encoding="utf-8")
    code, out, err = run_cli(command, str(path), "--lang", "en")
    assert code != 0
    text = out + err
    assert "is not defined" in text
    if meant is None:
        assert "did you mean" not in text
    else:
        assert f"did you mean '{meant}'?" in text, text


def test_did_you_mean_in_french(run_cli, tmp_path):
    path = tmp_path / "r.urdf.xacro"
    path.write_text(_XACRO.format(outside="${bras_lenght}", inside="${length}"), encoding="utf-8")
    _, out, _ = run_cli("validate", str(path), "--lang", "fr")
    assert "vouliez-vous dire 'bras_length' ?" in out


# --- gazebo says why it refuses first ---------------------------------------------------------------------

_GAZEBO = DATA / "gazebo"


def _refused_cases() -> list[Path]:
    from bras_kit.model.authoring import load
    from bras_kit.validate.urdf2sdf import gazebo_model

    cases = []
    for path in sorted(_GAZEBO.glob("*.urdf")):
        found = gazebo_model(load(str(path)))
        if found is not None and found.refused:
            cases.append(path)
    return cases


@pytest.mark.parametrize("lang", ["en", "fr"])
def test_gazebo_gives_the_reason_of_a_refusal_right_under_it(run_cli, tmp_path, lang):
    plain = tmp_path / "bras.urdf"  # the tutorial's arm as written: no inertial anywhere
    assert run_cli("urdf", "-o", str(plain))[0] == 0
    cases = [plain, *_refused_cases()]
    assert len(cases) >= 5  # a shared name, no inertial, a floating joint, an impossible inertia, NaN merging
    for path in cases:
        code, out, _ = run_cli("gazebo", str(path), "--lang", lang)
        assert code == 1, path
        # the oracle of the reasons: validate --target gazebo's errors for the same file
        _, report, _ = run_cli("validate", str(path), "--target", "gazebo", "--select", "BK7", "--lang", lang)
        errors = {line.split()[1] for line in report.splitlines() if " BK7" in line and line.split()[2] in
                  ("error", "erreur")}
        assert errors, (path, report)
        lines = out.splitlines()
        assert lines[0].startswith(("Gazebo refuses model", "Gazebo refuse le modèle")), out
        assert lines[1].split()[0] in errors, (path, out)


# --- new takes ros2 pkg create's own arguments ---------------------------------------------------------------
# The oracle: tests/data/ros2_pkg_create (ros2cli's Jazzy templates expanded by empy) and, for the options it
# was not made with, those templates read by hand (ros2cli jazzy, ros2pkg/resource/package_environment/
# package.xml.em: '@[for dep in dependencies]  <depend>@dep</depend>' then a blank line; ament_python/
# setup.py.em: "'@node_name = @project_name.@node_name:main'" in console_scripts; main.py.em; init.py.em empty).

CREATED = DATA / "ros2_pkg_create"
OWNER_ROS2 = ("--maintainer-name", "eleve", "--maintainer-email", "eleve@todo.todo")


def _files(root: Path) -> dict[str, str]:
    return {str(p.relative_to(root)): p.read_text(encoding="utf-8") for p in sorted(root.rglob("*")) if p.is_file()}


def test_the_tutorials_ros2_pkg_create_line_makes_its_package(run_cli, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)  # as in ~/ros2_cellule_ws/src
    code, out, err = run_cli("new", "--empty", "--build-type", "ament_python", "--license", "Apache-2.0",
                             "bras_description", *OWNER_ROS2, "--lang", "en")
    assert (code, err) == (0, ""), err
    assert _files(tmp_path / "bras_description") == _files(CREATED / "license_apache" / "bras_description")


def _expected(name: str = "bras_description", *, dependencies=(), node=None, library=None,  # type: ignore[no-untyped-def]
              description="TODO: Package description", package_format=3):
    files = _files(CREATED / "license_default" / "bras_description")
    files = {path.replace("bras_description", name): text.replace("bras_description", name)
             for path, text in files.items()}
    xml = files["package.xml"].replace("TODO: Package description", description)
    if package_format == 2:
        xml = xml.replace("package_format3.xsd", "package_format2.xsd").replace('format="3"', 'format="2"')
    if dependencies:
        block = "".join(f"  <depend>{d}</depend>\n" for d in dependencies) + "\n"
        xml = xml.replace("  <test_depend>ament_copyright", block + "  <test_depend>ament_copyright", 1)
    files["package.xml"] = xml
    setup = files["setup.py"].replace("TODO: Package description", description)
    if node is not None:
        setup = setup.replace("        'console_scripts': [\n",
                              f"        'console_scripts': [\n            '{node} = {name}.{node}:main'\n")
        files[f"{name}/{node}.py"] = (f"def main():\n    print('Hi from {name}.')\n\n\n"
                                      "if __name__ == '__main__':\n    main()\n")
    files["setup.py"] = setup
    if library is not None:
        files[f"{name}/{library}/__init__.py"] = ""
    return files


def _ros2_options():  # type: ignore[no-untyped-def]
    from hypothesis import strategies as st

    module = st.sampled_from(["animation", "publieur", "outils", "noeud_2"])
    return st.fixed_dictionaries({}, optional={
        "dependencies": st.lists(st.sampled_from(["rclpy", "sensor_msgs", "std_msgs", "python3-numpy"]),
                                 min_size=1, max_size=3, unique=True),
        "node": module, "library": module,
        "description": st.sampled_from(["Le bras du tutoriel", "A two-joint arm", "Bras à deux articulations"]),
        "package_format": st.sampled_from([2, 3]),
        "name": st.sampled_from(["bras_description", "mon_bras", "cellule"]),
        "destination": st.booleans(),
    })


def test_any_mix_of_ros2_pkg_create_options_writes_what_it_would(run_cli, tmp_path):
    import itertools

    from hypothesis import HealthCheck, given, settings

    counter = itertools.count()

    @settings(max_examples=30, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
    @given(options=_ros2_options())
    def check(options):  # type: ignore[no-untyped-def]
        where = tmp_path / str(next(counter))
        name = options.get("name", "bras_description")
        argv = ["new", "--empty", "--build-type", "ament_python", *OWNER_ROS2]
        tail = []
        if options.get("dependencies"):  # nargs='+', as ros2 pkg create's: the list ends the command line
            tail = ["--dependencies", *options["dependencies"]]
        for key, flag in (("node", "--node-name"), ("library", "--library-name"), ("description", "--description"),
                          ("package_format", "--package-format")):
            if key in options:
                argv += [flag, str(options[key])]
        if options.get("destination"):
            argv += ["--destination-directory", str(where / "src"), name]
            made = where / "src" / name
        else:
            argv += [str(where / name)]
            made = where / name
        code, _, err = run_cli("--lang", "en", *argv, *tail)
        assert code == 0, err
        node = options.get("node")
        if node is not None and node == options.get("library"):  # ros2pkg/verb/create.py renames the node
            node += "_node"
        expected = _expected(name, dependencies=options.get("dependencies", ()), node=node,
                             library=options.get("library"),
                             description=options.get("description", "TODO: Package description"),
                             package_format=options.get("package_format", 3))
        assert _files(made) == expected

    check()


@pytest.mark.parametrize(("argv", "words"), [
    (("--empty", "--build-type", "ament_cmake", "p"), "bras-kit makes ament_python packages only"),
    (("--empty", "--build-type", "cmake", "p"), "bras-kit makes ament_python packages only"),
    (("--build-type", "ament_cmake"), "bras-kit makes ament_python packages only"),
    (("--empty", "--build-type", "ament_rust", "p"), "invalid choice: 'ament_rust'"),
    (("--node-name", "animation"), "--node-name: ros2 pkg create's, with --empty only"),
    (("--dependencies", "rclpy", "--", "p"), "--dependencies: ros2 pkg create's, with --empty only"),
    (("--empty", "--dependencies", "Sensor Msgs", "--", "p"), "'Sensor Msgs' is not a package name for <depend>"),
    (("--empty", "--description", "un <b>bras</b>", "p"), "cannot be written into setup.py and package.xml"),
    (("--empty", "--node-name", "mon-noeud", "p"), "--node-name 'mon-noeud' cannot be a Python module's name"),
    (("--empty", "--library-name", "class", "p"), "--library-name 'class' cannot be a Python module's name"),
    (("--empty", "--package-format", "4", "p"), "invalid choice: 4"),
    (("--empty", "--destination-directory", "src", "a/b"), "give the package's name, not a folder"),
    (("--empty", "Mon-Bras"), "'Mon-Bras' is not a valid ROS package name"),
    (("--empty", "--dependencies", "rclpy", "mon_bras"), "no package name is left after the dependencies"),
])
def test_what_ros2_pkg_create_takes_and_bras_kit_cannot_make_is_refused_clearly(run_cli, tmp_path, monkeypatch,
                                                                                 argv, words):
    monkeypatch.chdir(tmp_path)
    code, out, err = run_cli("--lang", "en", "new", *argv)
    assert code == 2, (out, err)
    assert words in err and "Traceback" not in err
    assert list(tmp_path.iterdir()) == []  # nothing written


def test_the_build_type_refusal_in_french(run_cli, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    code, _, err = run_cli("new", "--empty", "--build-type", "ament_cmake", "p", "--lang", "fr")
    assert code == 2 and "bras-kit ne fait que des paquets ament_python" in err


# --- the camera keeps the whole arm in the picture, in every pose ----------------------------------------------
# The oracle: the links' geometry read from the robot's <visual> elements (box corners, cylinder rims), placed
# by the kinematics' forward transforms (not the renderer's scene nor its framing points), projected by the
# camera the renderer draws with.

def _rpy(r: float, p: float, y: float):  # type: ignore[no-untyped-def]
    import math

    import numpy as np

    cr, sr, cp, sp, cy, sy = math.cos(r), math.sin(r), math.cos(p), math.sin(p), math.cos(y), math.sin(y)
    return np.array([[cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
                     [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
                     [-sp, cp * sr, cp * cr]])


def _surface(geometry):  # type: ignore[no-untyped-def]
    import math

    import numpy as np

    if geometry.kind == "box":
        x, y, z = (s / 2 for s in geometry.size)
        return np.array([[i * x, j * y, k * z] for i in (-1, 1) for j in (-1, 1) for k in (-1, 1)])
    assert geometry.kind == "cylinder", geometry.kind  # the tutorial arm has boxes and a cylinder
    a = np.linspace(0, 2 * math.pi, 72, endpoint=False)
    ring = np.stack([geometry.radius * np.cos(a), geometry.radius * np.sin(a)], axis=1)
    return np.vstack([np.column_stack([ring, np.full(len(a), h)]) for h in (-geometry.length / 2, geometry.length / 2)])


def _furthest_in_picture(robot, camera, q) -> float:  # type: ignore[no-untyped-def]
    """The largest |x| or |y| of the arm's geometry on the picture, in normalised device coordinates (1: the edge)."""
    import numpy as np

    from bras_kit.kinematics.frames import fk_batch, tf_tree

    tree = tf_tree(robot)
    transforms = fk_batch(tree, np.atleast_2d(q))
    project = camera.projection() @ camera.view()
    furthest = 0.0
    for link in robot.links:
        for visual in link.visuals:
            local = _surface(visual.geometry) @ _rpy(*visual.origin.rpy).T + np.array(visual.origin.xyz)
            at = transforms[:, tree.links.index(link.name)]
            world = np.einsum("nij,kj->nki", at[:, :3, :3], local) + at[:, None, :3, 3]
            clip = np.concatenate([world, np.ones(world.shape[:2] + (1,))], axis=2) @ project.T
            assert (clip[..., 3] > 0).all()  # in front of the camera
            furthest = max(furthest, float(np.abs(clip[..., :2] / clip[..., 3:]).max()))
    return furthest


def _camera_cases():  # type: ignore[no-untyped-def]
    from hypothesis import strategies as st

    views = st.one_of(st.sampled_from(["iso", "front", "side", "top"]).map(lambda v: {"view": v}),
                      st.fixed_dictionaries({"azimuth": st.floats(-180, 180), "elevation": st.floats(-89, 89)}))
    return st.fixed_dictionaries({
        "wrist": st.booleans(),
        "view": views,
        "size": st.sampled_from([(640, 480), (480, 360), (300, 600), (800, 200)]),
        "lengths": st.fixed_dictionaries({}, optional={
            "bras_length": st.floats(0.2, 1.2).map(lambda v: round(v, 3)),
            "avant_bras_length": st.floats(0.2, 1.2).map(lambda v: round(v, 3)),
            "poignet_length": st.floats(0.05, 0.6).map(lambda v: round(v, 3))}),
        "seed": st.integers(0, 2**32 - 1),  # the poses: a pose is cut off in about 1 in 50 (seen from above or the side)
    })


def test_the_camera_keeps_the_whole_arm_in_every_pose():
    import numpy as np
    from hypothesis import given, settings

    from bras_kit.kinematics.frames import tf_tree
    from bras_kit.model.authoring import arm
    from bras_kit.render.renderer import Renderer

    @settings(max_examples=30, deadline=None)
    @given(case=_camera_cases())
    def check(case):  # type: ignore[no-untyped-def]
        robot = arm(wrist=case["wrist"], params=case["lengths"])
        bounds = np.array([joint.bounds() for joint in tf_tree(robot).dof_joints()])
        poses = bounds[:, 0] + np.random.default_rng(case["seed"]).random((12, len(bounds))) * (bounds[:, 1] - bounds[:, 0])
        options = {**case["view"], "size": case["size"], "backend": "software"}
        for q in poses:
            with Renderer(robot, fit=q[None, :], **options) as one:  # bras-kit render --set: framed on the pose
                assert _furthest_in_picture(robot, one.camera, q) <= 1.0, (case, q)
        with Renderer(robot, **options) as every:  # the viewer's sliders: framed over the joints' range
            assert _furthest_in_picture(robot, every.camera, poses) <= 1.0, case

    check()


def test_the_top_view_keeps_the_wrist_of_a_pose_seen_from_above(run_cli, tmp_path):
    """The case found: seen from above, the last step of the aim pushed the hand out of the picture."""
    import numpy as np

    from bras_kit.model.authoring import arm
    from bras_kit.render.renderer import Renderer

    robot, q = arm(wrist=True), np.array([0.06, -0.117, -0.518])
    with Renderer(robot, fit=q[None, :], view="top", backend="software", size=(640, 480)) as renderer:
        assert _furthest_in_picture(robot, renderer.camera, q) <= 1.0
