"""The library API that notebooks use: every exported name resolves, and importing stays light."""

from __future__ import annotations

import subprocess
import sys

import bras_kit


def test_every_exported_name_resolves():
    missing = [name for name in bras_kit.__all__ if name != "__version__" and not hasattr(bras_kit, name)]
    assert missing == []


def test_importing_the_package_loads_no_heavy_library():
    code = ("import sys, bras_kit; heavy = {'numpy', 'pyrender', 'matplotlib', 'trimesh', 'yourdfpy', 'PIL'};"
            "print(sorted(heavy & set(sys.modules)))")
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert result.stdout.strip() == "[]"


def test_unknown_attribute_is_an_attribute_error():
    try:
        bras_kit.not_a_function  # noqa: B018
    except AttributeError as exc:
        assert "not_a_function" in str(exc)
    else:
        raise AssertionError("expected AttributeError")
