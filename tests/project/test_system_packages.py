"""The README's set-up is the whole set-up: one list of system packages (system-packages.txt),
which .ci/run installs and README.md shows (issue 43: .ci/run installed libsdformat12-12 and tmux,
the README's apt line named neither, and a fresh machine following the README had 80 errors).

Oracles: the packages the tests themselves load or run (the paths and commands below, read from
the test files), Debian's apt (the list's Debian 12 column resolves on this Debian 12 machine),
and bash running .ci/run's own lines."""

from __future__ import annotations

import importlib.util
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
from paths import REPO

ROOT = REPO
LIST = ROOT / "system-packages.txt"


def _tool():
    spec = importlib.util.spec_from_file_location("system_packages", ROOT / "tools" / "system_packages.py")
    module = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = module  # dataclasses look their module up there
    spec.loader.exec_module(module)
    return module


TOOL = _tool()


def test_the_readme_shows_the_list_as_rendered():
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    assert TOOL.block() in readme, "README.md's system packages are stale: python tools/system_packages.py --write"
    for platform in TOOL.PLATFORMS:
        apt_line = "sudo apt-get update && sudo apt-get install -y " + " ".join(TOOL.column(platform))
        assert readme.count(apt_line) == 1
    # the set-up installs the system packages before the first pip command
    assert readme.index(TOOL.BEGIN) < readme.index('pip install -c constraints.txt -e ".[dev]"')
    assert len(re.findall(r"apt-get install", readme)) == len(TOOL.PLATFORMS)  # no second, partial list


def _ci_apt_lines() -> str:
    """The lines of .ci/run from the list's reading to its apt-get install."""
    text = (ROOT / ".ci" / "run").read_text(encoding="utf-8")
    start = text.index("SYSTEM_COLUMN=1")
    end = text.index('"${SYSTEM_PACKAGES[@]}"', start)
    return text[start:text.index("\n", end)]


@pytest.mark.parametrize(("os_release", "platform"), [("ID=debian\nVERSION_ID=\"12\"\n", "debian-12"),
                                                      ("ID=ubuntu\nVERSION_ID=\"24.04\"\n", "ubuntu-24.04")])
def test_ci_installs_the_lists_column_of_its_platform(tmp_path, os_release, platform):
    """.ci/run's own lines, run by bash with apt-get replaced by a recorder: the packages it
    installs are the list's column for the platform /etc/os-release names."""
    lines = _ci_apt_lines()
    assert "system-packages.txt" in lines and "apt-get install" in lines
    (tmp_path / "os-release").write_text(os_release, encoding="utf-8")
    shutil.copy(LIST, tmp_path / "system-packages.txt")
    script = lines.replace("/etc/os-release", str(tmp_path / "os-release"))
    recorder = 'apt_record() { printf "%s\\n" "$@" > installed.txt; }\nSUDO=""\n'
    script = script.replace("$SUDO apt-get update -qq", ":").replace("$SUDO apt-get install", "apt_record")
    done = subprocess.run(["bash", "-c", "set -euo pipefail\n" + recorder + script], cwd=tmp_path,
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    installed = [w for w in (tmp_path / "installed.txt").read_text().split() if not w.startswith("-")]
    assert installed == TOOL.column(platform)


def test_ci_names_no_system_package_outside_the_list():
    text = (ROOT / ".ci" / "run").read_text(encoding="utf-8")
    assert text.count("apt-get install") == 1
    for known in ("libsdformat12-12", "tmux", "chromium", "liburdfdom-tools"):
        assert known not in text.replace("system-packages.txt", ""), f".ci/run names {known} outside the list"


# what the suite loads or runs, as the test files name it -> the Debian package that provides it
NEEDED_BY_TESTS = {
    "libsdformat12-12": ("tests/sdformat_oracle.py", "libsdformat12.so.12"),
    "tmux": ("tests/exercises/test_exercises_watch.py", '"tmux"'),
    "chromium": ("tests/pages.py", '"/usr/bin/chromium"'),
    "liburdfdom-tools": ("tests/urdfdom_oracle.py", '"check_urdf", "liburdfdom-tools"'),
    "util-linux": ("tests/realros.py", '"unshare", "-rnm"'),
    "iproute2": ("tests/realros.py", "ip link set lo up"),
    "mesa-utils": ("tests/doctor/test_doctor_surroundings.py", '["glxinfo", "-B"]'),
    "xvfb": ("tests/doctor/test_doctor_surroundings.py", '["Xvfb", '),
}


@pytest.mark.parametrize("package", sorted(NEEDED_BY_TESTS))
def test_what_the_tests_load_is_on_the_list(package):
    path, needle = NEEDED_BY_TESTS[package]
    assert needle in (ROOT / path).read_text(encoding="utf-8"), f"{path} no longer uses {needle}: update this test"
    assert package in TOOL.column("debian-12")


def test_every_package_has_a_reason_and_both_platforms_say_something():
    packages = TOOL.read_list()
    assert len(packages) == len({p.names["debian-12"] for p in packages})
    for package in packages:
        assert len(package.why.split()) >= 2
        assert all(name == TOOL.ABSENT or re.fullmatch(r"[a-z0-9][a-z0-9.+-]+", name) for name in package.names.values())
        if TOOL.ABSENT in package.names.values():  # an absent package says what that platform has instead
            assert "Ubuntu 24.04" in package.why


def test_the_debian_column_resolves_with_apt_on_debian_12():
    """apt itself, on this machine (Debian 12, CI's platform), knows every name of the column."""
    release = Path("/etc/os-release").read_text(encoding="utf-8") if Path("/etc/os-release").exists() else ""
    assert 'VERSION_ID="12"' in release and "ID=debian" in release, "CI's platform is Debian 12"
    done = subprocess.run(["apt-get", "install", "-s", "--no-install-recommends", *TOOL.column("debian-12")],
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
