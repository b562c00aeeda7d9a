"""Build one corpus variant with the real colcon and with ``bras-kit build``; what each made, comparable.

What is normalised, and why (the rest is compared as it is):

* the workspace's absolute path in a file's text becomes ``<WS>`` (each tool builds in a folder of its own);
* a ``console_scripts`` script's text becomes ``<entry script NAME>``: setuptools writes it from a template
  whose shebang is the building interpreter's path, bras-kit from one of its own; where it lands and its
  mode are compared;
* a Python shebang in a ``scripts=`` file becomes ``#!python`` (setuptools' build_scripts puts the building
  interpreter there);
* colcon's environment files: the ``.dsv`` descriptors are data and compared as they are; a hook script
  (``share/PKG/hook/NAME.sh``, ``.ps1``) by the call it makes, its comment lines aside (bras-kit's say
  who wrote them); a package script (``share/PKG/package.{bash,ps1,sh,zsh}``) is bras-kit's own text,
  so only where it lands and its mode are compared here, and what sourcing it exports by
  :func:`exported`;
* left out: the egg-info folder (setuptools' metadata, SOURCES.txt and PKG-INFO), ``__pycache__``, and
  the workspace-level scripts (install/setup.*, local_setup.*, _local_setup_util_*.py, COLCON_IGNORE,
  .colcon_install_layout): bras-kit writes one setup.bash of its own instead, compared by what
  sourcing it exports (:func:`exported`).

The verdict: the exit code, the packages colcon says Finished and Failed, and colcon's error lines
(setuptools' ``error: ...``, ``CMake Error...``, catkin_pkg's) that bras-kit must print in colcon's words.
"""

from __future__ import annotations

import hashlib
import json
import os
import re
import stat
import subprocess
import sys
import tempfile
from dataclasses import dataclass
from pathlib import Path

import colcon_corpus
import realcolcon
from realros import _cache

_SKIPPED_TOP = re.compile(r"^(setup|local_setup)\.\w+$|^_local_setup_util_\w+\.py$|^COLCON_IGNORE$|"
                          r"^\.colcon_install_layout$")
_SKIPPED_PART = re.compile(r"\.egg-info(/|$)|(^|/)__pycache__(/|$)")
_HOOK_SCRIPT = re.compile(r"^[^/]+/share/[^/]+/hook/[^/]+\.(sh|ps1)$")
_PACKAGE_SCRIPT = re.compile(r"^[^/]+/share/[^/]+/package\.(bash|ps1|sh|zsh)$")
_ENTRY = re.compile(r"EASY-INSTALL-ENTRY-SCRIPT: '[^']*','console_scripts','([^']*)'")
_SHEBANG = re.compile(r"\A#![^\n]*python[0-9.]*[^\n]*")
_ERROR = re.compile(r"^(error: .*|CMake Error.*|Error\(s\) in package .*|ERROR:colcon.*|[A-Z]\w*(Error|Exception): .*)$")
_VERDICT = re.compile(r"^(Finished|Failed)\s+<<< (\S+)")


@dataclass
class Outcome:
    tree: dict[str, tuple[str, int, str]]  # path under install/ -> (kind, mode, text)
    code: int
    finished: frozenset[str]
    failed: frozenset[str]
    output: str  # stdout and stderr, the workspace's path as <WS>
    workspace: Path

    def errors(self) -> list[str]:
        return [line.strip() for line in self.output.splitlines() if _ERROR.match(line.strip())]


def make_workspace(root: Path, variant: str) -> Path:
    for relative, text in colcon_corpus.VARIANTS[variant].items():
        path = root / "src" / relative
        path.parent.mkdir(parents=True, exist_ok=True)
        path.write_text(text, encoding="utf-8")
    return root


def install_tree(workspace: Path) -> dict[str, tuple[str, int, str]]:
    install = workspace / "install"
    tree: dict[str, tuple[str, int, str]] = {}
    if not install.is_dir():
        return tree
    for folder, dirs, files in os.walk(install):
        for name in (*dirs, *files):
            path = Path(folder) / name
            relative = path.relative_to(install).as_posix()
            if ("/" not in relative and _SKIPPED_TOP.match(relative)) or _SKIPPED_PART.search(relative):
                continue
            info = path.lstat()
            if stat.S_ISLNK(info.st_mode):
                tree[relative] = ("link", 0, os.readlink(path).replace(str(workspace), "<WS>"))
            elif stat.S_ISDIR(info.st_mode):
                tree[relative] = ("dir", stat.S_IMODE(info.st_mode), "")
            else:
                text = path.read_bytes().decode("utf-8", "replace").replace(str(workspace), "<WS>")
                entry = _ENTRY.search(text)
                if _PACKAGE_SCRIPT.match(relative):
                    text = "<package script>"  # bras-kit's own text: what sourcing it exports is compared
                elif _HOOK_SCRIPT.match(relative):  # the call each hook makes, its comments aside
                    text = "\n".join(line for line in text.splitlines() if line.strip() and not line.startswith("#"))
                elif entry:
                    text = f"<entry script {entry.group(1)}>"
                else:
                    text = _SHEBANG.sub("#!python", text)
                tree[relative] = ("file", stat.S_IMODE(info.st_mode), text)
    return tree


def _outcome(workspace: Path, done: subprocess.CompletedProcess[str]) -> Outcome:
    output = (done.stdout + "\n" + done.stderr).replace(str(workspace), "<WS>")
    verdicts = [m.groups() for m in map(_VERDICT.match, output.splitlines()) if m]
    return Outcome(install_tree(workspace), done.returncode,
                   frozenset(p for v, p in verdicts if v == "Finished"),
                   frozenset(p for v, p in verdicts if v == "Failed"), output, workspace)


def by_colcon(variant: str, root: Path, *extra: str) -> Outcome:
    """The real colcon's build of ``variant``: run once for each content, then read back from the cache
    folder (see :func:`_key`), where the workspace it built stays, its scripts sourceable. ``root`` is
    used when nothing is kept (BRAS_KIT_COLCON_FRESH=1)."""
    if os.environ.get("BRAS_KIT_COLCON_FRESH"):
        workspace = make_workspace(root, variant)
        return _outcome(workspace, realcolcon.colcon_build(workspace, *extra))
    key = _key(variant, extra)
    base = _cache() / "colcon-outcomes"
    pointer = base / f"{key}.json"
    if pointer.is_file():
        done = json.loads(pointer.read_text())
        if (Path(done["workspace"]) / "src").is_dir():
            return _outcome(Path(done["workspace"]), subprocess.CompletedProcess([], done["code"], done["stdout"],
                                                                                 done["stderr"]))
    base.mkdir(parents=True, exist_ok=True)
    # built where it stays (colcon's package.sh holds its build-time prefix); the pointer written last,
    # whole (os.replace), so a session at the same time reads a finished build or builds its own
    workspace = make_workspace(Path(tempfile.mkdtemp(dir=base, prefix=f"{key}-")), variant)
    built = realcolcon.colcon_build(workspace, *extra)
    staged = pointer.with_suffix(f".{os.getpid()}")
    staged.write_text(json.dumps({"workspace": str(workspace), "code": built.returncode, "stdout": built.stdout,
                                  "stderr": built.stderr}))
    os.replace(staged, pointer)
    return _outcome(workspace, built)


# The real colcon's builds, kept: a workspace built by the pinned colcon depends on nothing but the
# variant's files, the flags, the pins, the Python and the oracle's environment and executable
# (tests/realcolcon.py), so each is kept under that content's hash under the cache folder, and a second
# session reads what colcon made instead of making it again. What is compared is read from the kept
# workspace each time (the normalisation above applies then). BRAS_KIT_COLCON_FRESH=1 builds anew.
def _key(variant: str, extra: tuple[str, ...]) -> str:
    given = json.dumps([sorted(colcon_corpus.VARIANTS[variant].items()), list(extra), sys.version_info[:2],
                        realcolcon.CONSTRAINTS.read_text(), Path(realcolcon.__file__).read_text(),
                        os.environ.get("BRAS_KIT_COLCON", "")])
    return hashlib.sha256(given.encode()).hexdigest()[:24]


def by_bras_kit(variant: str, root: Path, *extra: str) -> Outcome:
    workspace = make_workspace(root, variant)
    # the oracle's environment (no ROS, no colcon set-up of the caller's: conditions and chained prefixes
    # read alike), with what bras-kit itself needs from the caller's
    env = {k: v for k, v in realcolcon.colcon_env(root / ".colcon-home").items() if not k.startswith("COLCON_")}
    env.pop("BRAS_KIT_LANG", None)
    done = subprocess.run([sys.executable, "-m", "bras_kit", "build", str(workspace), *extra], cwd=workspace,
                          env=env, capture_output=True, text=True, timeout=120)
    return _outcome(workspace, done)


EXPORTED = ("AMENT_PREFIX_PATH", "COLCON_PREFIX_PATH", "PYTHONPATH", "PATH", "CMAKE_PREFIX_PATH", "LD_LIBRARY_PATH",
            "PKG_CONFIG_PATH", "CMAKE_MODULE_PATH", "COLCON_CURRENT_PREFIX")
CLEAN_PATH = "/usr/bin:/bin"


def exported(outcome: Outcome, script: str, shell: str = "bash") -> dict[str, str] | str:
    """What sourcing ``install/SCRIPT`` in a clean ``shell`` leaves set (the workspace's path as <WS>), or
    what it printed on stderr when it failed; {} when there is no such script."""
    path = outcome.workspace / "install" / script
    if not path.is_file():
        return {}
    done = subprocess.run([shell, "-c", '. "$1" && env -0', shell, str(path)], capture_output=True, timeout=30,
                          env={"PATH": CLEAN_PATH, "HOME": str(outcome.workspace), "LC_ALL": "C.UTF-8"})
    if done.returncode:
        return "failed: " + done.stderr.decode("utf-8", "replace").replace(str(outcome.workspace), "<WS>")
    values = dict(item.split("=", 1) for item in done.stdout.decode("utf-8", "replace").split("\0") if "=" in item)
    return {name: values[name].replace(str(outcome.workspace), "<WS>") for name in EXPORTED if name in values}


def differences(colcon: Outcome, ours: Outcome) -> list[str]:
    """What ``bras-kit build`` did otherwise than colcon, one line each (empty: they agree)."""
    out = []
    for path in sorted(set(colcon.tree) | set(ours.tree)):
        theirs, mine = colcon.tree.get(path), ours.tree.get(path)
        if theirs is None:
            out.append(f"only bras-kit made {path}")
        elif mine is None:
            out.append(f"only colcon made {path}")
        elif theirs != mine:
            out.append(f"{path}: colcon {theirs!r}, bras-kit {mine!r}")
    if colcon.code != ours.code:
        out.append(f"exit code: colcon {colcon.code}, bras-kit {ours.code}")
    if (colcon.finished, colcon.failed) != (ours.finished, ours.failed):
        out.append(f"verdicts: colcon finished {sorted(colcon.finished)} failed {sorted(colcon.failed)}, "
                   f"bras-kit finished {sorted(ours.finished)} failed {sorted(ours.failed)}")
    for line in colcon.errors():
        if line not in ours.output:
            out.append(f"colcon's words missing: {line}")
    return out


if __name__ == "__main__":  # python tests/colcon_compare.py [VARIANT...]: the table of agreements
    flags = [a for a in sys.argv[1:] if a.startswith("--")]  # --symlink-install, given to both
    names = [a for a in sys.argv[1:] if not a.startswith("--")] or list(colcon_corpus.VARIANTS)
    agree = 0
    for name in names:
        with tempfile.TemporaryDirectory() as a, tempfile.TemporaryDirectory() as b:
            found = differences(by_colcon(name, Path(a), *flags), by_bras_kit(name, Path(b), *flags))
        agree += not found
        print(f"{'agree ' if not found else 'DIFFER'} {name}")
        for line in found:
            print("    " + line[:300])
    print(f"{agree} of {len(names)} variants agree")
