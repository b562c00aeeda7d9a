"""bras-kit doctor in a learner's workspace, shell and machine: each state made for real (files
in a temporary workspace, environment variables, a mount namespace with a small /dev/shm or a
WSL2 kernel release bound over /proc), judged against the real rclpy of Jazzy where rcl or
Fast DDS has words of its own."""

from __future__ import annotations

import json
import os
import re
import shutil
import subprocess
import sys
import time
from pathlib import Path

import pytest
import realros

from bras_kit.core.i18n import say
from bras_kit.ros import surroundings as sr
from bras_kit.ros.workspace import find_workspace
from bras_kit.scaffold.package import scaffold_package

PKG = "bras_description"
BRAS_KIT = [sys.executable, "-m", "bras_kit"]


def clean_env(**extra: str) -> dict[str, str]:
    env = {k: v for k, v in os.environ.items()
           if not k.startswith(("ROS_", "RMW_", "AMENT_", "COLCON_", "LIBGL_"))}
    env.update(extra)
    return env


def doctor(cwd: Path, env: dict[str, str] | None = None, *args: str) -> subprocess.CompletedProcess[str]:
    return subprocess.run([*BRAS_KIT, "doctor", *args], cwd=cwd, env=env or clean_env(), capture_output=True,
                          text=True, timeout=120)


def workspace(tmp_path: Path, *names: str, build: bool = True) -> Path:
    root = tmp_path / "ws"
    for name in names or (PKG,):
        scaffold_package(root / "src" / name, name=name)
    if build:
        done = subprocess.run([*BRAS_KIT, "build"], cwd=root, env=clean_env(), capture_output=True, text=True,
                              timeout=300)
        assert done.returncode == 0, done.stdout + done.stderr
    return root


def texts(concerns) -> list[str]:
    return [say(c.found, "en") + " | " + (say(c.fix, "en") if c.fix else "") for c in concerns]


def of(concerns, status: str = "fail"):
    return [c for c in concerns if c.status == status]


# ---------------------------------------------------------------- the workspace


def test_edited_urdf_after_the_build_is_named_with_the_rebuild_command(tmp_path):
    root = workspace(tmp_path)
    urdf = next((root / "src" / PKG / "urdf").iterdir())
    time.sleep(0.05)
    urdf.write_text(urdf.read_text() + "<!-- moved the elbow -->\n")
    ws = find_workspace(str(root))
    (stale,) = of(sr.workspace_concerns(ws))
    text = texts([stale])[0]
    assert f"src/{PKG}/urdf/{urdf.name}" in text
    assert f"colcon build --packages-select {PKG}" in text and "source install/setup.bash" in text
    # from a folder below the root, through the command
    done = doctor(urdf.parent)
    assert done.returncode == 1 and f"src/{PKG}/urdf/{urdf.name}" in done.stdout
    # rebuilt: nothing stale any more
    subprocess.run([*BRAS_KIT, "build"], cwd=root, env=clean_env(), capture_output=True, timeout=300, check=True)
    assert not [c for c in sr.workspace_concerns(find_workspace(str(root))) if say(c.name, "en") == "installed copy"]


def test_edited_node_module_is_stale_too(tmp_path):
    root = workspace(tmp_path)
    node = root / "src" / PKG / PKG / "animation.py"
    node.write_text(node.read_text() + "\n# faster\n")
    (stale,) = of(sr.workspace_concerns(find_workspace(str(root))))
    assert f"src/{PKG}/{PKG}/animation.py" in texts([stale])[0]


def test_urdf_installed_under_another_folder_is_followed_through_data_files(tmp_path):
    """setup.py installs urdf/bras.urdf into share/PKG/description/: the copy there is compared."""
    root = workspace(tmp_path, build=False)
    setup = root / "src" / PKG / "setup.py"
    text = setup.read_text()
    entry = "installed('urdf', '*.urdf', '*.xacro'),"
    assert text.count(entry) == 1
    setup.write_text(text.replace(entry, "(os.path.join('share', package_name, 'description'), glob('urdf/*.urdf')),"))
    subprocess.run([*BRAS_KIT, "build"], cwd=root, env=clean_env(), capture_output=True, timeout=300, check=True)
    assert list((root / "install" / PKG / "share" / PKG / "description").iterdir())
    assert not of(sr.workspace_concerns(find_workspace(str(root))))
    urdf = next((root / "src" / PKG / "urdf").iterdir())
    urdf.write_text(urdf.read_text() + "<!-- x -->\n")
    (stale,) = of(sr.workspace_concerns(find_workspace(str(root))))
    assert f"src/{PKG}/urdf/{urdf.name}" in texts([stale])[0]


def test_symlink_install_is_never_stale(tmp_path):
    root = workspace(tmp_path)
    share = root / "install" / PKG / "share" / PKG / "urdf"
    for installed in share.iterdir():  # as colcon build --symlink-install leaves them
        source = root / "src" / PKG / "urdf" / installed.name
        installed.unlink()
        installed.symlink_to(source)
        source.write_text(source.read_text() + "<!-- x -->\n")
    assert not of(sr.workspace_concerns(find_workspace(str(root))))


def test_untouched_build_has_no_workspace_concern(tmp_path):
    root = workspace(tmp_path)
    assert sr.workspace_concerns(find_workspace(str(root))) == []


def test_package_never_built_is_a_note(tmp_path):
    root = workspace(tmp_path)
    scaffold_package(root / "src" / "cellule_bringup", name="cellule_bringup")
    (note,) = of(sr.workspace_concerns(find_workspace(str(root))), "note")
    assert "cellule_bringup" in texts([note])[0] and "never built" in texts([note])[0]


def test_folder_named_unlike_its_package(tmp_path):
    root = workspace(tmp_path, build=False)
    (root / "src" / PKG).rename(root / "src" / "mon_bras")
    (note,) = sr.workspace_concerns(find_workspace(str(root)))
    assert note.status == "note" and "src/mon_bras" in texts([note])[0] and f"'{PKG}'" in texts([note])[0]


def colcon_folders(place: Path, which=("build", "install", "log")) -> None:
    """The folders colcon leaves where it runs, with its markers (colcon-core verb/__init__.py,
    location.py)."""
    if "build" in which:
        (place / "build" / PKG).mkdir(parents=True)
        (place / "build" / ".built_by").write_text("colcon")
    if "install" in which:
        (place / "install").mkdir()
        (place / "install" / ".colcon_install_layout").write_text("isolated")
        (place / "install" / "setup.bash").write_text("")
    if "log" in which:
        (place / "log" / "build_2026-01-01_00-00-00").mkdir(parents=True)
        (place / "log" / "COLCON_IGNORE").write_text("")
        (place / "log" / "latest").symlink_to("build_2026-01-01_00-00-00")


@pytest.mark.parametrize("where", ["src", f"src/{PKG}"])
def test_colcon_run_inside_src(tmp_path, where):
    root = workspace(tmp_path, build=False)
    colcon_folders(root / where)
    (fail,) = of(sr.workspace_concerns(find_workspace(str(root))))
    text = texts([fail])[0]
    assert f"in {where}:" in text and "build/" in text and "install/" in text and "log/" in text
    assert f"rm -r {where}/build {where}/install {where}/log" in text


def test_a_learners_own_folder_named_build_is_not_colcons(tmp_path):
    root = workspace(tmp_path, build=False)
    (root / "src" / "build").mkdir()
    (root / "src" / "build" / "notes.txt").write_text("mes notes")
    assert sr.workspace_concerns(find_workspace(str(root))) == []


def test_two_packages_of_one_name_are_a_failure_not_a_traceback(tmp_path):
    root = workspace(tmp_path, build=False)
    shutil.copytree(root / "src" / PKG, root / "src" / "copie")
    done = doctor(root / "src")
    assert done.returncode == 1 and "Traceback" not in done.stderr
    assert "Duplicate package names not supported" in done.stdout and "copie" in done.stdout


# ---------------------------------------------------------------- the shell


def sourced_env(root: Path) -> dict[str, str]:
    """The environment after the real bash sourced install/setup.bash."""
    done = subprocess.run(["bash", "-c", f". {root}/install/setup.bash && env -0"], env=clean_env(),
                          capture_output=True, text=True, check=True)
    return dict(item.split("=", 1) for item in done.stdout.split("\0") if "=" in item)


def test_never_sourced_says_the_source_line(tmp_path):
    root = workspace(tmp_path)
    (fail,) = of(sr.shell_concerns(find_workspace(str(root)), clean_env()))
    assert f"source {root}/install/setup.bash" in texts([fail])[0]
    assert not of(sr.shell_concerns(find_workspace(str(root)), sourced_env(root)))


def test_package_built_after_sourcing(tmp_path):
    root = workspace(tmp_path)
    env = sourced_env(root)
    scaffold_package(root / "src" / "cellule_bringup", name="cellule_bringup")
    subprocess.run([*BRAS_KIT, "build"], cwd=root, env=clean_env(), capture_output=True, timeout=300, check=True)
    (fail,) = of(sr.shell_concerns(find_workspace(str(root)), env))
    assert "'cellule_bringup'" in texts([fail])[0] and "not see them yet" in texts([fail])[0]


def test_outside_the_workspace_the_sourced_one_is_examined(tmp_path):
    root = workspace(tmp_path)
    env = sourced_env(root)
    urdf = next((root / "src" / PKG / "urdf").iterdir())
    urdf.write_text(urdf.read_text() + "<!-- x -->\n")
    elsewhere = tmp_path / "ailleurs"
    elsewhere.mkdir()
    done = doctor(elsewhere, env)
    assert done.returncode == 1 and f"src/{PKG}/urdf/{urdf.name}" in done.stdout
    assert f"src/{PKG}/urdf" not in doctor(elsewhere).stdout


def test_older_workspace_earlier_on_the_path_shadows_this_one(tmp_path):
    old = workspace(tmp_path / "old")
    new = workspace(tmp_path / "new")
    old_env, new_env = sourced_env(old), sourced_env(new)
    old_prefix = old_env["AMENT_PREFIX_PATH"]
    shadowed = dict(new_env, AMENT_PREFIX_PATH=old_prefix + os.pathsep + new_env["AMENT_PREFIX_PATH"])
    (fail,) = of(sr.shell_concerns(find_workspace(str(new)), shadowed))
    assert old_prefix in texts([fail])[0] and f"source {new}/install/setup.bash" in texts([fail])[0]
    in_order = dict(new_env, AMENT_PREFIX_PATH=new_env["AMENT_PREFIX_PATH"] + os.pathsep + old_prefix)
    assert not of(sr.shell_concerns(find_workspace(str(new)), in_order))


# ---------------------------------------------------------------- the machine: rcl's words


RCL_STATES = {  # name -> environment; cases beyond the issue's
    "unset": {},
    "localhost_only_1": {"ROS_LOCALHOST_ONLY": "1"},
    "localhost_only_0": {"ROS_LOCALHOST_ONLY": "0"},
    "localhost_only_yes": {"ROS_LOCALHOST_ONLY": "yes"},
    "localhost_only_empty": {"ROS_LOCALHOST_ONLY": ""},
    "range_invalid": {"ROS_AUTOMATIC_DISCOVERY_RANGE": "EVERYWHERE"},
    "range_lowercase": {"ROS_AUTOMATIC_DISCOVERY_RANGE": "localhost"},
    "range_off": {"ROS_AUTOMATIC_DISCOVERY_RANGE": "OFF"},
    "range_system_default": {"ROS_AUTOMATIC_DISCOVERY_RANGE": "SYSTEM_DEFAULT"},
    "peer_too_long": {"ROS_STATIC_PEERS": "192.168.1.2;" + "h" * 300},
    "peers_with_localhost_only": {"ROS_STATIC_PEERS": "192.168.1.2", "ROS_LOCALHOST_ONLY": "1"},
    "domain_hex": {"ROS_DOMAIN_ID": "0x10"},
    "domain_word": {"ROS_DOMAIN_ID": "abc"},
    "domain_trailing": {"ROS_DOMAIN_ID": "5abc"},
}
RCL_ASIDE = {  # kept aside, run last
    "localhost_only_10": {"ROS_LOCALHOST_ONLY": "10"},
    "range_trailing_space": {"ROS_AUTOMATIC_DISCOVERY_RANGE": "LOCALHOST "},
    "domain_octal": {"ROS_DOMAIN_ID": "010"},
    "peers_empty_parts": {"ROS_STATIC_PEERS": ";;" + "p" * 256 + ";"},
}
PROBE = """
import json, os, subprocess, sys
states = json.loads(sys.argv[1])
out = {}
for name, env in states.items():
    full = {k: v for k, v in os.environ.items() if k != "ROS_AUTOMATIC_DISCOVERY_RANGE"}
    full.update(env)
    full.setdefault("ROS_DOMAIN_ID", "23")
    code = "import rclpy; rclpy.init(); n = rclpy.create_node('probe'); print('NODE-OK'); rclpy.shutdown()"
    done = subprocess.run([sys.executable, "-c", code], env=full, capture_output=True, text=True, timeout=60)
    out[name] = {"ok": "NODE-OK" in done.stdout, "log": done.stdout + done.stderr}
print(json.dumps(out))
"""


def rcl_verdicts(states: dict[str, dict[str, str]]) -> dict[str, dict]:
    """Each state given to the real rclpy of Jazzy (rclpy.init and a node), in a loopback namespace."""
    python = realros.oracle_python()
    done = subprocess.run(realros.in_loopback_namespace([python, "-c", PROBE, json.dumps(states)]),
                          env=realros.graph_env(realros.new_domain()), capture_output=True, text=True, timeout=600)
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout.strip().splitlines()[-1])


def rcl_warnings(log: str) -> list[str]:
    return [m.strip() for m in re.findall(r"\[WARN\] \[[\d.]+\] \[rcl\]: (.*)", log)]


def check_rcl_states(states: dict[str, dict[str, str]]) -> None:
    verdicts = rcl_verdicts(states)
    for name, env in states.items():
        concerns = sr.discovery_concerns(env)
        words = " ".join(texts(concerns))
        for warning in rcl_warnings(verdicts[name]["log"]):
            if warning.startswith("Static peer "):  # we cut the long peer: compare around it
                head, tail = warning.split(" specified to ", 1)
                assert "Static peer " in words and "specified to " + tail in words, (name, warning, words)
            else:
                assert warning in words, (name, warning, words)
        noted = [c for c in concerns if c.status != "ok" and say(c.name, "en") != "ROS_DOMAIN_ID"]
        # a note where rcl warns, and where discovery is OFF (test_discovery_off_...: no node finds another)
        expected = bool(rcl_warnings(verdicts[name]["log"])) or sr.discovery_range(env)[0] == "OFF"
        assert bool(noted) == expected, (name, verdicts[name]["log"], words)
        # a node is made exactly when nothing here is a failure
        assert (not of(concerns)) == verdicts[name]["ok"], (name, verdicts[name]["log"], words)


@pytest.mark.slow
def test_rcl_settings_judged_as_rcl_judges_them():
    check_rcl_states(RCL_STATES)


TWO_NODES = """
import rclpy, sys, time
rclpy.init()
node = rclpy.create_node(sys.argv[1])
end = time.time() + 4
while time.time() < end:
    rclpy.spin_once(node, timeout_sec=0.1)
print(sys.argv[1], ",".join(sorted(node.get_node_names())), flush=True)
rclpy.shutdown()
"""


@pytest.mark.slow
@pytest.mark.parametrize("value", ["OFF", "LOCALHOST"])
def test_discovery_off_means_no_node_finds_another(tmp_path, value):
    """What the OFF note says, as the real rclpy does it: two processes, one domain."""
    python, script = realros.oracle_python(), tmp_path / "two.py"
    script.write_text(TWO_NODES)
    line = f"{python} {script} rsp & {python} {script} rviz; wait"
    done = subprocess.run(realros.shell_in_loopback_namespace(line),
                          env=realros.graph_env(realros.new_domain(), ROS_AUTOMATIC_DISCOVERY_RANGE=value),
                          capture_output=True, text=True, timeout=120)
    seen = dict(line.split(" ", 1) for line in done.stdout.split("\n") if line.strip())
    found_other = "rviz" in seen["rsp"] or "rsp" in seen["rviz"]
    assert found_other == (value != "OFF"), done.stdout
    concerns = sr.discovery_concerns({"ROS_AUTOMATIC_DISCOVERY_RANGE": value})
    assert any(c.status == "note" for c in concerns) == (value == "OFF")


# ---------------------------------------------------------------- the machine: files and namespaces


def test_rmw_not_installed_in_the_sourced_prefix(tmp_path):
    prefix = tmp_path / "opt" / "ros" / "jazzy"  # apt's layout: the package's index marker and its library
    (prefix / sr.INDEX).mkdir(parents=True)
    (prefix / "lib").mkdir()
    (prefix / sr.INDEX / "rmw_fastrtps_cpp").write_text("")
    (prefix / "lib" / "librmw_fastrtps_cpp.so").write_text("")
    (prefix / sr.INDEX / "rmw_implementation").write_text("")
    # what /opt/ros/jazzy/setup.bash leaves: the prefix on AMENT_PREFIX_PATH, its lib/ on LD_LIBRARY_PATH
    env = {"AMENT_PREFIX_PATH": str(prefix), "LD_LIBRARY_PATH": str(prefix / "lib")}
    (fail,) = sr.rmw_concerns(dict(env, RMW_IMPLEMENTATION="rmw_cyclonedds_cpp"), system=[])
    assert fail.status == "fail" and "ros-jazzy-rmw-cyclonedds-cpp" in texts([fail])[0]
    assert "rmw_fastrtps_cpp" in texts([fail])[0]
    (ok,) = sr.rmw_concerns(dict(env, RMW_IMPLEMENTATION="rmw_fastrtps_cpp"), system=[])
    assert ok.status == "ok"
    (note,) = sr.rmw_concerns({"RMW_IMPLEMENTATION": "rmw_fastrtps_cpp"}, system=[])
    assert note.status == "note"
    assert sr.rmw_concerns(env, system=[]) == []


def test_rmw_in_a_prefix_whose_lib_is_not_on_ld_library_path_does_not_load(tmp_path):
    """rmw_implementation loads lib<NAME>.so through dlopen (rcutils shared_library.c): a prefix that
    holds it but is not on LD_LIBRARY_PATH (AMENT_PREFIX_PATH set by hand, say) does not count."""
    prefix = tmp_path / "opt" / "ros" / "jazzy"
    (prefix / sr.RMW_TYPESUPPORT).mkdir(parents=True)
    (prefix / "lib").mkdir()
    (prefix / sr.RMW_TYPESUPPORT / "rmw_cyclonedds_cpp").write_text("")
    (prefix / "lib" / "librmw_cyclonedds_cpp.so").write_text("")
    env = {"AMENT_PREFIX_PATH": str(prefix), "RMW_IMPLEMENTATION": "rmw_cyclonedds_cpp"}
    (fail,) = sr.rmw_concerns(env, system=[])
    assert fail.status == "fail" and "LD_LIBRARY_PATH does not name its folder" in texts([fail])[0]
    assert f"source {prefix}/setup.bash" in texts([fail])[0]
    (ok,) = sr.rmw_concerns(dict(env, LD_LIBRARY_PATH=f"/nowhere:{prefix / 'lib'}"), system=[])
    assert ok.status == "ok" and str(prefix / "lib" / "librmw_cyclonedds_cpp.so") in texts([ok])[0]
    # a library in the system's folders loads without any LD_LIBRARY_PATH (/usr/lib/... from a .deb)
    system = tmp_path / "usr" / "lib"
    system.mkdir(parents=True)
    (system / "librmw_zenoh_cpp.so").write_text("")
    (ok,) = sr.rmw_concerns(dict(env, RMW_IMPLEMENTATION="rmw_zenoh_cpp"), system=[str(system)])
    assert ok.status == "ok"


RCLPY_INIT = ("import rclpy\ntry:\n    rclpy.init()\n    rclpy.create_node('sonde').destroy_node()\n"
              "except Exception as exc:\n    print('FAILED', exc)\nelse:\n    print('STARTED')\n")


@pytest.mark.slow
@pytest.mark.parametrize("state", ["fastrtps_sourced", "cyclonedds_not_installed", "fastrtps_dynamic_missing"])
def test_rmw_verdict_agrees_with_the_real_rclpy(state, tmp_path):
    """The real rclpy of Jazzy (its venv is the sourced prefix: AMENT_PREFIX_PATH, and LD_LIBRARY_PATH as
    its wheels' bootstrap sets it) starts a node or stops at rcl's init; doctor says fail exactly when
    it stops (rcl's identifier check exits with 102, or init raises). The system's own library folders
    are searched as the dynamic linker searches them. The wheels' rmw_implementation reports Fast DDS
    whatever library it finds, so a library found off LD_LIBRARY_PATH is not a state this oracle can
    tell apart: the rule for it rests on rcutils' dlopen (the test above)."""
    python = Path(realros.oracle_python())
    venv = python.parent.parent
    env = {"AMENT_PREFIX_PATH": str(venv), "LD_LIBRARY_PATH": str(venv / "lib")}
    if state == "fastrtps_sourced":
        env["RMW_IMPLEMENTATION"] = "rmw_fastrtps_cpp"
    elif state == "cyclonedds_not_installed":
        env["RMW_IMPLEMENTATION"] = "rmw_cyclonedds_cpp"
    else:
        env["RMW_IMPLEMENTATION"] = "rmw_fastrtps_dynamic_cpp"
    (verdict,) = sr.rmw_concerns(env)
    done = realros.run_isolated([str(python), "-c", RCLPY_INIT], domain=realros.new_domain(), timeout=60,
                                **{k: v for k, v in env.items() if k != "LD_LIBRARY_PATH"})
    started = "STARTED" in done.stdout and done.returncode == 0
    assert started or "FAILED" in done.stdout or "Expected RMW implementation identifier" in done.stderr, \
        done.stdout + done.stderr
    assert (verdict.status != "fail") == started, (texts([verdict]), done.stdout + done.stderr)


def in_small_shm(size: str, argv: list[str]) -> list[str]:
    return ["unshare", "-rm", "sh", "-c", f'mount -t tmpfs -o size={size} tmpfs /dev/shm || exit 98; exec "$@"',
            "sh", *argv]


SHM_SIZES = {"256k": "fail", "1m": "note", "64m": "ok"}
SHM_ASIDE = {"600k": "note", "2600k": "ok"}


def check_shm(size: str, expected: str, tmp_path: Path) -> None:
    done = subprocess.run(in_small_shm(size, [*BRAS_KIT, "doctor"]), cwd=tmp_path, env=clean_env(),
                          capture_output=True, text=True, timeout=120)
    line = next(line for line in done.stdout.splitlines() if "/dev/shm" in line)
    assert line.startswith(expected), done.stdout
    if expected != "ok":
        assert "Unable to Register SHM Transport" in line


@pytest.mark.parametrize("size", sorted(SHM_SIZES))
def test_dev_shm_size(tmp_path, size):
    check_shm(size, SHM_SIZES[size], tmp_path)


@pytest.mark.slow
def test_dev_shm_too_small_for_fast_dds_as_fast_dds_says():
    """The real Fast DDS of Jazzy: one node in a 256 KiB /dev/shm says the words; in 1 MiB, not."""
    python = realros.oracle_python()
    code = "import rclpy; rclpy.init(); n = rclpy.create_node('probe'); rclpy.shutdown()"
    for size, fails in (("256k", True), ("1m", False)):
        script = (f"ip link set lo up; mount -t tmpfs -o size={size} tmpfs /dev/shm || exit 98; "
                  f"exec {python} -c \"{code}\"")
        done = subprocess.run(["unshare", "-rnm", "sh", "-c", script], env=realros.graph_env(realros.new_domain()),
                              capture_output=True, text=True, timeout=120)
        assert (sr.FASTDDS_SHM_FAILED in done.stdout + done.stderr) == fails, (size, done.stderr)


def test_wsl2_kernel_with_d3d12_renderer(tmp_path):
    release = tmp_path / "osrelease"
    release.write_text("5.15.153.1-microsoft-standard-WSL2\n")
    (fail,) = sr.graphics_concerns("D3D12 (Intel(R) UHD Graphics 620)", {}, str(release))
    assert fail.status == "fail" and "LIBGL_ALWAYS_SOFTWARE=1" in texts([fail])[0]
    (ok,) = sr.graphics_concerns("D3D12 (Intel(R) UHD Graphics 620)", {"LIBGL_ALWAYS_SOFTWARE": "1"}, str(release))
    assert ok.status == "ok"
    (vm,) = sr.graphics_concerns("llvmpipe (LLVM 15.0.6, 256 bits)", {}, "/nonexistent")
    assert vm.status == "note"
    (gpu,) = sr.graphics_concerns("Mesa Intel(R) UHD Graphics 620 (KBL GT2)", {}, "/nonexistent")
    assert gpu.status == "ok"


def test_wsl2_kernel_release_bound_over_proc(tmp_path):
    release = tmp_path / "osrelease"
    release.write_text("5.15.153.1-microsoft-standard-WSL2\n")
    script = f'mount --bind {release} /proc/sys/kernel/osrelease || exit 98; exec "$@"'
    done = subprocess.run(["unshare", "-rm", "sh", "-c", script, "sh", *BRAS_KIT, "doctor"], cwd=tmp_path,
                          env=clean_env(), capture_output=True, text=True, timeout=120)
    line = next(line for line in done.stdout.splitlines() if "graphics for RViz" in line)
    assert "WSL2" in line and "LIBGL_ALWAYS_SOFTWARE=1" in done.stdout
    done = doctor(tmp_path)
    assert "WSL2" not in done.stdout


@pytest.fixture
def x_display(tmp_path):
    """A real X server (Xvfb, Mesa's llvmpipe behind its GLX, as a virtual machine without 3D gives)."""
    for number in range(90 + os.getpid() % 50, 200):
        if not Path(f"/tmp/.X11-unix/X{number}").exists() and not Path(f"/tmp/.X{number}-lock").exists():
            break
    server = subprocess.Popen(["Xvfb", f":{number}", "-screen", "0", "320x240x24", "-nolisten", "tcp"],
                              stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        for _ in range(100):
            if Path(f"/tmp/.X11-unix/X{number}").exists():
                break
            time.sleep(0.05)
        yield f":{number}"
    finally:
        server.terminate()
        server.wait(timeout=10)


def test_the_renderer_is_the_one_glx_gives_rviz_on_the_display(x_display, tmp_path):
    """RViz opens its context through GLX on the display: doctor reads that renderer (glxinfo -B), not
    the off-screen EGL one, and says which it read; without a display, EGL's."""
    glxinfo = subprocess.run(["glxinfo", "-B"], env=clean_env(DISPLAY=x_display), capture_output=True, text=True,
                             timeout=30)
    said = re.search(r"^OpenGL renderer string: (.+)$", glxinfo.stdout, re.MULTILINE).group(1)
    done = doctor(tmp_path, clean_env(DISPLAY=x_display))
    line = next(line for line in done.stdout.splitlines() if "graphics for RViz" in line)
    assert f"{said}, GLX" in line, done.stdout
    assert line.startswith("note") and "llvmpipe" in said  # Mesa's software rasteriser: no GPU
    done = doctor(tmp_path, {k: v for k, v in clean_env().items() if k != "DISPLAY"})
    line = next(line for line in done.stdout.splitlines() if "graphics for RViz" in line)
    assert ", EGL" in line and ", GLX" not in line, done.stdout


def test_french(tmp_path):
    root = workspace(tmp_path)
    done = doctor(root, clean_env(ROS_LOCALHOST_ONLY="1"), "--lang", "fr")
    assert "ce terminal" in done.stdout and "source " + str(root) in done.stdout
    assert "ROS_LOCALHOST_ONLY is deprecated" in done.stdout and "obsolète" in done.stdout


def doctor_ros_live(cwd: Path, *args: str, **env: str) -> subprocess.CompletedProcess[str]:
    """bras-kit doctor --ros with the real rclpy, in a loopback namespace (nothing else on its graph)."""
    full = realros.graph_env(realros.new_domain(), BRAS_KIT_ROS_PYTHON=realros.oracle_python(), **env)
    full = {k: v for k, v in full.items() if not k.startswith(("AMENT_", "COLCON_"))}
    return subprocess.run(realros.in_loopback_namespace([*BRAS_KIT, "doctor", "--ros", "--duration", "0.5", *args]),
                          cwd=cwd, env=full, capture_output=True, text=True, timeout=120)


@pytest.mark.slow
def test_doctor_ros_shows_them_first(tmp_path):
    root = workspace(tmp_path)
    done = doctor_ros_live(root / "src", ROS_LOCALHOST_ONLY="1")
    assert f"source {root}/install/setup.bash" in done.stdout and "ROS_LOCALHOST_ONLY=1" in done.stdout, \
        done.stdout + done.stderr
    assert done.stdout.index("this terminal") < done.stdout.index("ROS 2 graph on ROS_DOMAIN_ID")


@pytest.mark.slow
def test_doctor_ros_json_carries_them(tmp_path):
    root = workspace(tmp_path)
    done = doctor_ros_live(root, "--format", "json")
    document = json.loads(done.stdout)
    assert any(f"source {root}/install/setup.bash" in (c["fix"] or "") for c in document["surroundings"]), document


# ---------------------------------------------------------------- kept aside, run last


@pytest.mark.slow
def test_zz_rcl_aside():
    check_rcl_states(RCL_ASIDE)


@pytest.mark.parametrize("size", sorted(SHM_ASIDE))
def test_zz_dev_shm_aside(tmp_path, size):
    check_shm(size, SHM_ASIDE[size], tmp_path)
