"""A wide matrix of commands and error paths, run twice: ``--lang en`` must print exactly what it
printed before the messages became data (the golden files in ``tests/data/i18n_golden/``), and
``--lang fr`` must print no English sentence.

Each case runs the command line in-process (``bras_kit.cli.main``) with its own temporary folder;
what it prints (stdout, stderr, exit code) and, for the commands that draw words (plot), the texts
of the figure are kept. Temporary paths, the repository's path and timings are normalised.

The English detector looks for whole words that only English uses (``the``, ``is``, ``not``,
``which``, ``frames``, ``beyond``, ...) outside what is not language: quoted names, paths, option
names, code, XML and the names a user types (joint and link names, rule codes and names, the
ROS names in :data:`ROS_NAMES`). Set ``BRAS_KIT_GOLDEN=1`` to write the golden files again (only
when an English wording changes on purpose).
"""

from __future__ import annotations

import contextlib
import functools
import io
import os
import re
import shutil
from pathlib import Path

import pytest
from paths import REPO, TESTS

from bras_kit.model.authoring import arm_urdf

DATA = TESTS / "data"

GOLDEN = DATA / "i18n_golden"
SMALL = ["--size", "96x72"]

# Words that, standing alone, are English sentences' glue; French never uses them as words.
ENGLISH_WORDS = (
    "the", "is", "are", "not", "which", "does", "do", "has", "have", "frames", "frame", "found", "beyond",
    "at", "names", "with", "without", "from", "to", "of", "and", "or", "this", "that", "there", "its",
    "it", "be", "was", "out of range", "written", "wrote", "error", "warning", "hint", "usage", "give",
    "use", "unknown", "joint", "joints", "limit", "limits", "held", "formulas", "formula", "seconds",
    "samples", "file", "files", "missing", "cannot", "can't", "must", "should", "would", "below",
    "above", "between", "into", "only", "then", "when", "where", "no", "none", "every", "each",
    "write", "read", "show", "shows", "will", "one", "two", "too", "than", "by", "in", "an",
    "for", "exists", "folder", "directory", "degree", "reached", "reach",
    "unreachable", "solution", "learners", "learner", "score", "checked", "passed", "failed",
)
ENGLISH = re.compile(r"(?<![\w'/.-])(" + "|".join(re.escape(w) for w in ENGLISH_WORDS) + r")(?![\w'/-])",
                     re.IGNORECASE)
# ROS and library names kept as they are in every language (documented allow-list).
ROS_NAMES = ("joint_states", "JointState", "robot_state_publisher", "joint_state_publisher_gui",
             "RViz", "rviz2", "tf2_echo", "view_frames", "ros2 launch", "colcon build", "MuJoCo",
             "MJCF", "URDF", "xacro", "Dask", "Gradescope", "EGL", "OSMesa", "ffmpeg", "PyPI", "Fixed Frame")


def _setup(tmp: Path) -> None:
    """The files the cases read: a good arm, broken files, a class of two learners, a waypoint
    file that moves too fast, and paths that already exist."""
    shutil.copy(DATA / "urdf" / "good" / "bras.urdf", tmp / "bras.urdf")
    shutil.copy(DATA / "urdf" / "broken" / "mal_forme.urdf", tmp / "mal_forme.urdf")
    shutil.copy(DATA / "urdf" / "broken" / "coude_trop_bas.urdf", tmp / "coude_trop_bas.urdf")
    (tmp / "wp.csv").write_text("time,epaule,coude\n0,0,0\n0.5,1,1.5\n", encoding="utf-8")
    (tmp / "exists.png").write_bytes(b"not a picture")
    (tmp / "adir").mkdir()
    (tmp / "rubric.yaml").write_text("items: [1, 2\n", encoding="utf-8")
    klass = tmp / "class"
    klass.mkdir()
    (klass / "alice.urdf").write_text(arm_urdf(), encoding="utf-8")
    (klass / "bob.urdf").write_text(arm_urdf().replace('<origin xyz="0 0 0.6"/>', '<origin xyz="0 0 0.3"/>'),
                                    encoding="utf-8")
    (klass / "carol.urdf").write_text("<robot name='x'><link name='a'>", encoding="utf-8")
    (klass / "dave.zip").write_bytes(b"PK\x03\x04 broken")


T = "{tmp}"
CASES: dict[str, list[str]] = {
    # top level and argparse
    "help": ["--help"],
    "no-command": [],
    "unknown-command": ["bogus"],
    "unknown-option": ["tree", "--bogus"],
    "bad-choice": ["render", "--view", "bogus"],
    "bad-type": ["render", "--fps", "abc"],
    "missing-argument": ["reach", "0.3"],
    "help-render": ["render", "--help"],
    "help-grade": ["grade", "--help"],
    # grade
    "grade-jobs-300": ["grade", f"{T}/class", "--jobs", "300"],
    "grade-ok": ["grade", f"{T}/class", "-o", f"{T}/report", "--no-pictures", "--jobs", "1"],
    "grade-missing": ["grade", f"{T}/absent"],
    "grade-explain-rubric": ["grade", "--explain-rubric"],
    "grade-bad-rubric": ["grade", f"{T}/class", "--rubric", f"{T}/rubric.yaml", "-o", f"{T}/r2"],
    # render
    "render-gif": ["render", "--gif", f"{T}/a.gif", "--fps", "7", *SMALL, "--duration", "1"],
    "render-png": ["render", "--set", "epaule=0.5", "-o", f"{T}/pose.png", *SMALL],
    "render-past-limit": ["render", "--set", "coude=3", "-o", f"{T}/lim.png", *SMALL],
    "render-degrees": ["render", "--set", "coude=90", "-o", f"{T}/deg.png", *SMALL],
    "render-exists": ["render", "-o", f"{T}/exists.png", *SMALL],
    "render-bad-size": ["render", "--size", "10", "-o", f"{T}/s.png"],
    "render-bad-fps": ["render", "--gif", f"{T}/b.gif", "--fps", "0", *SMALL],
    "render-bad-extension": ["render", "-o", f"{T}/pose.bmpx", *SMALL],
    # motion
    "motion-tutorial": ["motion", "--motion", "tutorial"],
    "motion-formula": ["motion", "--motion", "coude=0.69*sin(1.3*t)", "--duration", "1"],
    "motion-past-limits": ["motion", "--motion", "coude=2.5*sin(t)", "--duration", "3"],
    "motion-waypoints-too-fast": ["motion", "--motion", f"{T}/wp.csv"],
    "motion-bad-formula": ["motion", "--motion", "coude=foo(t)"],
    "motion-strict": ["motion", "--motion", "coude=2.5*sin(t)", "--duration", "3", "--strict"],
    "motion-csv": ["motion", "--duration", "0.2", "-o", f"{T}/m.csv"],
    "motion-bad-number": ["motion", "--motion", str(DATA / "motion" / "bad_number.csv")],
    "motion-bad-joint": ["motion", "--motion", str(DATA / "motion" / "bad_joint.csv")],
    "motion-bad-order": ["motion", "--motion", str(DATA / "motion" / "bad_order.csv")],
    "motion-bad-yaml": ["motion", "--motion", str(DATA / "motion" / "bad_indent.yaml")],
    "motion-wrist-narrow": ["motion", "--wrist", "--param", "poignet_upper=0.87", "--param", "poignet_lower=-0.87",
                            "--duration", "0.2"],
    "motion-bad-waypoint-json": ["motion", "--motion", str(DATA / "motion" / "bad_missing.json")],
    # plot (the figure's words are checked too)
    "plot-overrun": ["plot", "--motion", "coude=2.5*sin(t)", "-o", f"{T}/p.png"],
    "plot-missing-folder": ["plot", "-o", f"{T}/absent/p.png"],
    # validate
    "validate-ok": ["validate"],
    "validate-pose-unknown": ["validate", "--pose", "Coude=1"],
    "validate-broken-xml": ["validate", f"{T}/mal_forme.urdf"],
    "validate-pitfall": ["validate", f"{T}/coude_trop_bas.urdf"],
    "validate-missing-file": ["validate", f"{T}/absent.urdf"],
    "validate-bad-value": ["validate", "--set", "coude=abc"],
    "validate-time-in-pose": ["validate", "--set", "coude=t"],
    "validate-package": ["validate", str(DATA / "package_tutorial")],
    # fk
    "fk-set": ["fk", "--set", "coude=1"],
    "fk-link": ["fk", "--link", "avant_bras"],
    "fk-from-to": ["fk", "--from", "bras", "--to", "avant_bras"],
    "fk-unknown-joint": ["fk", "--set", "genou=1"],
    "fk-unknown-link": ["fk", "--link", "main"],
    "fk-bad-assignment": ["fk", "--set", "coude"],
    "fk-template-parameter": ["fk", "--set", "bras_length=1"],
    # reach
    "reach-ok": ["reach", "0.3", "0", "0.6"],
    "reach-unreachable": ["reach", "5", "0", "0"],
    "reach-json": ["reach", "0.3", "0", "0.6", "--format", "json"],
    "reach-wrist": ["reach", "--wrist", "0.2", "0.1", "0.7"],
    # urdf, xacro, new
    "urdf-list-params": ["urdf", "--list-params"],
    "urdf-unknown-parameter": ["urdf", "--param", "bras_lenght=1"],
    "urdf-joint-as-parameter": ["urdf", "--param", "coude=1"],
    "urdf-deprecated-set": ["urdf", "--set", "bras_length=0.8", "-o", f"{T}/b.urdf"],
    "urdf-exists": ["urdf", "-o", f"{T}/exists.png"],
    "urdf-into-folder": ["urdf", "-o", f"{T}/adir"],
    "urdf-missing-parent": ["urdf", "-o", f"{T}/no/where/b.urdf"],
    "xacro-ok": ["xacro", str(REPO / "bras_kit" / "templates" / "robot" / "bras.urdf.xacro"), "-o", f"{T}/x.urdf"],
    "xacro-missing": ["xacro", f"{T}/absent.xacro"],
    "xacro-undefined-property": ["xacro", str(DATA / "xacro" / "broken" / "undefined_property.xacro")],
    "new-ok": ["new", f"{T}/pkg"],
    "new-exists": ["new", f"{T}/class"],
    # tree, frames, workspace
    "tree-ok": ["tree"],
    "tree-set": ["tree", "--set", "coude=pi/2"],
    "tree-wrist-without-flag": ["tree", "--set", "poignet=1"],
    "tree-missing-file": ["tree", f"{T}/absent.urdf"],
    "tree-wrist-with-file": ["tree", f"{T}/bras.urdf", "--wrist"],
    "frames-svg": ["frames", "-o", f"{T}/f.svg"],
    "frames-past-limit": ["frames", "-o", f"{T}/f2.dot", "--set", "coude=3"],
    "frames-bad-extension": ["frames", "-o", f"{T}/f.xyz"],
    "workspace-ok": ["workspace", "-o", f"{T}/ws.png", "--samples", "50"],
    "workspace-bad-link": ["workspace", "-o", f"{T}/ws2.png", "--link", "main"],
    # simulate, mjcf
    "simulate-ok": ["simulate", "--inertials", "--duration", "0.5", "-o", f"{T}/sim.csv"],
    "simulate-no-inertials": ["simulate", "--duration", "0.5", "-o", f"{T}/sim2.csv"],
    "mjcf-ok": ["mjcf", "--inertials", "-o", f"{T}/arm.xml"],
    "mjcf-no-inertials": ["mjcf", "-o", f"{T}/arm2.xml"],
    # demo, explain, view
    "demo-ok": ["demo", f"{T}/demo", "--duration", "0.5", "--fps", "4", "--size", "96x72"],
    "explain-rule": ["explain", "BK301"],
    "explain-list": ["explain"],
    "explain-unknown": ["explain", "BK999"],
    "view-export": ["view", "--export", f"{T}/v.html", "--duration", "1", "--fps", "2"],
    "view-export-exists": ["view", "--export", f"{T}/exists.png"],
}
# What a figure draws: plot files whose words are read back from the matplotlib figure.
DRAWN = {"plot-overrun", "frames-svg", "frames-past-limit", "workspace-ok"}


def _normalise(text: str, tmp: Path) -> str:
    text = text.replace(str(tmp), "<TMP>").replace(str(REPO), "<REPO>")
    text = re.sub(r"(in|en) \d+(\.\d+)? ?s\b", r"\1 <T>", text)
    text = re.sub(r"\(\d+\.\d s\)$", "(<T>)", text, flags=re.M)  # demo's step timings
    text = re.sub(r"port \d+|:\d{4,5}/", "<PORT>", text)
    return text


def _run(name: str, lang: str, tmp: Path) -> str:
    from bras_kit.cli import main
    from bras_kit.core import i18n

    argv = ["--lang", lang] + [a.replace(T, str(tmp)) for a in CASES[name]]
    out, err = io.StringIO(), io.StringIO()
    figures: list[str] = []
    if name in DRAWN:
        _keep_figures(figures)
    try:
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            try:
                code = main(argv)
            except SystemExit as exc:
                code = exc.code if isinstance(exc.code, int) else 2
    finally:
        i18n._language.clear()
        _keep_figures(None)
    drawn = "".join(f"[drawn] {w}\n" for w in figures)
    return _normalise(f"$ bras-kit {' '.join(CASES[name])}\n[exit {code}]\n[stdout]\n{out.getvalue()}"
                      f"[stderr]\n{err.getvalue()}{drawn}", tmp)


_FIGURES: list[list[str] | None] = [None]


def _keep_figures(into: list[str] | None) -> None:
    """While a drawing case runs, every figure saved to a file gives its words to ``into``."""
    from matplotlib.figure import Figure

    original = getattr(Figure, "_matrix_savefig", None)
    if original is None:
        original = Figure.savefig
        Figure._matrix_savefig = original  # type: ignore[attr-defined]

        def savefig(self, *args, **kwargs):  # type: ignore[no-untyped-def]
            sink = _FIGURES[0]
            if sink is not None:
                from matplotlib.text import Text

                sink += [t.get_text() for t in self.findobj(Text) if t.get_text().strip()]
            return original(self, *args, **kwargs)

        Figure.savefig = savefig  # type: ignore[method-assign]
    _FIGURES[0] = into


@pytest.fixture(scope="module")
def matrix_dir(tmp_path_factory):
    return tmp_path_factory.mktemp("matrix")


def _case_dir(root: Path, name: str, lang: str) -> Path:
    # the same path length in both languages and every run: outputs that wrap stay the same
    folder = root / f"{lang}" / name
    folder.mkdir(parents=True, exist_ok=True)
    if not any(folder.iterdir()):
        _setup(folder)
    return folder


@pytest.mark.parametrize("name", sorted(CASES))
def test_english_output_equals_the_golden(name, matrix_dir):
    text = _run(name, "en", _case_dir(matrix_dir, name, "en"))
    golden = GOLDEN / f"{name}.txt"
    if os.environ.get("BRAS_KIT_GOLDEN") == "1":
        golden.parent.mkdir(parents=True, exist_ok=True)
        golden.write_text(text, encoding="utf-8")
    assert golden.exists(), f"no golden for {name}: run with BRAS_KIT_GOLDEN=1"
    assert _last_digits_dropped(text) == _last_digits_dropped(golden.read_text(encoding="utf-8"))


# A number printed with all of a double's digits (JSON output) differs in its last one or two
# between numpy/LAPACK releases, or from one Python's wheels to another's: the golden checks the
# words and the values to ten significant digits, not the floating-point bits of a dependency.
_FULL_PRECISION = re.compile(r"-?\d+\.\d{11,}(?:[eE][-+]?\d+)?")


def _last_digits_dropped(text: str) -> str:
    return _FULL_PRECISION.sub(lambda m: format(float(m.group()), ".10g"), text)


@functools.cache
def _typed_names() -> tuple[str, ...]:
    """Names a user types, the same in every language: option metavars, rule names, ROS names."""
    from bras_kit import cli
    from bras_kit.findings.registry import RULES

    names: set[str] = set(ROS_NAMES)
    for command in cli.COMMANDS:
        cli.build_parser(command)
        for action in cli._SUBPARSERS[command]._actions:
            metavar = action.metavar
            names.update(metavar if isinstance(metavar, tuple) else [metavar or action.dest.upper()])
    names.update(rule.name for rule in RULES.values())
    return tuple(sorted((n for n in names if n), key=len, reverse=True))


def english_left(text: str) -> list[str]:
    """English words left in ``text`` once what is not language is taken out."""
    lines = [line for line in text.splitlines() if not line.startswith("$ bras-kit")]
    text = "\n".join(lines)
    text = re.sub(r"bras-kit( \w+)?", " ", text)  # the command and its sub-command
    text = re.sub(r"(?m)^ {2,6}[a-z]+(?= {2,})", " ", text)  # command names in the help's list
    text = re.sub(r"(?m)^\s*-?\s*\w+:\s*(\[[^\]\n]*\]|[\w.-]+)\s*$", " ", text)  # YAML keys and values
    text = re.sub(r"<[^<>\n]*>", " ", text)  # XML and <TMP>-like placeholders
    text = re.sub(r"'[^'\n]*'|\"[^\"\n]*\"|`[^`\n]*`|«[^»\n]*»", " ", text)  # quoted names and values
    text = re.sub(r"(?<=\w)-\n\s+(?=\w)", "-", text)  # argparse wraps help lines at hyphens
    text = re.sub(r"(?<![\w-])--?[A-Za-z][\w-]*", " ", text)  # options
    text = re.sub(r"\S*[/\\]\S*|\S+\.(png|gif|svg|csv|json|urdf|xacro|xml|html|dot|pdf|yaml|py|mp4)\b", " ", text)
    text = re.sub(r"\b\w+\s*=\s*\S+", " ", text)  # name=value, formulas
    for name in _typed_names():
        text = re.sub(r"(?<![\w-])" + re.escape(name) + r"(?![\w-])", " ", text)
    return sorted({m.lower() for m in ENGLISH.findall(text)})


@pytest.mark.parametrize("name", sorted(CASES))
def test_french_output_has_no_english_sentence(name, matrix_dir):
    text = _run(name, "fr", _case_dir(matrix_dir, name, "fr"))
    assert "Traceback" not in text
    left = english_left(text)
    assert not left, f"English words {left} in:\n{text}"


def test_the_detector_sees_english_and_leaves_names_alone():
    assert english_left("a.gif écrit: 7 frames at 7 fps (1 s)") == ["at", "frames"]
    assert english_left("bras-kit frames: écrit") == []
    assert english_left("--pose names joint 'Coude', which this robot does not have") == \
        ["does", "have", "joint", "names", "not", "this", "which"]
    assert english_left("mouvement : 0.5 rad au-delà de la butée à t=7.85 s") == []
    assert english_left("publie sur joint_states avec 'the' <link name=\"to\"/> --from A") == []
    assert english_left("At base -> bras") == ["at"]
    assert english_left("  frames        dessiner l'arbre des repères") == []
    assert english_left("    severity: error") == []
