"""Mutation test over real robot files (example-robot-data): numbers replaced by what urdfdom or
Python read differently (nan, inf, 1e308, '١', '1_0', 'None'...), elements dropped, then every
command that reads a robot runs on the result. Whatever the file, a command ends with exit 0, 1
or 2 and a message: never a traceback, never "internal error".

The budget is fixed and derandomized (the same mutants every run); the oracle is the CLI's own
contract, checked on the output text, not the code under test.
"""

from __future__ import annotations

import contextlib
import io
import re
import site
import tempfile
from pathlib import Path

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from bras_kit.cli import main

ROBOTS = next((Path(folder) / "cmeel.prefix" / "share" / "example-robot-data" / "robots"
               for folder in site.getsitepackages()
               if (Path(folder) / "cmeel.prefix" / "share" / "example-robot-data" / "robots").is_dir()), None)
if ROBOTS is None:  # pragma: no cover - a non-standard layout: ask the package
    import example_robot_data  # type: ignore[import-not-found]

    ROBOTS = Path(example_robot_data.getModelPath("ur_description/urdf/ur5_robot.urdf")) / "example-robot-data" / "robots"
FILES = ["double_pendulum_description/urdf/double_pendulum.urdf", "asr_twodof_description/urdf/TwoDofs.urdf",
         "ur_description/urdf/ur5_robot.urdf", "so_arm_description/urdf/so100.urdf"]
NUMBER = re.compile(r'\b(xyz|rpy|value|lower|upper|effort|velocity|ixx|iyy|izz|ixy|ixz|iyz|size|radius|length|'
                    r'damping|friction|multiplier|offset)="([^"]*)"')
REPLACEMENTS = ["nan", "inf", "-inf", "1e308", "-1e308", "0", "-1", "1e-300", "\u0661", "\uff11", "1_0", "None", "",
                "1 2", "0x10", "nan nan nan", "1e308 1e308 0", "-0"]
DROPPABLE = re.compile(r"<(inertial|limit|axis|origin|dynamics)\b[^>]*/>|<inertial>.*?</inertial>", re.S)
EXAMPLES = 12


def mutate(text: str, edits: list[tuple[int, str]], drops: list[int]) -> str:
    for index, replacement in edits:
        found = list(NUMBER.finditer(text))
        match = found[index % len(found)]
        text = text[:match.start(2)] + replacement + text[match.end(2):]
    for index in drops:
        found = list(DROPPABLE.finditer(text))
        if found:
            match = found[index % len(found)]
            text = text[:match.start()] + text[match.end():]
    return text


def run(*argv: str) -> tuple[int, str]:
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        try:
            code = main(list(argv))
        except SystemExit as exit:  # argparse
            code = int(exit.code or 0)
    return code, out.getvalue() + err.getvalue()


def commands(path: Path, folder: Path) -> list[list[str]]:
    packages = ["--package-path", str(ROBOTS.parent)]
    return [
        ["validate", str(path), *packages],
        ["tree", str(path)],
        ["fk", str(path), *packages],
        ["frames", str(path), "-o", str(folder / "frames.svg"), "--force"],
        ["render", str(path), *packages, "--size", "64x48", "-o", str(folder / "robot.png"), "--force"],
        ["mjcf", str(path), *packages, "-o", str(folder / "robot.xml"), "--force"],
        ["simulate", str(path), *packages, "--duration", "0.1", "-o", str(folder / "states.csv"), "--force"],
    ]


def test_the_real_robots_to_mutate_are_installed():
    """example-robot-data is in the dev extra: without it the mutation test below would prove nothing."""
    assert ROBOTS is not None and all((ROBOTS / name).is_file() for name in FILES)


@settings(max_examples=EXAMPLES, derandomize=True, deadline=None, database=None,
          suppress_health_check=[HealthCheck.too_slow])
@given(st.sampled_from(FILES),
       st.lists(st.tuples(st.integers(0, 10_000), st.sampled_from(REPLACEMENTS)), min_size=1, max_size=3),
       st.lists(st.integers(0, 1000), max_size=2))
def test_every_command_on_a_mutated_real_robot_ends_cleanly(name, edits, drops):
    assert ROBOTS is not None, "example-robot-data is missing: pip install -e .[dev]"
    text = mutate((ROBOTS / name).read_text(encoding="utf-8"), edits, drops)
    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / Path(name).name
        path.write_text(text, encoding="utf-8")
        for argv in commands(path, Path(folder)):
            code, output = run(*argv)
            assert code in (0, 1, 2), (argv[0], code, output[-2000:])
            assert "Traceback" not in output and "internal error" not in output, (argv[0], edits, drops, output[-2000:])
            assert ".py:" not in output, (argv[0], output[-2000:])  # no Python warning with a source path
