"""The command line itself: help, version, `python -m bras_kit`, and a start-up free of heavy imports."""

from __future__ import annotations

import json
import subprocess
import sys

import pytest

import bras_kit
from bras_kit.cli import COMMANDS, build_parser, command_groups

HEAVY = ("pyrender", "matplotlib", "trimesh", "yourdfpy", "PIL", "imageio", "scipy")


def listed_commands(help_text: str) -> list[str]:
    """Command names as the help prints them: one per line, indented, before their help."""
    names = []
    for line in help_text.splitlines():
        words = line.split()
        if line.startswith("  ") and words and words[0] in COMMANDS:
            names.append(words[0])
    return names


def test_help_lists_every_command(run_cli):
    code, out, _ = run_cli("--help")
    assert code == 0
    assert listed_commands(out) == [name for _, names in command_groups() for name in names]
    assert sorted(listed_commands(out)) == sorted(COMMANDS)


def test_no_command_prints_help_and_succeeds(run_cli):
    code, out, _ = run_cli()
    assert code == 0
    assert sorted(listed_commands(out)) == sorted(COMMANDS)


def test_version(run_cli):
    code, out, _ = run_cli("--version")
    assert code == 0
    assert out.strip() == f"bras-kit {bras_kit.__version__}"


def test_unknown_command_is_a_usage_error(run_cli):
    code, _, err = run_cli("fly")
    assert code == 2
    assert "invalid choice: 'fly'" in err


def test_python_dash_m_runs_the_cli():
    result = subprocess.run([sys.executable, "-m", "bras_kit", "--help"], capture_output=True,
                            text=True, timeout=120)
    assert result.returncode == 0, result.stderr
    assert sorted(listed_commands(result.stdout)) == sorted(COMMANDS)
    version = subprocess.run([sys.executable, "-m", "bras_kit", "--version"], capture_output=True,
                             text=True, timeout=120)
    assert version.stdout.strip() == f"bras-kit {bras_kit.__version__}"


def modules_after(code: str) -> set[str]:
    """Top-level modules loaded by a fresh interpreter after running ``code``."""
    script = code + "\nimport json, sys\nprint(json.dumps(sorted({m.split('.')[0] for m in sys.modules})))"
    result = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=120)
    assert result.returncode == 0, result.stderr
    return set(json.loads(result.stdout.splitlines()[-1]))


@pytest.mark.parametrize("code", [
    "from bras_kit.cli import main\ntry:\n    main(['--help'])\nexcept SystemExit:\n    pass",
    "from bras_kit.cli import build_parser\nbuild_parser(None)",
    *(f"from bras_kit.cli import main\ntry:\n    main(['{name}', '--help'])\nexcept SystemExit:\n    pass"
      for name in ("urdf", "xacro", "new")),
    "import bras_kit, bras_kit.model.authoring, bras_kit.model.robot, bras_kit.kinematics.frames, bras_kit.model.xmlio",
], ids=["help", "build-parser", "urdf-help", "xacro-help", "new-help", "library-core"])
def test_start_up_loads_no_heavy_module(code):
    loaded = modules_after(code)
    assert "bras_kit" in loaded
    assert not loaded & set(HEAVY), sorted(loaded & set(HEAVY))


def test_heavy_module_check_can_see_a_heavy_import():
    """The probe above really reports what was imported (so its emptiness means something)."""
    assert "PIL" in modules_after("import PIL.Image")


def test_new_command_parses_its_options():
    parser = build_parser("new")
    args = parser.parse_args(["new", "out", "--name", "mon_bras", "--wrist", "--param", "bras_length=0.8"])
    assert (args.command, args.dir, args.name, args.wrist, args.params) == (
        "new", "out", "mon_bras", True, ["bras_length=0.8"])
