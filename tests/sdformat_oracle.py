"""The tests' oracle for Gazebo: libsdformat 12 itself (Debian 12's ``libsdformat12-12``).

``ign sdf -k FILE`` and ``ign sdf -p FILE`` call the library's C entry points ``cmdCheck`` and
``cmdPrint`` (src/ign.cc of gazebosim/sdformat, tag sdformat12_12.3.0); so does this module,
through ctypes, in a child process: the library writes to the C stdout and stderr, which the
child's pipes capture, and a crash in it cannot take the test run down.

Nothing here re-implements the URDF conversion: the links and joints "kept" are read from the
SDF that ``cmdPrint`` returns.
"""

from __future__ import annotations

import ctypes.util
import glob
import os
import re
import subprocess
import sys
import xml.etree.ElementTree as ET
from dataclasses import dataclass
from functools import cache

import system

_CHILD = r"""
import ctypes, sys
lib = ctypes.CDLL(sys.argv[1])
call = getattr(lib, sys.argv[2])
call.argtypes = [ctypes.c_char_p]
call.restype = ctypes.c_int
sys.stdout.flush()
rc = call(sys.argv[3].encode())
libc = ctypes.CDLL(None)
libc.fflush(None)
sys.exit(0 if rc == 0 else 1)
"""


_BATCH = r"""
import ctypes, os, sys
lib = ctypes.CDLL(sys.argv[1])
libc = ctypes.CDLL(None)
for entry in ("cmdCheck", "cmdPrint"):
    getattr(lib, entry).argtypes = [ctypes.c_char_p]
    getattr(lib, entry).restype = ctypes.c_int
for path in sys.argv[2:]:
    for entry in ("cmdCheck", "cmdPrint"):
        rc = getattr(lib, entry)(path.encode())
        libc.fflush(None)
        mark = f"\n@@bras-kit@@ {entry} {rc} {path}\n".encode()
        os.write(1, mark)
        os.write(2, mark)
"""


def library() -> str | None:
    """The path of libsdformat 12's shared library, or None when it is not installed."""
    found = sorted(glob.glob("/usr/lib/*/libsdformat12.so.12*")) + sorted(glob.glob("/usr/lib/libsdformat12.so.12*"))
    if found:
        return found[0]
    name = ctypes.util.find_library("sdformat12")
    return name


def require() -> str:
    """libsdformat 12's library: the one gate of the Gazebo tests (skipped without it, failed in CI)."""
    found = library()
    if found is None:
        system.missing("libsdformat12-12", "libsdformat 12 (the oracle of the Gazebo rules' tests)")
    assert found is not None
    return found


# why libsdformat refuses a model -> the BK7xx rule that must say so (bras-kit's refusal reasons)
REFUSAL_RULES = {"empty": {"BK701", "BK702", "BK703"}, "name-shared": {"BK700"}, "joint-not-converted": {"BK709"},
                 "centre-of-mass-nan": {"BK710"}, "invalid-inertia": {"BK711"}}


@dataclass(frozen=True)
class Verdict:
    """What libsdformat makes of one URDF file."""

    valid: bool  # cmdCheck returned 0 ("Valid.")
    check_output: str  # cmdCheck's stdout and stderr
    sdf: str  # cmdPrint's SDF ("" when it failed)
    links: tuple[str, ...]  # the <link>s of the converted model, in order
    joints: tuple[str, ...]  # the <joint>s of the converted model
    joint_types: dict[str, str]
    colours: dict[str, tuple[float, ...]]  # visual name -> diffuse

    @property
    def urdfdom_refused(self) -> bool:
        """urdfdom (under libsdformat) refused the URDF before any conversion."""
        return bool(re.search(r"Error:[^\n]*\n\s*at line \d+ in \S*urdf_parser/src/", self.check_output)) \
            or "Unable to call parseURDF" in self.check_output

    def mentions(self, text: str) -> bool:
        return text in self.check_output


def _call(entry: str, path: str) -> tuple[int, str, str]:
    lib = require()
    done = subprocess.run([sys.executable, "-c", _CHILD, lib, entry, os.path.abspath(path)],
                          capture_output=True, text=True, timeout=120, env={**os.environ, "LC_ALL": "C"})
    return done.returncode, done.stdout, done.stderr


def verdicts(paths: list[str]) -> dict[str, Verdict]:
    """:func:`verdict` of many files from one child process (a crash falls back to one child per file)."""
    lib = require()
    full = [os.path.abspath(p) for p in paths]
    done = subprocess.run([sys.executable, "-c", _BATCH, lib, *full], capture_output=True, text=True,
                          timeout=60 + 10 * len(full), env={**os.environ, "LC_ALL": "C"})
    if done.returncode != 0:
        return {p: verdict(p) for p in paths}
    outs, errs = _split(done.stdout), _split(done.stderr)
    return {p: _verdict(*outs[("cmdCheck", f)], errs[("cmdCheck", f)][1], *outs[("cmdPrint", f)])
            for p, f in zip(paths, full)}


def _split(text: str) -> dict[tuple[str, str], tuple[int, str]]:
    out, chunk = {}, []
    for line in text.split("\n"):
        if line.startswith("@@bras-kit@@ "):
            _, entry, rc, path = line.split(" ", 3)
            out[(entry, path)] = (int(rc), "\n".join(chunk))
            chunk = []
        else:
            chunk.append(line)
    return out


@cache
def verdict(path: str) -> Verdict:
    """libsdformat's check and conversion of the URDF at ``path``."""
    rc, out, err = _call("cmdCheck", path)
    prc, sdf, _ = _call("cmdPrint", path)
    return _verdict(rc, out, err, prc, sdf)


def _verdict(rc: int, out: str, err: str, prc: int, sdf: str) -> Verdict:
    links: list[str] = []
    joints: list[str] = []
    types: dict[str, str] = {}
    colours: dict[str, tuple[float, ...]] = {}
    if prc == 0 and sdf.strip():
        # plugin blobs copied from <gazebo> may hold names such as <ignition::corrected_offsets> or
        # <sensor:camera> with no namespace declared: not XML names; they are not links or joints
        text = re.sub(r"(</?|\s)([\w.-]+)::?(?=[\w.-])", r"\1\2_", sdf[sdf.index("<sdf"):])
        root = ET.fromstring(text)
        model = root.find("model")
        if model is not None:
            for link in model.findall("link"):
                links.append(link.get("name", ""))
                for visual in link.findall("visual"):
                    diffuse = visual.findtext("material/diffuse")
                    if diffuse:
                        colours[visual.get("name", "")] = tuple(float(v) for v in diffuse.split())
            for joint in model.findall("joint"):
                joints.append(joint.get("name", ""))
                types[joint.get("name", "")] = joint.get("type", "")
    return Verdict(rc == 0 and "Valid." in out, out + err, sdf if prc == 0 else "", tuple(links), tuple(joints),
                   types, colours)
