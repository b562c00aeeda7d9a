"""BK628-BK629: setup.cfg as colcon and setuptools read it. The oracle is the real setuptools of
the system Python (outside a venv, as a learner's colcon runs it: inside one, setuptools skips
install-* keys of setup.cfg without a word), run with the command line colcon runs (colcon-core ``task/python/build.py`` lines
110-131: ``setup.py egg_info ... build ... install --record ... [--install-scripts VALUE]
--single-version-externally-managed``), and its own deprecation warnings."""

from __future__ import annotations

import configparser
import re
import subprocess
import sys
from pathlib import Path

import pytest

from bras_kit.scaffold.package import scaffold_package
from bras_kit.validate.package import validate_package

PKG = "bras_description"
SYSTEM_PYTHON = "/usr/bin/python3"
GOOD = "[develop]\nscript_dir=$base/lib/{pkg}\n[install]\ninstall_scripts=$base/lib/{pkg}\n"

# name -> setup.cfg text (None: no file). Cases beyond the two: a missing section, the
# old package's name after a copy, ${base}, a trailing slash, keys in other sections, comments
CASES: dict[str, str | None] = {
    "good": GOOD,
    "missing": None,
    "dash_keys": "[develop]\nscript-dir=$base/lib/{pkg}\n[install]\ninstall-scripts=$base/lib/{pkg}\n",
    "mixed": "[develop]\nscript-dir=$base/lib/{pkg}\n[install]\ninstall_scripts=$base/lib/{pkg}\n",
    "no_install_section": "[develop]\nscript_dir=$base/lib/{pkg}\n",
    "empty": "",
    "copied_name": "[develop]\nscript_dir=$base/lib/my_package\n[install]\ninstall_scripts=$base/lib/my_package\n",
    "dollar_braced": "[develop]\nscript_dir=${{base}}/lib/{pkg}\n[install]\ninstall_scripts=${{base}}/lib/{pkg}/\n",
    "format_braced": "[install]\ninstall_scripts={{base}}/lib/{pkg}/\n",
    "bin": "[install]\ninstall_scripts=$base/bin\n",
    "metadata_dash": "[metadata]\nlong-description = x\n" + GOOD,
    "not_setuptools_section": "[flake8]\nmax-line-length = 99\n" + GOOD,
    "entry_points_dash": "[options.entry_points]\nconsole-scripts-x = \n" + GOOD,
    "commented": "# script-dir=$base/lib/x\n" + GOOD,
    "upper_section_key": "[install]\ninstall-scripts = $base/lib/{pkg}\n[egg_info]\ntag-build = \n",
}
ASIDE = {  # kept aside, run last
    "develop_only_dash": "[develop]\nscript-dir=$base/lib/{pkg}\n[install]\ninstall_scripts=$base/lib/{pkg}\n"
                         "[bdist_wheel]\nuniversal-x = 0\n",
    "broken": "[install\ninstall_scripts=$base/lib/{pkg}\n",
}


def make(tmp_path: Path, cfg: str | None) -> Path:
    folder = tmp_path / PKG
    scaffold_package(folder)
    target = folder / "setup.cfg"
    target.unlink()
    if cfg is not None:
        target.write_text(cfg.format(pkg=PKG), encoding="utf-8")
    return folder


def codes(folder: Path) -> dict[str, list[int | None]]:
    found: dict[str, list[int | None]] = {}
    for result in validate_package(str(folder)):
        for finding in result.findings:
            if finding.code in ("BK628", "BK629"):
                found.setdefault(finding.code, []).append(finding.line)
    return found


def colcon_install(folder: Path, tmp_path: Path) -> tuple[Path, str]:
    """setup.py run as colcon runs it; the prefix and setuptools' stderr."""
    prefix, build = tmp_path / "install" / PKG, tmp_path / "build" / PKG
    build.mkdir(parents=True)
    parser = configparser.ConfigParser()
    parser.optionxform = str  # type: ignore[assignment,method-assign]
    scripts = None
    try:
        parser.read(folder / "setup.cfg")
        scripts = parser.get("install", "install-scripts", fallback=None) or \
            parser.get("install", "install_scripts", fallback=None)
    except configparser.Error:
        pass
    cmd = [SYSTEM_PYTHON, "-W", "ignore:setup.py install is deprecated", "setup.py", "egg_info", "--egg-base",
           str(build), "build", "--build-base", str(build / "build"), "install", "--prefix", str(prefix),
           "--record", str(build / "install.log")]
    if scripts:
        cmd += ["--install-scripts", scripts]
    cmd += ["--single-version-externally-managed", "--install-layout", "deb"]  # Debian's Python (build.py 372-378)
    done = subprocess.run(cmd, cwd=folder, capture_output=True, text=True, timeout=120)
    return prefix, done.stdout + done.stderr


def oracle(folder: Path, tmp_path: Path) -> tuple[bool, set[str], bool]:
    """(the script lands in lib/PKG, the dash keys setuptools warns about, setuptools refused the file)."""
    prefix, output = colcon_install(folder, tmp_path)
    in_lib = (prefix / "lib" / PKG / "animation").is_file()
    warned = set(re.findall(r"Usage of dash-separated '([^']+)'", output))
    refused = "ParsingError" in output or "MissingSectionHeaderError" in output or "Error" in output and not in_lib \
        and not (prefix / "bin" / "animation").is_file()
    return in_lib, warned, refused


def check_against_setuptools(tmp_path: Path, cfg: str | None) -> None:
    folder = make(tmp_path, cfg)
    found = codes(folder)
    in_lib, warned, refused = oracle(folder, tmp_path)
    assert ("BK628" in found) == (not in_lib), (found, in_lib)
    text = (folder / "setup.cfg").read_text() if cfg is not None else ""
    dash_lines = [n for n, line in enumerate(text.splitlines(), 1)
                  if any(line.strip().startswith(key) for key in warned)]
    if not refused:
        assert sorted(found.get("BK629", [])) == sorted(dash_lines), (found, warned)


@pytest.mark.parametrize("case", sorted(CASES))
def test_setup_cfg_judged_as_setuptools_installs(tmp_path: Path, case: str) -> None:
    check_against_setuptools(tmp_path, CASES[case])


def test_missing_setup_cfg_puts_the_script_in_bin(tmp_path: Path) -> None:
    folder = make(tmp_path, None)
    prefix, _ = colcon_install(folder, tmp_path)
    assert (prefix / "bin" / "animation").is_file()
    (finding,) = [f for r in validate_package(str(folder)) for f in r.findings if f.code == "BK628"]
    message = finding.as_dict("en")["message"]
    assert "No executable found" in message
    assert "install/bras_description/bin/" in message


def test_dash_key_quotes_setuptools_words(tmp_path: Path) -> None:
    folder = make(tmp_path, CASES["dash_keys"])
    _, output = colcon_install(folder, tmp_path)
    ours = [f.as_dict("en")["message"] for r in validate_package(str(folder)) for f in r.findings
            if f.code == "BK629"]
    theirs = re.findall(r"(Usage of dash-separated .*? instead)", output.replace("\n", " "))
    assert len(theirs) == 2
    assert len(ours) == 2
    for sentence in theirs:
        assert any(sentence.rstrip(".") in message for message in ours), (sentence, ours)


def test_no_console_script_no_bk628(tmp_path: Path) -> None:
    folder = make(tmp_path, None)
    setup = folder / "setup.py"
    setup.write_text(re.sub(r"'console_scripts': \[[^\]]*\]", "'console_scripts': []", setup.read_text()))
    assert "BK628" not in codes(folder)


def test_french_words(tmp_path: Path) -> None:
    folder = make(tmp_path, CASES["dash_keys"])
    done = subprocess.run([sys.executable, "-m", "bras_kit", "--lang", "fr", "validate", str(folder)],
                          capture_output=True, text=True, timeout=120)
    assert "BK629" in done.stdout, done.stdout + done.stderr
    assert "écrivez script_dir au lieu de script-dir" in done.stdout


@pytest.mark.parametrize("case", sorted(ASIDE))
def test_zz_aside_cases(tmp_path: Path, case: str) -> None:
    check_against_setuptools(tmp_path, ASIDE[case])


