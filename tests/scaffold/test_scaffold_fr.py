"""bras-kit new --lang fr, and the generator's guards: the French package says the same facts as the
English one in French, its Python runs, its URDF is one urdfdom and the validator accept, and
nothing is written for a parameter, an address or a language the generator refuses."""

from __future__ import annotations

import ast
import io
import re
import subprocess
import sys
import tokenize

import pytest

from bras_kit import __version__
from bras_kit.core.errors import ParameterError
from bras_kit.model.authoring import load
from bras_kit.scaffold.package import check_email, render_package, scaffold_package

PKG = "bras_description"
# Whole words a French reader should not meet in the package's prose (any case).
ENGLISH = ("the", "and", "joint", "joints", "build", "with", "link", "links", "file", "files", "of",
           "to", "is", "it", "this", "from", "each", "every", "node", "arm", "motion", "run", "shows")


def english_words(text: str) -> list[str]:
    """The words of ENGLISH in ``text``, not counting parts of names (data_files, motion.py, launch/)."""
    words = re.findall(r"(?<![\w/.])[A-Za-z]+(?![\w/]|\.\w)", text)
    return sorted({w for w in words if w.lower() in ENGLISH})


def prose(markdown: str) -> str:
    """The README without its code blocks and inline code."""
    without_blocks = re.sub(r"```.*?```", " ", markdown, flags=re.S)
    return re.sub(r"`[^`]*`", " ", without_blocks)


def words_of_python(source: str) -> str:
    """Every docstring and comment of a Python file."""
    tree = ast.parse(source)
    texts = [ast.get_docstring(node) or "" for node in ast.walk(tree)
             if isinstance(node, (ast.Module, ast.ClassDef, ast.FunctionDef))]
    texts += [tok.string for tok in tokenize.generate_tokens(io.StringIO(source).readline)
              if tok.type == tokenize.COMMENT]
    text = "\n".join(texts)
    return re.sub(r"'ros2 [^']*'|^\s+ros2 .*$", " ", text, flags=re.M)  # commands are not prose


@pytest.fixture(scope="module")
def both(tmp_path_factory) -> dict[str, dict[str, str]]:
    """The wrist-and-inertials package in each language, as {path: text}."""
    return {lang: render_package(wrist=True, inertials=True, params={"coude_upper": "1"}, lang=lang)
            for lang in ("en", "fr")}


# --- French words ----------------------------------------------------------------------------------

def test_french_readme_has_no_english_outside_code(both):
    readme = both["fr"]["README.md"]
    assert english_words(prose(readme)) == []
    assert english_words(prose(both["en"]["README.md"]))  # the oracle finds English where there is some


def test_french_readme_gives_the_same_facts_as_the_english(both):
    fr, en = both["fr"]["README.md"], both["en"]["README.md"]
    def commands(readme: str) -> list[list[str]]:  # the code blocks, without their shell comments
        return [[line.split("#")[0].rstrip() for line in block.splitlines()]
                for block in re.findall(r"```.*?```", readme, flags=re.S)]

    assert commands(fr) == commands(en)
    assert len(commands(fr)) == 5
    joint_rows = re.compile(r"^\| `(\w+)` \| (.+?) \| (.+?) \|$", re.M)
    assert joint_rows.findall(fr) == joint_rows.findall(en)
    assert [row[0] for row in joint_rows.findall(fr)] == ["epaule", "coude", "poignet"]
    # -2..1 cannot hold 1.2 sin(0.7t) with 10 % margins (0.15 rad): centred at -0.5, 1.2 fits in 1.35
    assert ("coude", "-0.5 + 1.2 sin(0.7 t)", "-2.0 .. 1.0") in joint_rows.findall(fr)
    assert "`bras-kit new --lang fr --wrist --inertials --param coude_upper=1.0`" in fr
    files = re.compile(r"^\| `([^`]+)` \| ", re.M)
    assert files.findall(fr)[1:] == files.findall(en)[1:]  # the same files, after the header row


@pytest.mark.parametrize("path", [f"{PKG}/animation.py", f"{PKG}/motion.py", f"{PKG}/__init__.py",
                                  "launch/affichage.launch.py", "test/test_motion.py", "setup.py"])
def test_french_python_is_commented_in_french(both, path):
    source = both["fr"][path]
    compile(source, path, "exec")
    words = words_of_python(source)
    assert words.strip()
    assert english_words(words) == [], words
    assert english_words(words_of_python(both["en"][path]))  # the same check finds the English


def test_french_node_uses_the_tutorials_names(both):
    tree = ast.parse(both["fr"][f"{PKG}/animation.py"])
    classes = [node.name for node in tree.body if isinstance(node, ast.ClassDef)]
    assert classes == ["Animation"]
    (main,) = [node for node in tree.body if isinstance(node, ast.FunctionDef) and node.name == "main"]
    assigned = [target.id for node in ast.walk(main) if isinstance(node, ast.Assign)
                for target in node.targets if isinstance(target, ast.Name)]
    assert assigned == ["noeud"]
    assert "launch/affichage.launch.py" in both["fr"]


def test_french_launch_argument_is_described_in_french(both):
    tree = ast.parse(both["fr"]["launch/affichage.launch.py"])
    (call,) = [node for node in ast.walk(tree) if isinstance(node, ast.Call)
               and getattr(node.func, "id", "") == "DeclareLaunchArgument"]
    (description,) = [k.value for k in call.keywords if k.arg == "description"]
    text = ast.literal_eval(description)
    assert text.startswith("true : le nœud d'animation") and english_words(text.replace("true", "")) == []


def test_both_languages_move_the_same_numbers(both):
    def constants(source: str) -> dict:
        tree = ast.parse(source)
        return {t.id: ast.literal_eval(node.value) for node in tree.body if isinstance(node, ast.Assign)
                for t in node.targets if isinstance(t, ast.Name) and t.id in ("WAVES", "LIMITS")}

    assert constants(both["fr"][f"{PKG}/motion.py"]) == constants(both["en"][f"{PKG}/motion.py"])
    assert len(constants(both["fr"][f"{PKG}/motion.py"])["WAVES"]) == 3


def test_french_package_metadata_and_rviz_names(both):
    from catkin_pkg.package import parse_package_string

    package = parse_package_string(both["fr"]["package.xml"])
    package.validate()
    assert package.description.startswith("Description du robot bras (base, bras, avant_bras, main)")
    assert "name=package_name" in both["fr"]["setup.py"]
    assert "description='Description, affichage et animation du robot bras'" in both["fr"]["setup.py"]
    names = re.findall(r"^      Name: (.+)$", both["fr"][f"rviz/{PKG}.rviz"], flags=re.M)
    assert names == ["Grille", "Modèle du robot", "Repères (TF)", "Current View"]  # the view's is RViz's own


@pytest.fixture(scope="module")
def with_xacro() -> dict[str, dict[str, str]]:
    """The same package made with --xacro (its robot as urdf/bras.urdf.xacro only)."""
    return {lang: render_package(wrist=True, inertials=True, params={"coude_upper": "1"}, lang=lang, xacro=True)
            for lang in ("en", "fr")}


def test_french_urdf_and_xacro_comments(both, with_xacro):
    urdf, xacro = both["fr"]["urdf/bras.urdf"], with_xacro["fr"]["urdf/bras.urdf.xacro"]
    assert "urdf/bras.urdf.xacro" not in both["fr"] and "urdf/bras.urdf" not in with_xacro["fr"]
    assert urdf.splitlines()[1] == (f"<!-- Créé par bras-kit {__version__} pour le paquet {PKG} : le bras du "
                                    "tutoriel, à vous de le modifier -->")
    comments = re.findall(r"<!--(.*?)-->", xacro, flags=re.S)
    assert len(comments) >= 10
    assert all(english_words(c.replace("inertials", "").replace("wrist", "")) == [] for c in comments), comments
    assert all("--" not in c for c in re.findall(r"<!--(.*?)-->", urdf + xacro, flags=re.S))


def test_french_xacro_expands_to_the_french_urdf(both, with_xacro, tmp_path):
    """--xacro and the hand-written URDF describe the same robot: xacro's expansion is its body."""
    from bras_kit.model.xacro import expand_xacro

    (tmp_path / "bras.urdf.xacro").write_text(with_xacro["fr"]["urdf/bras.urdf.xacro"], encoding="utf-8")
    expanded = expand_xacro(tmp_path / "bras.urdf.xacro", {})

    def body(text: str) -> str:
        return text[text.index("<robot"):]

    assert body(expanded) == body(both["fr"]["urdf/bras.urdf"])


def test_generated_python_keeps_rclpy_style_lines(tmp_path):
    """ament_flake8 (ROS 2's linter) allows 99 characters a line, and no unused import."""
    for lang in ("en", "fr"):
        scaffold_package(tmp_path / lang, wrist=True, inertials=True, lang=lang)
    checked = subprocess.run([sys.executable, "-m", "ruff", "check", "--no-cache", "--isolated", "--select", "E,W,F",
                              "--line-length", "99", str(tmp_path)], capture_output=True, text=True, timeout=120)
    assert checked.returncode == 0, checked.stdout


@pytest.mark.slow
def test_french_package_test_runs_with_pytest(tmp_path):
    scaffold_package(tmp_path / PKG, wrist=True, lang="fr")
    result = subprocess.run([sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", "test"],
                            cwd=tmp_path / PKG, capture_output=True, text=True, timeout=300)
    assert result.returncode == 0 and "2 passed" in result.stdout, result.stdout + result.stderr


def test_unknown_language_is_refused():
    with pytest.raises(ParameterError, match="unknown language 'de'"):
        render_package(lang="de")


# --- the root link and its inertial -------------------------------------------------------------------

@pytest.mark.parametrize("lang", ["en", "fr"])
def test_inertials_package_urdf_passes_check_urdf_with_no_root_inertial(tmp_path, lang):
    from bras_kit.validate import validate

    scaffold_package(tmp_path / PKG, wrist=True, inertials=True, lang=lang)
    urdf = tmp_path / PKG / "urdf" / "bras.urdf"
    checked = subprocess.run(["/usr/bin/check_urdf", str(urdf)], capture_output=True, text=True, timeout=60)
    assert checked.returncode == 0, checked.stdout + checked.stderr
    assert "root Link: world has 1 child(ren)\n    child(1):  base\n" in checked.stdout
    robot = load(urdf)
    # KDL warns "The root link world has an inertia specified in the URDF": the root has none; Gazebo
    # drops a root without one: the base, fixed to the bare root, has its own
    assert robot.link("world").inertial is None and robot.link("world").visuals == []
    assert all(robot.link(name).inertial is not None for name in ("base", "bras", "avant_bras", "main"))
    assert [f.code for f in validate(robot) if f.severity == "error"] == []


# --- e-mail -------------------------------------------------------------------------------------------------

ADDRESSES = ["jean.dupont@todo.todo", "a+b@example.org", "prof_ros@lycee-exemple.fr", "x@y.z", "jean@",
             "jean dupont@example.org", "@example.org", "jean@example", "jean@@example.org", "jean@exa mple.org",
             "jean.@example.org", "jean@example.o"]


@pytest.mark.parametrize("address", ADDRESSES)
def test_email_check_agrees_with_catkin_pkg(address):
    """catkin_pkg (what colcon reads package.xml with) is the oracle: what it refuses, new refuses."""
    from catkin_pkg.package import InvalidPackage, parse_package_string

    xml = render_package(email="jean.dupont@todo.todo")["package.xml"].replace("jean.dupont@todo.todo", address)
    try:
        parse_package_string(xml).validate()
        catkin_accepts = True
    except InvalidPackage:
        catkin_accepts = False
    try:
        check_email(address)
        we_accept = True
    except ParameterError:
        we_accept = False
    assert we_accept == catkin_accepts


def test_new_refuses_a_bad_email_and_writes_nothing(run_cli, tmp_path):
    code, out, err = run_cli("new", str(tmp_path / "p"), "--email", "jean@example")
    assert code == 2
    assert "'jean@example' is not an email address colcon accepts" in err and "--email" in err
    assert not (tmp_path / "p").exists()
    code, _, err = run_cli("new", str(tmp_path / "q"), "--email", "jean@lycee.fr", "--maintainer", "Jean")
    assert code == 0, err
    assert '<maintainer email="jean@lycee.fr">Jean</maintainer>' in (tmp_path / "q" / "package.xml").read_text()


# --- parameters of new ------------------------------------------------------------------------------------

def test_new_refuses_a_zero_length_and_writes_nothing(run_cli, tmp_path):
    code, _, err = run_cli("new", str(tmp_path / "p"), "--param", "bras_length=0")
    assert code == 2 and "bras_length=0: a length must be between 0.001 and 10 m" in err
    assert not (tmp_path / "p").exists()


def test_new_takes_the_old_set_with_a_note(run_cli, tmp_path):
    code, _, err = run_cli("new", str(tmp_path / "p"), "--set", "bras_length=0.8")
    assert code == 0
    assert "--set is deprecated for template parameters: use --param" in err
    assert load(tmp_path / "p" / "urdf" / "bras.urdf").joint("coude").origin.xyz == (0.0, 0.0, 0.8)


def test_new_points_a_joint_given_to_param_to_set(run_cli, tmp_path):
    code, _, err = run_cli("new", str(tmp_path / "p"), "--param", "coude=1")
    assert code == 2 and "'coude' is a joint, not a template parameter" in err and "--set" in err
    assert not (tmp_path / "p").exists()


def test_new_in_french_prints_french(run_cli, tmp_path):
    code, out, err = run_cli("new", str(tmp_path / "p"), "--lang", "fr")
    assert code == 0, err
    assert out.startswith(f"paquet ROS 2 '{PKG}' créé dans ")
    assert "# bras_description\n\nLe robot `bras` sous forme de paquet ROS 2" in (tmp_path / "p" / "README.md").read_text()


# --- one tutorial motion ------------------------------------------------------------------------------------

def test_scaffold_reads_the_waves_from_the_one_definition(monkeypatch):
    """Change the definition in bras_kit.motion: the package follows, with no number of its own."""
    from bras_kit.motion import sources

    monkeypatch.setitem(sources.TUTORIAL_WAVES, "poignet", (0.5, 2.0, 0.0))
    files = render_package(wrist=True)
    namespace: dict = {}
    exec(compile(files[f"{PKG}/motion.py"], "motion.py", "exec"), namespace)
    assert namespace["WAVES"]["poignet"] == (0.0, 0.5, 2.0, 0.0)
    assert "poignet 0.5 sin 2.0t" in files[f"{PKG}/motion.py"]
