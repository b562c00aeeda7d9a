"""Every .xacro shipped in real robot packages on PyPI expands exactly as the real xacro does.

The oracle is the real ``xacro`` package with its own ``eval``, run on the same files with
the same package folders; bras-kit's expansion (allow-list evaluator, sandboxed child) must
give the same bytes, and fail where xacro fails.
"""

from __future__ import annotations

import contextlib
import io
import os
import site
from pathlib import Path

import pytest

from bras_kit.core.errors import BrasKitError
from bras_kit.model.xacro import expand_xacro

pytestmark = pytest.mark.slow


def _site_dirs() -> list[Path]:
    return [Path(p) for p in site.getsitepackages() + [site.getusersitepackages()] if Path(p).is_dir()]


def _corpus() -> tuple[list[Path], list[Path]]:
    trees, roots = [], []
    for base in _site_dirs():
        erd = base / "cmeel.prefix" / "share" / "example-robot-data"
        if erd.is_dir():
            trees.append(erd)
            roots.append(erd.parent)
        rtb = base / "rtbdata"
        if rtb.is_dir():
            trees.append(rtb)
            roots += [rtb / "xacro", rtb / "xacro" / "kuka_description", rtb / "armer_xarm" / "data" / "xacro"]
    files = sorted({f for tree in trees for f in tree.rglob("*.xacro")})
    return files, roots


FILES, ROOTS = _corpus()


def _real_xacro(path: Path) -> str | None:
    """The real xacro's output, or None when it fails; $(find) resolved by a plain folder lookup."""
    import xacro
    import xacro.substitution_args as subst

    def find(name: str) -> str:
        for root in ROOTS:
            if (root / name).is_dir():
                return str(root / name)
        raise subst.SubstitutionException(f"package {name} not found")

    saved = subst._eval_find, subst._eval_dict.get("find")
    subst._eval_find = subst._eval_dict["find"] = find
    try:
        with contextlib.redirect_stderr(io.StringIO()):
            return str(xacro.process_file(str(path), mappings={}).toprettyxml(indent="  "))
    except Exception:  # the oracle failed: bras-kit must fail too
        return None
    finally:
        subst._eval_find, subst._eval_dict["find"] = saved[0], saved[1]
        xacro.init_stacks(None)


def test_the_corpus_is_real_and_large():
    assert len(FILES) >= 50, FILES


def test_every_shipped_xacro_expands_byte_identical_to_real_xacro(monkeypatch):
    monkeypatch.delenv("BRAS_KIT_PACKAGE_PATH", raising=False)
    identical, both_failed, mismatched = 0, 0, []
    for path in FILES:
        os.chdir(path.parent)
        expected = _real_xacro(path)
        try:
            got = expand_xacro(path, package_paths=[str(r) for r in ROOTS])
        except BrasKitError as exc:
            got = None
            error = str(exc)
        if expected is None and got is None:
            both_failed += 1
        elif expected == got:
            identical += 1
        else:
            mismatched.append((str(path), "bras-kit failed: " + error if got is None else "different output"))
    print(f"{identical} identical, {both_failed} refused by both, of {len(FILES)}")
    assert not mismatched, mismatched
    assert identical >= 40
