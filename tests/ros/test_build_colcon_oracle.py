"""``bras-kit build`` against the real colcon (colcon-core 0.21.3, colcon-ros 0.5.0: tests/realcolcon.py).

Each variant of tests/colcon_corpus.py is built twice, in two fresh workspaces: by ``colcon build
--base-paths src`` and by ``bras-kit build WS``, once as they are and once with ``--symlink-install``
given to both (the install tree's links are compared by their text, the workspace's path as <WS>). The install trees are compared file for file (path,
kind, mode, text) and the verdicts (exit code, packages Finished and Failed, colcon's error lines in
bras-kit's output), and what sourcing the scripts exports; tests/colcon_compare.py says what is
normalised. The variants kept aside while build.py was fixed (colcon_corpus.ASIDE and ASIDE_GENERATED)
run last. Each variant is built once a session by each tool and mode, both builds at once, and the
three comparisons read the same pair. The real colcon's builds are kept per content under the cache
folder (tests/colcon_compare.py, by_colcon): measured on the 2-core test machine with other suites
running, the module (50 variants, 2 modes, 303 tests) takes 2 min 42 s when colcon builds everything
(BRAS_KIT_COLCON_FRESH=1, a fresh CI runner) and 51 s when its builds are kept.
"""

from __future__ import annotations

import os
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import colcon_compare
import colcon_corpus
import pytest
import realcolcon

pytestmark = pytest.mark.slow

ASIDE = (*colcon_corpus.ASIDE, *colcon_corpus.ASIDE_GENERATED)
ORDER = [name for name in colcon_corpus.VARIANTS if name not in ASIDE] + list(ASIDE)

MODES = {"copy": (), "symlink": ("--symlink-install",)}
_built: dict[tuple[str, str], tuple[colcon_compare.Outcome, colcon_compare.Outcome]] = {}


@pytest.fixture(scope="module")
def builds(tmp_path_factory: pytest.TempPathFactory) -> dict[str, tuple[colcon_compare.Outcome, colcon_compare.Outcome]]:
    realcolcon.colcon_executable()  # the oracle venv, made once (a few seconds from PyPI's wheels)
    return _built


def _both(variant: str, builds: dict, tmp_path_factory: pytest.TempPathFactory, mode: str = "copy"
          ) -> tuple[colcon_compare.Outcome, colcon_compare.Outcome]:
    if (variant, mode) not in builds:
        # the two builds at once, one a core: each is a child process of its own, in a workspace of its own
        with ThreadPoolExecutor(2) as pool:
            colcon = pool.submit(colcon_compare.by_colcon, variant,
                                 tmp_path_factory.mktemp(f"colcon-{mode}-{variant}"), *MODES[mode])
            ours = pool.submit(colcon_compare.by_bras_kit, variant,
                               tmp_path_factory.mktemp(f"braskit-{mode}-{variant}"), *MODES[mode])
            builds[variant, mode] = (colcon.result(), ours.result())
    return builds[variant, mode]


CASES = [pytest.param(name, mode, id=f"{name}-{mode}") for part in (ORDER[:-len(ASIDE)], ASIDE)
         for mode in MODES for name in part]


def test_the_oracle_is_the_pinned_colcon() -> None:
    python = Path(realcolcon.colcon_executable()).with_name("python")
    versions = subprocess.run(
        [str(python), "-c", "from importlib.metadata import version as v; "
         "print(v('colcon-core'), v('colcon-ros'), v('setuptools'))"],
        capture_output=True, text=True, check=True).stdout.split()
    assert versions == ["0.21.3", "0.5.0", "68.1.2"]


@pytest.mark.parametrize(("variant", "mode"), CASES)
def test_verdict_is_colcons(variant: str, mode: str, builds: dict, tmp_path_factory: pytest.TempPathFactory) -> None:
    colcon, ours = _both(variant, builds, tmp_path_factory, mode)
    tree_lines = {"only colcon made", "only bras-kit made"}
    found = [line for line in colcon_compare.differences(colcon, ours)
             if not any(line.startswith(t) for t in tree_lines) and ": colcon (" not in line]
    assert found == [], "\n".join(found) + "\n--- bras-kit said:\n" + ours.output


@pytest.mark.parametrize(("variant", "mode"), CASES)
def test_install_tree_is_colcons(variant: str, mode: str, builds: dict,
                                 tmp_path_factory: pytest.TempPathFactory) -> None:
    colcon, ours = _both(variant, builds, tmp_path_factory, mode)
    found = [line for line in colcon_compare.differences(colcon, ours)
             if line.startswith(("only colcon made", "only bras-kit made")) or ": colcon (" in line]
    assert found == [], "\n".join(found)


@pytest.mark.parametrize(("variant", "mode"), CASES)
def test_sourcing_exports_what_colcons_does(variant: str, mode: str, builds: dict,
                                            tmp_path_factory: pytest.TempPathFactory) -> None:
    """What a learner's shell holds after ``source install/setup.bash`` (bras-kit's own script against
    colcon's), and after sourcing each package's share/PKG/package.sh (in sh) and package.bash (in bash):
    AMENT_PREFIX_PATH, PYTHONPATH, PATH, COLCON_PREFIX_PATH... as colcon's scripts leave them."""
    colcon, ours = _both(variant, builds, tmp_path_factory, mode)
    scripts = [("setup.bash", "bash"), ("local_setup.bash", "bash")]
    for path in sorted(colcon.tree):
        if path.endswith(("/package.sh", "/package.bash")):
            scripts.append((path, "sh" if path.endswith(".sh") else "bash"))
    found = [f"{script} ({shell}): colcon {theirs!r}, bras-kit {mine!r}" for script, shell in scripts
             if (theirs := colcon_compare.exported(colcon, script, shell)) != (mine := colcon_compare.exported(
                 ours, script, shell))]
    assert found == [], "\n".join(found)


def test_every_variant_builds_something_or_fails_in_colcon(builds: dict,
                                                           tmp_path_factory: pytest.TempPathFactory) -> None:
    """The corpus is not empty of meaning: colcon finishes most variants and fails some, and the
    trees it makes hold the tutorial's files."""
    outcomes = {name: _both(name, builds, tmp_path_factory)[0] for name in ORDER}
    finished = [n for n, o in outcomes.items() if o.code == 0]
    failed = [n for n, o in outcomes.items() if o.code != 0]
    assert len(finished) >= 30 and len(failed) >= 10
    assert outcomes["tutorial"].tree["bras_description/lib/bras_description/publie"][:2] == ("file", 0o755)
    assert "bras_description/bin/publie" in outcomes["setup_cfg_missing"].tree


def test_symlink_install_shows_an_edited_urdf_without_a_new_build(tmp_path: Path) -> None:
    """What --symlink-install is for: the installed URDF is the package's own, through build/PKG."""
    workspace = colcon_compare.make_workspace(tmp_path, "tutorial")
    done = subprocess.run([sys.executable, "-m", "bras_kit", "build", str(workspace), "--symlink-install"],
                          cwd=workspace, capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stdout + done.stderr
    installed = workspace / "install/bras_description/share/bras_description/urdf/bras.urdf"
    assert installed.is_symlink()
    assert Path(os.readlink(installed)) == workspace / "build/bras_description/urdf/bras.urdf"
    (workspace / "src/bras_description/urdf/bras.urdf").write_text('<robot name="poignet"/>\n')
    assert installed.read_text() == '<robot name="poignet"/>\n'
    egg_link = workspace / "install/bras_description/lib" / f"python{sys.version_info[0]}.{sys.version_info[1]}" \
        / "site-packages/bras-description.egg-link"
    assert egg_link.read_text() == f"{workspace / 'build/bras_description'}\n."
