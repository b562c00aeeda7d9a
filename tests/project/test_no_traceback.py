"""No traceback, ever: every command over a table of bad inputs, each in a real process.

Each case must end with exit code 1 or 2, a one-line ``error:`` (or a finding) that says what
is wrong, and no ``Traceback`` anywhere in the output.
"""

from __future__ import annotations

import os
import resource
import subprocess
import sys

import pytest
from paths import TESTS

from bras_kit.cli import COMMANDS

pytestmark = pytest.mark.slow

HOSTILE = TESTS / "data" / "hostile"

# commands reading a robot description from FILE
FILE_COMMANDS = ["validate", "tree", "fk", "motion", "render", "frames", "plot", "workspace", "simulate", "mjcf",
                 "xacro", "view", "gazebo"]
# command -> how it is asked to write a file
OUTPUTS = {
    "urdf": ["-o"], "xacro": ["-o"], "frames": ["-o"], "plot": ["-o"], "motion": ["-o"], "render": ["-o"],
    "workspace": ["-o"], "mjcf": ["--inertials", "-o"], "simulate": ["--inertials", "-o"], "view": ["--export"],
    "run": ["-o"],
}
EXTRA = {"reach": ["0.3", "0", "0.5"], "xacro": []}


@pytest.fixture(scope="module")
def bad(tmp_path_factory):
    root = tmp_path_factory.mktemp("bad")
    (root / "folder.urdf").mkdir()
    os.mkfifo(root / "pipe.urdf")
    (root / "notxml.urdf").write_text("this is not xml <<<\n")
    (root / "latin1.urdf").write_bytes('<robot name="é"><link name="a"/></robot>\n'.encode("latin-1"))
    (root / "a_file").write_text("x")
    os.symlink(root / "nowhere" / "victim.png", root / "dangling.png")
    chain = ['<robot name="chain">'] + [f'<link name="l{i}"/>' for i in range(100_000)] + [
        f'<joint name="j{i}" type="fixed"><parent link="l{i - 1}"/><child link="l{i}"/></joint>'
        for i in range(1, 100_000)] + ["</robot>"]
    (root / "chain100k.urdf").write_text("\n".join(chain))
    return root


def _run(args, cwd, limit_memory: int | None = None):
    def limits():  # pragma: no cover - runs in the child
        if limit_memory:
            resource.setrlimit(resource.RLIMIT_AS, (limit_memory, limit_memory))

    env = dict(os.environ, MPLBACKEND="Agg")
    return subprocess.run([sys.executable, "-m", "bras_kit", *args], cwd=cwd, capture_output=True, text=True,
                          timeout=300, stdin=subprocess.DEVNULL, env=env, preexec_fn=limits)


def _clean(result, words: str | None = None) -> None:
    output = result.stdout + result.stderr
    assert "Traceback" not in output, output
    assert result.returncode in (1, 2), (result.returncode, output)
    if words:
        assert words in output, output


def _file_cases() -> list[tuple[str, str, str]]:
    cases = []
    for command in FILE_COMMANDS:
        for name, words in [("missing.urdf", "no such file"), ("folder.urdf", "folder"),
                            ("pipe.urdf", "not a regular file"), ("/dev/zero", ""),
                            ("notxml.urdf", ""), (str(HOSTILE / "power_tower.xacro"), "too large")]:
            if command == "xacro" and not name.endswith(".xacro") and name != "missing.urdf":
                continue
            cases.append((command, name, words))
    return cases


def test_the_table_covers_every_command_that_reads_or_writes():
    listed = set(FILE_COMMANDS) | set(OUTPUTS) | set(EXTRA) | {"demo", "new", "explain", "grade", "doctor", "build",
                                                                   "launch", "exercises"}
    assert set(COMMANDS) <= listed


@pytest.mark.parametrize("argv,words", [
    (["grade", "no_such_class"], "is not a folder"),
    (["grade", "a_file"], "is not a folder"),
    (["grade", "folder.urdf"], "is empty"),
    (["grade", ".", "-o", "a_file"], "exists and is not a folder"),
    (["grade", ".", "-o", "dangling.png"], "exists and is not a folder"),
    (["grade", ".", "--rubric", "/dev/zero"], "rubric"),
    (["grade", ".", "--jobs", "0"], "out of range"),
    (["grade", ".", "--scheduler", "tcp://127.0.0.1:9"], "cannot reach the Dask scheduler"),
])
def test_grade_bad_input_is_a_clean_error(bad, argv, words):
    _clean(_run(argv, bad), words)


@pytest.mark.parametrize("command,name,words", _file_cases(), ids=lambda v: str(v).replace("/", "_"))
def test_unreadable_input_is_a_clean_error(bad, command, name, words):
    _clean(_run([command, name], bad), words)


OUTPUT_CASES = [
    ("a folder", "outdir.png", "is a folder"),
    ("/proc", "/proc/self/bras_kit_out.png", "cannot write"),
    ("under a file", "a_file/x.png", "cannot write a_file/x"),
    ("missing folder", "no/such/dir/x.png", "does not exist"),
    ("dangling link", "dangling.png", "already exists"),
]


@pytest.mark.parametrize("command", sorted(OUTPUTS))
@pytest.mark.parametrize("label,target,words", OUTPUT_CASES, ids=[c[0] for c in OUTPUT_CASES])
def test_bad_output_path_is_a_clean_error(bad, command, label, target, words):
    suffix = {"urdf": ".urdf", "xacro": ".urdf", "motion": ".csv", "mjcf": ".xml", "simulate": ".csv",
              "run": ".csv"}.get(command)
    if suffix and target.endswith(".png"):
        target = target[:-4] + suffix
    if label == "a folder":
        (bad / target).mkdir(exist_ok=True)
    if suffix and label == "dangling link" and not os.path.lexists(bad / target):
        os.symlink(bad / "nowhere" / f"victim{suffix}", bad / target)
    args = [command] + ([str(HOSTILE.parent / "xacro" / "features.xacro")] if command == "xacro" else [])
    if command == "run":  # a node that runs, so the output is the only thing wrong
        args += [str(HOSTILE.parent / "tutorial_package"), "--duration", "0.5", "--quiet"]
    result = _run([*args, *OUTPUTS[command], target], bad)
    _clean(result, words)
    assert not (bad / "nowhere").exists(), "a dangling link was followed"


def test_force_replaces_a_symlink_itself_never_its_target(bad, tmp_path):
    victim = tmp_path / "victim.txt"
    victim.write_text("precious\n")
    link = tmp_path / "out.urdf"
    os.symlink(victim, link)
    result = _run(["urdf", "-o", str(link), "--force"], tmp_path)
    assert result.returncode == 0, result.stderr
    assert victim.read_text() == "precious\n"
    assert not link.is_symlink() and "<robot" in link.read_text()


@pytest.mark.parametrize("args,words", [
    (["fk", "--set", "epaule=nan"], "finite"),
    (["render", "--set", "epaule=inf", "-o", "x.png"], "finite"),
    (["tree", "--set", "coude=nan"], "finite"),
    (["plot", "--set", "coude=-inf", "-o", "p.png"], "finite"),
    (["validate", "--pose", "epaule=nan"], "finite"),
    (["reach", "nan", "0", "0.5"], ""),
    (["render", "--size", "0x0", "-o", "y.png"], "out of range"),
    (["render", "--fps", "0", "--gif", "z.gif"], ""),
    (["explain", "BK999"], ""),
    (["new", "a_file"], ""),
    (["demo", "a_file"], "not a folder"),
])
def test_bad_values_are_clean_errors(bad, args, words):
    _clean(_run(args, bad), words)


def test_a_picture_too_large_for_memory_is_refused_with_the_largest_that_fits(bad):
    result = _run(["render", "--size", "8192x8192", "-o", "huge.png"], bad, limit_memory=3 << 30)
    _clean(result, "the largest square picture that fits")


@pytest.mark.parametrize("command,words", [
    ("tree", None), ("validate", None), ("frames", "more than 2000"), ("render", "more than the 5,000"),
])
def test_a_100000_link_model_works_or_is_refused_clearly(bad, command, words):
    result = _run([command, "chain100k.urdf"], bad, limit_memory=4 << 30)
    output = result.stdout + result.stderr
    assert "Traceback" not in output
    if words is None:
        assert result.returncode in (0, 1), output[-500:]
        assert "l99999" in output or command == "validate"
    else:
        _clean(result, words)
