"""The one YAML loader (bras_kit/trust/yaml_gate.py): every YAML text bras-kit reads for a learner or a
stranger goes through it, and it refuses, before anything is built, what would make bras-kit's
own process swell or recurse.

Categories: aliases ("billion laughs": anchors of lists of aliases, of mappings, of long texts;
merge keys ``<<`` repeating an anchor's pairs), nesting (flow and block, sequences and mappings),
an alias inside the value it names, texts longer than the bound, values the constructor cannot
make (an integer of 5,000 digits). Oracles: the expanded size computed here from the bomb's
shape (width ** levels), PyYAML's own ``safe_load`` on what the gate accepts (the same value),
and the source of bras_kit read with :mod:`ast` (no loader of PyYAML called outside the gate).
End to end: ``bras-kit validate`` on a package whose ``.rviz`` is a bomb, measured."""

from __future__ import annotations

import ast
import os
import subprocess
import sys
import time
from pathlib import Path

import pytest
import yaml
from hypothesis import given, settings
from hypothesis import strategies as st
from paths import REPO

from bras_kit.trust import yaml_gate

PACKAGE = REPO / "bras_kit"
GATE = PACKAGE / "trust" / "yaml_gate.py"
# every function of PyYAML that parses, composes or constructs
LOADERS = {"load", "safe_load", "full_load", "unsafe_load", "load_all", "safe_load_all", "full_load_all",
           "unsafe_load_all", "compose", "compose_all", "parse", "scan"}


def laughs(levels: int, width: int, leaf: str = "lol") -> str:
    """a0 is a list of ``width`` texts, each a(i) a list of ``width`` aliases of a(i-1)."""
    lines = [f"a0: &a0 [{', '.join([leaf] * width)}]"]
    lines += [f"a{i}: &a{i} [{', '.join([f'*a{i - 1}'] * width)}]" for i in range(1, levels)]
    return "\n".join(lines) + "\n"


def expanded(levels: int, width: int) -> int:
    """The values of :func:`laughs` once every alias is expanded: the lists and their texts."""
    return sum(sum(width ** k for k in range(1, i + 2)) + 1 for i in range(levels)) + 1


# ------------------------------------------------------------------ no other loader in bras_kit


def _loader_calls(path: Path) -> list[str]:
    tree = ast.parse(path.read_text(encoding="utf-8"))
    found = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Call):
            func = node.func
            if isinstance(func, ast.Attribute) and func.attr in LOADERS:
                base = func.value
                # yaml.load(...), __import__("yaml").load(...)
                if (isinstance(base, ast.Name) and base.id == "yaml") or (
                        isinstance(base, ast.Call) and isinstance(base.func, ast.Name)
                        and base.func.id == "__import__" and any(
                            isinstance(a, ast.Constant) and a.value == "yaml" for a in base.args)):
                    found.append(f"{path.relative_to(PACKAGE.parent)}:{node.lineno} yaml.{func.attr}")
            # a loader instance driven by hand: SafeLoader(text).get_single_data()
            if isinstance(func, ast.Attribute) and func.attr in ("get_single_data", "get_data", "get_single_node"):
                found.append(f"{path.relative_to(PACKAGE.parent)}:{node.lineno} .{func.attr}")
        if isinstance(node, ast.ImportFrom) and node.module and node.module.split(".")[0] in ("yaml", "_yaml"):
            for alias in node.names:
                if alias.name in LOADERS or alias.name.endswith(("Loader", "Parser", "Composer", "Constructor")):
                    found.append(f"{path.relative_to(PACKAGE.parent)}:{node.lineno} from yaml import {alias.name}")
    return found


def test_no_module_of_bras_kit_loads_yaml_but_the_gate():
    calls = [call for path in sorted(PACKAGE.rglob("*.py")) if path != GATE for call in _loader_calls(path)]
    assert calls == []


def test_the_ast_check_sees_each_way_of_calling_a_loader(tmp_path):
    """The check above is no blind one: each spelling of a direct load is found."""
    sample = PACKAGE / "_yaml_gate_sample.py"  # under the package, for relative_to; removed at once
    sample.write_text("import yaml\nfrom yaml import safe_load\nfrom yaml import CSafeLoader\n"
                      "yaml.safe_load('a')\nyaml.load('a', Loader=yaml.SafeLoader)\n"
                      "__import__('yaml').compose('a')\nyaml.SafeLoader('a').get_single_data()\n",
                      encoding="utf-8")
    try:
        found = _loader_calls(sample)
    finally:
        sample.unlink()
    assert len(found) == 6, found


# ------------------------------------------------------------------ aliases


@settings(max_examples=40, deadline=None)
@given(levels=st.integers(1, 12), width=st.integers(1, 12))
def test_laughs_are_refused_exactly_when_their_expansion_passes_the_bound(levels, width):
    text = laughs(levels, width)
    if expanded(levels, width) > yaml_gate.MAX_NODES:
        with pytest.raises(yaml_gate.YamlRefused) as refused:
            yaml_gate.load(text)
        assert refused.value.kind == "nodes"
        assert isinstance(refused.value, yaml.YAMLError)  # the callers' except yaml.YAMLError
    else:
        assert yaml_gate.load(text) == yaml.safe_load(text)


def test_the_bound_sits_between_two_neighbouring_bombs():
    # 10 ** 4 lists at the last level: accepted; 10 ** 5: refused
    assert expanded(4, 10) < yaml_gate.MAX_NODES < expanded(5, 10)
    yaml_gate.load(laughs(4, 10))
    with pytest.raises(yaml_gate.YamlRefused):
        yaml_gate.load(laughs(5, 10))


def test_a_bomb_of_mappings_is_refused():
    lines = ["m0: &m0 {" + ", ".join(f"k{j}: v" for j in range(10)) + "}"]
    lines += [f"m{i}: &m{i} {{" + ", ".join(f"k{j}: *m{i - 1}" for j in range(10)) + "}" for i in range(1, 9)]
    with pytest.raises(yaml_gate.YamlRefused, match="aliases are expanded"):
        yaml_gate.load("\n".join(lines))


def test_an_alias_of_a_long_text_counts_its_length():
    text = "t: &t " + "x" * 100_000 + "\nl: [" + ", ".join(["*t"] * 1000) + "]\n"  # 100 MB once expanded
    with pytest.raises(yaml_gate.YamlRefused, match="aliases"):
        yaml_gate.load(text)
    assert yaml_gate.load("t: &t " + "x" * 100_000 + "\nl: [*t, *t]\n")["l"][1] == "x" * 100_000


def test_merge_keys_repeating_an_anchor_are_counted():
    # each << copies the anchor's 1,000 pairs into the mapping: 200 of them make 200,000 pairs
    base = "base: &b {" + ", ".join(f"k{j}: {j}" for j in range(1000)) + "}\n"
    merges = "".join(f"m{i}: {{<<: *b}}\n" for i in range(200))
    with pytest.raises(yaml_gate.YamlRefused):
        yaml_gate.load(base + merges)
    small = base + "".join(f"m{i}: {{<<: [*b, *b]}}\n" for i in range(5))
    assert yaml_gate.load(small) == yaml.safe_load(small)


def test_an_alias_inside_the_value_it_names_is_refused():
    for text in ("&a [*a]", "a: &a {b: *a}", "- &x\n  - 1\n  - *x\n"):
        with pytest.raises(yaml_gate.YamlRefused) as refused:
            yaml_gate.load(text)
        assert refused.value.kind == "recursive"
    assert yaml.safe_load("&a [*a]")[0][0][0] is not None  # PyYAML alone builds a list holding itself


# ------------------------------------------------------------------ nesting, sizes, values


@pytest.mark.parametrize("opening, closing", [("[", "]"), ("{a: ", "}")])
@pytest.mark.parametrize("levels", [yaml_gate.MAX_DEPTH + 1, 999, 5000, 100_000])
def test_deep_flow_nesting_is_refused_without_recursion(opening, closing, levels):
    with pytest.raises(yaml_gate.YamlRefused, match="levels deep"):
        yaml_gate.load(opening * levels + closing * levels)


def test_deep_block_nesting_is_refused_at_its_line():
    text = "".join("  " * k + f"k{k}:\n" for k in range(200)) + "  " * 200 + "leaf\n"
    with pytest.raises(yaml_gate.YamlRefused) as refused:
        yaml_gate.load(text)
    assert refused.value.kind == "depth" and refused.value.line == yaml_gate.MAX_DEPTH + 1


def test_nesting_up_to_the_bound_loads_as_pyyaml_does():
    text = "[" * yaml_gate.MAX_DEPTH + "1" + "]" * yaml_gate.MAX_DEPTH
    assert yaml_gate.load(text) == yaml.safe_load(text)


def test_pure_python_pyyaml_recurses_where_the_gate_refuses():
    """The oracle for the bound: PyYAML's Python composer and constructor recurse per level."""
    text = "[" * 3000 + "]" * 3000
    with pytest.raises(RecursionError):
        yaml.load(text, Loader=yaml.SafeLoader)  # noqa: S506 - the test's oracle
    with pytest.raises(yaml_gate.YamlRefused):
        yaml_gate.load(text, loader=yaml.SafeLoader)


def test_a_text_past_the_size_bound_is_refused_unparsed():
    with pytest.raises(yaml_gate.YamlRefused) as refused:
        yaml_gate.load("x" * (yaml_gate.MAX_CHARS + 1))
    assert refused.value.kind == "size"
    with pytest.raises(yaml_gate.YamlRefused):
        yaml_gate.load("a: 1\n", limit=3)


@pytest.mark.parametrize("text", ["n: " + "9" * 5000, "d: 2001-13-45", "- " + "1" * 4301])
def test_a_value_the_constructor_cannot_make_is_a_yaml_error(text):
    with pytest.raises(ValueError):
        yaml.safe_load(text)  # PyYAML alone: not a YAMLError, an internal error for its callers
    with pytest.raises(yaml_gate.YamlRefused) as refused:
        yaml_gate.load(text)
    assert refused.value.kind == "value"


@settings(max_examples=60, deadline=None)
@given(st.recursive(st.none() | st.booleans() | st.integers() | st.floats(allow_nan=False) | st.text(max_size=20),
                    lambda children: st.lists(children, max_size=4) | st.dictionaries(st.text(max_size=8), children,
                                                                                       max_size=4),
                    max_leaves=30))
def test_ordinary_documents_load_as_pyyaml_loads_them(value):
    text = yaml.safe_dump(value)
    assert yaml_gate.load(text) == yaml.safe_load(text)


def test_the_refusal_carries_words_in_french():
    from bras_kit.core.i18n import say

    with pytest.raises(yaml_gate.YamlRefused) as refused:
        yaml_gate.load(laughs(6, 10))
    french = say(refused.value.message, "fr")
    assert "alias" in french and french != str(refused.value)


# ------------------------------------------------------------------ end to end, measured


def _run_measured(args: list[str], limit: int = 1 << 30) -> tuple[subprocess.CompletedProcess, float, float]:
    """bras-kit ``args`` in a child held to ``limit`` bytes of address space: its result, its peak
    resident memory (MB) and seconds."""
    code = ("import resource, subprocess, sys\n"
            f"resource.setrlimit(resource.RLIMIT_AS, ({limit}, {limit}))\n"
            "p = subprocess.run(sys.argv[1:], capture_output=True, text=True, timeout=120)\n"
            "sys.stdout.write(p.stdout); sys.stderr.write(p.stderr)\n"
            "print('MAXRSS', resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss)\n"
            "sys.exit(p.returncode)\n")
    start = time.monotonic()
    done = subprocess.run([sys.executable, "-c", code, sys.executable, "-m", "bras_kit", *args],
                          capture_output=True, text=True, timeout=180, env={**os.environ, "BRAS_KIT_LANG": "en"})
    seconds = time.monotonic() - start
    peak = int(done.stdout.rsplit("MAXRSS", 1)[1]) / 1024
    return done, peak, seconds


def test_a_rviz_bomb_is_a_finding_and_bras_kit_stays_small(tmp_path):
    """Before the gate: 790 MB and 97 s (str() of the Fixed Frame, 10 ** 8 texts), here 23 MB."""
    from bras_kit.scaffold.package import scaffold_package

    scaffold_package(tmp_path / "pkg")
    rviz = tmp_path / "pkg" / "rviz" / "bras_description.rviz"
    text = rviz.read_text(encoding="utf-8")
    assert "Fixed Frame: base" in text
    rviz.write_text(laughs(8, 10) + text.replace("Fixed Frame: base", "Fixed Frame: *a7"), encoding="utf-8")
    done, peak, seconds = _run_measured(["validate", str(tmp_path / "pkg")])
    assert done.returncode == 1, done.stderr
    assert "BK600" in done.stdout and "aliases are expanded" in done.stdout
    assert "Traceback" not in done.stderr
    assert peak < 300 and seconds < 60, (peak, seconds)
