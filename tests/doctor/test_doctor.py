"""bras-kit doctor, run for real: EGL here draws its test picture, MuJoCo drops its ball, viser's
client is there; without OpenGL (pyrender made unimportable in the child) it says the pictures
come from the pure-CPU fallback, names the fix and exits 1. Both languages."""

from __future__ import annotations

import os
import re
import subprocess
import sys

from bras_kit.core.message import M
from bras_kit.doctor.install import FAIL, OK, Check, healthy, run_checks

HIDE = "import sys\nfor name in {names!r}: sys.modules[name] = None\n"
MAIN = "from bras_kit.cli import main\nraise SystemExit(main({argv!r}))\n"


def _doctor(tmp_path, *args: str, hide: tuple[str, ...] = (), browser: str | None = "true"):
    env = {k: v for k, v in os.environ.items() if k not in ("DISPLAY", "WAYLAND_DISPLAY", "BROWSER")}
    env["XDG_CACHE_HOME"] = str(tmp_path / "cache")
    if browser:
        env["BROWSER"] = browser
    code = HIDE.format(names=list(hide)) + MAIN.format(argv=["doctor", *args])
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env,
                            timeout=120, cwd=tmp_path)
    assert "Traceback" not in result.stderr, result.stderr
    return result


def _line(output: str, name: str) -> str:
    (line,) = [line for line in output.splitlines() if re.match(rf"^\S+\s+{re.escape(name)} ?: ", line)]
    return line


def test_doctor_on_this_machine_finds_everything_working_and_exits_0(tmp_path):
    (tmp_path / "cache" / "bras-kit" / "meshes").mkdir(parents=True)
    (tmp_path / "cache" / "bras-kit" / "meshes" / "a.npz").write_bytes(b"x" * 2_000_000)
    result = _doctor(tmp_path)
    assert result.returncode == 0, result.stdout + result.stderr
    out = result.stdout
    assert out.splitlines()[-1] == "everything bras-kit needs works here"
    assert _line(out, "versions") == (f"ok    versions: Python {sys.version.split()[0]} (CPython), bras-kit 0.1.0")
    opengl = _line(out, "OpenGL")
    assert opengl.startswith("ok    OpenGL: EGL, ")
    assert "software rendering, no GPU (llvmpipe" in opengl  # Mesa's rasteriser: no GPU on this machine
    pixels = int(re.search(r"with (\d+) arm pixels", opengl).group(1))
    assert 200 < pixels < 64 * 48 / 2
    # a free fall of 0.5 s: g t^2 / 2 with g = 9.81 m/s^2, independent of MuJoCo's own numbers
    fallen = float(re.search(r"a ball fell ([\d.]+) m in 0.5 s", _line(out, "MuJoCo")).group(1))
    assert abs(fallen - 9.81 * 0.5**2 / 2) < 0.02
    assert _line(out, "browser viewer").startswith("ok    browser viewer: viser ")
    assert _line(out, "web browser") == "ok    web browser: 'bras-kit view' opens true"
    # the folder holds the 2 MB file and what the doctor's own test picture cached (the arm's URDF)
    files = [p for p in (tmp_path / "cache" / "bras-kit").rglob("*") if p.is_file()]
    megabytes = sum(p.stat().st_size for p in files) / 1e6
    assert _line(out, "cache folder") == (f"ok    cache folder: {tmp_path}/cache/bras-kit: "
                                          f"{len(files)} files, {megabytes:.1f} MB")
    assert len(files) == 2 and megabytes >= 2.0


def test_without_opengl_doctor_names_the_cpu_fallback_and_the_fix_and_exits_1(tmp_path):
    result = _doctor(tmp_path, hide=("pyrender",))
    assert result.returncode == 1
    lines = result.stdout.splitlines()
    opengl = _line(result.stdout, "OpenGL")
    assert opengl.startswith("fail  OpenGL: none (pyrender (OpenGL) cannot be loaded (ModuleNotFoundError: ")
    assert "pictures come from the pure-CPU fallback, slower" in opengl
    assert int(re.search(r"\((\d+) arm pixels", opengl).group(1)) > 200  # the fallback still draws the arm
    assert lines[lines.index(opengl) + 1] == "      fix: install it: pip install pyrender"
    assert lines[-1] == "1 problem to fix: see 'fix' above"
    assert _line(result.stdout, "MuJoCo").startswith("ok ")


def test_a_missing_mujoco_and_no_browser_in_french(tmp_path):
    result = _doctor(tmp_path, "--lang", "fr", hide=("mujoco",), browser=None)
    assert result.returncode == 1
    lines = result.stdout.splitlines()
    mujoco = _line(result.stdout, "MuJoCo")
    assert mujoco.startswith("échec     MuJoCo : MuJoCo ne peut pas être chargé (ModuleNotFoundError")
    assert lines[lines.index(mujoco) + 1] == "          correctif : installez-le : pip install mujoco"
    browser = _line(result.stdout, "navigateur web")
    assert browser.startswith("remarque  navigateur web : aucun")  # no display, no $BROWSER: a note, not a failure
    assert lines[-1] == "1 problème à corriger : voir « correctif » ci-dessus"
    assert _line(result.stdout, "OpenGL").startswith("ok        OpenGL : EGL, rendu logiciel, sans GPU")


def test_a_check_that_crashes_is_a_failed_line_and_the_others_still_run():
    def check_boom() -> Check:
        raise RuntimeError("boom")

    def check_fine() -> Check:
        return Check(M("fine"), OK, M("yes"))

    results = run_checks([check_boom, check_fine])
    assert [r.status for r in results] == [FAIL, OK]
    assert str(results[0].found) == "RuntimeError: boom"
    assert not healthy(results) and healthy(results[1:])


def test_doctor_counts_the_decoded_meshes_and_clear_cache_removes_them_alone(tmp_path):
    meshes = tmp_path / "cache" / "bras-kit" / "meshes"
    meshes.mkdir(parents=True)
    for k in range(3):
        (meshes / f"{k:040x}.npz").write_bytes(b"x" * 500_000)  # entry names: 40 hex digits
    (meshes / "mine.txt").write_text("not an entry")
    result = _doctor(tmp_path)
    assert _line(result.stdout, "mesh cache") == (f"ok    mesh cache: 3 decoded meshes, 1.5 MB of at most 537 MB, "
                                                  f"in {meshes}")
    result = _doctor(tmp_path, "--clear-cache")
    assert result.stdout.splitlines()[0] == f"removed 3 decoded meshes (1.5 MB) from {meshes}"
    assert _line(result.stdout, "mesh cache").startswith("ok    mesh cache: 0 decoded meshes, 0.0 MB")
    assert [p.name for p in meshes.iterdir()] == ["mine.txt"]
