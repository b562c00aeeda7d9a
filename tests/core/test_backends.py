"""A missing or broken heavy backend is one error naming what to install, never a traceback.

Each case runs the real command in a fresh interpreter where the backend cannot be imported:
``sys.modules[name] = None`` is exactly what Python does for a package that is not there
(``ModuleNotFoundError``); a finder that raises a plain ``ImportError`` plays a package whose
shared library is missing (PyOpenGL without libEGL).
"""

from __future__ import annotations

import subprocess
import sys
import textwrap

import pytest

MISSING = "import sys\nfor name in {names!r}: sys.modules[name] = None\n"
BROKEN = textwrap.dedent("""
    import sys
    class Broken:
        def find_spec(self, name, path=None, target=None):
            if name.split('.')[0] in {names!r}:
                raise ImportError('Unable to load EGL library')
    sys.meta_path.insert(0, Broken())
""")
MAIN = "from bras_kit.cli import main\nraise SystemExit(main({argv!r}))\n"


def _run(prelude: str, argv: list[str], cwd) -> subprocess.CompletedProcess[str]:
    return subprocess.run([sys.executable, "-c", prelude + MAIN.format(argv=argv)], cwd=cwd,
                          capture_output=True, text=True, timeout=120)


def _error_lines(result: subprocess.CompletedProcess[str]) -> list[str]:
    assert "Traceback" not in result.stderr, result.stderr
    return [line for line in result.stderr.splitlines() if line.strip()]


@pytest.mark.parametrize(("names", "argv", "first", "hint"), [
    (["mujoco"], ["simulate", "--inertials", "--duration", "0.1"],
     "bras-kit simulate: error: MuJoCo cannot be loaded (ModuleNotFoundError: import of mujoco halted; None in sys.modules)",
     "  hint: install it: pip install mujoco"),
    (["mujoco"], ["mjcf", "--inertials", "-o", "arm.xml"],
     "bras-kit mjcf: error: MuJoCo cannot be loaded (ModuleNotFoundError: import of mujoco halted; None in sys.modules)",
     "  hint: install it: pip install mujoco"),
    (["viser"], ["view", "--export", "arm.html", "--duration", "0.2"],
     "bras-kit view: error: viser cannot be loaded (ModuleNotFoundError: import of viser halted; None in sys.modules)",
     "  hint: install it: pip install viser"),
    (["matplotlib"], ["frames", "-o", "frames.png"],
     "bras-kit frames: error: matplotlib cannot be loaded (ModuleNotFoundError: import of matplotlib halted; None in sys.modules)",
     "  hint: install it: pip install matplotlib"),
    (["pyrender"], ["render", "--backend", "egl", "-o", "arm.png"],
     "bras-kit render: error: pyrender (OpenGL) cannot be loaded (ModuleNotFoundError: import of pyrender halted; None in sys.modules)",
     "  hint: install it: pip install pyrender"),
    (["distributed"], ["grade", "submissions", "--scheduler", "tcp://127.0.0.1:1"],
     "bras-kit grade: error: Dask distributed cannot be loaded (ModuleNotFoundError: import of distributed halted; None in sys.modules)",
     "  hint: install it: pip install 'bras-kit[cluster]'"),
])
def test_a_missing_backend_is_one_error_naming_the_package_to_install(tmp_path, names, argv, first, hint):
    (tmp_path / "submissions" / "alice").mkdir(parents=True)
    result = _run(MISSING.format(names=names), argv, tmp_path)
    assert result.returncode == 2, result.stderr
    assert _error_lines(result) == [first, hint]
    if argv[0] != "grade":  # grade makes its report folder before it reaches the scheduler
        assert sorted(p.name for p in tmp_path.iterdir()) == ["submissions"], "nothing written"


def test_opengl_whose_library_fails_to_load_names_the_system_packages(tmp_path):
    result = _run(BROKEN.format(names=["OpenGL"]), ["render", "--backend", "egl", "-o", "arm.png"], tmp_path)
    assert result.returncode == 2
    assert _error_lines(result) == [
        "bras-kit render: error: pyrender (OpenGL) cannot be loaded (ImportError: Unable to load EGL library)",
        "  hint: on Debian/Ubuntu install the system libraries: sudo apt-get install "
        "libegl1 libegl-mesa0 libgl1 libgl1-mesa-dri libgbm1",
    ]


def test_without_pyrender_auto_falls_back_to_the_cpu_renderer_and_still_draws(tmp_path):
    from PIL import Image

    result = _run(MISSING.format(names=["pyrender"]), ["render", "-o", "arm.png", "--size", "64x48"], tmp_path)
    assert result.returncode == 0, result.stderr
    assert "software renderer" in result.stderr and "pyrender (OpenGL) cannot be loaded" in result.stderr
    with Image.open(tmp_path / "arm.png") as picture:
        assert picture.size == (64, 48)
        assert len(picture.convert("RGB").getcolors(maxcolors=1 << 16)) > 2  # the arm, not a blank picture


def test_the_french_error_is_worded_from_the_catalog(tmp_path):
    result = _run(MISSING.format(names=["mujoco"]), ["simulate", "--inertials", "--duration", "0.1", "--lang", "fr"], tmp_path)
    assert result.returncode == 2
    lines = _error_lines(result)
    assert lines[0].startswith("bras-kit simulate : erreur : MuJoCo ne peut pas être chargé (")
    assert lines[1] == "  conseil : installez-le : pip install mujoco"


def test_the_cli_starts_without_importing_any_backend():
    code = ("import contextlib, sys\nfrom bras_kit.cli import main\n"
            "with contextlib.suppress(SystemExit): main(['--help'])\n"
            "heavy = {'pyrender', 'OpenGL', 'mujoco', 'viser', 'matplotlib', 'distributed', 'dask', 'trimesh'}\n"
            "print(sorted(heavy & set(sys.modules)))\n")
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=60)
    assert result.stdout.splitlines()[-1] == "[]"
